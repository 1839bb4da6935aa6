/*
 * helical_turn.c - one step of the helical-turn law (docs/control-law.md).
 *
 * Internal formats: the target tilt is carried in Q30 and every error of the
 * actual row in Q28 int32, so that the errors the gains amplify are not the
 * Q14 rounding of earlier steps: at the largest legal proportional gain
 * (kp * v_ref / S = 64 * 32) one LSB of Q28 in an error is 1/8 LSB of a
 * surface, and the unnormalized row (up to 2 per element) doubles a tilt
 * error. Rates are carried in Q25 rad/s, the tilt ratio in Q28, the airspeed
 * scale in Q25; each surface's demand is the sum of its three products
 * formed exactly (qi_dot3) and rounded once. Every narrowing rounds to
 * nearest and saturates. Products are exact before their one rounding
 * (q_inline.h); the ones marked _fit are bounded by construction: unit-size
 * factors (|tilt| <= 1 in Q30, |row| <= 2 in Q14), rates below 2^30 in Q25,
 * and the parameter ranges of ht_init.
 *
 * Cost (bench/README.md): no division, and three reciprocal square roots,
 * one each for Eq. 5 (1 + r^2), Eq. 6 (1 + p^2) and Eq. 11 (X^2 + Z^2), each
 * a table and one second-order step (qi_rsqrt_norm_q30, 1.5e-9 relative);
 * the target tilt is the closed form [-r c1 c2, -p c2, c1 c2] rather than
 * two vector normalizations.
 */
#include <stdbool.h>
#include <stddef.h>

#include "helical/law/helical_turn.h"

#include "law/ht_options.h"
#include "math/q_inline.h"

/* 2^35 * 32 / 980.665: (Q11 rad/s * cm/s) -> Q16 ratio with a shift of 35,
 * Q28 with a shift of 23. */
#define RATIO_FROM_OMEGA_S 1121189833L
#define RATIO_Q28_SHIFT    23u

#define Q28_ONE      ((int32_t)0x10000000) /* 2^28 */
#define Q30_ONE      ((int32_t)0x40000000) /* 2^30 */
#define S_FF_ONE_Q25 ((int32_t)0x2000000)  /* 2^25 */

static q14_t q14_from_q28(int32_t v)
{
    return qi_sat16(qi_rshift_round(v, 14u));
}

static q11_t q11_from_q25(int32_t v)
{
    return qi_sat16(qi_rshift_round(v, 14u));
}

/* The same roundings where the value is known to fit (|v| <= 1 in Q30, a
 * turn rate no larger than the Q11 input it came from). */
static q14_t q14_from_q30_fit(int32_t v)
{
    return (q14_t)qi_rshift_round(v, 16u);
}

static q11_t q11_from_q26_fit(int32_t v)
{
    return (q11_t)qi_rshift_round(v, 15u);
}

static int32_t sign_unit_q28(int32_t v)
{
    return (v >= 0) ? Q28_ONE : -Q28_ONE; /* sign(0) = +1 */
}

/* round(v / 2^shift) for shift in [0, 31]. */
static int32_t qi_rshift_round_0(int32_t v, unsigned shift)
{
    return (shift == 0u) ? v : qi_rshift_round(v, shift);
}

/* The turn rate and tilt ratio after the tilt limit (step 1). The ratio is
 * carried in Q28 into the target tilt: its rounding reaches the roll error
 * (times a row element of up to 2) and the surfaces through gains up to
 * 2048, so a Q24 ratio (2^-25) could cost 2 LSB. */
typedef struct {
    int32_t omega_q26; /* |.| <= 16 rad/s: 2^30 */
    int32_t ratio_q28; /* |.| <= max_tilt <= 8 after the limit (8 itself: INT32_MAX) */
    q16_t ratio_q16;   /* the output's rounding of it */
} turn_t;

/* 1/S, for the tilt limit and the airspeed scales: 1/S = inv_q30 * 2^-(30 + exp). */
typedef struct {
    int32_t inv_q30;
    unsigned exp;
} recip_t;

/* 1/S to a few 2^-30 relative (q_recip_q30's third-order step): the largest
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
    const int32_t omega_times_s = (int32_t)omega_q11 * s_cm_s; /* |.| <= 2^30 */
    /* saturates at +/-8, where the limit acts whatever max_tilt (<= 8) */
    t.ratio_q28 = qi_mul32(omega_times_s, RATIO_FROM_OMEGA_S, RATIO_Q28_SHIFT);
    t.omega_q26 = (int32_t)omega_q11 * 32768; /* |.| <= 2^30 */
    /* max_tilt in Q28; 8 itself (2^31) is one LSB short */
    const int32_t max_q28 =
        (ctl->max_tilt < HT_MAX_TILT_LIMIT_Q16) ? (ctl->max_tilt * 4096) : INT32_MAX;
    const bool saturated = (t.ratio_q28 == INT32_MAX) || (t.ratio_q28 == INT32_MIN);
    if (saturated || t.ratio_q28 > max_q28 || t.ratio_q28 < -max_q28) {
        /* max_tilt * g / S: Q18 * Q30 * 2^-(30 + exp) -> Q26; below |omega| */
        int32_t omega_max_q26 = qi_mul32_fit(ctl->max_tilt_g_q18, inv_s.inv_q30, 22u + inv_s.exp);
        *flags |= HT_F_TILT_LIMITED;
        t.ratio_q28 = (t.ratio_q28 > 0) ? max_q28 : -max_q28;
        t.ratio_q16 = (t.ratio_q28 > 0) ? ctl->max_tilt : -ctl->max_tilt;
        t.omega_q26 = (omega_q11 > 0) ? omega_max_q26 : -omega_max_q26;
    } else {
        t.ratio_q16 = qi_rshift_round(t.ratio_q28, 12u);
    }
    return t;
}

/* c = 1/sqrt(1 + v^2) = y_q30 * 2^-(30 + down): a Q30 mantissa, so that a
 * product v * c is rounded once (Eq. 5's r * c1 is near 1 where c1 is small). */
typedef struct {
    int32_t y_q30;
    unsigned down; /* [0, 3] */
} inv_hypot_t;

/* 1/sqrt(1 + v^2) for a Q28 v, |v| <= 8 (INT32_MAX for 8). 1 + v^2 is formed
 * in the finest of Q28, Q26 and Q24 that holds it (v^2 below 2^30: relative
 * 2^-29 or better) and read by the normalized 1/sqrt as Q28, i.e. scaled by
 * 4^-j, so the root comes out 2^j too large. v == 0 gives exactly 1. */
static inv_hypot_t inv_hypot1_q28(int32_t v_q28)
{
    inv_hypot_t c = {Q30_ONE, 0u};
    if (v_q28 == 0) {
        return c;
    }
    const uint32_t mag = (v_q28 < 0) ? ((uint32_t)0 - (uint32_t)v_q28) : (uint32_t)v_q28;
    unsigned j = 0u; /* |v| < 2 */
    if (mag >= ((uint32_t)1u << 30)) {
        j = 2u; /* |v| in [4, 8] */
    } else if (mag >= ((uint32_t)1u << 29)) {
        j = 1u; /* |v| in [2, 4) */
    } else {
        /* j = 0 */
    }
    const int32_t sq = qi_mul32_fit(v_q28, v_q28, 28u + (2u * j)); /* v^2 in Q(28 - 2j) < 2^30 */
    const uint32_t one = 0x10000000u >> (2u * j);
    const qi_rsqrt30_t r = qi_rsqrt_norm_q30((uint32_t)sq + one);
    /* (1 + v^2)^-1/2 = y * 2^(exp2 - j), exp2 in [-1, 0] here */
    const int down = (int)j - r.exp2;
    c.y_q30 = r.y_q30;
    c.down = (unsigned)down;
    return c;
}

/* Pitch ratios below 8 take the fast path of Eq. 6. */
#define UNIT_ARG_MAX_Q16 ((int32_t)0x80000) /* 8 in Q16 */

/* Eq. 6's pitch pair for |p| >= 8 (beyond 82 degrees, up to any int32):
 * with q = 1/p (|q| <= 1/8, the reciprocal the airspeed already uses),
 * 1/sqrt(1 + p^2) = |q| h and p/sqrt(1 + p^2) = sign(p) h, h = 1/sqrt(1 + q^2):
 * the same normalization as the fast path, every result in absolute Q30. */
static int32_t steep_pitch_q30(q16_t pitch_q16, int32_t *c2)
{
    const int32_t mag =
        (pitch_q16 == INT32_MIN) ? INT32_MAX : ((pitch_q16 < 0) ? -pitch_q16 : pitch_q16);
    unsigned e;
    const int32_t m_q30 = q_recip_q30(mag, &e); /* 1/mag = m * 2^-(30 + e), e in [19, 30] */
    /* 1/p_real = 2^16 / mag = m * 2^(-14 - e): in Q31, m >> (e - 17) */
    const int32_t q_q31 = qi_rshift_round(m_q30, e - 17u); /* (2^-16, 1/8] */
    /* 1 + q^2 in Q28, in [1, 1 + 1/64]: exp2 is 0 and h = y */
    const int32_t one_plus_sq = qi_mul32_fit(q_q31, q_q31, 34u) + Q28_ONE;
    const qi_rsqrt30_t r = qi_rsqrt_norm_q30((uint32_t)one_plus_sq);
    *c2 = qi_mul32_fit(q_q31, r.y_q30, 31u);
    return (pitch_q16 > 0) ? -r.y_q30 : r.y_q30;
}

/* The target tilt (Eq. 5, 6, inverted flight) in Q30, and t = sqrt(X^2 + Z^2)
 * of the target. Eq. 5 gives the roll unit vector (X1, Z1) = c1 * (-r, 1)
 * with c1 = 1/sqrt(1 + r^2); Eq. 6 renormalizes [X1, -p, Z1], whose length is
 * sqrt(1 + p^2), so with c2 = 1/sqrt(1 + p^2) the target is
 * [-r * c1 * c2, -p * c2, c1 * c2] and t = c2. Two normalizations, three
 * products. */
typedef struct {
    int32_t x, y, z; /* Q30 */
    int32_t t;       /* Q30 */
    int32_t c1;      /* Q30: 1/sqrt(1 + r^2), for the roll-in option */
} target_t;

static target_t target_tilt(int32_t ratio_q28, q16_t pitch_q16, uint8_t inverted)
{
    target_t tg;
    int32_t c2;
    if (pitch_q16 < UNIT_ARG_MAX_Q16 && pitch_q16 > -UNIT_ARG_MAX_Q16) {
        const inv_hypot_t h2 = inv_hypot1_q28(pitch_q16 * 4096); /* Q16 -> Q28, |p| < 8 */
        c2 = qi_rshift_round_0(h2.y_q30, h2.down);
        tg.y = -qi_mul32_fit(pitch_q16, h2.y_q30, 16u + h2.down); /* |p * c2| < 1 */
    } else {
        tg.y = steep_pitch_q30(pitch_q16, &c2);
    }
    const inv_hypot_t h1 = inv_hypot1_q28(ratio_q28);
    const int32_t c1 = qi_rshift_round_0(h1.y_q30, h1.down);
    const int32_t r_c1 = qi_mul32_fit(ratio_q28, h1.y_q30, 28u + h1.down); /* |r * c1| < 1 */
    const int32_t x = -qi_mul32_fit(r_c1, c2, 30u);
    const int32_t z = qi_mul32_fit(c1, c2, 30u);
    tg.x = (inverted != 0u) ? -x : x;
    tg.z = (inverted != 0u) ? -z : z;
    tg.t = c2;
    tg.c1 = c1;
    return tg;
}

/* a*b - c*d with a, c in Q14 (the actual row) and b, d in Q30: result Q28. */
static int32_t cross_q28(q14_t a, int32_t b, q14_t c, int32_t d)
{
    return qi_mul32x16_fit(b, a, 16u) - qi_mul32x16_fit(d, c, 16u); /* each |.| <= 2^29 */
}

/* Roll error (Eq. 8, 9). */
static int32_t roll_error(const ht_input_t *in, const target_t *tg, int32_t *dot, int32_t *cross,
                          uint8_t *flags)
{
    *dot = qi_mul32x16_fit(tg->x, in->x, 16u) + qi_mul32x16_fit(tg->z, in->z, 16u);
    *cross = cross_q28(in->z, tg->x, in->x, tg->z);
    if (*dot > 0) {
        return *cross;
    }
    *flags |= HT_F_ROLL_BEYOND_90;
    return sign_unit_q28(*cross);
}

/* k * v / 2^shift for a Q30 k and a Q14 row element, shift in [0, 15]; the
 * caller has shown the result fits (|v| * 2^-shift <= a, and |k| / a bounded). */
static int32_t scale_row(int32_t k, q14_t v, unsigned shift)
{
    if (shift == 0u) {
        return k * (int32_t)v; /* fits: the caller's proof */
    }
    return qi_mul32x16_fit(k, v, shift);
}

/* Earth-frame pitch error (Eq. 10) and its projection (Eq. 11): body[0],
 * body[2] = pe * [-Z, X] / a with a = sqrt(X^2 + Z^2). One normalization:
 * 1/a = y * 2^exp2 (y in Q30), which gives the unit [X, Z] / a in Q30 and
 * a = (X^2 + Z^2) * y * 2^exp2. Below the saturation the projection is taken
 * as pe * X / a = Yt * X - t * Y * (X / a) (pe = Yt * a - Y * t): the error
 * of 1/a then weighs |t * Y| <= 2 rather than |pe| <= 4.83. */
static int32_t pitch_earth_frame(const ht_input_t *in, const target_t *tg, int32_t body[3],
                                 uint8_t *flags)
{
    const int32_t x2 = (int32_t)in->x * in->x; /* each <= 2^30 */
    const int32_t z2 = (int32_t)in->z * in->z;
    const uint32_t m_q28 = (uint32_t)x2 + (uint32_t)z2;
    int32_t a = 0;
    qi_rsqrt30_t r = {0, 0, 0};
    if (m_q28 != 0u) {
        r = qi_rsqrt_norm_q30(m_q28);
        /* sqrt(m) = m_n * y * 2^-exp2 / 2^30 with m_n the normalized m in
         * [1, 4): a constant-shift product, then the power of two (a <= 2.83,
         * below 2^30 in Q28) */
        const int32_t root_q28 = qi_mul32_fit(r.xn_q28, r.y_q30, 30u);
        a = (r.exp2 >= 0) ? qi_rshift_round_0(root_q28, (unsigned)r.exp2) : root_q28 * 2;
    } else {
        /* Fuselage vertical: [-Z, 0, X] / a has no direction. Define it as the
         * upright one, [-1, 0, 0], so the whole pitch error goes to the
         * elevator: finite, bounded by |pe|, deterministic. */
        *flags |= HT_F_FUSELAGE_VERTICAL;
    }
    /* |Yt * a| <= 2.83 * 2^28 and |Y * t| <= 2^29: the sums stay below 2^31 */
    int32_t pe = qi_mul32_fit(tg->y, a, 30u) - qi_mul32x16_fit(tg->t, in->y, 16u);
    const int32_t agree = qi_mul32x16_fit(tg->y, in->y, 16u) + qi_mul32_fit(a, tg->t, 30u);
    const bool beyond = (agree <= 0);
    if (beyond) {
        *flags |= HT_F_PITCH_BEYOND_90;
        pe = sign_unit_q28(pe);
    }
    if (m_q28 == 0u) {
        body[0] = -pe;
        body[2] = 0;
        return pe;
    }
    /* the unit [X, Z] / a = [X, Z] * y * 2^(exp2 - 14) in Q30 (|.| <= 1) */
    const int down = 14 - r.exp2; /* exp2 in [-1, 14] */
    const unsigned shift = (unsigned)down;
    const int32_t ux = scale_row(r.y_q30, in->x, shift);
    const int32_t uz = scale_row(r.y_q30, in->z, shift);
    /* below the saturation k = t * Y and the target's own term Yt; beyond it
     * pe = +/-1 and the projection is pe * [-Z, X] / a itself: k = -pe, no Yt */
    const int32_t k_q29 = beyond ? (-pe * 2) : qi_mul32x16_fit(tg->t, in->y, 15u); /* |.| <= 2 */
    const int32_t yt = beyond ? 0 : tg->y;
    /* each term below 2 in Q28, the differences below 4 */
    body[0] = qi_mul32_fit(k_q29, uz, 31u) - qi_mul32x16_fit(yt, in->z, 16u);
    body[2] = qi_mul32x16_fit(yt, in->x, 16u) - qi_mul32_fit(k_q29, ux, 31u);
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
 * Scheduled (s_p = s_ff) it is s_ff * ((kff + kd)*w_d - kd*g - kp*e): the
 * three products are summed exactly in Q44 (qi_dot3) and rounded once to a
 * format that holds every unsaturated demand (|sum| <= 1/s_ff: Q29 when
 * s_ff >= 1, else Q22 since s_ff >= 1/327.67), where the amplification by
 * s_ff <= 32 leaves a rounding of at most 2^-18; beyond it the sum
 * saturates, and the surface with it. Unscheduled it is
 * (kff*s_ff)*w_d + kd*(w_d - g) - kp*e summed exactly in Q46 and rounded once;
 * kff*s_ff <= 512 (ht_init) is rounded to Q21 first (at most 2^-22 * 32 rad/s
 * = 1/8 LSB). The target rate w_d is Q25 (exact when the tilt limit does not
 * act) and s_ff Q25 (below 2^-30 relative).
 */
/* Or'ed into axis_demand's axis: a term is added after it (the sideslip
 * rudder), so its sum must not saturate early (a flag rather than a seventh
 * argument, which the step would pass on the stack). */
#define AXIS_WIDE 4u

static int32_t axis_demand(const ht_controller_t *ctl, unsigned axis_flags, int32_t s_ff_q25,
                           int32_t e_q28, int32_t rate_d_q25, q11_t gyro_q11)
{
    const unsigned axis = axis_flags & 3u;
    const bool wide = (axis_flags & AXIS_WIDE) != 0u;
    const q16_t kp = ctl->gains.kp[axis];
    const q16_t kff = ctl->gains.kff[axis];
    const q16_t kd = ctl->gains.kd[axis];
    if (ctl->schedule != 0u) {
        /* Q44 terms: (kff + kd) * 8 <= 2^26 by Q25 (2^56), kd * 2^8 by g * 2^9
         * (2^54), kp by Q28 (2^52.3) */
        unsigned fmt = 22u;
        if (s_ff_q25 >= S_FF_ONE_Q25) {
            fmt = 29u;
        }
        if (wide) {
            /* a term added after this one (the sideslip rudder, up to 128)
             * must not meet a demand saturated below it: the sum holds
             * 129 / s_ff (Q23 when s_ff >= 1, else Q15 since s_ff >= 2^-8.4),
             * its rounding at most 2^-24 * 32 or 2^-16 (1/4 LSB) */
            if (fmt == 29u) {
                fmt = 23u;
            } else {
                fmt = 15u;
            }
        }
        const int32_t sum = qi_dot3((kff + kd) * 8, rate_d_q25, -kd * 256, (int32_t)gyro_q11 * 512,
                                    -kp, e_q28, 44u - fmt);
        return qi_mul32(sum, s_ff_q25, fmt + 5u);
    }
    /* |w_d| <= 2^30 and |g| <= 2^29 in Q25: the difference fits */
    const int32_t rate_error_q25 = rate_d_q25 - ((int32_t)gyro_q11 * 16384);
    const int32_t kff_s_q21 = qi_mul32_fit(kff, s_ff_q25, 20u); /* <= 512 * 2^21 */
    /* Q46 terms: 2^60, kd * 32 by Q25 (2^57.6), kp * 4 by Q28 (2^54.3) */
    return qi_dot3(kff_s_q21, rate_d_q25, kd * 32, rate_error_q25, -kp * 4, e_q28, 26u);
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
    const target_t tg = target_tilt(turn.ratio_q28, in->pitch_ratio, in->inverted);

    /* 4. Target body rate from the actual tilt (Eq. 3), Q25 rad/s: exact
     * when the tilt limit does not act (a Q11 times a Q14 value). */
    const q14_t row[3] = {in->x, in->y, in->z};
    int32_t rate_d[3];
    for (unsigned i = 0; i < 3u; i++) {
        rate_d[i] = qi_mul32x16_fit(turn.omega_q26, row[i], 15u); /* <= 16 * 2 * 2^25 = 2^30 */
    }
    o->rate_x_rad_s = q11_from_q25(rate_d[0]);
    o->rate_y_rad_s = q11_from_q25(rate_d[1]);
    o->rate_z_rad_s = q11_from_q25(rate_d[2]);

    /* Option roll-in: the target's own bank rate joins the roll axis' target
     * rate (feed-forward and damping); none while the tilt limit holds the
     * target. |rate_d[1] + roll_in| <= 2^30 + 2^28 in Q25. The outputs are
     * written where they are known (fewer values live across the step). */
    o->roll_in_rate_rad_s = 0;
    if (ctl->roll_in != 0u && (flags & (uint8_t)HT_F_TILT_LIMITED) == 0u) {
        const int32_t r = ht_opt_roll_in_q25(ctl, in->turn_accel_rad_s2, s_cm_s, tg.c1, &flags);
        rate_d[1] += r;
        o->roll_in_rate_rad_s = q11_from_q25(r);
    }

    /* 5-8. The error vector e = [pitch_x, roll, pitch_z]. */
    int32_t e[3], roll_dot, roll_cross, pe = 0;
    e[1] = roll_error(in, &tg, &roll_dot, &roll_cross, &flags);
    /* Option vertical fade: the roll error (Eq. 9's +/-1 near a vertical
     * fuselage) times min(1, sqrt(X^2 + Z^2) / vertical_fade). */
    o->roll_fade = Q14_ONE;
    if (ctl->fade2_q28 != 0u) {
        const int32_t f = ht_opt_fade_q30(ctl, in->x, in->z, &flags);
        o->roll_fade = q14_from_q30_fit(f);
        if (f < Q30_ONE) {
            e[1] = qi_mul32_fit(e[1], f, 30u); /* |.| <= 2^29 */
        }
    }
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
    /* Option sideslip: rudder toward zero lateral specific force. */
    int32_t rudder_q20;
    if (ctl->kp_sideslip == 0) {
        rudder_q20 = axis_demand(ctl, 2u, s_ff_q25, e[2], rate_d[2], in->gyro_rad_s[2]);
        o->sideslip_rudder = 0;
    } else {
        const int32_t ss_q20 = ht_opt_sideslip_q20(ctl, in->accel_lat_g);
        rudder_q20 = qi_add_sat32(
            axis_demand(ctl, 2u | AXIS_WIDE, s_ff_q25, e[2], rate_d[2], in->gyro_rad_s[2]), ss_q20);
        o->sideslip_rudder = qi_sat16(qi_rshift_round(ss_q20, 6u));
    }
    o->rudder = surface_from_q20(rudder_q20, &flags);

    o->turn_rate_used_rad_s = q11_from_q26_fit(turn.omega_q26);
    o->tilt_ratio = turn.ratio_q16;
    o->tilt_x = q14_from_q30_fit(tg.x);
    o->tilt_y = q14_from_q30_fit(tg.y);
    o->tilt_z = q14_from_q30_fit(tg.z);
    o->roll_dot = q14_from_q28(roll_dot);
    o->roll_cross = q14_from_q28(roll_cross);
    o->roll_error = q14_from_q28(e[1]);
    o->pitch_error = q14_from_q28(pe);
    o->pitch_body_x = q14_from_q28(e[0]);
    o->pitch_body_z = q14_from_q28(e[2]);
    o->flags = flags;
}
