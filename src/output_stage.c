/*
 * output_stage.c - commands to servo pulses (see output_stage.h).
 * int32_t throughout: correct on 16-bit-int targets as well.
 */
#include "helical/output_stage.h"

#include <stddef.h>

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

/* The end points, applied last. An inverted pair yields min_us (documented). */
static uint16_t limit(const os_channel_t *ch, int32_t pulse)
{
    int32_t p = pulse;
    if (p > (int32_t)ch->max_us) {
        p = ch->max_us;
    }
    if (p < (int32_t)ch->min_us) {
        p = ch->min_us;
    }
    return (uint16_t)p;
}

uint16_t os_pulse_us(const os_channel_t *ch, q14_t command)
{
    if (ch == NULL) {
        return 0u;
    }
    int32_t c = command;
    if (c > Q14_ONE) {
        c = Q14_ONE;
    } else if (c < -Q14_ONE) {
        c = -Q14_ONE;
    } else {
        /* already within [-1, 1] */
    }
    if (ch->reversed != 0u) {
        c = -c; /* safe: c is already within [-16384, 16384] */
    }
    /* |c * travel| <= 2^14 * 65535 < 2^31. Round half away from zero so a
     * reversed channel mirrors a normal one exactly. */
    const int32_t prod = c * (int32_t)ch->travel_us;
    const int32_t half = 8192; /* 2^13 */
    /* both operands of >> are non-negative: a plain division by 2^14 */
    // cppcheck-suppress misra-c2012-10.1 ; non-negative signed operand of >>
    const int32_t offset = (prod >= 0) ? ((prod + half) >> 14) : -((-prod + half) >> 14);
    return limit(ch, (int32_t)ch->centre_us + (int32_t)ch->trim_us + offset);
}

os_status_t os_compute(const os_config_t *cfg, const os_command_t *cmd,
                       uint16_t pulse_us[OS_MAX_CHANNELS])
{
    if (cfg == NULL || cmd == NULL || pulse_us == NULL) {
        return OS_ERR_NULL;
    }
    if (cfg->count == 0u || cfg->count > OS_MAX_CHANNELS) {
        return OS_ERR_CONFIG;
    }
    for (uint8_t i = 0; i < cfg->count; ++i) {
        pulse_us[i] = os_pulse_us(&cfg->ch[i], os_mix(cmd, cfg->ch[i].function));
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
