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
 *
 * Cost (bench/README.md): no division, and three reciprocal square roots,
 * one each for Eq. 5 (1 + r^2), Eq. 6 (1 + p^2) and Eq. 11 (X^2 + Z^2), each
 * a table, one Newton step and a single wide product; the target tilt is the
 * closed form [-r c1 c2, -p c2, c1 c2] rather than two vector
 * normalizations; shifts are chosen in [17, 32] where the portable product
 * has its short path.
 */
#include <stddef.h>

#include "helical/helical_turn.h"

#include "q_inline.h"

/* 2^35 * 32 / 980.665: (Q11 rad/s * cm/s) -> Q16 ratio with a shift of 35,
 * Q24 with a shift of 27. */
#define RATIO_FROM_OMEGA_S 1121189833L
#define RATIO_Q24_SHIFT    27u

#define Q28_ONE ((int32_t)0x10000000) /* 2^28 */

static q14_t q14_from_q28(int32_t v)
{
    return qi_sat16(qi_rshift_round(v, 14u));
}

static q11_t q11_from_q25(int32_t v)
{
    return qi_sat16(qi_rshift_round(v, 14u));
}

/* The same roundings where the value is known to fit (|v| <= 1 in Q28, a
 * turn rate no larger than the Q11 input it came from). */
static q14_t q14_from_q28_fit(int32_t v)
{
    return (q14_t)qi_rshift_round(v, 14u);
}

static q11_t q11_from_q26_fit(int32_t v)
{
    return (q11_t)qi_rshift_round(v, 15u);
}

static int32_t sign_unit_q28(int32_t v)
{
    return (v >= 0) ? Q28_ONE : -Q28_ONE; /* sign(0) = +1 */
}

/* The turn rate and tilt ratio after the tilt limit (step 1). The ratio is
 * carried in Q24 into the target tilt: its Q16 rounding (7.6e-6) would reach
 * the roll error unchanged and the aileron through the largest scheduled
 * gains (30 x 0.125 LSB). */
typedef struct {
    int32_t omega_q26; /* |.| <= 16 rad/s: 2^30 */
    int32_t ratio_q24; /* |.| <= max_tilt <= 8 after the limit */
    q16_t ratio_q16;   /* the output's rounding of it */
} turn_t;

/* 1/S, for the tilt limit and the airspeed scales: 1/S = inv_q30 * 2^-(30 + exp). */
typedef struct {
    int32_t inv_q30;
    unsigned exp;
} recip_t;

/* 1/S to a few 2^-30 relative (q_recip_q30's two Newton steps): the largest
 * legal rate gain (512 per rad/s) times a 32 rad/s target rate would turn an
 * error of 2^-24 into 1.6 LSB. S is in [100, 32767], so exp is in [6, 14]. */
static recip_t recip_airspeed(int32_t s_cm_s)
{
    recip_t r;
    r.inv_q30 = q_recip_q30(s_cm_s, &r.exp);
    return r;
}

static turn_t limit_turn(const ht_controller_t *ctl, q11_t omega_q11, int32_t s_cm_s, recip_t inv_s,
                         uint8_t *flags)
{
    turn_t t;
    int32_t omega_times_s = (int32_t)omega_q11 * s_cm_s; /* |.| <= 2^30 */
    /* saturates beyond 128, far past any max_tilt (<= 8) */
    t.ratio_q24 = qi_mul32(omega_times_s, RATIO_FROM_OMEGA_S, RATIO_Q24_SHIFT);
    t.omega_q26 = (int32_t)omega_q11 * 32768;    /* |.| <= 2^30 */
    const int32_t max_q24 = ctl->max_tilt * 256; /* <= 2^27 */
    if (t.ratio_q24 > max_q24 || t.ratio_q24 < -max_q24) {
        /* max_tilt * g / S: Q18 * Q30 * 2^-(30 + exp) -> Q26; below |omega| */
        int32_t omega_max_q26 = qi_mul32_fit(ctl->max_tilt_g_q18, inv_s.inv_q30, 22u + inv_s.exp);
        *flags |= HT_F_TILT_LIMITED;
        t.ratio_q24 = (t.ratio_q24 > 0) ? max_q24 : -max_q24;
        t.ratio_q16 = (t.ratio_q24 > 0) ? ctl->max_tilt : -ctl->max_tilt;
        t.omega_q26 = (omega_q11 > 0) ? omega_max_q26 : -omega_max_q26;
    } else {
        t.ratio_q16 = qi_rshift_round(t.ratio_q24, 8u);
    }
    return t;
}

/* 1/sqrt(1 + v^2) in Q28 from v^2 in Q24 (v^2 <= 64): 1 + v^2 (at most
 * 65 * 2^24) read by the normalized 1/sqrt as Q28 is divided by 16, so the
 * root comes out 4 times too large. */
static int32_t inv_hypot1_from_sq_q24(int32_t sq_q24)
{
    const int32_t one_plus_sq_q24 = sq_q24 + (int32_t)0x01000000; /* <= 2^30 + 2^24 */
    const qi_rsqrt_t r = qi_rsqrt_norm_q28((uint32_t)one_plus_sq_q24);
    /* 1/sqrt((1 + v^2) / 16) = y * 2^exp2, so c = y * 2^(exp2 - 2); exp2 in [-1, 2] */
    const int down = 2 - r.exp2;
    return (down <= 0) ? r.y_q28 : qi_rshift_round(r.y_q28, (unsigned)down);
}

/* Pitch ratios up to 8 take the fast path of Eq. 6. */
#define UNIT_ARG_MAX_Q16 ((int32_t)0x80000) /* 8 in Q16 */

/* c = 1/sqrt(1 + v^2) in Q28 for a Q24 v with |v| <= 8 (2^27): v^2 / 2^24 <=
 * 2^30. v == 0 gives exactly 1 without the work. */
static int32_t inv_hypot1_q24_q28(int32_t v_q24)
{
    if (v_q24 == 0) {
        return Q28_ONE;
    }
    return inv_hypot1_from_sq_q24(qi_mul32_fit(v_q24, v_q24, 24u));
}

/* Eq. 6's pitch pair for |p| > 8 (beyond 83 degrees, up to any int32):
 * with q = 1/p (|q| < 1/8, the reciprocal the airspeed already uses),
 * 1/sqrt(1 + p^2) = |q| h and p/sqrt(1 + p^2) = sign(p) h, h = 1/sqrt(1 + q^2):
 * the same normalization as the fast path, every result in absolute Q28. */
static int32_t steep_pitch_q28(q16_t pitch_q16, int32_t *c2)
{
    const int32_t mag =
        (pitch_q16 == INT32_MIN) ? INT32_MAX : ((pitch_q16 < 0) ? -pitch_q16 : pitch_q16);
    unsigned e;
    const int32_t m_q30 = q_recip_q30(mag, &e); /* 1/mag = m * 2^-(30 + e), e in [19, 30] */
    /* 1/p_real = 2^16 / mag = m * 2^(-14 - e): in Q28, m >> (e - 14) */
    const int32_t q_q28 = qi_rshift_round(m_q30, e - 14u); /* (2^-16, 1/8] */
    const int32_t h = inv_hypot1_from_sq_q24(qi_mul32_fit(q_q28, q_q28, 32u));
    *c2 = qi_mul32_fit(q_q28, h, 28u);
    return (pitch_q16 > 0) ? -h : h;
}

/* The target tilt (Eq. 5, 6, inverted flight) in Q28, and t = sqrt(X^2 + Z^2)
 * of the target. Eq. 5 gives the roll unit vector (X1, Z1) = c1 * (-r, 1)
 * with c1 = 1/sqrt(1 + r^2); Eq. 6 renormalizes [X1, -p, Z1], whose length is
 * sqrt(1 + p^2), so with c2 = 1/sqrt(1 + p^2) the target is
 * [-r * c1 * c2, -p * c2, c1 * c2] and t = c2. Two normalizations, three
 * products. */
typedef struct {
    int32_t x, y, z; /* Q28 */
    int32_t t_q28;
} target_t;

static target_t target_tilt(int32_t ratio_q24, q16_t pitch_q16, uint8_t inverted)
{
    target_t tg;
    int32_t c2;
    if (pitch_q16 <= UNIT_ARG_MAX_Q16 && pitch_q16 >= -UNIT_ARG_MAX_Q16) {
        c2 = inv_hypot1_q24_q28(pitch_q16 * 256); /* Q16 -> Q24, |p| <= 8 */
        tg.y = -qi_mul32_fit(pitch_q16, c2, 16u); /* |p * c2| < 1 */
    } else {
        tg.y = steep_pitch_q28(pitch_q16, &c2);
    }
    const int32_t c1 = inv_hypot1_q24_q28(ratio_q24); /* |ratio| <= max_tilt <= 8 */
    int32_t c12 = c2;
    if (c1 != Q28_ONE) {
        c12 = (c2 == Q28_ONE) ? c1 : qi_mul32_fit(c1, c2, 28u);
    }
    const int32_t x = -qi_mul32_fit(ratio_q24, c12, 24u); /* |r * c1| < 1 */
    tg.x = (inverted != 0u) ? -x : x;
    tg.z = (inverted != 0u) ? -c12 : c12;
    tg.t_q28 = c2;
    return tg;
}

/* a*b - c*d with a, c in Q14 (the actual row) and b, d in Q28: result Q28. */
static int32_t cross_q28(q14_t a, int32_t b, q14_t c, int32_t d)
{
    return qi_mul32x16_fit(b, a, 14u) - qi_mul32x16_fit(d, c, 14u); /* each |.| <= 2^29 */
}

/* Roll error (Eq. 8, 9). */
static int32_t roll_error(const ht_input_t *in, const target_t *tg, int32_t *dot, int32_t *cross,
                          uint8_t *flags)
{
    *dot = qi_mul32x16_fit(tg->x, in->x, 14u) + qi_mul32x16_fit(tg->z, in->z, 14u);
    *cross = cross_q28(in->z, tg->x, in->x, tg->z);
    if (*dot > 0) {
        return *cross;
    }
    *flags |= HT_F_ROLL_BEYOND_90;
    return sign_unit_q28(*cross);
}

/* k * v / 2^shift for a Q28 k and a Q14 row element, shift in [0, 15]; the
 * caller has shown the result fits (|v| * 2^-shift <= a, and |k| / a bounded). */
static int32_t scale_row_q28(int32_t k, q14_t v, unsigned shift)
{
    if (shift == 0u) {
        return k * (int32_t)v; /* fits: the caller's proof */
    }
    return qi_mul32x16_fit(k, v, shift);
}

/* round(v / 2^shift) for shift in [0, 31]. */
static int32_t qi_rshift_round_0(int32_t v, unsigned shift)
{
    return (shift == 0u) ? v : qi_rshift_round(v, shift);
}

/* Earth-frame pitch error (Eq. 10) and its projection (Eq. 11): body[0],
 * body[2] = pe * [-Z, X] / a with a = sqrt(X^2 + Z^2). One normalization:
 * 1/a = y * 2^exp2 in Q28, so a = (X^2 + Z^2) * y * 2^exp2 and
 * pe / a * X = (pe * y) * X * 2^(exp2 - 14) in Q28. */
static int32_t pitch_earth_frame(const ht_input_t *in, const target_t *tg, int32_t body[3],
                                 uint8_t *flags)
{
    const int32_t x2 = (int32_t)in->x * in->x; /* each <= 2^30 */
    const int32_t z2 = (int32_t)in->z * in->z;
    const uint32_t m_q28 = (uint32_t)x2 + (uint32_t)z2;
    int32_t a = 0;
    qi_rsqrt_t r = {0, 0, 0};
    if (m_q28 != 0u) {
        r = qi_rsqrt_norm_q28(m_q28);
        /* sqrt(m) = m_n * y * 2^-exp2 / 2^28 with m_n the normalized m in
         * [1, 4): a constant-shift product, then the power of two (a <= 2.83,
         * below 2^30 in Q28) */
        const int32_t root_q28 = qi_mul32_fit(r.xn_q28, r.y_q28, 28u);
        a = (r.exp2 >= 0) ? qi_rshift_round_0(root_q28, (unsigned)r.exp2) : root_q28 * 2;
    } else {
        /* Fuselage vertical: [-Z, 0, X] / a has no direction. Define it as the
         * upright one, [-1, 0, 0], so the whole pitch error goes to the
         * elevator: finite, bounded by |pe|, deterministic. */
        *flags |= HT_F_FUSELAGE_VERTICAL;
    }
    /* |Yt * a| <= 2.83 * 2^28 and |Y * t| <= 2^29: the sums stay below 2^31 */
    int32_t pe = qi_mul32_fit(tg->y, a, 28u) - qi_mul32x16_fit(tg->t_q28, in->y, 14u);
    const int32_t agree = qi_mul32x16_fit(tg->y, in->y, 14u) + qi_mul32_fit(a, tg->t_q28, 28u);
    if (agree <= 0) {
        *flags |= HT_F_PITCH_BEYOND_90;
        pe = sign_unit_q28(pe);
    }
    if (m_q28 == 0u) {
        body[0] = -pe;
        body[2] = 0;
        return pe;
    }
    /* k = pe * y: |pe| <= 4.83 in Q28, y <= 2^28; |X|, |Z| <= a, so each
     * component is at most |pe| */
    const int32_t k = qi_mul32_fit(pe, r.y_q28, 28u);
    const int down = 14 - r.exp2; /* exp2 in [-1, 14] */
    const unsigned shift = (unsigned)down;
    body[0] = -scale_row_q28(k, in->z, shift);
    body[2] = scale_row_q28(k, in->x, shift);
    return pe;
}

/* Eq. A.13: the tilt cross product, [Y*Zt - Yt*Z, 0, X*Yt - Xt*Y]. */
static void pitch_tilt_cross(const ht_input_t *in, const target_t *tg, int32_t body[3])
{
    body[0] = cross_q28(in->y, tg->z, in->z, tg->y);
    body[2] = cross_q28(in->x, tg->y, in->y, tg->x);
}

/*
 * One axis, in Q20 commands:
 *   d = -kp*s_p*e + kff*s_ff*w_d + kd*s_p*(w_d - g).
 * Scheduled (s_p = s_ff) it is s_ff * ((kff + kd)*w_d - kd*g - kp*e): three
 * products and the scale; unscheduled, s_ff * (kff*w_d) + kd*(w_d - g) - kp*e.
 * The target rate w_d is Q25 (exact when the tilt limit does not act) and
 * s_ff Q25, so a rate gain of 512 (ht_init's limit) times s_ff <= 32 does not
 * amplify a rounding of either beyond a fraction of an LSB. Each product is
 * exact before its one rounding; the terms that can exceed int32 (huge rates
 * times large gains) saturate, and so does every sum.
 */
static int32_t axis_demand(const ht_controller_t *ctl, unsigned axis, int32_t s_ff_q25,
                           int32_t e_q28, int32_t rate_d_q25, q11_t gyro_q11)
{
    const q16_t kp = ctl->gains.kp[axis];
    const q16_t kff = ctl->gains.kff[axis];
    const q16_t kd = ctl->gains.kd[axis];
    /* |kp * e| <= 64 * 4.83 commands: fits Q20 */
    const int32_t p_term = qi_mul32_fit(kp, e_q28, 24u);
    if (ctl->schedule != 0u) {
        const int32_t kd_g = qi_mul32x16_fit(kd, gyro_q11, 7u); /* Q16 * Q11 -> Q20, <= 2^30 */
        int32_t sum = qi_mul32(kff + kd, rate_d_q25, 21u);      /* kff + kd <= 2^23 */
        sum = qi_sub_sat32(qi_sub_sat32(sum, kd_g), p_term);
        return qi_mul32(sum, s_ff_q25, 25u);
    }
    /* |w_d| <= 2^30 and |g| <= 2^29 in Q25: the difference fits */
    const int32_t rate_error_q25 = rate_d_q25 - ((int32_t)gyro_q11 * 16384);
    int32_t d = qi_mul32(qi_mul32(kff, rate_d_q25, 21u), s_ff_q25, 25u);
    d = qi_add_sat32(d, qi_mul32(kd, rate_error_q25, 21u));
    return qi_sub_sat32(d, p_term);
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
    const recip_t inv_s = recip_airspeed(s_cm_s);
    turn_t turn = limit_turn(ctl, in->turn_rate_rad_s, s_cm_s, inv_s, &flags);

    /* 2-3. Target tilt. */
    const target_t tg = target_tilt(turn.ratio_q24, in->pitch_ratio, in->inverted);

    /* 4. Target body rate from the actual tilt (Eq. 3), Q25 rad/s: exact
     * when the tilt limit does not act (a Q11 times a Q14 value). */
    const q14_t row[3] = {in->x, in->y, in->z};
    int32_t rate_d[3];
    for (unsigned i = 0; i < 3u; i++) {
        rate_d[i] = qi_mul32x16_fit(turn.omega_q26, row[i], 15u); /* <= 16 * 2 * 2^25 = 2^30 */
    }

    /* 5-8. The error vector e = [pitch_x, roll, pitch_z]. */
    int32_t e[3], roll_dot, roll_cross, pe = 0;
    e[1] = roll_error(in, &tg, &roll_dot, &roll_cross, &flags);
    if (ctl->pitch_mode == (uint8_t)HT_PITCH_TILT_CROSS) {
        pitch_tilt_cross(in, &tg, e);
    } else {
        pe = pitch_earth_frame(in, &tg, e, &flags);
    }

    /* 9. Airspeed scale, Q25: s_ff = v_ref / S <= v_ref / v_min <= 32 (ht_init),
     * so below 2^30 (s_p is s_ff when scheduled, else 1). */
    const int32_t s_ff_q25 = qi_mul32x16_fit(inv_s.inv_q30, ctl->v_ref_cm_s, 5u + inv_s.exp);

    /* 10-11. Demands and surfaces. */
    o->elevator = surface_from_q20(
        qi_sub_sat32(0, axis_demand(ctl, 0u, s_ff_q25, e[0], rate_d[0], in->gyro_rad_s[0])),
        &flags);
    o->aileron = surface_from_q20(
        axis_demand(ctl, 1u, s_ff_q25, e[1], rate_d[1], in->gyro_rad_s[1]), &flags);
    o->rudder = surface_from_q20(axis_demand(ctl, 2u, s_ff_q25, e[2], rate_d[2], in->gyro_rad_s[2]),
                                 &flags);

    o->turn_rate_used_rad_s = q11_from_q26_fit(turn.omega_q26);
    o->tilt_ratio = turn.ratio_q16;
    o->tilt_x = q14_from_q28_fit(tg.x);
    o->tilt_y = q14_from_q28_fit(tg.y);
    o->tilt_z = q14_from_q28_fit(tg.z);
    o->rate_x_rad_s = q11_from_q25(rate_d[0]);
    o->rate_y_rad_s = q11_from_q25(rate_d[1]);
    o->rate_z_rad_s = q11_from_q25(rate_d[2]);
    o->roll_dot = q14_from_q28(roll_dot);
    o->roll_cross = q14_from_q28(roll_cross);
    o->roll_error = q14_from_q28(e[1]);
    o->pitch_error = q14_from_q28(pe);
    o->pitch_body_x = q14_from_q28(e[0]);
    o->pitch_body_z = q14_from_q28(e[2]);
    o->flags = flags;
}
