/*
 * log_replay.c - `ht_replay --log FILE` (log_replay.h). The log is read
 * record by record as its own FMT records describe it (fields found by
 * their labels, not by fixed offsets), so a log with more fields still
 * replays. PARM records set the rows of a default configuration by their
 * MAVLink names (the link's table, the names the writer used); the law is
 * initialised from it the way fw_init does, one controller per pitch method,
 * and again after any later PARM. Each HTIN is stepped and its HTO compared
 * field by field.
 */
#include "log_replay.h"

#include <math.h>
#include <stdint.h>
#include <string.h>

#include "fw_step.h"
#include "helical/law/helical_turn.h"
#include "link/fw_link_param_table.h"

typedef struct {
    uint8_t known;
    uint8_t length;
    char name[5];
    char format[17];
    char labels[65];
} fmt_t;

static size_t char_size(char c)
{
    switch (c) {
    case 'b':
    case 'B':
    case 'M':
        return 1u;
    case 'h':
    case 'H':
    case 'c':
    case 'C':
        return 2u;
    case 'i':
    case 'I':
    case 'e':
    case 'E':
    case 'L':
    case 'f':
    case 'n':
        return 4u;
    case 'q':
    case 'Q':
    case 'd':
        return 8u;
    case 'N':
        return 16u;
    case 'Z':
    case 'a':
        return 64u;
    default:
        return 0u;
    }
}

/* The offset of label in the record body (after the 3-byte header) and its
 * format character; -1 if absent. */
static long field_at(const fmt_t *f, const char *label, char *kind)
{
    size_t off = 0u;
    const char *lab = f->labels;
    for (size_t i = 0u; f->format[i] != '\0'; ++i) {
        const char *end = strchr(lab, ',');
        const size_t n = (end != NULL) ? (size_t)(end - lab) : strlen(lab);
        if ((n == strlen(label)) && (strncmp(lab, label, n) == 0)) {
            *kind = f->format[i];
            return (long)off;
        }
        off += char_size(f->format[i]);
        if (end == NULL) {
            break;
        }
        lab = end + 1;
    }
    return -1;
}

/* An integer field as logged (raw, little-endian, signed by its character). */
static int get_int(const fmt_t *f, const uint8_t *body, const char *label, int64_t *v)
{
    char k = 0;
    const long off = field_at(f, label, &k);
    if (off < 0) {
        return -1;
    }
    const uint8_t *p = &body[off];
    switch (k) {
    case 'b':
        *v = (int8_t)p[0];
        return 0;
    case 'B':
    case 'M':
        *v = p[0];
        return 0;
    case 'h':
    case 'c':
        *v = (int16_t)(uint16_t)(p[0] | (p[1] << 8));
        return 0;
    case 'H':
    case 'C':
        *v = (uint16_t)(p[0] | (p[1] << 8));
        return 0;
    case 'i':
    case 'e':
    case 'L':
    case 'I':
    case 'E': {
        const uint32_t u = (uint32_t)p[0] | ((uint32_t)p[1] << 8) | ((uint32_t)p[2] << 16) |
                           ((uint32_t)p[3] << 24);
        *v = ((k == 'I') || (k == 'E')) ? (int64_t)u : (int64_t)(int32_t)u;
        return 0;
    }
    case 'Q':
    case 'q': {
        uint64_t u = 0u;
        for (unsigned i = 0u; i < 8u; ++i) {
            u |= (uint64_t)p[i] << (8u * i);
        }
        *v = (int64_t)u;
        return 0;
    }
    default:
        return -1;
    }
}

typedef struct {
    fw_config_t cfg;
    fw_link_params_t link; /* the LNK_ rows: read, not used */
    ht_controller_t law[2];
    int dirty;
    ht_input_t in;
    int have_in;
    uint8_t pitch_mode;
    long steps, parms, parms_unknown;
} replay_t;

static int law_init(replay_t *r, FILE *err)
{
    for (uint8_t m = 0u; m < 2u; ++m) {
        ht_params_t p = r->cfg.law;
        p.pitch_mode = m;
        ht_param_id_t bad = HT_P_NONE;
        if (ht_init(&r->law[m], &p, &bad) != HT_OK) {
            (void)fprintf(err, "ht_replay: the log's law parameters are refused by ht_init (%s)\n",
                          ht_param_name(bad));
            return -1;
        }
    }
    r->dirty = 0;
    return 0;
}

static void on_parm(replay_t *r, const uint8_t *body)
{
    char name[17];
    memcpy(name, &body[8], 16u);
    name[16] = '\0';
    float value;
    memcpy(&value, &body[24], sizeof value); /* host tool: the log's binary32 */
    ++r->parms;
    const int32_t index = fw_link_param_find(name);
    const ht_param_info_t *row = NULL;
    if ((index < 0) ||
        (fw_link_param_get_cfg(&r->cfg, &r->link, (uint16_t)index, NULL, &row) != 0) ||
        (row == NULL) || !isfinite(value)) {
        ++r->parms_unknown;
        return;
    }
    const double raw = round((double)value * (double)row->scale); /* the writer's value, back */
    if (fw_link_param_put_cfg(&r->cfg, &r->link, (uint16_t)index, (int32_t)raw) != 0) {
        ++r->parms_unknown;
        return;
    }
    r->dirty = 1;
}

static int on_htin(replay_t *r, const fmt_t *f, const uint8_t *body)
{
    static const char *const labels[] = {"X",  "Y",  "Z",    "Turn", "Pitch", "Asp", "GX",
                                         "GY", "GZ", "TAcc", "ALat", "Inv",   "PMod"};
    int64_t v[13];
    for (size_t i = 0u; i < 13u; ++i) {
        if (get_int(f, body, labels[i], &v[i]) != 0) {
            return -1;
        }
    }
    ht_input_t in = {0};
    in.x = (q14_t)v[0];
    in.y = (q14_t)v[1];
    in.z = (q14_t)v[2];
    in.turn_rate_rad_s = (q11_t)v[3];
    in.pitch_ratio = (q16_t)v[4];
    in.airspeed_cm_s = (int16_t)v[5];
    in.gyro_rad_s[0] = (q11_t)v[6];
    in.gyro_rad_s[1] = (q11_t)v[7];
    in.gyro_rad_s[2] = (q11_t)v[8];
    in.turn_accel_rad_s2 = (q11_t)v[9];
    in.accel_lat_g = (q14_t)v[10];
    in.inverted = (uint8_t)v[11];
    r->in = in;
    r->pitch_mode = (v[12] != 0) ? 1u : 0u;
    r->have_in = 1;
    return 0;
}

/* 0 equal; 1 a mismatch (named); -1 a field missing. */
static int on_hto(replay_t *r, const fmt_t *f, const uint8_t *body, long offset, FILE *err)
{
    if (!r->have_in) {
        return 0; /* an HTO without its HTIN (a gap in the log): nothing to replay */
    }
    ht_output_t o;
    ht_step(&r->law[r->pitch_mode], &r->in, &o);
    const struct {
        const char *label;
        int64_t replayed;
    } want[] = {{"TrnU", o.turn_rate_used_rad_s},
                {"Tilt", o.tilt_ratio},
                {"TX", o.tilt_x},
                {"TY", o.tilt_y},
                {"TZ", o.tilt_z},
                {"REr", o.roll_error},
                {"PEr", o.pitch_error},
                {"Ail", o.aileron},
                {"Elv", o.elevator},
                {"Rud", o.rudder},
                {"RIn", o.roll_in_rate_rad_s},
                {"Fade", o.roll_fade},
                {"Slip", o.sideslip_rudder},
                {"Flg", o.flags}};
    r->have_in = 0;
    ++r->steps;
    for (size_t i = 0u; i < sizeof want / sizeof want[0]; ++i) {
        int64_t logged = 0;
        if (get_int(f, body, want[i].label, &logged) != 0) {
            return -1;
        }
        if (logged != want[i].replayed) {
            int64_t t = 0;
            (void)get_int(f, body, "TimeUS", &t);
            (void)fprintf(err,
                          "ht_replay: byte %ld (TimeUS %lld, step %ld): HTO.%s logged %lld, "
                          "replayed %lld\n",
                          offset, (long long)t, r->steps, want[i].label, (long long)logged,
                          (long long)want[i].replayed);
            return 1;
        }
    }
    return 0;
}

int ht_log_replay(const char *path, FILE *out, FILE *err)
{
    FILE *in = fopen(path, "rb");
    if (in == NULL) {
        (void)fprintf(err, "ht_replay: %s: cannot open\n", path);
        return 3;
    }
    static fmt_t fmts[256];
    static replay_t r;
    memset(fmts, 0, sizeof fmts);
    memset(&r, 0, sizeof r);
    fw_config_default(&r.cfg);
    ht_link_params_default(&r.link);
    r.dirty = 1;
    fmts[0x80].known = 1u;
    fmts[0x80].length = 89u;
    long offset = 0;
    int status = 0;
    uint8_t rec[256];
    for (;;) {
        const size_t got = fread(rec, 1u, 3u, in);
        if (got == 0u) {
            break;
        }
        if ((got < 3u) || (rec[0] != 0xA3u) || (rec[1] != 0x95u)) {
            (void)fprintf(err, "ht_replay: %s: byte %ld: not a record header (A3 95)\n", path,
                          offset);
            status = 1;
            break;
        }
        const fmt_t *f = &fmts[rec[2]];
        if (!f->known || (f->length < 3u)) {
            (void)fprintf(err, "ht_replay: %s: byte %ld: record type 0x%02X before its FMT\n", path,
                          offset, rec[2]);
            status = 1;
            break;
        }
        const size_t body_len = (size_t)f->length - 3u;
        if (fread(&rec[3], 1u, body_len, in) != body_len) {
            (void)fprintf(err, "ht_replay: %s: byte %ld: the last record is cut short\n", path,
                          offset);
            status = 1;
            break;
        }
        const uint8_t *body = &rec[3];
        if (rec[2] == 0x80u) {
            fmt_t *nf = &fmts[body[0]];
            nf->known = 1u;
            nf->length = body[1];
            memcpy(nf->name, &body[2], 4u);
            memcpy(nf->format, &body[6], 16u);
            memcpy(nf->labels, &body[22], 64u);
        } else if (strcmp(f->name, "PARM") == 0) {
            on_parm(&r, body);
        } else if (strcmp(f->name, "HTIN") == 0) {
            if (on_htin(&r, f, body) != 0) {
                (void)fprintf(err, "ht_replay: %s: byte %ld: HTIN lacks a law input field\n", path,
                              offset);
                status = 1;
                break;
            }
        } else if (strcmp(f->name, "HTO") == 0) {
            if (r.dirty && (law_init(&r, err) != 0)) {
                status = 1;
                break;
            }
            const int c = on_hto(&r, f, body, offset, err);
            if (c != 0) {
                if (c < 0) {
                    (void)fprintf(err, "ht_replay: %s: byte %ld: HTO lacks a law output field\n",
                                  path, offset);
                }
                status = 1;
                break;
            }
        }
        offset += (long)f->length;
    }
    if (ferror(in)) {
        (void)fprintf(err, "ht_replay: %s: read error\n", path);
        status = 3;
    }
    (void)fclose(in);
    if ((status == 0) && (r.steps == 0)) {
        (void)fprintf(err, "ht_replay: %s: no HTIN/HTO steps to replay\n", path);
        status = 1;
    }
    if (status == 0) {
        (void)fprintf(out,
                      "ht_replay: %s: %ld steps replayed, every law output equal to the log "
                      "(%ld PARM records read, %ld of them not rows of this build's table)\n",
                      path, r.steps, r.parms, r.parms_unknown);
    }
    return status;
}
