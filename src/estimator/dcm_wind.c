/*
 * dcm_wind.c - the estimator's wind estimate: see dcm_wind.h for why and how.
 *
 * Formats: velocities in cm/s Q8, held to +/-231.7 m/s per component (the
 * weight of one solution is about 1/100, so a 1 cm/s change still moves a
 * mean by 2.6 LSB); second moments in (cm/s)^2, which the bound keeps below
 * 2^30 (the variance of a modest turn is a difference of large moments:
 * their resolution is the regression's); A in Q28.
 */
#include "estimator/dcm_wind.h"

#include "helical/math/q14.h"
#include "math/q_inline.h"

#define V_MAX_CM_S ((int32_t)23170)
#define V_MAX_Q8   (V_MAX_CM_S * 256)
/* The course's velocities are held to +/-327.67 m/s (their Q8 fits). */
#define COURSE_MAX_CM_S ((int32_t)32767)
#define WIND_MAX_Q8     ((int32_t)DCM_WIND_MAX_CM_S * 256)
#define A_ONE_Q28       ((int32_t)268435456)
/* |A|^2 in Q27 bounds: |A| in [0.5, 2] */
#define A_MAG2_MIN_Q27 ((int32_t)33554432)
#define A_MAG2_MAX_Q27 ((int32_t)536870912)
/* The denominator is brought below 2^17 before the division (A then has
 * 17 significant bits: W = my - A mx is within 0.02 cm/s at 20 m/s). */
#define DEN_MAX ((int32_t)131071)

/* m += (x - m) * alpha (Q30); |x|, |m| < 2^30 */
static int32_t low_pass(int32_t m, int32_t x, int32_t alpha_q30)
{
    return m + qi_mul32(x - m, alpha_q30, 30u);
}

/* x / d in Q28 for 0 <= x < d < 2^17: in two steps of 14 bits, so that
 * no product leaves 31 bits */
static int32_t frac_q28(int32_t x, int32_t d)
{
    const int32_t hi = (x * 16384) / d; /* x * 2^14 < 2^31 */
    const int32_t rem = (x * 16384) - (hi * d);
    const int32_t lo = (rem * 16384) / d;
    return (hi * 16384) + lo;
}

/* num / den in Q28, |num| <= 2 den, 0 < den < 2^17 */
static int32_t quotient_q28(int32_t num, int32_t den)
{
    const int32_t mag = (num >= 0) ? num : -num;
    const int32_t whole = mag / den; /* 0, 1 or 2 */
    const int32_t q = (whole * A_ONE_Q28) + frac_q28(mag - (whole * den), den);
    return (num >= 0) ? q : -q;
}

/*
 * A = num / den in Q28, when the quotient is a plausible heading error and
 * airspeed scale: 1, else 0 (A untouched). den > 0.
 */
static int solve_a(int32_t num_re, int32_t num_im, int32_t den, int32_t a_q28[2])
{
    /* den > 0: its bits above DEN_MAX's counted on the unsigned value */
    unsigned shift = 0u;
    const uint32_t den_u = (uint32_t)den;
    while ((den_u >> shift) > (uint32_t)DEN_MAX) {
        shift++;
    }
    const int32_t dn = qi_rshift_round(den, shift);
    const int32_t nr = qi_rshift_round(num_re, shift);
    const int32_t ni = qi_rshift_round(num_im, shift);
    /* |A| <= 2 per component */
    if (dn <= 0 || nr > (2 * dn) || nr < (-2 * dn) || ni > (2 * dn) || ni < (-2 * dn)) {
        return 0;
    }
    const int32_t ar = quotient_q28(nr, dn);
    const int32_t ai = quotient_q28(ni, dn);
    /* |A|^2 in Q27: each square <= 2^30 */
    const int32_t mag2_q27 = qi_mul32(ar, ar, 29u) + qi_mul32(ai, ai, 29u);
    if (ar <= 0 || mag2_q27 < A_MAG2_MIN_Q27 || mag2_q27 > A_MAG2_MAX_Q27) {
        return 0;
    }
    a_q28[0] = ar;
    a_q28[1] = ai;
    return 1;
}

void dcm_wind_learn(const ht_dcm_t *d, ht_dcm_wind_t *w, const int32_t air_q8[2],
                    const int32_t gps_cm_s[2], int32_t turn_c, int32_t turn_s, uint32_t period)
{
    /* x: the air velocity turned back to the GPS epoch (a rotation by minus
     * the turn); y: the GPS velocity; both cm/s in Q8 */
    const int32_t an = qi_mul32(air_q8[0], turn_c, 30u) + qi_mul32(air_q8[1], turn_s, 30u);
    const int32_t ae = qi_mul32(air_q8[1], turn_c, 30u) - qi_mul32(air_q8[0], turn_s, 30u);
    const int32_t x[2] = {q_clamp32(an, -V_MAX_Q8, V_MAX_Q8), q_clamp32(ae, -V_MAX_Q8, V_MAX_Q8)};
    const int32_t y[2] = {q_clamp32(gps_cm_s[0], -V_MAX_CM_S, V_MAX_CM_S) * 256,
                          q_clamp32(gps_cm_s[1], -V_MAX_CM_S, V_MAX_CM_S) * 256};
    /* this solution's moments in (cm/s)^2: Q8 * Q8 / 2^16, each product
     * <= 23170^2 < 2^29 */
    const int32_t xx = qi_mul32(x[0], x[0], 16u) + qi_mul32(x[1], x[1], 16u);
    const int32_t xy_re = qi_mul32(y[0], x[0], 16u) + qi_mul32(y[1], x[1], 16u);
    const int32_t xy_im = qi_mul32(y[1], x[0], 16u) - qi_mul32(y[0], x[1], 16u);
    if (w->primed == 0u) {
        for (unsigned i = 0u; i < 2u; i++) {
            w->mx_q8[i] = x[i];
            w->my_q8[i] = y[i];
        }
        w->sxx = xx;
        w->sxy[0] = xy_re;
        w->sxy[1] = xy_im;
        w->a_q28[0] = A_ONE_Q28;
        w->a_q28[1] = 0;
        w->primed = 1u;
    } else {
        /* the weight of one solution: its period over the time constant */
        uint32_t n = period;
        if (n > (uint32_t)d->p.imu_rate_hz) {
            n = d->p.imu_rate_hz;
        }
        const int32_t alpha = d->wind_alpha_q30 * (int32_t)n; /* <= 2^30 / tau */
        for (unsigned i = 0u; i < 2u; i++) {
            w->mx_q8[i] = low_pass(w->mx_q8[i], x[i], alpha);
            w->my_q8[i] = low_pass(w->my_q8[i], y[i], alpha);
        }
        w->sxx = low_pass(w->sxx, xx, alpha);
        w->sxy[0] = low_pass(w->sxy[0], xy_re, alpha);
        w->sxy[1] = low_pass(w->sxy[1], xy_im, alpha);
    }
    /* var(x) = sxx - |mx|^2 and cov(y, x) = sxy - my conj(mx), the means in
     * Q8: a shift of 16 */
    const int32_t *mx = w->mx_q8;
    const int32_t *my = w->my_q8;
    const int32_t den = w->sxx - qi_mul32(mx[0], mx[0], 16u) - qi_mul32(mx[1], mx[1], 16u);
    const int32_t num_re = w->sxy[0] - qi_mul32(my[0], mx[0], 16u) - qi_mul32(my[1], mx[1], 16u);
    const int32_t num_im = w->sxy[1] - qi_mul32(my[1], mx[0], 16u) + qi_mul32(my[0], mx[1], 16u);
    /* a turn: var(x) >= mean |x|^2 / 8; then A and W. Outside turns W
     * holds (a heading error and a cross wind are one unknown there) */
    if (den <= 0 || den < (w->sxx / 8) || solve_a(num_re, num_im, den, w->a_q28) == 0) {
        return;
    }
    const int32_t ar = w->a_q28[0];
    const int32_t ai = w->a_q28[1];
    const int32_t wn = my[0] - (qi_mul32(ar, mx[0], 28u) - qi_mul32(ai, mx[1], 28u));
    const int32_t we = my[1] - (qi_mul32(ar, mx[1], 28u) + qi_mul32(ai, mx[0], 28u));
    /* a wind beyond DCM_WIND_MAX_CM_S per component is not taken */
    if (wn <= WIND_MAX_Q8 && wn >= -WIND_MAX_Q8 && we <= WIND_MAX_Q8 && we >= -WIND_MAX_Q8) {
        w->w_q8[0] = wn;
        w->w_q8[1] = we;
        w->solved = 1u;
    }
}

void dcm_wind_through_air(const ht_dcm_wind_t *w, const int32_t gps_cm_s[2], int32_t out_q8[2])
{
    for (unsigned i = 0u; i < 2u; i++) {
        out_q8[i] = (q_clamp32(gps_cm_s[i], -COURSE_MAX_CM_S, COURSE_MAX_CM_S) * 256) - w->w_q8[i];
    }
}
