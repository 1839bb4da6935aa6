/*
 * ht_options.c - the law's options beyond the seed (ht_options.h,
 * docs/control-law.md "Extensions beyond the seed"). Integer only; each
 * result is formed from exact products with one or two roundings, so that
 * through the largest legal gains it stays within the core's 2 LSB of the
 * double-precision law (tests/unit/test_ht_options.c).
 */
#include "law/ht_options.h"

#include "math/q_inline.h"

#define Q30_ONE ((int32_t)0x40000000) /* 2^30 */

/* 2^39 / 980.665: (Q11 rad/s^2 * cm/s * 2^7) -> Q25 rad/s after a shift of
 * 32, i.e. 2^25 / (2^11 * 2^7 * 100 * g). */
#define BANK_RATE_FROM_ACCEL_S 560594917L

int32_t ht_opt_roll_in_q25(const ht_controller_t *ctl, q11_t turn_accel_q11, int32_t s_cm_s,
                           int32_t c1_q30, uint8_t *flags)
{
    /* d/dt atan(r) = r_dot * c1^2 with c1 = 1/sqrt(1 + r^2) <= 1 (Q30), and
     * r_dot = turn_accel * S / g. turn_accel * S is an exact integer below
     * 2^30; times c1^2 and 2^7 it is rounded once, saturating where the bank
     * rate is beyond 8.35 rad/s (above every legal bound, so the clamp below
     * gives the bound); a unit of it is 0.13 LSB of the Q25 result. */
    const int32_t accel_times_s = (int32_t)turn_accel_q11 * s_cm_s; /* |.| <= 2^30 */
    const int32_t c1_sq_q30 = qi_mul32_fit(c1_q30, c1_q30, 30u);    /* <= 2^30 */
    const int32_t t = qi_mul32(accel_times_s, c1_sq_q30, 23u);
    int32_t rate_q25 = qi_mul32_fit(t, BANK_RATE_FROM_ACCEL_S, 32u); /* |.| < 2^28.1 */
    const int32_t lim = ctl->roll_in_max_q25;
    if (rate_q25 > lim || rate_q25 < -lim) {
        *flags |= (uint8_t)HT_F_ROLL_IN_LIMITED;
        rate_q25 = (rate_q25 > 0) ? lim : -lim;
    }
    return rate_q25;
}

int32_t ht_opt_fade_q30(const ht_controller_t *ctl, q14_t x, q14_t z, uint8_t *flags)
{
    const int32_t x2 = (int32_t)x * x; /* each <= 2^30 */
    const int32_t z2 = (int32_t)z * z;
    const uint32_t m_q28 = (uint32_t)x2 + (uint32_t)z2;
    /* m >= fade2 is exactly sqrt(X^2 + Z^2) >= vertical_fade (fade2 is
     * ceil(fade_q16^2 / 16)): there the fade does not act */
    if (m_q28 >= ctl->fade2_q28) {
        return Q30_ONE;
    }
    *flags |= (uint8_t)HT_F_ROLL_FADED;
    if (m_q28 == 0u) {
        return 0; /* vertical: no roll authority from the roll error */
    }
    /* sqrt(m) = root * 2^(-28 - exp2) with root = x_n * y in [1, 2) (Q28), and
     * 1/fade = inv * 2^(16 - 30 - e): f = root * inv * 2^-(42 + exp2 + e),
     * rounded once in Q30 (shift in [11, 42]; f < 1 by the test above, up to
     * the roundings) */
    const qi_rsqrt30_t r = qi_rsqrt_norm_q30(m_q28);
    const int32_t root_q28 = qi_mul32_fit(r.xn_q28, r.y_q30, 30u);
    const int shift = 12 + r.exp2 + (int)ctl->fade_inv_exp;
    const int32_t f = qi_mul32_fit(root_q28, ctl->fade_inv_q30, (unsigned)shift);
    return (f > Q30_ONE) ? Q30_ONE : f;
}

int32_t ht_opt_sideslip_q20(const ht_controller_t *ctl, q14_t accel_lat_g)
{
    /* Q16 * Q14 -> Q20: |.| <= 2^22 * 2^15 / 2^10 = 2^27 */
    return qi_mul32x16_fit(ctl->kp_sideslip, accel_lat_g, 10u);
}
