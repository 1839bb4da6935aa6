#include "ht_test_support.h"

#include <math.h>
#include <stdio.h>

uint64_t ts_rng_next(uint64_t *state)
{
    uint64_t z = (*state += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

double ts_uniform(uint64_t *state, double lo, double hi)
{
    double u = (double)(ts_rng_next(state) >> 11) * (1.0 / 9007199254740992.0);
    return lo + (hi - lo) * u;
}

double ts_gaussian(uint64_t *state)
{
    double u1 = ts_uniform(state, 1e-300, 1.0);
    double u2 = ts_uniform(state, 0.0, 1.0);
    return sqrt(-2.0 * log(u1)) * cos(6.283185307179586 * u2);
}

int16_t ts_fix16(double v, int frac_bits)
{
    double f = floor(v * ldexp(1.0, frac_bits) + 0.5);
    if (f > 32767.0) {
        return INT16_MAX;
    }
    if (f < -32768.0) {
        return INT16_MIN;
    }
    return (int16_t)f;
}

int32_t ts_fix32(double v, int frac_bits)
{
    double f = floor(v * ldexp(1.0, frac_bits) + 0.5);
    if (f > 2147483647.0) {
        return INT32_MAX;
    }
    if (f < -2147483648.0) {
        return INT32_MIN;
    }
    return (int32_t)f;
}

int ts_on_branch_boundary(const ht_ref_output_t *r, const ht_ref_params_t *p)
{
    if (fabs(r->ratio_margin) < TS_BRANCH_EPS) {
        return 1;
    }
    if (fabs(r->roll_dot) < TS_BRANCH_EPS ||
        (r->roll_dot <= 0 && fabs(r->roll_cross) < TS_BRANCH_EPS)) {
        return 1;
    }
    return p->pitch_mode == HT_PITCH_EARTH_FRAME &&
           (fabs(r->pitch_agree) < TS_BRANCH_EPS ||
            (r->pitch_agree <= 0 && fabs(r->pitch_raw) < TS_BRANCH_EPS));
}

#define GAIN(x) Q16_FROM_REAL(x)

/* Designated initialisers: a row added to the parameter table is 0 here
 * (its default must then be 0 or the set given it). */
const ts_gain_set_t ts_gain_sets[] = {
    {"default (control-law.md)", HT_PARAMS_DEFAULT},
    {"c172p (kp 3/6/0.3, kd 0.5/1/1, kff 0/1/0.5, v_ref 50)",
     {.kp_aileron = GAIN(3),
      .kp_elevator = GAIN(6),
      .kp_rudder = GAIN(0.3),
      .kff_aileron = GAIN(0),
      .kff_elevator = GAIN(1),
      .kff_rudder = GAIN(0.5),
      .kd_aileron = GAIN(0.5),
      .kd_elevator = GAIN(1),
      .kd_rudder = GAIN(1),
      .v_ref_cm_s = 5000,
      .v_min_cm_s = 500,
      .schedule = 0,
      .max_tilt = GAIN(4),
      .pitch_mode = HT_PITCH_EARTH_FRAME}},
    {"T37 (kp 2/4/0.3, kd 0.3/1/1, kff 0/1/0.5, v_ref 110, v_min 20)",
     {.kp_aileron = GAIN(2),
      .kp_elevator = GAIN(4),
      .kp_rudder = GAIN(0.3),
      .kff_aileron = GAIN(0),
      .kff_elevator = GAIN(1),
      .kff_rudder = GAIN(0.5),
      .kd_aileron = GAIN(0.3),
      .kd_elevator = GAIN(1),
      .kd_rudder = GAIN(1),
      .v_ref_cm_s = 11000,
      .v_min_cm_s = 2000,
      .schedule = 0,
      .max_tilt = GAIN(4),
      .pitch_mode = HT_PITCH_EARTH_FRAME}},
    {"c172p scheduled (schedule = 1, v_min 10)",
     {.kp_aileron = GAIN(3),
      .kp_elevator = GAIN(6),
      .kp_rudder = GAIN(0.3),
      .kff_aileron = GAIN(0),
      .kff_elevator = GAIN(1),
      .kff_rudder = GAIN(0.5),
      .kd_aileron = GAIN(0.5),
      .kd_elevator = GAIN(1),
      .kd_rudder = GAIN(1),
      .v_ref_cm_s = 5000,
      .v_min_cm_s = 1000,
      .schedule = 1,
      .max_tilt = GAIN(4),
      .pitch_mode = HT_PITCH_EARTH_FRAME}},
    {"tilt cross product (Eq. A.13), kp 2, kff 1, kd 0.5",
     {.kp_aileron = GAIN(2),
      .kp_elevator = GAIN(2),
      .kp_rudder = GAIN(2),
      .kff_aileron = GAIN(1),
      .kff_elevator = GAIN(1),
      .kff_rudder = GAIN(1),
      .kd_aileron = GAIN(0.5),
      .kd_elevator = GAIN(0.5),
      .kd_rudder = GAIN(0.5),
      .v_ref_cm_s = 1500,
      .v_min_cm_s = 500,
      .schedule = 0,
      .max_tilt = GAIN(4),
      .pitch_mode = HT_PITCH_TILT_CROSS}},
};
const int ts_gain_set_count = (int)(sizeof ts_gain_sets / sizeof ts_gain_sets[0]);

void ts_err_add(ts_err_t *e, double core_real, double ref_real)
{
    double err = fabs(core_real - ref_real) / e->lsb;
    if (err > e->worst) {
        e->worst = err;
    }
    e->samples++;
}

const char *const ts_output_names[TS_N_OUTPUTS] = {
    "turn_rate_used", "tilt_x",   "tilt_y",     "tilt_z",     "rate_x",      "rate_y",
    "rate_z",         "roll_dot", "roll_cross", "roll_error", "pitch_error", "pitch_body_x",
    "pitch_body_z",   "aileron",  "elevator",   "rudder"};

void ts_errs_init(ts_err_t errs[TS_N_OUTPUTS])
{
    for (int i = 0; i < TS_N_OUTPUTS; i++) {
        int is_rate = (i == 0 || (i >= 4 && i <= 6));
        errs[i].name = ts_output_names[i];
        errs[i].lsb = is_rate ? 1.0 / 2048.0 : 1.0 / 16384.0;
        errs[i].worst = 0.0;
        errs[i].samples = 0;
    }
}

void ts_errs_add_step(ts_err_t errs[TS_N_OUTPUTS], const ht_output_t *c, const ht_ref_output_t *r)
{
    const double q14 = 1.0 / 16384.0, q11 = 1.0 / 2048.0;
    const double core[TS_N_OUTPUTS] = {c->turn_rate_used_rad_s * q11,
                                       c->tilt_x * q14,
                                       c->tilt_y * q14,
                                       c->tilt_z * q14,
                                       c->rate_x_rad_s * q11,
                                       c->rate_y_rad_s * q11,
                                       c->rate_z_rad_s * q11,
                                       c->roll_dot * q14,
                                       c->roll_cross * q14,
                                       c->roll_error * q14,
                                       c->pitch_error * q14,
                                       c->pitch_body_x * q14,
                                       c->pitch_body_z * q14,
                                       c->aileron * q14,
                                       c->elevator * q14,
                                       c->rudder * q14};
    /* The reference is not clamped to the output formats: clamp it the way
     * the core documents (Q11 rates saturate at +/-16 rad/s, Q14 at +/-2). */
    const double ref[TS_N_OUTPUTS] = {
        r->turn_rate_used, r->tilt[0],    r->tilt[1],     r->tilt[2],
        r->rate[0],        r->rate[1],    r->rate[2],     r->roll_dot,
        r->roll_cross,     r->roll_error, r->pitch_error, r->pitch_body_x,
        r->pitch_body_z,   r->aileron,    r->elevator,    r->rudder};
    for (int i = 0; i < TS_N_OUTPUTS; i++) {
        double hi = 32767.0 * errs[i].lsb, lo = -32768.0 * errs[i].lsb;
        double v = ref[i] > hi ? hi : (ref[i] < lo ? lo : ref[i]);
        ts_err_add(&errs[i], core[i], v);
    }
}

void ts_errs_print(const char *title, const ts_err_t errs[TS_N_OUTPUTS])
{
    printf("worst error vs double reference, %s (%ld steps)\n", title, errs[0].samples);
    for (int i = 0; i < TS_N_OUTPUTS; i++) {
        printf("  %-15s %6.2f LSB (%s)\n", errs[i].name, errs[i].worst,
               errs[i].lsb > 1.0 / 4096.0 ? "Q11 rad/s" : "Q14");
    }
}

ht_params_t ts_gains3(q16_t kp, q16_t kff, q16_t kd, int32_t v_ref, int32_t v_min, uint8_t schedule,
                      q16_t max_tilt, uint8_t pitch_mode)
{
    ht_params_t p = HT_PARAMS_DEFAULT;
    p.kp_aileron = p.kp_elevator = p.kp_rudder = kp;
    p.kff_aileron = p.kff_elevator = p.kff_rudder = kff;
    p.kd_aileron = p.kd_elevator = p.kd_rudder = kd;
    p.v_ref_cm_s = v_ref;
    p.v_min_cm_s = v_min;
    p.schedule = schedule;
    p.max_tilt = max_tilt;
    p.pitch_mode = pitch_mode;
    return p;
}
