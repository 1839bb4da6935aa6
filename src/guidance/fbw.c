/*
 * fbw.c - fly-by-wire sticks (fbw.h). Integer only, no state.
 */
#include "helical/guidance/fbw.h"

#include <stddef.h>

#define DEG_TO_RAD_Q30 18740330L /* pi / 180 in Q30 */

int ht_fbw_init(ht_fbw_t *f, const ht_fbw_params_t *p, ht_fbw_param_id_t *bad_field)
{
    if (bad_field != NULL) {
        *bad_field = HT_FBW_P_NONE;
    }
    if (f == NULL || p == NULL) {
        return 1;
    }
    ht_fbw_t z = {0};
    *f = z;
    const ht_fbw_param_id_t bad = ht_fbw_first_bad(p);
    if (bad != HT_FBW_P_NONE) {
        if (bad_field != NULL) {
            *bad_field = bad;
        }
        return 2;
    }
    f->deadband_us = p->deadband_us;
    f->turn_rate_max_rad_s = q_mul32((int32_t)p->turn_rate_max_deg_s * 65536, DEG_TO_RAD_Q30, 30u);
    f->pitch_max = p->pitch_max;
    f->inverted_input = p->inverted_input;
    f->inverted_threshold_us = p->inverted_threshold_us;
    f->ready = 1u;
    return 0;
}

static int pulse_valid(uint16_t us)
{
    return us >= OS_RC_VALID_MIN_US && us <= OS_RC_VALID_MAX_US;
}

q14_t ht_fbw_stick_q14(const os_rc_cal_t *cal, uint16_t deadband_us, uint16_t pulse_us)
{
    if (cal == NULL || !pulse_valid(pulse_us) || cal->travel_us <= deadband_us) {
        return 0;
    }
    int32_t s = (int32_t)pulse_us - (int32_t)cal->centre_us;
    if (cal->reversed != 0u) {
        s = -s;
    }
    int32_t mag = (s < 0) ? -s : s;
    if (mag <= (int32_t)deadband_us) {
        return 0;
    }
    int32_t num = (mag - (int32_t)deadband_us) * 16384; /* < 65536 * 16384 = 2^30 */
    int32_t den = (int32_t)cal->travel_us - (int32_t)deadband_us;
    int32_t q = (num + (den / 2)) / den; /* ties away from zero (on the magnitude) */
    if (q > Q14_ONE) {
        q = Q14_ONE;
    }
    return (q14_t)((s < 0) ? -q : q);
}

static uint16_t pulse_at(const uint16_t rc_us[], uint8_t rc_count, uint8_t input)
{
    return (input < rc_count) ? rc_us[input] : 0u;
}

void ht_fbw_step(const ht_fbw_t *f, const os_rc_map_t *map, const uint16_t rc_us[],
                 uint8_t rc_count, ht_fbw_output_t *out)
{
    if (out == NULL) {
        return;
    }
    ht_fbw_output_t o = {0};
    if (f == NULL || map == NULL || rc_us == NULL || !f->ready) {
        *out = o;
        return;
    }
    o.aileron_stick = ht_fbw_stick_q14(&map->aileron, f->deadband_us,
                                       pulse_at(rc_us, rc_count, map->aileron.input));
    o.elevator_stick = ht_fbw_stick_q14(&map->elevator, f->deadband_us,
                                        pulse_at(rc_us, rc_count, map->elevator.input));
    o.turn_rate_rad_s = q_mul32(f->turn_rate_max_rad_s, o.aileron_stick, 14u);
    o.pitch_ratio = q_mul32(f->pitch_max, o.elevator_stick, 14u);
    uint16_t sw = pulse_at(rc_us, rc_count, f->inverted_input);
    o.inverted = (pulse_valid(sw) && (sw >= f->inverted_threshold_us)) ? 1u : 0u;
    *out = o;
}
