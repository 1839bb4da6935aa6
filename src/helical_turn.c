/*
 * helical_turn.c - one step of the helical-turn law (docs/control-law.md).
 *
 * Internal formats: unit-size quantities (target tilt, errors) are carried in
 * Q28 int32, so that the errors the gains amplify are not the Q14 rounding of
 * earlier steps (a gain of 30 would turn half an LSB into 15); rates and the
 * turn rate are carried in Q20 rad/s; the surface terms are summed in Q20
 * commands and rounded once to Q14. Every narrowing rounds to nearest and
 * saturates. Products are exact before their one rounding (q_inline.h); the
 * ones marked _fit are bounded by construction: unit-size factors (|tilt| <= 1
 * in Q28, |row| <= 2 in Q14, so every product or sum of two is below 2^30),
 * rates below 2^25 in Q20, and the parameter ranges of ht_init.
 */
#include <stddef.h>

#include "helical/helical_turn.h"

#include "q_inline.h"

/* 2^35 * 32 / 980.665: (Q11 rad/s * cm/s) -> Q16 ratio, shift 35. */
#define RATIO_FROM_OMEGA_S 1121189833L
#define RATIO_SHIFT        35u

#define Q28_ONE ((int32_t)0x10000000) /* 2^28 */

static q14_t q14_from_q28(int32_t v)
{
    return qi_sat16(qi_rshift_round(v, 14u));
}

static q11_t q11_from_q20(int32_t v)
{
    return qi_sat16(qi_rshift_round(v, 9u));
}

static int32_t sign_unit_q28(int32_t v)
{
    return (v >= 0) ? Q28_ONE : -Q28_ONE; /* sign(0) = +1 */
}

/* The turn rate and tilt ratio after the tilt limit (step 1). */
typedef struct {
    int32_t omega_q20;
    q16_t ratio_q16;
} turn_t;

/* 1/S, for the tilt limit and the airspeed scales: 1/S = inv_q30 * 2^-(30 + exp). */
typedef struct {
    int32_t inv_q30;
    unsigned exp;
} recip_t;

static turn_t limit_turn(const ht_controller_t *ctl, q11_t omega_q11, int32_t s_cm_s, recip_t inv_s,
                         uint8_t *flags)
{
    turn_t t;
    int32_t omega_times_s = (int32_t)omega_q11 * s_cm_s; /* |.| <= 2^30 */
    t.ratio_q16 = qi_mul32_fit(omega_times_s, RATIO_FROM_OMEGA_S, RATIO_SHIFT);
    t.omega_q20 = (int32_t)omega_q11 * 512;
    if (t.ratio_q16 > ctl->max_tilt || t.ratio_q16 < -ctl->max_tilt) {
        /* max_tilt * g / S: Q16 * Q30 * 2^-(30 + exp) -> Q20 */
        int32_t omega_max_q20 = qi_mul32_fit(ctl->max_tilt_g_q16, inv_s.inv_q30, 26u + inv_s.exp);
        *flags |= HT_F_TILT_LIMITED;
        t.ratio_q16 = (t.ratio_q16 > 0) ? ctl->max_tilt : -ctl->max_tilt;
        t.omega_q20 = (omega_q11 > 0) ? omega_max_q20 : -omega_max_q20;
    }
    return t;
}

/* Target tilt (Eq. 5, 6 and inverted flight), Q28, and t = sqrt(X^2 + Z^2)
 * of the target. Eq. 6 renormalizes [X1, -p, Z1] with X1^2 + Z1^2 = 1, which
 * is [X1 * t, -p * t, Z1 * t] with t = 1 / sqrt(1 + p^2): (-p*t, t) is the
 * unit vector of (-p, 1). */
static void target_tilt(q16_t ratio_q16, q16_t pitch_q16, uint8_t inverted, int32_t tilt[3],
                        int32_t *t_q28)
{
    int32_t roll[2] = {-ratio_q16, Q16_ONE}; /* becomes (X1, Z1) */
    int32_t pitch[2] = {(pitch_q16 == INT32_MIN) ? INT32_MAX : -pitch_q16, Q16_ONE}; /* (Yt, t) */
    (void)q_unit_q28(roll, 2u, roll);
    (void)q_unit_q28(pitch, 2u, pitch);
    int32_t sign = 1;
    if (inverted != 0u) {
        sign = -1;
    }
    tilt[0] = sign * qi_mul32_fit(roll[0], pitch[1], 28u);
    tilt[1] = pitch[0];
    tilt[2] = sign * qi_mul32_fit(roll[1], pitch[1], 28u);
    *t_q28 = pitch[1];
}

/* a*b - c*d with a, c in Q14 (the actual row) and b, d in Q28: result Q28. */
static int32_t cross_q28(q14_t a, int32_t b, q14_t c, int32_t d)
{
    return qi_mul32x16_fit(b, a, 14u) - qi_mul32x16_fit(d, c, 14u); /* each |.| <= 2^29 */
}

/* Roll error (Eq. 8, 9). */
static int32_t roll_error(const ht_input_t *in, const int32_t tilt[3], int32_t *dot, int32_t *cross,
                          uint8_t *flags)
{
    *dot = qi_mul32x16_fit(tilt[0], in->x, 14u) + qi_mul32x16_fit(tilt[2], in->z, 14u);
    *cross = cross_q28(in->z, tilt[0], in->x, tilt[2]);
    if (*dot > 0) {
        return *cross;
    }
    *flags |= HT_F_ROLL_BEYOND_90;
    return sign_unit_q28(*cross);
}

/* Earth-frame pitch error (Eq. 10) and its projection (Eq. 11): body[0], body[2]. */
static int32_t pitch_earth_frame(const ht_input_t *in, const int32_t tilt[3], int32_t t_q28,
                                 int32_t body[3], uint8_t *flags)
{
    int32_t u[2] = {in->x, in->z}; /* becomes [X, Z] / a */
    int32_t a;
    if (q_unit_q28(u, 2u, u) != 0) {
        /* [X, Z].u = |[X, Z]| <= 2.83: each product below 2^30 */
        a = qi_mul32x16_fit(u[0], in->x, 14u) + qi_mul32x16_fit(u[1], in->z, 14u);
    } else {
        /* Fuselage vertical: [-Z, 0, X] / a has no direction. Define it as the
         * upright one, [-1, 0, 0], so the whole pitch error goes to the
         * elevator: finite, bounded by |pe|, deterministic. */
        *flags |= HT_F_FUSELAGE_VERTICAL;
        u[0] = 0;
        u[1] = Q28_ONE;
        a = 0;
    }
    /* |Yt * a| <= 2.83 * 2^28 and |Y * t| <= 2^29: the sums stay below 2^31 */
    int32_t pe = qi_mul32_fit(tilt[1], a, 28u) - qi_mul32x16_fit(t_q28, in->y, 14u);
    int32_t agree = qi_mul32x16_fit(tilt[1], in->y, 14u) + qi_mul32_fit(a, t_q28, 28u);
    if (agree <= 0) {
        *flags |= HT_F_PITCH_BEYOND_90;
        pe = sign_unit_q28(pe);
    }
    body[0] = qi_mul32_fit(-pe, u[1], 28u);
    body[2] = qi_mul32_fit(pe, u[0], 28u);
    return pe;
}

/* Eq. A.13: the tilt cross product, [Y*Zt - Yt*Z, 0, X*Yt - Xt*Y]. */
static void pitch_tilt_cross(const ht_input_t *in, const int32_t tilt[3], int32_t body[3])
{
    body[0] = cross_q28(in->y, tilt[2], in->z, tilt[1]);
    body[2] = cross_q28(in->x, tilt[1], in->y, tilt[0]);
}

/* One axis: d = -kp*s_p*e + kff*s_ff*w_d + kd*s_p*(w_d - g), in Q20 commands. */
static int32_t axis_demand(const ht_controller_t *ctl, unsigned axis, int32_t s_ff_q20,
                           int32_t e_q28, int32_t rate_d_q20, q11_t gyro_q11)
{
    q16_t gp = ctl->gains.kp[axis];
    q16_t gd = ctl->gains.kd[axis];
    if (ctl->schedule != 0u) { /* s_p = s_ff; unscheduled, s_p = 1 costs nothing */
        gp = qi_mul32_fit(gp, s_ff_q20, 20u);
        gd = qi_mul32_fit(gd, s_ff_q20, 20u);
    }
    q16_t gff = qi_mul32_fit(ctl->gains.kff[axis], s_ff_q20, 20u);
    int32_t rate_error_q20 = rate_d_q20 - (int32_t)gyro_q11 * 512;
    int32_t d = qi_mul32(gp, e_q28, 24u);
    d = qi_sub_sat32(qi_mul32(gff, rate_d_q20, 16u), d);
    return qi_add_sat32(d, qi_mul32(gd, rate_error_q20, 16u));
}

static q14_t surface_from_q20(int32_t d_q20, uint8_t *flags)
{
    int32_t s = qi_rshift_round(d_q20, 6u);
    if (s > Q14_ONE || s < -Q14_ONE) {
        *flags |= HT_F_SURFACE_SATURATED;
        s = (s > 0) ? Q14_ONE : -Q14_ONE;
    }
    return (q14_t)s;
}

void ht_step(const ht_controller_t *ctl, const ht_input_t *in, ht_output_t *out)
{
    if (out == NULL) {
        return;
    }
    if (ctl == NULL || in == NULL || !ctl->ready) {
        const ht_output_t zero = {0};
        *out = zero;
        return;
    }
    ht_output_t *o = out; /* written field by field: no copy of the struct on the stack */
    uint8_t flags = 0u;

    /* 1. Airspeed floor and tilt limit. */
    int32_t s_cm_s = in->airspeed_cm_s;
    if (s_cm_s < ctl->v_min_cm_s) {
        s_cm_s = ctl->v_min_cm_s;
        flags |= HT_F_AIRSPEED_FLOORED;
    }
    recip_t inv_s;
    inv_s.inv_q30 = q_recip_q30(s_cm_s, &inv_s.exp);
    turn_t turn = limit_turn(ctl, in->turn_rate_rad_s, s_cm_s, inv_s, &flags);

    /* 2-3. Target tilt. */
    int32_t tilt[3], t_q28;
    target_tilt(turn.ratio_q16, in->pitch_ratio, in->inverted, tilt, &t_q28);

    /* 4. Target body rate from the actual tilt (Eq. 3), Q20 rad/s. */
    const q14_t row[3] = {in->x, in->y, in->z};
    int32_t rate_d[3];
    for (unsigned i = 0; i < 3u; i++) {
        rate_d[i] = qi_mul32x16_fit(turn.omega_q20, row[i], 14u); /* <= 2^25 */
    }

    /* 5-8. The error vector e = [pitch_x, roll, pitch_z]. */
    int32_t e[3], roll_dot, roll_cross, pe = 0;
    e[1] = roll_error(in, tilt, &roll_dot, &roll_cross, &flags);
    if (ctl->pitch_mode == (uint8_t)HT_PITCH_TILT_CROSS) {
        pitch_tilt_cross(in, tilt, e);
    } else {
        pe = pitch_earth_frame(in, tilt, t_q28, e, &flags);
    }

    /* 9. Airspeed scale, Q20: s_ff = v_ref / S (s_p is s_ff when scheduled, else 1). */
    int32_t s_ff_q20 = qi_mul32_fit(ctl->v_ref_cm_s, inv_s.inv_q30, 10u + inv_s.exp);

    /* 10-11. Demands and surfaces. */
    o->elevator = surface_from_q20(
        qi_sub_sat32(0, axis_demand(ctl, 0u, s_ff_q20, e[0], rate_d[0], in->gyro_rad_s[0])),
        &flags);
    o->aileron = surface_from_q20(
        axis_demand(ctl, 1u, s_ff_q20, e[1], rate_d[1], in->gyro_rad_s[1]), &flags);
    o->rudder = surface_from_q20(axis_demand(ctl, 2u, s_ff_q20, e[2], rate_d[2], in->gyro_rad_s[2]),
                                 &flags);

    o->turn_rate_used_rad_s = q11_from_q20(turn.omega_q20);
    o->tilt_ratio = turn.ratio_q16;
    o->tilt_x = q14_from_q28(tilt[0]);
    o->tilt_y = q14_from_q28(tilt[1]);
    o->tilt_z = q14_from_q28(tilt[2]);
    o->rate_x_rad_s = q11_from_q20(rate_d[0]);
    o->rate_y_rad_s = q11_from_q20(rate_d[1]);
    o->rate_z_rad_s = q11_from_q20(rate_d[2]);
    o->roll_dot = q14_from_q28(roll_dot);
    o->roll_cross = q14_from_q28(roll_cross);
    o->roll_error = q14_from_q28(e[1]);
    o->pitch_error = q14_from_q28(pe);
    o->pitch_body_x = q14_from_q28(e[0]);
    o->pitch_body_z = q14_from_q28(e[2]);
    o->flags = flags;
}
