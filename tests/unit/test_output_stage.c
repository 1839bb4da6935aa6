/*
 * test_output_stage.c - the pulse conversion, end points, reversing, config
 * checks, os_compute and os_failsafe. The pulse conversion is checked for
 * EVERY int16 command against an independent double-precision reference, on
 * channels chosen so that each clamp and each rounding edge is reached.
 */
#include "unity.h"

#include "helical/output/output_stage.h"

#include <stdint.h>
#include <stdio.h>

void setUp(void) {}

void tearDown(void) {}

static os_channel_t chan(uint16_t centre, int16_t trim, uint16_t travel, uint8_t reversed,
                         uint16_t min_us, uint16_t max_us)
{
    os_channel_t c;
    os_channel_default(&c, (uint8_t)OS_FN_AILERON);
    c.centre_us = centre;
    c.trim_us = trim;
    c.travel_us = travel;
    c.reversed = reversed;
    c.min_us = min_us;
    c.max_us = max_us;
    return c;
}

/* The specification, written independently: clamp in the real numbers,
 * scale, round half away from zero, add, clamp to the end points. */
static long reference_pulse(const os_channel_t *c, int32_t cmd)
{
    double x = (double)cmd / 16384.0;
    if (x > 1.0) {
        x = 1.0;
    }
    if (x < -1.0) {
        x = -1.0;
    }
    if (c->reversed) {
        x = -x;
    }
    const double v = x * (double)c->travel_us; /* exact: a multiple of 2^-14 */
    const long r = (v >= 0.0) ? (long)(v + 0.5) : -(long)(-v + 0.5);
    long p = (long)c->centre_us + (long)c->trim_us + r;
    if (p > (long)c->max_us) {
        p = (long)c->max_us;
    }
    if (p < (long)c->min_us) {
        p = (long)c->min_us;
    }
    return p;
}

/* Every int16 command: equal to the reference, inside the end points, and
 * monotonic in the command (non-decreasing, or non-increasing if reversed). */
static void exhaustive(const os_channel_t *c)
{
    long mismatches = 0;
    long first_cmd = 0, first_got = 0, first_want = 0;
    long prev = -1;
    const uint16_t lo = c->min_us; /* callers here always pass min_us <= max_us */
    const uint16_t hi = c->max_us;
    for (int32_t cmd = INT16_MIN; cmd <= INT16_MAX; ++cmd) {
        const uint16_t got = os_pulse_us(c, (q14_t)cmd);
        const long want = reference_pulse(c, cmd);
        if ((long)got != want || got < lo || got > hi) {
            if (mismatches == 0) {
                first_cmd = cmd;
                first_got = got;
                first_want = want;
            }
            ++mismatches;
        }
        if (prev >= 0) {
            if (!c->reversed) {
                TEST_ASSERT_TRUE_MESSAGE((long)got >= prev, "not monotonic");
            } else {
                TEST_ASSERT_TRUE_MESSAGE((long)got <= prev, "not monotonic (reversed)");
            }
        }
        prev = got;
    }
    if (mismatches != 0) {
        char msg[120];
        (void)snprintf(msg, sizeof msg, "%ld mismatches; first cmd %ld got %ld want %ld",
                       mismatches, first_cmd, first_got, first_want);
        TEST_FAIL_MESSAGE(msg);
    }
}

static void test_exhaustive_default(void)
{
    os_channel_t c;
    os_channel_default(&c, (uint8_t)OS_FN_ELEVATOR);
    exhaustive(&c);
    /* the real numbers at the edges */
    TEST_ASSERT_EQUAL_UINT16(1500, os_pulse_us(&c, 0));
    TEST_ASSERT_EQUAL_UINT16(2000, os_pulse_us(&c, Q14_ONE));
    TEST_ASSERT_EQUAL_UINT16(1000, os_pulse_us(&c, (q14_t)-Q14_ONE));
    TEST_ASSERT_EQUAL_UINT16(2000, os_pulse_us(&c, INT16_MAX)); /* clamped to +1 first */
    TEST_ASSERT_EQUAL_UINT16(1000, os_pulse_us(&c, INT16_MIN));
    TEST_ASSERT_EQUAL_UINT16(1750, os_pulse_us(&c, 8192)); /* 0.5 * 500 */
    /* rounding: 500 * 16 / 16384 = 0.488 -> 0; 500 * 17 / 16384 = 0.519 -> 1 */
    TEST_ASSERT_EQUAL_UINT16(1500, os_pulse_us(&c, 16));
    TEST_ASSERT_EQUAL_UINT16(1501, os_pulse_us(&c, 17));
    TEST_ASSERT_EQUAL_UINT16(1500, os_pulse_us(&c, -16));
    TEST_ASSERT_EQUAL_UINT16(1499, os_pulse_us(&c, -17));
}

static void test_exhaustive_reversed_is_exact_mirror(void)
{
    os_channel_t n = chan(1500, 0, 500, 0, 1000, 2000);
    os_channel_t r = chan(1500, 0, 500, 1, 1000, 2000);
    exhaustive(&r);
    for (int32_t cmd = INT16_MIN; cmd <= INT16_MAX; ++cmd) {
        const int32_t a = (int32_t)os_pulse_us(&n, (q14_t)cmd) - 1500;
        const int32_t b = (int32_t)os_pulse_us(&r, (q14_t)cmd) - 1500;
        if (a != -b) {
            TEST_FAIL_MESSAGE("reversed channel is not the mirror image");
        }
    }
    TEST_ASSERT_EQUAL_UINT16(1000, os_pulse_us(&r, Q14_ONE));
    TEST_ASSERT_EQUAL_UINT16(2000, os_pulse_us(&r, INT16_MIN));
}

static void test_exhaustive_ties(void)
{
    /* travel 2: c * 2 / 16384 has an exact .5 at c = +/-4096 */
    os_channel_t c = chan(1500, 0, 2, 0, 1000, 2000);
    exhaustive(&c);
    TEST_ASSERT_EQUAL_UINT16(1501, os_pulse_us(&c, 4096));  /* 0.5 -> 1 */
    TEST_ASSERT_EQUAL_UINT16(1499, os_pulse_us(&c, -4096)); /* -0.5 -> -1 */
    TEST_ASSERT_EQUAL_UINT16(1500, os_pulse_us(&c, 4095));
    TEST_ASSERT_EQUAL_UINT16(1500, os_pulse_us(&c, -4095));
}

static void test_exhaustive_trim_and_odd_travel(void)
{
    os_channel_t c = chan(1520, -37, 333, 0, 900, 2100);
    exhaustive(&c);
    TEST_ASSERT_EQUAL_UINT16(1483, os_pulse_us(&c, 0));
    TEST_ASSERT_EQUAL_UINT16(1816, os_pulse_us(&c, Q14_ONE));
    TEST_ASSERT_EQUAL_UINT16(1150, os_pulse_us(&c, (q14_t)-Q14_ONE));
    c.reversed = 1;
    exhaustive(&c);
    TEST_ASSERT_EQUAL_UINT16(1150, os_pulse_us(&c, Q14_ONE));
}

static void test_exhaustive_end_points_bite(void)
{
    /* travel would reach 1000..2000, the end points cut it to 1200..1650 */
    os_channel_t c = chan(1500, 0, 500, 0, 1200, 1650);
    exhaustive(&c);
    TEST_ASSERT_EQUAL_UINT16(1650, os_pulse_us(&c, Q14_ONE));
    TEST_ASSERT_EQUAL_UINT16(1200, os_pulse_us(&c, (q14_t)-Q14_ONE));
    /* the edge itself: 150 us = 4915.2 -> the first command reaching 1650 */
    TEST_ASSERT_EQUAL_UINT16(1649, os_pulse_us(&c, 4882)); /* 148.99 -> 149 */
    TEST_ASSERT_EQUAL_UINT16(1650, os_pulse_us(&c, 4900)); /* 149.5 -> 150 */
    TEST_ASSERT_EQUAL_UINT16(1650, os_pulse_us(&c, 4916)); /* 150.02 -> 150 */
    /* trim that puts the centre itself outside the end points */
    c.trim_us = 400;
    exhaustive(&c);
    TEST_ASSERT_EQUAL_UINT16(1650, os_pulse_us(&c, 0));
    TEST_ASSERT_EQUAL_UINT16(1650, os_pulse_us(&c, (q14_t)-Q14_ONE / 4)); /* 1900 - 125 */
    TEST_ASSERT_EQUAL_UINT16(1400, os_pulse_us(&c, (q14_t)-Q14_ONE));
}

static void test_exhaustive_zero_and_full_travel(void)
{
    os_channel_t z = chan(1500, 10, 0, 0, 1000, 2000);
    exhaustive(&z);
    TEST_ASSERT_EQUAL_UINT16(1510, os_pulse_us(&z, INT16_MIN));
    os_channel_t f = chan(1500, 0, OS_TRAVEL_MAX_US, 0, OS_PULSE_MIN_US, OS_PULSE_MAX_US);
    exhaustive(&f);
    TEST_ASSERT_EQUAL_UINT16(2500, os_pulse_us(&f, Q14_ONE));
    TEST_ASSERT_EQUAL_UINT16(500, os_pulse_us(&f, (q14_t)-Q14_ONE));
}

static void test_unchecked_configs_never_leave_end_points(void)
{
    /* Values os_channel_check refuses still cannot overflow or escape. */
    os_channel_t c = chan(65535, 32767, 65535, 0, 1000, 2000);
    exhaustive(&c);
    TEST_ASSERT_EQUAL_UINT16(2000, os_pulse_us(&c, (q14_t)-Q14_ONE));
    c = chan(0, INT16_MIN, 65535, 1, 1000, 2000);
    exhaustive(&c);
    TEST_ASSERT_EQUAL_UINT16(2000, os_pulse_us(&c, (q14_t)-Q14_ONE)); /* 0-32768+65535 */
    TEST_ASSERT_EQUAL_UINT16(1000, os_pulse_us(&c, Q14_ONE));         /* 0-32768-65535 */
    /* an inverted pair yields min_us, as documented */
    c = chan(1500, 0, 500, 0, 1800, 1200);
    for (int32_t cmd = INT16_MIN; cmd <= INT16_MAX; cmd += 7) {
        TEST_ASSERT_EQUAL_UINT16(1800, os_pulse_us(&c, (q14_t)cmd));
    }
    TEST_ASSERT_EQUAL_UINT16(0, os_pulse_us(NULL, 0));
}

/* The rounding of c * travel, proved for EVERY command in [-1, 1], EVERY
 * travel os_channel_check accepts (and some it refuses, up to 65535), both
 * reversed states, against the double reference. The end points are wide and
 * the centre mid-range so that no clamp hides a rounding error (for travels up
 * to 32767; above, the reference clamps the same way). */
static void test_rounding_every_command_every_travel(void)
{
    static const uint16_t big[] = {1001u,  1023u,  1024u,  4097u,  16383u,
                                   16384u, 16385u, 32767u, 32768u, 65535u};
    const uint32_t n_small = (uint32_t)OS_TRAVEL_MAX_US + 1u;
    const uint32_t n_all = n_small + (uint32_t)(sizeof big / sizeof big[0]);
    long mismatches = 0;
    char msg[120] = "";
    for (uint32_t t = 0u; t < n_all; ++t) {
        const uint16_t travel = (t < n_small) ? (uint16_t)t : big[t - n_small];
        for (uint8_t rev = 0u; rev <= 1u; ++rev) {
            const os_channel_t c = chan(32768u, 0, travel, rev, 0u, 65535u);
            for (int32_t cmd = -(int32_t)Q14_ONE; cmd <= (int32_t)Q14_ONE; ++cmd) {
                const uint16_t got = os_pulse_us(&c, (q14_t)cmd);
                const long want = reference_pulse(&c, cmd);
                if ((long)got != want) {
                    if (mismatches == 0) {
                        (void)snprintf(
                            msg, sizeof msg, "travel %u reversed %u cmd %ld: %u, want %ld",
                            (unsigned)travel, (unsigned)rev, (long)cmd, (unsigned)got, want);
                    }
                    ++mismatches;
                }
            }
        }
    }
    TEST_ASSERT_EQUAL_INT32_MESSAGE(0, mismatches, msg);
}

/* os_compute is documented as os_pulse_us(ch, os_mix(cmd, function)) for each
 * channel; it computes that with the command clamped once. Checked on every
 * function (and unknown ones), reversal, trims, odd travels, biting and
 * inverted end points, over every combination of edge commands and a long
 * pseudo-random run of int16 commands. */
static void compute_matches_mix_then_pulse(const os_config_t *cfg, const os_command_t *cmd)
{
    uint16_t p[OS_MAX_CHANNELS];
    TEST_ASSERT_EQUAL(OS_OK, os_compute(cfg, cmd, p));
    for (uint8_t i = 0; i < cfg->count; ++i) {
        const uint16_t want = os_pulse_us(&cfg->ch[i], os_mix(cmd, cfg->ch[i].function));
        if (p[i] != want) {
            char msg[120];
            (void)snprintf(msg, sizeof msg, "channel %u cmd %d %d %d %d: %u, want %u", (unsigned)i,
                           cmd->aileron, cmd->elevator, cmd->rudder, cmd->throttle, (unsigned)p[i],
                           (unsigned)want);
            TEST_FAIL_MESSAGE(msg);
        }
    }
}

static void test_compute_equals_mix_then_pulse(void)
{
    static const uint8_t fns[2][OS_MAX_CHANNELS] = {
        {OS_FN_AILERON, OS_FN_AILERON2, OS_FN_ELEVATOR, OS_FN_RUDDER, OS_FN_THROTTLE, OS_FN_NONE,
         OS_FN_COUNT, 255u},
        {OS_FN_VTAIL_LEFT, OS_FN_VTAIL_RIGHT, OS_FN_ELEVON_LEFT, OS_FN_ELEVON_RIGHT, OS_FN_AILERON,
         OS_FN_THROTTLE, OS_FN_ELEVATOR, OS_FN_RUDDER}};
    static const int16_t edges[] = {INT16_MIN, -16385, -16384, -16383, -8193, -8192, -1,       0,
                                    1,         8192,   8193,   16383,  16384, 16385, INT16_MAX};
    const uint32_t ne = (uint32_t)(sizeof edges / sizeof edges[0]);
    for (uint8_t set = 0u; set < 2u; ++set) {
        os_config_t cfg;
        cfg.count = OS_MAX_CHANNELS;
        for (uint8_t i = 0; i < OS_MAX_CHANNELS; ++i) {
            os_channel_default(&cfg.ch[i], fns[set][i]);
            cfg.ch[i].reversed = (uint8_t)((i + set) % 2u);
        }
        cfg.ch[1].trim_us = -37;
        cfg.ch[2].travel_us = 333u;
        cfg.ch[3].min_us = 1200u; /* end points that bite */
        cfg.ch[3].max_us = 1650u;
        cfg.ch[4].travel_us = 1u;
        cfg.ch[5].min_us = 1800u; /* an inverted pair */
        cfg.ch[5].max_us = 1200u;
        cfg.ch[6].travel_us = 65535u; /* unchecked values */
        cfg.ch[6].trim_us = INT16_MIN;
        cfg.ch[6].min_us = 0u;
        cfg.ch[6].max_us = 65535u;
        cfg.ch[7].travel_us = 0u;
        cfg.ch[7].centre_us = 2500u;
        cfg.ch[7].trim_us = 500;
        for (uint32_t a = 0u; a < ne; ++a) {
            for (uint32_t e = 0u; e < ne; ++e) {
                for (uint32_t r = 0u; r < ne; ++r) {
                    for (uint32_t t = 0u; t < ne; ++t) {
                        const os_command_t cmd = {edges[a], edges[e], edges[r], edges[t]};
                        compute_matches_mix_then_pulse(&cfg, &cmd);
                    }
                }
            }
        }
        uint32_t x = 12345u; /* LCG: any int16 in each field */
        for (uint32_t k = 0u; k < 200000u; ++k) {
            int16_t v[4];
            for (uint8_t j = 0u; j < 4u; ++j) {
                x = (x * 1664525u) + 1013904223u;
                v[j] = (int16_t)((int32_t)((x >> 16) & 0xFFFFu) - 32768);
            }
            const os_command_t cmd = {v[0], v[1], v[2], v[3]};
            compute_matches_mix_then_pulse(&cfg, &cmd);
        }
        /* fewer channels: the same values, nothing beyond count written */
        uint16_t p[OS_MAX_CHANNELS] = {9, 9, 9, 9, 9, 9, 9, 9};
        const os_command_t cmd = {1234, -5678, 9012, 3456};
        for (uint8_t n = 1u; n <= OS_MAX_CHANNELS; ++n) {
            cfg.count = n;
            compute_matches_mix_then_pulse(&cfg, &cmd);
        }
        cfg.count = 3u;
        TEST_ASSERT_EQUAL(OS_OK, os_compute(&cfg, &cmd, p));
        for (uint8_t i = 3u; i < OS_MAX_CHANNELS; ++i) {
            TEST_ASSERT_EQUAL_UINT16(9, p[i]);
        }
    }
}

static void test_channel_check_edges(void)
{
    os_channel_t c;
    os_channel_default(&c, (uint8_t)OS_FN_RUDDER);
    TEST_ASSERT_EQUAL(OS_OK, os_channel_check(&c));
    TEST_ASSERT_EQUAL(OS_ERR_NULL, os_channel_check(NULL));

    c.travel_us = OS_TRAVEL_MAX_US;
    TEST_ASSERT_EQUAL(OS_OK, os_channel_check(&c));
    c.travel_us = OS_TRAVEL_MAX_US + 1u;
    TEST_ASSERT_EQUAL(OS_ERR_CONFIG, os_channel_check(&c));
    os_channel_default(&c, (uint8_t)OS_FN_RUDDER);

    c.trim_us = OS_TRIM_MAX_US;
    TEST_ASSERT_EQUAL(OS_OK, os_channel_check(&c));
    c.trim_us = OS_TRIM_MAX_US + 1;
    TEST_ASSERT_EQUAL(OS_ERR_CONFIG, os_channel_check(&c));
    c.trim_us = -OS_TRIM_MAX_US;
    TEST_ASSERT_EQUAL(OS_OK, os_channel_check(&c));
    c.trim_us = -OS_TRIM_MAX_US - 1;
    TEST_ASSERT_EQUAL(OS_ERR_CONFIG, os_channel_check(&c));
    os_channel_default(&c, (uint8_t)OS_FN_RUDDER);

    c.min_us = OS_PULSE_MIN_US;
    c.max_us = OS_PULSE_MAX_US;
    TEST_ASSERT_EQUAL(OS_OK, os_channel_check(&c));
    c.min_us = OS_PULSE_MIN_US - 1u;
    TEST_ASSERT_EQUAL(OS_ERR_CONFIG, os_channel_check(&c));
    c.min_us = OS_PULSE_MIN_US;
    c.max_us = OS_PULSE_MAX_US + 1u;
    TEST_ASSERT_EQUAL(OS_ERR_CONFIG, os_channel_check(&c));
    os_channel_default(&c, (uint8_t)OS_FN_RUDDER);

    c.min_us = 1600u; /* equal end points are allowed (a fixed output) */
    c.max_us = 1600u;
    TEST_ASSERT_EQUAL(OS_OK, os_channel_check(&c));
    c.max_us = 1599u;
    TEST_ASSERT_EQUAL(OS_ERR_CONFIG, os_channel_check(&c));
    os_channel_default(&c, (uint8_t)OS_FN_RUDDER);

    c.centre_us = OS_PULSE_MAX_US + 1u;
    TEST_ASSERT_EQUAL(OS_ERR_CONFIG, os_channel_check(&c));
    c.centre_us = OS_PULSE_MIN_US - 1u;
    TEST_ASSERT_EQUAL(OS_ERR_CONFIG, os_channel_check(&c));
    os_channel_default(&c, (uint8_t)OS_FN_RUDDER);

    c.failsafe_us = 0u;
    TEST_ASSERT_EQUAL(OS_ERR_CONFIG, os_channel_check(&c));
    os_channel_default(&c, (uint8_t)OS_FN_RUDDER);

    c.function = (uint8_t)(OS_FN_COUNT - 1);
    TEST_ASSERT_EQUAL(OS_OK, os_channel_check(&c));
    c.function = (uint8_t)OS_FN_COUNT;
    TEST_ASSERT_EQUAL(OS_ERR_CONFIG, os_channel_check(&c));
}

static os_config_t standard_config(void)
{
    os_config_t cfg;
    cfg.count = 5;
    os_channel_default(&cfg.ch[0], (uint8_t)OS_FN_AILERON);
    os_channel_default(&cfg.ch[1], (uint8_t)OS_FN_ELEVATOR);
    os_channel_default(&cfg.ch[2], (uint8_t)OS_FN_THROTTLE);
    os_channel_default(&cfg.ch[3], (uint8_t)OS_FN_RUDDER);
    os_channel_default(&cfg.ch[4], (uint8_t)OS_FN_AILERON2);
    cfg.ch[4].reversed = 1; /* mirror-mounted second aileron servo */
    for (uint8_t i = 5; i < OS_MAX_CHANNELS; ++i) {
        os_channel_default(&cfg.ch[i], (uint8_t)OS_FN_NONE);
    }
    return cfg;
}

static void test_config_check(void)
{
    os_config_t cfg = standard_config();
    uint8_t bad = 99;
    TEST_ASSERT_EQUAL(OS_OK, os_config_check(&cfg, &bad));
    TEST_ASSERT_EQUAL_UINT8(99, bad);
    cfg.ch[3].travel_us = 2000u;
    TEST_ASSERT_EQUAL(OS_ERR_CONFIG, os_config_check(&cfg, &bad));
    TEST_ASSERT_EQUAL_UINT8(3, bad);
    TEST_ASSERT_EQUAL(OS_ERR_CONFIG, os_config_check(&cfg, NULL));
    cfg = standard_config();
    cfg.count = 0;
    TEST_ASSERT_EQUAL(OS_ERR_CONFIG, os_config_check(&cfg, &bad));
    TEST_ASSERT_EQUAL_UINT8(0, bad);
    cfg.count = OS_MAX_CHANNELS + 1u;
    TEST_ASSERT_EQUAL(OS_ERR_CONFIG, os_config_check(&cfg, &bad));
    TEST_ASSERT_EQUAL_UINT8(OS_MAX_CHANNELS + 1u, bad);
    cfg.count = OS_MAX_CHANNELS;
    TEST_ASSERT_EQUAL(OS_OK, os_config_check(&cfg, &bad));
    TEST_ASSERT_EQUAL(OS_ERR_NULL, os_config_check(NULL, &bad));
}

static void test_compute_standard(void)
{
    os_config_t cfg = standard_config();
    const os_command_t cmd = {Q14_FROM_REAL(0.5), Q14_FROM_REAL(-0.25), Q14_FROM_REAL(1.0),
                              Q14_FROM_REAL(0.75)};
    uint16_t p[OS_MAX_CHANNELS] = {0};
    p[5] = 7777; /* beyond count: must stay untouched */
    cfg.count = 5;
    TEST_ASSERT_EQUAL(OS_OK, os_compute(&cfg, &cmd, p));
    TEST_ASSERT_EQUAL_UINT16(1750, p[0]); /* aileron +0.5 */
    TEST_ASSERT_EQUAL_UINT16(1375, p[1]); /* elevator -0.25 */
    TEST_ASSERT_EQUAL_UINT16(1750, p[2]); /* throttle 0.75: idle 1000 + 750 */
    TEST_ASSERT_EQUAL_UINT16(2000, p[3]); /* rudder +1 */
    TEST_ASSERT_EQUAL_UINT16(1250, p[4]); /* second aileron, reversed */
    TEST_ASSERT_EQUAL_UINT16(7777, p[5]);
}

static void test_compute_throttle_edges(void)
{
    os_config_t cfg = standard_config();
    uint16_t p[OS_MAX_CHANNELS] = {0};
    os_command_t cmd = {0, 0, 0, (q14_t)-1};
    TEST_ASSERT_EQUAL(OS_OK, os_compute(&cfg, &cmd, p));
    TEST_ASSERT_EQUAL_UINT16(1000, p[2]); /* negative throttle is idle */
    cmd.throttle = INT16_MAX;
    TEST_ASSERT_EQUAL(OS_OK, os_compute(&cfg, &cmd, p));
    TEST_ASSERT_EQUAL_UINT16(2000, p[2]);
    cmd.throttle = 1; /* 1000/16384 = 0.06 us -> idle */
    TEST_ASSERT_EQUAL(OS_OK, os_compute(&cfg, &cmd, p));
    TEST_ASSERT_EQUAL_UINT16(1000, p[2]);
    cmd.throttle = 9; /* 0.549 us -> 1 */
    TEST_ASSERT_EQUAL(OS_OK, os_compute(&cfg, &cmd, p));
    TEST_ASSERT_EQUAL_UINT16(1001, p[2]);
    /* a reversed throttle runs from idle downwards */
    cfg.ch[2].centre_us = 2000u;
    cfg.ch[2].reversed = 1;
    cmd.throttle = Q14_ONE;
    TEST_ASSERT_EQUAL(OS_OK, os_compute(&cfg, &cmd, p));
    TEST_ASSERT_EQUAL_UINT16(1000, p[2]);
    /* the OS_FN_NONE channels sit at centre */
    cfg.count = OS_MAX_CHANNELS;
    TEST_ASSERT_EQUAL(OS_OK, os_compute(&cfg, &cmd, p));
    TEST_ASSERT_EQUAL_UINT16(1500, p[7]);
}

static void test_compute_bad_arguments(void)
{
    os_config_t cfg = standard_config();
    const os_command_t cmd = {0, 0, 0, 0};
    uint16_t p[OS_MAX_CHANNELS] = {1, 2, 3, 4, 5, 6, 7, 8};
    TEST_ASSERT_EQUAL(OS_ERR_NULL, os_compute(NULL, &cmd, p));
    TEST_ASSERT_EQUAL(OS_ERR_NULL, os_compute(&cfg, NULL, p));
    TEST_ASSERT_EQUAL(OS_ERR_NULL, os_compute(&cfg, &cmd, NULL));
    cfg.count = 0;
    TEST_ASSERT_EQUAL(OS_ERR_CONFIG, os_compute(&cfg, &cmd, p));
    cfg.count = OS_MAX_CHANNELS + 1u;
    TEST_ASSERT_EQUAL(OS_ERR_CONFIG, os_compute(&cfg, &cmd, p));
    TEST_ASSERT_EQUAL(OS_ERR_CONFIG, os_failsafe(&cfg, p));
    for (uint16_t i = 0; i < OS_MAX_CHANNELS; ++i) {
        TEST_ASSERT_EQUAL_UINT16(i + 1u, p[i]); /* nothing written */
    }
    TEST_ASSERT_EQUAL(OS_ERR_NULL, os_failsafe(NULL, p));
    TEST_ASSERT_EQUAL(OS_ERR_NULL, os_failsafe(&cfg, NULL));
}

static void test_failsafe_pulses_respect_end_points(void)
{
    os_config_t cfg = standard_config();
    uint16_t p[OS_MAX_CHANNELS] = {0};
    cfg.ch[0].failsafe_us = 1600u;
    cfg.ch[1].failsafe_us = 2400u; /* beyond max 2000 */
    cfg.ch[3].failsafe_us = 600u;  /* below min 1000 */
    TEST_ASSERT_EQUAL(OS_OK, os_failsafe(&cfg, p));
    TEST_ASSERT_EQUAL_UINT16(1600, p[0]);
    TEST_ASSERT_EQUAL_UINT16(2000, p[1]);
    TEST_ASSERT_EQUAL_UINT16(1000, p[2]); /* throttle idle */
    TEST_ASSERT_EQUAL_UINT16(1000, p[3]);
    TEST_ASSERT_EQUAL_UINT16(1500, p[4]);
}

static void test_default_channels(void)
{
    os_channel_t c;
    os_channel_default(&c, (uint8_t)OS_FN_THROTTLE);
    TEST_ASSERT_EQUAL_UINT16(1000, c.centre_us);
    TEST_ASSERT_EQUAL_UINT16(1000, c.travel_us);
    TEST_ASSERT_EQUAL_UINT16(1000, c.failsafe_us);
    TEST_ASSERT_EQUAL(OS_OK, os_channel_check(&c));
    os_channel_default(&c, (uint8_t)OS_FN_ELEVON_LEFT);
    TEST_ASSERT_EQUAL_UINT16(1500, c.centre_us);
    TEST_ASSERT_EQUAL_UINT16(500, c.travel_us);
    TEST_ASSERT_EQUAL_UINT16(1000, c.min_us);
    TEST_ASSERT_EQUAL_UINT16(2000, c.max_us);
    TEST_ASSERT_EQUAL_UINT8(OS_FN_ELEVON_LEFT, c.function);
    os_channel_default(NULL, 0); /* no crash */
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_exhaustive_default);
    RUN_TEST(test_exhaustive_reversed_is_exact_mirror);
    RUN_TEST(test_exhaustive_ties);
    RUN_TEST(test_exhaustive_trim_and_odd_travel);
    RUN_TEST(test_exhaustive_end_points_bite);
    RUN_TEST(test_exhaustive_zero_and_full_travel);
    RUN_TEST(test_unchecked_configs_never_leave_end_points);
    RUN_TEST(test_rounding_every_command_every_travel);
    RUN_TEST(test_channel_check_edges);
    RUN_TEST(test_config_check);
    RUN_TEST(test_compute_standard);
    RUN_TEST(test_compute_throttle_edges);
    RUN_TEST(test_compute_bad_arguments);
    RUN_TEST(test_compute_equals_mix_then_pulse);
    RUN_TEST(test_failsafe_pulses_respect_end_points);
    RUN_TEST(test_default_channels);
    return UNITY_END();
}
