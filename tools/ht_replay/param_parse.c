/* param_parse.c - NAME=VALUE to ht_params_t; see param_parse.h. */
#include "param_parse.h"

#include <stdint.h>
#include <string.h>

#include "number.h"

typedef enum { KIND_GAIN_Q16, KIND_SPEED_CM_S, KIND_FLAG, KIND_PITCH_MODE } kind_t;

typedef struct {
    ht_param_id_t id;
    const char *name;
    kind_t kind;
    const char *unit; /* for --help */
} param_desc_t;

static const param_desc_t params[] = {
    {HT_P_KP_AILERON, "kp_aileron", KIND_GAIN_Q16, "per unit error"},
    {HT_P_KP_ELEVATOR, "kp_elevator", KIND_GAIN_Q16, "per unit error"},
    {HT_P_KP_RUDDER, "kp_rudder", KIND_GAIN_Q16, "per unit error"},
    {HT_P_KFF_AILERON, "kff_aileron", KIND_GAIN_Q16, "per rad/s at v_ref"},
    {HT_P_KFF_ELEVATOR, "kff_elevator", KIND_GAIN_Q16, "per rad/s at v_ref"},
    {HT_P_KFF_RUDDER, "kff_rudder", KIND_GAIN_Q16, "per rad/s at v_ref"},
    {HT_P_KD_AILERON, "kd_aileron", KIND_GAIN_Q16, "per rad/s"},
    {HT_P_KD_ELEVATOR, "kd_elevator", KIND_GAIN_Q16, "per rad/s"},
    {HT_P_KD_RUDDER, "kd_rudder", KIND_GAIN_Q16, "per rad/s"},
    {HT_P_V_REF, "v_ref", KIND_SPEED_CM_S, "m/s"},
    {HT_P_V_MIN, "v_min", KIND_SPEED_CM_S, "m/s"},
    {HT_P_SCHEDULE, "schedule", KIND_FLAG, "0/1"},
    {HT_P_MAX_TILT, "max_tilt", KIND_GAIN_Q16, "tilt ratio"},
    {HT_P_PITCH_MODE, "pitch_mode", KIND_PITCH_MODE, "earth|cross"},
};

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

/* The field of *p that a parameter sets. Q16 gains and max_tilt share a
 * type, as do the speeds, so one pointer per kind covers the table. */
static q16_t *q16_field(ht_params_t *p, ht_param_id_t id)
{
    switch (id) {
    case HT_P_KP_AILERON:
        return &p->kp_aileron;
    case HT_P_KP_ELEVATOR:
        return &p->kp_elevator;
    case HT_P_KP_RUDDER:
        return &p->kp_rudder;
    case HT_P_KFF_AILERON:
        return &p->kff_aileron;
    case HT_P_KFF_ELEVATOR:
        return &p->kff_elevator;
    case HT_P_KFF_RUDDER:
        return &p->kff_rudder;
    case HT_P_KD_AILERON:
        return &p->kd_aileron;
    case HT_P_KD_ELEVATOR:
        return &p->kd_elevator;
    case HT_P_KD_RUDDER:
        return &p->kd_rudder;
    case HT_P_MAX_TILT:
        return &p->max_tilt;
    default:
        return NULL;
    }
}

static int32_t *speed_field(ht_params_t *p, ht_param_id_t id)
{
    if (id == HT_P_V_REF) {
        return &p->v_ref_cm_s;
    }
    if (id == HT_P_V_MIN) {
        return &p->v_min_cm_s;
    }
    return NULL;
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
                       "elevator, rudder; v_ref, v_min, schedule, max_tilt, pitch_mode)",
                       name);
        return -1;
    }

    show(value, shown, sizeof shown);
    if (d->kind == KIND_PITCH_MODE) {
        uint8_t mode;
        if (strcmp(value, "earth") == 0 || strcmp(value, "0") == 0) {
            mode = (uint8_t)HT_PITCH_EARTH_FRAME;
        } else if (strcmp(value, "cross") == 0 || strcmp(value, "1") == 0) {
            mode = (uint8_t)HT_PITCH_TILT_CROSS;
        } else {
            (void)snprintf(msg, size, "--param %s: \"%s\" is not earth, cross, 0 or 1", d->name,
                           shown);
            return -1;
        }
        p->pitch_mode = mode;
    } else {
        double v = 0.0;
        const char *why = ht_parse_number(value, strlen(value), &v);
        if (why != NULL) {
            (void)snprintf(msg, size, "--param %s: %s: \"%s\"", d->name, why, shown);
            return -1;
        }
        long fixed = 0;
        switch (d->kind) {
        case KIND_GAIN_Q16:
            if (ht_decimal_round(value, strlen(value), 65536u, INT32_MIN, INT32_MAX, &fixed) != 0) {
                (void)snprintf(msg, size, "--param %s: %s does not fit Q16 [-32768, 32767.99998]",
                               d->name, shown);
                return -1;
            }
            *q16_field(p, d->id) = (q16_t)fixed;
            break;
        case KIND_SPEED_CM_S:
            if (ht_decimal_round(value, strlen(value), 100u, INT32_MIN, INT32_MAX, &fixed) != 0) {
                (void)snprintf(msg, size, "--param %s: %s m/s does not fit int32 cm/s", d->name,
                               shown);
                return -1;
            }
            *speed_field(p, d->id) = (int32_t)fixed;
            break;
        case KIND_FLAG:
            if (v != 0.0 && v != 1.0) {
                (void)snprintf(msg, size, "--param %s: \"%s\" is not 0 or 1", d->name, shown);
                return -1;
            }
            p->schedule = v != 0.0 ? 1u : 0u;
            break;
        default:
            break;
        }
    }
    if (id != NULL) {
        *id = d->id;
    }
    return 0;
}

/* The value of d's field in *p, in --param units. */
static void format_desc_value(const param_desc_t *d, const ht_params_t *p, char *buf, size_t size)
{
    ht_params_t copy = *p; /* the field accessors take a non-const pointer */
    switch (d->kind) {
    case KIND_GAIN_Q16:
        (void)snprintf(buf, size, "%.6g", (double)*q16_field(&copy, d->id) / 65536.0);
        break;
    case KIND_SPEED_CM_S:
        (void)snprintf(buf, size, "%.6g", (double)*speed_field(&copy, d->id) / 100.0);
        break;
    case KIND_FLAG:
        (void)snprintf(buf, size, "%u", (unsigned)copy.schedule);
        break;
    default:
        if (copy.pitch_mode == (uint8_t)HT_PITCH_EARTH_FRAME) {
            (void)snprintf(buf, size, "earth");
        } else if (copy.pitch_mode == (uint8_t)HT_PITCH_TILT_CROSS) {
            (void)snprintf(buf, size, "cross");
        } else {
            (void)snprintf(buf, size, "%u", (unsigned)copy.pitch_mode);
        }
        break;
    }
}

int ht_param_format_value(const ht_params_t *p, ht_param_id_t id, char *buf, size_t size)
{
    for (size_t i = 0; i < N_PARAMS; i++) {
        if (params[i].id == id) {
            format_desc_value(&params[i], p, buf, size);
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
        format_desc_value(&params[i], p, value, sizeof value);
        (void)fprintf(out, "  %-13s %-20s default %s\n", params[i].name, params[i].unit, value);
    }
}
