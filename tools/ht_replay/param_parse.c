/* param_parse.c - NAME=VALUE to ht_params_t; see param_parse.h. */
#include "param_parse.h"

#include <stdint.h>
#include <string.h>

#include "number.h"

/* The storage formats of the table's rows (include/helical/params.h). */
typedef enum { FMT_Q16, FMT_CM32, FMT_CM16, FMT_U8, FMT_U16 } fmt_t;

typedef struct {
    ht_param_id_t id;
    const char *name;
    fmt_t fmt;
    const char *unit; /* for --help */
} param_desc_t;

/* One row per parameter of include/helical/params.def: the option names are
 * the table's names, in its order. */
#define DESC(id, name, field, unit, fmt, lo, hi, def, desc) {HT_P_##id, #name, FMT_##fmt, unit},
static const param_desc_t params[] = {HT_PARAMS_LAW(DESC)};

#define N_PARAMS (sizeof params / sizeof params[0])

const char *ht_param_tool_name(ht_param_id_t id)
{
    for (size_t i = 0; i < N_PARAMS; i++) {
        if (params[i].id == id) {
            return params[i].name;
        }
    }
    return "";
}

/* The stored value of a field, and the store (the value fits the field's
 * type: the callers check it against the format first). */
#define GET_RAW(id, name, field, unit, fmt, lo, hi, def, desc)                                     \
    case HT_P_##id:                                                                                \
        return (long)p->field;

static long get_raw(const ht_params_t *p, ht_param_id_t id)
{
    switch (id) {
        HT_PARAMS_LAW(GET_RAW)
    default:
        return 0;
    }
}

#define SET_RAW(id, name, field, unit, fmt, lo, hi, def, desc)                                     \
    case HT_P_##id:                                                                                \
        p->field = (HT_PFMT_TYPE_##fmt)v;                                                          \
        break;

static void set_raw(ht_params_t *p, ht_param_id_t id, long v)
{
    switch (id) {
        HT_PARAMS_LAW(SET_RAW)
    default:
        break;
    }
}

/* Text for a message: s[0..len) cut with "..." to fit buf, bytes outside
 * printable ASCII as '?' (an argument is printed back to a terminal). */
static void show_n(const char *s, size_t len, char *buf, size_t size)
{
    size_t n = len < size - 1 ? len : size - 4;
    for (size_t i = 0; i < n; i++) {
        unsigned char c = (unsigned char)s[i];
        buf[i] = (c < 0x20 || c > 0x7e) ? '?' : (char)c;
    }
    if (n < len) {
        memcpy(buf + n, "...", 3);
        n += 3;
    }
    buf[n] = '\0';
}

static void show(const char *s, char *buf, size_t size)
{
    show_n(s, strlen(s), buf, size);
}

void ht_param_show_text(const char *text, char *buf, size_t size)
{
    show(text, buf, size);
}

/* A value of an integer format (U8, U16): an integer within the table's
 * range, refused here because a uint8 cannot even hold most wrong values. */
static int parse_integer(const param_desc_t *d, const char *value, double v, long *out, char *msg,
                         size_t size)
{
    const ht_param_info_t *info = ht_param_info(d->id);
    char shown[44];
    show(value, shown, sizeof shown);
    if (v != (double)(long)v || (long)v < (long)info->min_raw || (long)v > (long)info->max_raw) {
        if (info->min_raw == 0 && info->max_raw == 1) {
            (void)snprintf(msg, size, "--param %s: \"%s\" is not 0 or 1", d->name, shown);
        } else {
            (void)snprintf(msg, size, "--param %s: \"%s\" is not an integer in [%ld, %ld]", d->name,
                           shown, (long)info->min_raw, (long)info->max_raw);
        }
        return -1;
    }
    *out = (long)v;
    return 0;
}

int ht_param_parse(ht_params_t *p, const char *arg, ht_param_id_t *id, char *msg, size_t size)
{
    char shown[44];
    const char *eq = strchr(arg, '=');
    if (eq == NULL || eq == arg) {
        show(arg, shown, sizeof shown);
        (void)snprintf(msg, size, "--param \"%s\": expected NAME=VALUE", shown);
        return -1;
    }
    size_t name_len = (size_t)(eq - arg);
    const char *value = eq + 1;
    const param_desc_t *d = NULL;
    for (size_t i = 0; i < N_PARAMS; i++) {
        if (strlen(params[i].name) == name_len && memcmp(params[i].name, arg, name_len) == 0) {
            d = &params[i];
            break;
        }
    }
    if (d == NULL) {
        char name[44];
        show_n(arg, name_len, name, sizeof name);
        (void)snprintf(msg, size,
                       "--param: unknown parameter \"%s\" (known: kp_, kff_, kd_ + aileron, "
                       "elevator, rudder; v_ref, v_min, schedule, max_tilt, pitch_mode; "
                       "ht_replay --help lists them)",
                       name);
        return -1;
    }

    show(value, shown, sizeof shown);
    long fixed = 0;
    if (d->id == HT_P_PITCH_MODE) {
        /* the one enumeration: its names, or its numbers */
        if (strcmp(value, "earth") == 0 || strcmp(value, "0") == 0) {
            fixed = (long)HT_PITCH_EARTH_FRAME;
        } else if (strcmp(value, "cross") == 0 || strcmp(value, "1") == 0) {
            fixed = (long)HT_PITCH_TILT_CROSS;
        } else {
            (void)snprintf(msg, size, "--param %s: \"%s\" is not earth, cross, 0 or 1", d->name,
                           shown);
            return -1;
        }
    } else {
        double v = 0.0;
        const char *why = ht_parse_number(value, strlen(value), &v);
        if (why != NULL) {
            (void)snprintf(msg, size, "--param %s: %s: \"%s\"", d->name, why, shown);
            return -1;
        }
        /* The format's own limits only: the range is ht_init's verdict (the
         * same table), reported with the bounds by the tool. */
        switch (d->fmt) {
        case FMT_Q16:
            if (ht_decimal_round(value, strlen(value), 65536u, INT32_MIN, INT32_MAX, &fixed) != 0) {
                (void)snprintf(msg, size, "--param %s: %s does not fit Q16 [-32768, 32767.99998]",
                               d->name, shown);
                return -1;
            }
            break;
        case FMT_CM32:
        case FMT_CM16: {
            const long lo = (d->fmt == FMT_CM32) ? (long)INT32_MIN : (long)INT16_MIN;
            const long hi = (d->fmt == FMT_CM32) ? (long)INT32_MAX : (long)INT16_MAX;
            if (ht_decimal_round(value, strlen(value), 100u, lo, hi, &fixed) != 0) {
                (void)snprintf(msg, size, "--param %s: %s %s does not fit %s cm/s", d->name, shown,
                               d->unit, (d->fmt == FMT_CM32) ? "int32" : "int16");
                return -1;
            }
            break;
        }
        default: /* FMT_U8, FMT_U16 */
            if (parse_integer(d, value, v, &fixed, msg, size) != 0) {
                return -1;
            }
            break;
        }
    }
    set_raw(p, d->id, fixed);
    if (id != NULL) {
        *id = d->id;
    }
    return 0;
}

/* A stored value in --param units ("1.5", "15", "earth"). */
static void format_raw(const param_desc_t *d, long raw, char *buf, size_t size)
{
    const ht_param_info_t *info = ht_param_info(d->id);
    if (d->id == HT_P_PITCH_MODE && raw == (long)HT_PITCH_EARTH_FRAME) {
        (void)snprintf(buf, size, "earth");
    } else if (d->id == HT_P_PITCH_MODE && raw == (long)HT_PITCH_TILT_CROSS) {
        (void)snprintf(buf, size, "cross");
    } else if (info->scale == 1) {
        (void)snprintf(buf, size, "%ld", raw);
    } else {
        (void)snprintf(buf, size, "%.6g", (double)raw / (double)info->scale);
    }
}

int ht_param_format_value(const ht_params_t *p, ht_param_id_t id, char *buf, size_t size)
{
    for (size_t i = 0; i < N_PARAMS; i++) {
        if (params[i].id == id) {
            format_raw(&params[i], get_raw(p, id), buf, size);
            return 0;
        }
    }
    (void)snprintf(buf, size, "?");
    return -1;
}

int ht_param_format_range(ht_param_id_t id, char *buf, size_t size)
{
    for (size_t i = 0; i < N_PARAMS; i++) {
        if (params[i].id == id) {
            const ht_param_info_t *info = ht_param_info(id);
            char lo[24];
            char hi[24];
            format_raw(&params[i], (long)info->min_raw, lo, sizeof lo);
            format_raw(&params[i], (long)info->max_raw, hi, sizeof hi);
            (void)snprintf(buf, size, "%s in [%s, %s] %s (%s)", params[i].name, lo, hi,
                           params[i].unit, info->format);
            return 0;
        }
    }
    (void)snprintf(buf, size, "?");
    return -1;
}

void ht_param_print_table(FILE *out, const ht_params_t *p)
{
    for (size_t i = 0; i < N_PARAMS; i++) {
        char value[32];
        format_raw(&params[i], get_raw(p, params[i].id), value, sizeof value);
        (void)fprintf(out, "  %-13s %-20s default %s\n", params[i].name, params[i].unit, value);
    }
}

void ht_param_print_ranges(FILE *out)
{
    for (size_t i = 0; i < N_PARAMS; i++) {
        char range[96];
        (void)ht_param_format_range(params[i].id, range, sizeof range);
        (void)fprintf(out, "  %s\n", range);
    }
}
