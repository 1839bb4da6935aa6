/*
 * mixer.c - airframe mixes and the RC pass-through (see mixer.h).
 * All arithmetic is done in int32_t explicitly: the library also builds for
 * 16-bit-int targets (XC16), where int16 + int16 would overflow an int.
 */
#include "helical/output/mixer.h"

#include <stddef.h>

#include "output/mix_inline.h"

static q14_t clamp_q14(int32_t x, int32_t lo, int32_t hi)
{
    if (x < lo) {
        return (q14_t)lo;
    }
    if (x > hi) {
        return (q14_t)hi;
    }
    return (q14_t)x;
}

q14_t os_mix(const os_command_t *cmd, uint8_t function)
{
    if (cmd == NULL) {
        return 0;
    }
    /* the rules live in mix_inline.h, shared with os_compute */
    const mix_inputs_t in = mix_inputs(cmd);
    return (q14_t)mix_pick(&in, function);
}

os_status_t os_rc_cal_check(const os_rc_cal_t *cal)
{
    if (cal == NULL) {
        return OS_ERR_NULL;
    }
    if (cal->centre_us < OS_RC_VALID_MIN_US || cal->centre_us > OS_RC_VALID_MAX_US ||
        cal->travel_us < OS_RC_TRAVEL_MIN_US || cal->travel_us > OS_RC_TRAVEL_MAX_US) {
        return OS_ERR_CONFIG;
    }
    return OS_OK;
}

os_status_t os_rc_to_q14(const os_rc_cal_t *cal, uint16_t pulse_us, q14_t *out)
{
    if (out == NULL) {
        return OS_ERR_NULL;
    }
    *out = 0;
    const os_status_t st = os_rc_cal_check(cal);
    if (st != OS_OK) {
        return st;
    }
    if (pulse_us < OS_RC_VALID_MIN_US || pulse_us > OS_RC_VALID_MAX_US) {
        return OS_ERR_RANGE;
    }
    int32_t d = (int32_t)pulse_us - (int32_t)cal->centre_us;
    if (cal->reversed != 0u) {
        d = -d;
    }
    /* |d| <= 1400 and travel >= 100: the quotient is below 2^18 and the
     * numerator below 2^25, so uint32 holds it. Round half away from zero. */
    const uint32_t mag = (d < 0) ? (uint32_t)-d : (uint32_t)d;
    const uint32_t travel = cal->travel_us;
    const uint32_t q = ((mag * (uint32_t)Q14_ONE) + (travel / 2u)) / travel;
    const int32_t v = (d < 0) ? -(int32_t)q : (int32_t)q;
    *out = clamp_q14(v, cal->unipolar ? 0 : -(int32_t)Q14_ONE, (int32_t)Q14_ONE);
    return OS_OK;
}

static os_status_t rc_axis(const os_rc_cal_t *cal, const uint16_t rc_us[], uint8_t rc_count,
                           q14_t *out)
{
    if (cal->input >= rc_count) {
        *out = 0;
        return OS_ERR_CONFIG;
    }
    return os_rc_to_q14(cal, rc_us[cal->input], out);
}

os_status_t os_rc_command(const os_rc_map_t *map, const uint16_t rc_us[], uint8_t rc_count,
                          os_command_t *out)
{
    if (out == NULL) {
        return OS_ERR_NULL;
    }
    const os_command_t neutral = {0, 0, 0, 0};
    *out = neutral;
    if (map == NULL || rc_us == NULL) {
        return OS_ERR_NULL;
    }
    os_command_t c;
    os_status_t st = rc_axis(&map->aileron, rc_us, rc_count, &c.aileron);
    if (st == OS_OK) {
        st = rc_axis(&map->elevator, rc_us, rc_count, &c.elevator);
    }
    if (st == OS_OK) {
        st = rc_axis(&map->rudder, rc_us, rc_count, &c.rudder);
    }
    if (st == OS_OK) {
        st = rc_axis(&map->throttle, rc_us, rc_count, &c.throttle);
    }
    if (st == OS_OK) {
        *out = c;
    }
    return st;
}
