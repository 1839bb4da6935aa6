/*
 * libFuzzer target: arbitrary bytes -> a channel configuration and the
 * commands. For every configuration that os_config_check accepts: every
 * pulse within its channel's end points, the same pulses twice, and the
 * failsafe pulses within the end points too. For any configuration at all:
 * no crash, and os_pulse_us still clamps to [min_us, max_us] when min <= max.
 */
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>

#include "helical/output/output_stage.h"

static void check(int ok)
{
    if (!ok) {
        abort();
    }
}

static uint32_t take(const uint8_t **p, size_t *n, unsigned count)
{
    uint32_t v = 0;
    for (unsigned i = 0; i < count; i++) {
        v = (v << 8) | (*n ? ((*n)--, *(*p)++) : 0u);
    }
    return v;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    const uint8_t *p = data;
    size_t n = size;
    os_config_t cfg;
    cfg.count = (uint8_t)take(&p, &n, 1);
    for (unsigned i = 0; i < OS_MAX_CHANNELS; i++) {
        os_channel_t *c = &cfg.ch[i];
        c->function = (uint8_t)take(&p, &n, 1);
        c->reversed = (uint8_t)take(&p, &n, 1);
        c->centre_us = (uint16_t)take(&p, &n, 2);
        c->trim_us = (int16_t)(uint16_t)take(&p, &n, 2);
        c->travel_us = (uint16_t)take(&p, &n, 2);
        c->min_us = (uint16_t)take(&p, &n, 2);
        c->max_us = (uint16_t)take(&p, &n, 2);
        c->failsafe_us = (uint16_t)take(&p, &n, 2);
    }
    os_command_t cmd;
    cmd.aileron = (q14_t)(uint16_t)take(&p, &n, 2);
    cmd.elevator = (q14_t)(uint16_t)take(&p, &n, 2);
    cmd.rudder = (q14_t)(uint16_t)take(&p, &n, 2);
    cmd.throttle = (q14_t)(uint16_t)take(&p, &n, 2);

    /* any channel, checked or not: a sane end-point pair is always honoured */
    for (unsigned i = 0; i < OS_MAX_CHANNELS; i++) {
        const os_channel_t *c = &cfg.ch[i];
        uint16_t pulse = os_pulse_us(c, cmd.aileron);
        if (c->min_us <= c->max_us) {
            check(pulse >= c->min_us && pulse <= c->max_us);
        }
    }

    uint8_t bad = 0;
    if (os_config_check(&cfg, &bad) != OS_OK) {
        check(cfg.count == 0u || cfg.count > OS_MAX_CHANNELS || bad < cfg.count);
        return 0;
    }
    uint16_t a[OS_MAX_CHANNELS], b[OS_MAX_CHANNELS];
    check(os_compute(&cfg, &cmd, a) == OS_OK);
    check(os_compute(&cfg, &cmd, b) == OS_OK);
    for (unsigned i = 0; i < cfg.count; i++) {
        check(a[i] == b[i]);
        check(a[i] >= cfg.ch[i].min_us && a[i] <= cfg.ch[i].max_us);
        check(a[i] >= OS_PULSE_MIN_US && a[i] <= OS_PULSE_MAX_US);
    }
    check(os_failsafe(&cfg, a) == OS_OK);
    for (unsigned i = 0; i < cfg.count; i++) {
        check(a[i] >= cfg.ch[i].min_us && a[i] <= cfg.ch[i].max_us);
    }
    return 0;
}
