/*
 * holds.c - altitude hold and airspeed hold, the outer loops around the
 * helical-turn law (see holds.h). Integer only: no float, no libm, no
 * allocation, no recursion, no global mutable state.
 */
#include "helical/guidance/holds.h"

#include "math/q_inline.h"

#include <stdbool.h>
#include <stddef.h>

#define HOLD_CLIMB_MAX_CM_S    100000L
#define HOLD_AIRSPEED_MAX_CM_S 32767L

/* A length or speed in cm (or cm/s), already bounded to +-1e6, as metres
 * (or m/s) in Q8: round(v * 256 / 100) = round(v * 64 / 25). */
static int32_t cm_to_m_q8(int32_t v_cm)
{
    return qi_div_round(v_cm * 64, 25);
}

/* --- altitude hold ------------------------------------------------------- */

ht_hold_status_t ht_alt_hold_check(const ht_alt_hold_params_t *p)
{
    if (p == NULL) {
        return HT_HOLD_ERR_NULL;
    }
    return (ht_alt_hold_first_bad(p) == HT_ALT_P_NONE) ? HT_HOLD_OK : HT_HOLD_ERR_PARAM;
}

void ht_alt_hold_reset(ht_alt_hold_state_t *s)
{
    if (s != NULL) {
        s->integral_q20[0] = 0;
        s->integral_q20[1] = 0;
        s->airspeed_q8 = 0;
        s->airspeed_valid = 0u;
    }
}

/* The protection's airspeed: a valid reading (>= protect_valid_cm_s) moves
 * the filter by 1/n of the difference, n = tau * rate (at least 1; the first
 * reading after a reset is taken as it is). Returns whether the filter holds
 * a reading; the filtered airspeed in cm/s goes to *v_cm_s. */
static bool alt_airspeed(const ht_alt_hold_params_t *p, ht_alt_hold_state_t *s,
                         int16_t airspeed_cm_s, int32_t *v_cm_s)
{
    const int32_t v_q8 = (int32_t)airspeed_cm_s * 256; /* |v| <= 2^15: fits */
    if ((int32_t)airspeed_cm_s >= p->protect_valid_cm_s) {
        if (s->airspeed_valid == 0u) {
            s->airspeed_q8 = v_q8;
            s->airspeed_valid = 1u;
        } else {
            /* tau <= 60000 ms, rate <= 1000 Hz: n <= 60000 */
            int32_t n = qi_div_round((int32_t)p->protect_tau_ms * (int32_t)p->rate_hz, 1000);
            if (n < 1) {
                n = 1;
            }
            /* saturating: the state is the caller's */
            s->airspeed_q8 =
                q_add_sat32(s->airspeed_q8, qi_div_round(q_sub_sat32(v_q8, s->airspeed_q8), n));
        }
    }
    *v_cm_s = q_clamp32(q_rshift_round(s->airspeed_q8, 8), 0, HOLD_AIRSPEED_MAX_CM_S);
    return s->airspeed_valid != 0u;
}

/* Upper limit of the pitch ratio: max_pitch, or the airspeed protection's
 * ceiling (holds.h) while the airspeed is below protect_cm_s and the reading
 * is valid (not below protect_valid_cm_s). */
static int32_t alt_ceiling_q16(const ht_alt_hold_params_t *p, ht_alt_hold_state_t *s, bool protect,
                               int16_t airspeed_cm_s)
{
    if (!protect || p->protect_cm_s == 0) {
        return p->max_pitch;
    }
    int32_t v_cm_s = 0;
    const bool have = alt_airspeed(p, s, airspeed_cm_s, &v_cm_s);
    if (!have || (int32_t)airspeed_cm_s < p->protect_valid_cm_s || v_cm_s >= p->protect_cm_s) {
        return p->max_pitch;
    }
    /* deficit <= 32767 cm/s -> <= 83884 in Q8; * kv (<= 2^22) fits q_mul32 */
    const int32_t deficit_m_q8 = cm_to_m_q8(p->protect_cm_s - v_cm_s);
    const int32_t drop_q16 = q_mul32(p->kv_pitch_per_m_s, deficit_m_q8, 8);
    return q_clamp32(q_sub_sat32(p->max_pitch, drop_q16), -p->max_pitch, p->max_pitch);
}

static q16_t alt_hold_step(const ht_alt_hold_params_t *p, ht_alt_hold_state_t *s, int32_t target_cm,
                           int32_t altitude_cm, int32_t climb_cm_s, uint8_t inverted, bool protect,
                           int16_t airspeed_cm_s)
{
    if (s == NULL || ht_alt_hold_check(p) != HT_HOLD_OK) {
        return 0;
    }
    int idx = 0;
    if (inverted != 0u) {
        idx = 1;
    }
    const int32_t err_cm =
        q_clamp32(q_sub_sat32(target_cm, altitude_cm), -p->max_error_cm, p->max_error_cm);
    const int32_t err_m_q8 = cm_to_m_q8(err_cm);
    const int32_t climb_m_q8 =
        cm_to_m_q8(q_clamp32(climb_cm_s, -HOLD_CLIMB_MAX_CM_S, HOLD_CLIMB_MAX_CM_S));
    const int32_t ceiling_q16 = alt_ceiling_q16(p, s, protect, airspeed_cm_s);

    /* Q16 * Q8 >> 8 = Q16 */
    const int32_t p_term_q16 = q_mul32(p->kp_pitch_per_m, err_m_q8, 8);
    const int32_t d_term_q16 = q_mul32(p->kd_pitch_per_m_s, climb_m_q8, 8);
    /* Q16 * Q8 >> 4 = Q20, per step */
    const int32_t inc_q20 =
        qi_div_round(q_mul32(p->ki_pitch_per_m_s, err_m_q8, 4), (int32_t)p->rate_hz);

    const int32_t max_i_q20 = p->max_integral_pitch * 16; /* <= 4 * 2^20 */
    int32_t integral_q20 = s->integral_q20[idx];

    /* Output with the old integral decides whether integrating is allowed;
     * the upper limit is the ceiling (max_pitch unless the protection cuts it). */
    const int32_t pd_q16 = q_sub_sat32(p_term_q16, d_term_q16);
    const int32_t before_q16 = q_add_sat32(pd_q16, q_rshift_round(integral_q20, 4));
    const bool saturated_high = before_q16 >= ceiling_q16;
    const bool saturated_low = before_q16 <= -p->max_pitch;
    const bool in_band = (err_cm <= p->integral_band_cm) && (err_cm >= -p->integral_band_cm);
    if (in_band && !((saturated_high && inc_q20 > 0) || (saturated_low && inc_q20 < 0))) {
        integral_q20 = q_add_sat32(integral_q20, inc_q20);
    }
    /* clamped whether or not it integrated: a bound lowered in flight (a
     * parameter set) holds from this step on, for both integrators */
    s->integral_q20[idx] = q_clamp32(integral_q20, -max_i_q20, max_i_q20);
    s->integral_q20[1 - idx] = q_clamp32(s->integral_q20[1 - idx], -max_i_q20, max_i_q20);
    integral_q20 = s->integral_q20[idx];

    const int32_t out_q16 = q_add_sat32(pd_q16, q_rshift_round(integral_q20, 4));
    return q_clamp32(out_q16, -p->max_pitch, ceiling_q16);
}

q16_t ht_alt_hold_step(const ht_alt_hold_params_t *p, ht_alt_hold_state_t *s, int32_t target_cm,
                       int32_t altitude_cm, int32_t climb_cm_s, uint8_t inverted)
{
    return alt_hold_step(p, s, target_cm, altitude_cm, climb_cm_s, inverted, false, 0);
}

q16_t ht_alt_hold_step_v(const ht_alt_hold_params_t *p, ht_alt_hold_state_t *s, int32_t target_cm,
                         int32_t altitude_cm, int32_t climb_cm_s, uint8_t inverted,
                         int16_t airspeed_cm_s)
{
    return alt_hold_step(p, s, target_cm, altitude_cm, climb_cm_s, inverted, true, airspeed_cm_s);
}

/* --- airspeed hold ------------------------------------------------------- */

ht_hold_status_t ht_speed_hold_check(const ht_speed_hold_params_t *p)
{
    if (p == NULL) {
        return HT_HOLD_ERR_NULL;
    }
    return (ht_speed_hold_first_bad(p) == HT_SPEED_P_NONE) ? HT_HOLD_OK : HT_HOLD_ERR_PARAM;
}

void ht_speed_hold_reset(ht_speed_hold_state_t *s)
{
    if (s != NULL) {
        s->integral_q20 = 0;
    }
}

q14_t ht_speed_hold_step(const ht_speed_hold_params_t *p, ht_speed_hold_state_t *s,
                         int16_t target_cm_s, int16_t airspeed_cm_s, q16_t pitch_q16)
{
    if (s == NULL || ht_speed_hold_check(p) != HT_HOLD_OK) {
        return 0;
    }
    const int32_t err_m_q8 = cm_to_m_q8((int32_t)target_cm_s - (int32_t)airspeed_cm_s);
    const int32_t p_term_q16 = q_mul32(p->kp_throttle_per_m_s, err_m_q8, 8);
    const int32_t ff_term_q16 = q_mul32(p->kff_throttle_per_pitch, pitch_q16, 16);
    const int32_t inc_q20 =
        qi_div_round(q_mul32(p->ki_throttle_per_m, err_m_q8, 4), (int32_t)p->rate_hz);

    const int32_t lo_q16 = (int32_t)p->throttle_min * 4;
    const int32_t hi_q16 = (int32_t)p->throttle_max * 4;
    const int32_t max_i_q20 = (int32_t)p->max_integral_throttle * 64;
    const int32_t base_q16 =
        q_add_sat32(q_add_sat32((int32_t)p->throttle_trim * 4, ff_term_q16), p_term_q16);

    int32_t integral_q20 = s->integral_q20;
    const int32_t before_q16 = q_add_sat32(base_q16, q_rshift_round(integral_q20, 4));
    if (!((before_q16 >= hi_q16 && inc_q20 > 0) || (before_q16 <= lo_q16 && inc_q20 < 0))) {
        integral_q20 = q_add_sat32(integral_q20, inc_q20);
    }
    /* clamped whether or not it integrated: a bound lowered in flight holds
     * from this step on */
    integral_q20 = q_clamp32(integral_q20, -max_i_q20, max_i_q20);
    s->integral_q20 = integral_q20;

    const int32_t out_q16 =
        q_clamp32(q_add_sat32(base_q16, q_rshift_round(integral_q20, 4)), lo_q16, hi_q16);
    return (q14_t)q_clamp32(q_rshift_round(out_q16, 2), p->throttle_min, p->throttle_max);
}
