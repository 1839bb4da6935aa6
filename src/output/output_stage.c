/*
 * output_stage.c - commands to servo pulses (see output_stage.h).
 * int32_t throughout: correct on 16-bit-int targets as well.
 */
#include "helical/output/output_stage.h"

#include <stddef.h>

#include "output/mix_inline.h"

void os_channel_default(os_channel_t *ch, uint8_t function)
{
    if (ch == NULL) {
        return;
    }
    ch->function = function;
    ch->reversed = 0u;
    ch->trim_us = 0;
    ch->min_us = 1000u;
    ch->max_us = 2000u;
    if (function == (uint8_t)OS_FN_THROTTLE) {
        ch->centre_us = 1000u; /* idle */
        ch->travel_us = 1000u;
        ch->failsafe_us = 1000u;
    } else {
        ch->centre_us = 1500u;
        ch->travel_us = 500u;
        ch->failsafe_us = 1500u;
    }
}

static int pulse_ok(uint16_t us)
{
    return us >= OS_PULSE_MIN_US && us <= OS_PULSE_MAX_US;
}

os_status_t os_channel_check(const os_channel_t *ch)
{
    if (ch == NULL) {
        return OS_ERR_NULL;
    }
    if (ch->function >= (uint8_t)OS_FN_COUNT || !pulse_ok(ch->centre_us) || !pulse_ok(ch->min_us) ||
        !pulse_ok(ch->max_us) || !pulse_ok(ch->failsafe_us) || ch->min_us > ch->max_us ||
        ch->travel_us > OS_TRAVEL_MAX_US || ch->trim_us < -OS_TRIM_MAX_US ||
        ch->trim_us > OS_TRIM_MAX_US) {
        return OS_ERR_CONFIG;
    }
    return OS_OK;
}

os_status_t os_config_check(const os_config_t *cfg, uint8_t *bad_channel)
{
    if (cfg == NULL) {
        return OS_ERR_NULL;
    }
    if (cfg->count == 0u || cfg->count > OS_MAX_CHANNELS) {
        if (bad_channel != NULL) {
            *bad_channel = cfg->count;
        }
        return OS_ERR_CONFIG;
    }
    for (uint8_t i = 0; i < cfg->count; ++i) {
        if (os_channel_check(&cfg->ch[i]) != OS_OK) {
            if (bad_channel != NULL) {
                *bad_channel = i;
            }
            return OS_ERR_CONFIG;
        }
    }
    return OS_OK;
}

/* The end points, applied last. An inverted pair yields min_us (documented).
 * A pulse inside the end points, the usual case, costs two compares and two
 * untaken branches; the clamp itself is the inner part only. */
static inline uint16_t limit(const os_channel_t *ch, int32_t pulse)
{
    const int32_t lo = ch->min_us;
    const int32_t hi = ch->max_us;
    int32_t p = pulse;
    if (p > hi || p < lo) {
        if (p > hi) {
            p = hi;
        }
        if (p < lo) {
            p = lo;
        }
    }
    return (uint16_t)p;
}

/*
 * round(s * travel / 2^14), ties away from zero, for |s| <= 2^14 (so nothing
 * below overflows: |s * travel| <= 2^14 * 65535). With p = s * travel,
 * floor((p + 2^13 - neg) / 2^14), neg = 1 when p < 0 and 0 otherwise, is
 * exactly that rounding: for p >= 0 it is floor(p / 2^14 + 1/2); for
 * p = -q < 0 it is floor((2^13 - 1 - q) / 2^14) = -floor((q + 2^13) / 2^14),
 * the mirror image. This costs one add and one shift where a branch on the
 * sign and two negations did before. neg is taken from s rather than from p,
 * so that it does not wait for the product: the two differ only when
 * travel = 0, where floor((2^13 - 1) / 2^14) = 0 all the same. The >> is the
 * floor (arithmetic >> is required by the library: q14.h). Checked against
 * the double reference for every command in [-1, 1] and every travel in
 * [0, OS_TRAVEL_MAX_US] (and beyond, up to 65535), both reversed states, in
 * tests/unit/test_output_stage.c.
 */
static inline int32_t scale_round(int32_t s, uint16_t travel_us)
{
    int32_t neg = 0;
    if (s < 0) {
        neg = 1;
    }
    // cppcheck-suppress misra-c2012-10.1 ; arithmetic >> by design (q14.c static assert)
    return ((s * (int32_t)travel_us) + (8192 - neg)) >> 14;
}

/* The pulse for a command c already within [-16384, 16384]. Reversing negates
 * before the rounding, which is symmetric: a reversed channel is the exact
 * mirror of a normal one about centre + trim. */
static inline uint16_t pulse_of(const os_channel_t *ch, int32_t c)
{
    const int32_t s = (ch->reversed != 0u) ? -c : c;
    const int32_t base = (int32_t)ch->centre_us + (int32_t)ch->trim_us;
    return limit(ch, base + scale_round(s, ch->travel_us));
}

uint16_t os_pulse_us(const os_channel_t *ch, q14_t command)
{
    if (ch == NULL) {
        return 0u;
    }
    return pulse_of(ch, mix_surface(command));
}

os_status_t os_compute(const os_config_t *cfg, const os_command_t *cmd,
                       uint16_t pulse_us[OS_MAX_CHANNELS])
{
    if (cfg == NULL || cmd == NULL || pulse_us == NULL) {
        return OS_ERR_NULL;
    }
    const uint32_t n = cfg->count;
    if (n == 0u || n > OS_MAX_CHANNELS) {
        return OS_ERR_CONFIG;
    }
    /* The same as os_pulse_us(ch, os_mix(cmd, function)) per channel, with
     * the command clamped once per call instead of once per channel, and no
     * clamp before the pulse: every mixed value is within [-1, 1] already. */
    const mix_inputs_t in = mix_inputs(cmd);
    for (uint32_t i = 0u; i < n; ++i) {
        const os_channel_t *ch = &cfg->ch[i];
        pulse_us[i] = pulse_of(ch, mix_pick(&in, ch->function));
    }
    return OS_OK;
}

os_status_t os_failsafe(const os_config_t *cfg, uint16_t pulse_us[OS_MAX_CHANNELS])
{
    if (cfg == NULL || pulse_us == NULL) {
        return OS_ERR_NULL;
    }
    if (cfg->count == 0u || cfg->count > OS_MAX_CHANNELS) {
        return OS_ERR_CONFIG;
    }
    for (uint8_t i = 0; i < cfg->count; ++i) {
        pulse_us[i] = limit(&cfg->ch[i], cfg->ch[i].failsafe_us);
    }
    return OS_OK;
}
