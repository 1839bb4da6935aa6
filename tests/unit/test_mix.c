/*
 * test_mix.c - every airframe mix (standard, second aileron, V-tail,
 * elevon, throttle), the saturation of each sum at its edges, and the manual
 * pass-through from RC pulses, all through os_compute down to pulses.
 */
#include "unity.h"

#include "helical/output/output_stage.h"

#include <stdint.h>

void setUp(void) {}

void tearDown(void) {}

#define ONE  ((int32_t)Q14_ONE)
#define HALF ((q14_t)8192)
#define QTR  ((q14_t)4096)

static os_command_t cmd4(int32_t ail, int32_t ele, int32_t rud, int32_t thr)
{
    os_command_t c = {(q14_t)ail, (q14_t)ele, (q14_t)rud, (q14_t)thr};
    return c;
}

static void test_standard_mix_passes_each_axis(void)
{
    const os_command_t c = cmd4(1000, -2000, 3000, 4000);
    TEST_ASSERT_EQUAL_INT16(1000, os_mix(&c, OS_FN_AILERON));
    TEST_ASSERT_EQUAL_INT16(1000, os_mix(&c, OS_FN_AILERON2));
    TEST_ASSERT_EQUAL_INT16(-2000, os_mix(&c, OS_FN_ELEVATOR));
    TEST_ASSERT_EQUAL_INT16(3000, os_mix(&c, OS_FN_RUDDER));
    TEST_ASSERT_EQUAL_INT16(4000, os_mix(&c, OS_FN_THROTTLE));
    TEST_ASSERT_EQUAL_INT16(0, os_mix(&c, OS_FN_NONE));
    TEST_ASSERT_EQUAL_INT16(0, os_mix(&c, OS_FN_COUNT)); /* unknown */
    TEST_ASSERT_EQUAL_INT16(0, os_mix(&c, 255));
    TEST_ASSERT_EQUAL_INT16(0, os_mix(NULL, OS_FN_AILERON));
}

static void test_single_axis_clamps(void)
{
    const os_command_t hi = cmd4(INT16_MAX, ONE + 1, INT16_MAX, INT16_MAX);
    TEST_ASSERT_EQUAL_INT16(ONE, os_mix(&hi, OS_FN_AILERON));
    TEST_ASSERT_EQUAL_INT16(ONE, os_mix(&hi, OS_FN_ELEVATOR));
    TEST_ASSERT_EQUAL_INT16(ONE, os_mix(&hi, OS_FN_RUDDER));
    TEST_ASSERT_EQUAL_INT16(ONE, os_mix(&hi, OS_FN_THROTTLE));
    const os_command_t lo = cmd4(INT16_MIN, -ONE - 1, INT16_MIN, -1);
    TEST_ASSERT_EQUAL_INT16(-ONE, os_mix(&lo, OS_FN_AILERON));
    TEST_ASSERT_EQUAL_INT16(-ONE, os_mix(&lo, OS_FN_ELEVATOR));
    TEST_ASSERT_EQUAL_INT16(-ONE, os_mix(&lo, OS_FN_RUDDER));
    TEST_ASSERT_EQUAL_INT16(0, os_mix(&lo, OS_FN_THROTTLE));
    const os_command_t edge = cmd4(ONE, -ONE, ONE, ONE);
    TEST_ASSERT_EQUAL_INT16(ONE, os_mix(&edge, OS_FN_AILERON));
    TEST_ASSERT_EQUAL_INT16(-ONE, os_mix(&edge, OS_FN_ELEVATOR));
    TEST_ASSERT_EQUAL_INT16(ONE, os_mix(&edge, OS_FN_THROTTLE));
}

static void test_vtail_mix(void)
{
    /* pitch up only: both ruddervators trailing edge up */
    os_command_t c = cmd4(0, HALF, 0, 0);
    TEST_ASSERT_EQUAL_INT16(HALF, os_mix(&c, OS_FN_VTAIL_LEFT));
    TEST_ASSERT_EQUAL_INT16(HALF, os_mix(&c, OS_FN_VTAIL_RIGHT));
    /* yaw right only: left up, right down */
    c = cmd4(0, 0, QTR, 0);
    TEST_ASSERT_EQUAL_INT16(QTR, os_mix(&c, OS_FN_VTAIL_LEFT));
    TEST_ASSERT_EQUAL_INT16(-QTR, os_mix(&c, OS_FN_VTAIL_RIGHT));
    /* both: pitch +/- yaw */
    c = cmd4(0, HALF, QTR, 0);
    TEST_ASSERT_EQUAL_INT16(HALF + QTR, os_mix(&c, OS_FN_VTAIL_LEFT));
    TEST_ASSERT_EQUAL_INT16(HALF - QTR, os_mix(&c, OS_FN_VTAIL_RIGHT));
    /* aileron has no effect on a V-tail */
    c = cmd4(ONE, HALF, QTR, 0);
    TEST_ASSERT_EQUAL_INT16(HALF + QTR, os_mix(&c, OS_FN_VTAIL_LEFT));
    /* saturation edge: exactly 1.0 passes, one LSB more clamps */
    c = cmd4(0, HALF, HALF, 0);
    TEST_ASSERT_EQUAL_INT16(ONE, os_mix(&c, OS_FN_VTAIL_LEFT));
    TEST_ASSERT_EQUAL_INT16(0, os_mix(&c, OS_FN_VTAIL_RIGHT));
    c = cmd4(0, HALF + 1, HALF, 0);
    TEST_ASSERT_EQUAL_INT16(ONE, os_mix(&c, OS_FN_VTAIL_LEFT));
    c = cmd4(0, ONE, ONE, 0);
    TEST_ASSERT_EQUAL_INT16(ONE, os_mix(&c, OS_FN_VTAIL_LEFT));
    TEST_ASSERT_EQUAL_INT16(0, os_mix(&c, OS_FN_VTAIL_RIGHT));
    c = cmd4(0, -ONE, ONE, 0);
    TEST_ASSERT_EQUAL_INT16(0, os_mix(&c, OS_FN_VTAIL_LEFT));
    TEST_ASSERT_EQUAL_INT16(-ONE, os_mix(&c, OS_FN_VTAIL_RIGHT));
    /* inputs beyond +/-1 are clamped before mixing: -2 + 1 is 0, not -1 */
    c = cmd4(0, INT16_MIN, ONE, 0);
    TEST_ASSERT_EQUAL_INT16(0, os_mix(&c, OS_FN_VTAIL_LEFT));
    c = cmd4(0, INT16_MAX, INT16_MAX, 0);
    TEST_ASSERT_EQUAL_INT16(ONE, os_mix(&c, OS_FN_VTAIL_LEFT));
    TEST_ASSERT_EQUAL_INT16(0, os_mix(&c, OS_FN_VTAIL_RIGHT));
}

static void test_elevon_mix(void)
{
    /* roll right only: right elevon up, left down */
    os_command_t c = cmd4(QTR, 0, 0, 0);
    TEST_ASSERT_EQUAL_INT16(-QTR, os_mix(&c, OS_FN_ELEVON_LEFT));
    TEST_ASSERT_EQUAL_INT16(QTR, os_mix(&c, OS_FN_ELEVON_RIGHT));
    /* pitch up only: both up */
    c = cmd4(0, HALF, 0, 0);
    TEST_ASSERT_EQUAL_INT16(HALF, os_mix(&c, OS_FN_ELEVON_LEFT));
    TEST_ASSERT_EQUAL_INT16(HALF, os_mix(&c, OS_FN_ELEVON_RIGHT));
    c = cmd4(QTR, HALF, ONE, 0); /* rudder ignored */
    TEST_ASSERT_EQUAL_INT16(HALF - QTR, os_mix(&c, OS_FN_ELEVON_LEFT));
    TEST_ASSERT_EQUAL_INT16(HALF + QTR, os_mix(&c, OS_FN_ELEVON_RIGHT));
    c = cmd4(-ONE, -ONE, 0, 0);
    TEST_ASSERT_EQUAL_INT16(0, os_mix(&c, OS_FN_ELEVON_LEFT));
    TEST_ASSERT_EQUAL_INT16(-ONE, os_mix(&c, OS_FN_ELEVON_RIGHT));
    c = cmd4(-ONE, ONE, 0, 0);
    TEST_ASSERT_EQUAL_INT16(ONE, os_mix(&c, OS_FN_ELEVON_LEFT));
    c = cmd4(-(HALF + 1), HALF, 0, 0);
    TEST_ASSERT_EQUAL_INT16(ONE, os_mix(&c, OS_FN_ELEVON_LEFT));
    TEST_ASSERT_EQUAL_INT16(-1, os_mix(&c, OS_FN_ELEVON_RIGHT));
}

/* The mixes as specified (mixer.h), written independently of the library:
 * clamp each input, then sum, then saturate. */
static long ref_clamp(long x, long lo, long hi)
{
    return (x < lo) ? lo : ((x > hi) ? hi : x);
}

static long reference_mix(const os_command_t *c, unsigned function)
{
    const long a = ref_clamp(c->aileron, -ONE, ONE);
    const long e = ref_clamp(c->elevator, -ONE, ONE);
    const long r = ref_clamp(c->rudder, -ONE, ONE);
    switch (function) {
    case 1:
    case 2:
        return a;
    case 3:
        return e;
    case 4:
        return r;
    case 5:
        return ref_clamp(c->throttle, 0, ONE);
    case 6:
        return ref_clamp(e + r, -ONE, ONE);
    case 7:
        return ref_clamp(e - r, -ONE, ONE);
    case 8:
        return ref_clamp(e - a, -ONE, ONE);
    case 9:
        return ref_clamp(e + a, -ONE, ONE);
    default:
        return 0;
    }
}

/* Every function (and unknown ones) against the reference: each input over
 * EVERY int16 value while the other three take each edge value, then a long
 * pseudo-random run over all four. */
static void test_mix_matches_reference_every_input(void)
{
    static const int16_t edges[] = {INT16_MIN, -16385, -16384, -16383, -8192, -1,       0,
                                    1,         8191,   16383,  16384,  16385, INT16_MAX};
    static const unsigned fns[] = {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 200, 255};
    const unsigned ne = (unsigned)(sizeof edges / sizeof edges[0]);
    const unsigned nf = (unsigned)(sizeof fns / sizeof fns[0]);
    long mismatches = 0;
    for (unsigned axis = 0; axis < 4u; ++axis) {
        for (unsigned k = 0; k < ne; ++k) {
            for (int32_t v = INT16_MIN; v <= INT16_MAX; ++v) {
                int16_t f[4] = {edges[k], edges[k], edges[k], edges[k]};
                f[axis] = (int16_t)v;
                const os_command_t c = {f[0], f[1], f[2], f[3]};
                for (unsigned j = 0; j < nf; ++j) {
                    if ((long)os_mix(&c, (uint8_t)fns[j]) != reference_mix(&c, fns[j])) {
                        ++mismatches;
                    }
                }
            }
        }
    }
    uint32_t x = 6u; /* LCG */
    for (uint32_t n = 0; n < 300000u; ++n) {
        int16_t f[4];
        for (unsigned j = 0; j < 4u; ++j) {
            x = (x * 1664525u) + 1013904223u;
            f[j] = (int16_t)((int32_t)(x >> 16) - 32768);
        }
        const os_command_t c = {f[0], f[1], f[2], f[3]};
        for (unsigned j = 0; j < nf; ++j) {
            if ((long)os_mix(&c, (uint8_t)fns[j]) != reference_mix(&c, fns[j])) {
                ++mismatches;
            }
        }
    }
    TEST_ASSERT_EQUAL_INT32(0, mismatches);
}

static void test_mix_sums_always_in_range(void)
{
    /* a coarse sweep of the whole int16 plane: every mixed surface in [-1, 1] */
    for (int32_t a = INT16_MIN; a <= INT16_MAX; a += 257) {
        for (int32_t b = INT16_MIN; b <= INT16_MAX; b += 263) {
            const os_command_t c = cmd4(a, b, a, b);
            for (uint8_t f = 0; f < (uint8_t)OS_FN_COUNT; ++f) {
                const int32_t m = os_mix(&c, f);
                if (m < -ONE || m > ONE) {
                    TEST_FAIL_MESSAGE("mixed command outside [-1, 1]");
                }
            }
        }
    }
}

static os_config_t config_of(const uint8_t *fn, uint8_t n)
{
    os_config_t cfg;
    cfg.count = n;
    for (uint8_t i = 0; i < OS_MAX_CHANNELS; ++i) {
        os_channel_default(&cfg.ch[i], i < n ? fn[i] : (uint8_t)OS_FN_NONE);
    }
    return cfg;
}

static void test_vtail_pulses_with_reversal(void)
{
    const uint8_t fn[] = {OS_FN_VTAIL_LEFT, OS_FN_VTAIL_RIGHT, OS_FN_THROTTLE};
    os_config_t cfg = config_of(fn, 3);
    cfg.ch[1].reversed = 1; /* servos mounted mirror-image */
    const os_command_t c = cmd4(0, HALF, QTR, ONE);
    uint16_t p[OS_MAX_CHANNELS] = {0};
    TEST_ASSERT_EQUAL(OS_OK, os_config_check(&cfg, NULL));
    TEST_ASSERT_EQUAL(OS_OK, os_compute(&cfg, &c, p));
    TEST_ASSERT_EQUAL_UINT16(1875, p[0]); /* +0.75 */
    TEST_ASSERT_EQUAL_UINT16(1375, p[1]); /* +0.25, reversed */
    TEST_ASSERT_EQUAL_UINT16(2000, p[2]);
}

static void test_delta_pulses_with_end_points(void)
{
    const uint8_t fn[] = {OS_FN_ELEVON_LEFT, OS_FN_ELEVON_RIGHT};
    os_config_t cfg = config_of(fn, 2);
    cfg.ch[0].max_us = 1800u; /* limited up-throw on the left elevon */
    const os_command_t c = cmd4(-HALF, HALF, 0, 0);
    uint16_t p[OS_MAX_CHANNELS] = {0};
    TEST_ASSERT_EQUAL(OS_OK, os_compute(&cfg, &c, p));
    TEST_ASSERT_EQUAL_UINT16(1800, p[0]); /* +1.0 -> 2000, cut to 1800 */
    TEST_ASSERT_EQUAL_UINT16(1500, p[1]); /* 0 */
}

static void test_second_aileron_channel(void)
{
    const uint8_t fn[] = {OS_FN_AILERON, OS_FN_ELEVATOR, OS_FN_RUDDER, OS_FN_AILERON2};
    os_config_t cfg = config_of(fn, 4);
    cfg.ch[3].reversed = 1;
    cfg.ch[3].trim_us = 12;
    const os_command_t c = cmd4(-QTR, 0, 0, 0);
    uint16_t p[OS_MAX_CHANNELS] = {0};
    TEST_ASSERT_EQUAL(OS_OK, os_compute(&cfg, &c, p));
    TEST_ASSERT_EQUAL_UINT16(1375, p[0]);
    TEST_ASSERT_EQUAL_UINT16(1500, p[1]);
    TEST_ASSERT_EQUAL_UINT16(1500, p[2]);
    TEST_ASSERT_EQUAL_UINT16(1637, p[3]); /* 1512 + 125 */
}

/* --- RC input ------------------------------------------------------------ */

static os_rc_cal_t rc(uint8_t input, uint16_t centre, uint16_t travel, uint8_t rev, uint8_t uni)
{
    os_rc_cal_t c = {input, rev, uni, centre, travel};
    return c;
}

static void test_rc_to_q14_values_and_rounding(void)
{
    const os_rc_cal_t c = rc(0, 1500, 500, 0, 0);
    q14_t v = 123;
    TEST_ASSERT_EQUAL(OS_OK, os_rc_to_q14(&c, 1500, &v));
    TEST_ASSERT_EQUAL_INT16(0, v);
    TEST_ASSERT_EQUAL(OS_OK, os_rc_to_q14(&c, 2000, &v));
    TEST_ASSERT_EQUAL_INT16(ONE, v);
    TEST_ASSERT_EQUAL(OS_OK, os_rc_to_q14(&c, 1000, &v));
    TEST_ASSERT_EQUAL_INT16(-ONE, v);
    TEST_ASSERT_EQUAL(OS_OK, os_rc_to_q14(&c, 1625, &v));
    TEST_ASSERT_EQUAL_INT16(4096, v);
    /* 1 us = 32.768 -> 33 ; -1 us -> -33 (ties/rounding symmetric) */
    TEST_ASSERT_EQUAL(OS_OK, os_rc_to_q14(&c, 1501, &v));
    TEST_ASSERT_EQUAL_INT16(33, v);
    TEST_ASSERT_EQUAL(OS_OK, os_rc_to_q14(&c, 1499, &v));
    TEST_ASSERT_EQUAL_INT16(-33, v);
    /* beyond full stick clamps */
    TEST_ASSERT_EQUAL(OS_OK, os_rc_to_q14(&c, 2200, &v));
    TEST_ASSERT_EQUAL_INT16(ONE, v);
    TEST_ASSERT_EQUAL(OS_OK, os_rc_to_q14(&c, 800, &v));
    TEST_ASSERT_EQUAL_INT16(-ONE, v);
    /* travel 300: 1 us = 54.61 -> 55 (up), 2 us = 109.23 -> 109 (down), and
     * mirrored. (No exact tie exists: travel <= 1000 cannot hold 2^15.) */
    const os_rc_cal_t t = rc(0, 1500, 300, 0, 0);
    TEST_ASSERT_EQUAL(OS_OK, os_rc_to_q14(&t, 1501, &v));
    TEST_ASSERT_EQUAL_INT16(55, v);
    TEST_ASSERT_EQUAL(OS_OK, os_rc_to_q14(&t, 1502, &v));
    TEST_ASSERT_EQUAL_INT16(109, v);
    TEST_ASSERT_EQUAL(OS_OK, os_rc_to_q14(&t, 1498, &v));
    TEST_ASSERT_EQUAL_INT16(-109, v);
}

static void test_rc_reversed_and_unipolar(void)
{
    const os_rc_cal_t r = rc(0, 1500, 500, 1, 0);
    q14_t v = 0;
    TEST_ASSERT_EQUAL(OS_OK, os_rc_to_q14(&r, 1750, &v));
    TEST_ASSERT_EQUAL_INT16(-HALF, v);
    const os_rc_cal_t thr = rc(0, 1100, 800, 0, 1);
    TEST_ASSERT_EQUAL(OS_OK, os_rc_to_q14(&thr, 1100, &v));
    TEST_ASSERT_EQUAL_INT16(0, v);
    TEST_ASSERT_EQUAL(OS_OK, os_rc_to_q14(&thr, 1000, &v)); /* below idle */
    TEST_ASSERT_EQUAL_INT16(0, v);
    TEST_ASSERT_EQUAL(OS_OK, os_rc_to_q14(&thr, 1500, &v));
    TEST_ASSERT_EQUAL_INT16(HALF, v);
    TEST_ASSERT_EQUAL(OS_OK, os_rc_to_q14(&thr, 1900, &v));
    TEST_ASSERT_EQUAL_INT16(ONE, v);
    TEST_ASSERT_EQUAL(OS_OK, os_rc_to_q14(&thr, 2100, &v));
    TEST_ASSERT_EQUAL_INT16(ONE, v);
}

static void test_rc_bad_pulses_and_calibrations(void)
{
    const os_rc_cal_t c = rc(0, 1500, 500, 0, 0);
    q14_t v = 5;
    TEST_ASSERT_EQUAL(OS_ERR_RANGE, os_rc_to_q14(&c, 0, &v));
    TEST_ASSERT_EQUAL_INT16(0, v);
    v = 5;
    TEST_ASSERT_EQUAL(OS_ERR_RANGE, os_rc_to_q14(&c, OS_RC_VALID_MIN_US - 1u, &v));
    TEST_ASSERT_EQUAL_INT16(0, v);
    TEST_ASSERT_EQUAL(OS_ERR_RANGE, os_rc_to_q14(&c, OS_RC_VALID_MAX_US + 1u, &v));
    TEST_ASSERT_EQUAL(OS_OK, os_rc_to_q14(&c, OS_RC_VALID_MIN_US, &v));
    TEST_ASSERT_EQUAL(OS_OK, os_rc_to_q14(&c, OS_RC_VALID_MAX_US, &v));
    TEST_ASSERT_EQUAL(OS_ERR_NULL, os_rc_to_q14(&c, 1500, NULL));
    TEST_ASSERT_EQUAL(OS_ERR_NULL, os_rc_to_q14(NULL, 1500, &v));

    os_rc_cal_t b = rc(0, 1500, OS_RC_TRAVEL_MIN_US - 1u, 0, 0);
    TEST_ASSERT_EQUAL(OS_ERR_CONFIG, os_rc_to_q14(&b, 1500, &v));
    b.travel_us = 0; /* would divide by zero */
    TEST_ASSERT_EQUAL(OS_ERR_CONFIG, os_rc_to_q14(&b, 1500, &v));
    b.travel_us = OS_RC_TRAVEL_MAX_US + 1u;
    TEST_ASSERT_EQUAL(OS_ERR_CONFIG, os_rc_cal_check(&b));
    b.travel_us = OS_RC_TRAVEL_MAX_US;
    TEST_ASSERT_EQUAL(OS_OK, os_rc_cal_check(&b));
    b.travel_us = OS_RC_TRAVEL_MIN_US;
    TEST_ASSERT_EQUAL(OS_OK, os_rc_cal_check(&b));
    b.centre_us = OS_RC_VALID_MIN_US - 1u;
    TEST_ASSERT_EQUAL(OS_ERR_CONFIG, os_rc_cal_check(&b));
    b.centre_us = OS_RC_VALID_MAX_US + 1u;
    TEST_ASSERT_EQUAL(OS_ERR_CONFIG, os_rc_cal_check(&b));
    TEST_ASSERT_EQUAL(OS_ERR_NULL, os_rc_cal_check(NULL));
}

static void test_rc_full_pulse_range_is_bounded(void)
{
    /* every pulse, shortest travel: always in [-1, 1] and monotonic */
    const os_rc_cal_t c = rc(0, 1500, OS_RC_TRAVEL_MIN_US, 0, 0);
    int32_t prev = -ONE;
    for (uint32_t us = 0; us <= 65535u; ++us) {
        q14_t v = 0;
        const os_status_t st = os_rc_to_q14(&c, (uint16_t)us, &v);
        if (us < OS_RC_VALID_MIN_US || us > OS_RC_VALID_MAX_US) {
            TEST_ASSERT_EQUAL(OS_ERR_RANGE, st);
            TEST_ASSERT_EQUAL_INT16(0, v);
        } else {
            TEST_ASSERT_EQUAL(OS_OK, st);
            TEST_ASSERT_TRUE(v >= -ONE && v <= ONE);
            TEST_ASSERT_TRUE(v >= prev);
            prev = v;
        }
    }
}

static os_rc_map_t standard_rc_map(void)
{
    os_rc_map_t m;
    m.aileron = rc(0, 1500, 500, 0, 0);
    m.elevator = rc(1, 1500, 500, 1, 0); /* pulled stick = short pulse on many sets */
    m.throttle = rc(2, 1000, 1000, 0, 1);
    m.rudder = rc(3, 1500, 500, 0, 0);
    return m;
}

static void test_manual_pass_through_vtail(void)
{
    const os_rc_map_t m = standard_rc_map();
    const uint16_t sticks[5] = {1500, 1250, 1600, 1625, 1000};
    os_command_t c;
    TEST_ASSERT_EQUAL(OS_OK, os_rc_command(&m, sticks, 5, &c));
    TEST_ASSERT_EQUAL_INT16(0, c.aileron);
    TEST_ASSERT_EQUAL_INT16(HALF, c.elevator); /* reversed input */
    TEST_ASSERT_EQUAL_INT16(QTR, c.rudder);
    TEST_ASSERT_EQUAL_INT16(9830, c.throttle); /* 0.6 * 16384 = 9830.4 */

    const uint8_t fn[] = {OS_FN_VTAIL_LEFT, OS_FN_VTAIL_RIGHT, OS_FN_THROTTLE};
    const os_config_t cfg = config_of(fn, 3);
    uint16_t p[OS_MAX_CHANNELS] = {0};
    TEST_ASSERT_EQUAL(OS_OK, os_compute(&cfg, &c, p));
    TEST_ASSERT_EQUAL_UINT16(1875, p[0]);
    TEST_ASSERT_EQUAL_UINT16(1625, p[1]);
    TEST_ASSERT_EQUAL_UINT16(1600, p[2]);
}

static void test_manual_pass_through_failures_are_neutral(void)
{
    os_rc_map_t m = standard_rc_map();
    uint16_t sticks[4] = {1700, 1300, 1500, 1600};
    os_command_t c;
    sticks[3] = 0; /* rudder channel lost */
    TEST_ASSERT_EQUAL(OS_ERR_RANGE, os_rc_command(&m, sticks, 4, &c));
    TEST_ASSERT_EQUAL_INT16(0, c.aileron);
    TEST_ASSERT_EQUAL_INT16(0, c.elevator);
    TEST_ASSERT_EQUAL_INT16(0, c.rudder);
    TEST_ASSERT_EQUAL_INT16(0, c.throttle);
    sticks[3] = 1500;
    TEST_ASSERT_EQUAL(OS_ERR_CONFIG, os_rc_command(&m, sticks, 3, &c)); /* input 3 >= 3 */
    TEST_ASSERT_EQUAL_INT16(0, c.aileron);
    m.throttle.travel_us = 0;
    TEST_ASSERT_EQUAL(OS_ERR_CONFIG, os_rc_command(&m, sticks, 4, &c));
    m = standard_rc_map();
    TEST_ASSERT_EQUAL(OS_OK, os_rc_command(&m, sticks, 4, &c));
    TEST_ASSERT_EQUAL_INT16(6554, c.aileron); /* 200/500 = 0.4 -> 6553.6 */
    TEST_ASSERT_EQUAL(OS_ERR_NULL, os_rc_command(NULL, sticks, 4, &c));
    TEST_ASSERT_EQUAL(OS_ERR_NULL, os_rc_command(&m, NULL, 4, &c));
    TEST_ASSERT_EQUAL(OS_ERR_NULL, os_rc_command(&m, sticks, 4, NULL));
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_standard_mix_passes_each_axis);
    RUN_TEST(test_single_axis_clamps);
    RUN_TEST(test_vtail_mix);
    RUN_TEST(test_elevon_mix);
    RUN_TEST(test_mix_sums_always_in_range);
    RUN_TEST(test_mix_matches_reference_every_input);
    RUN_TEST(test_vtail_pulses_with_reversal);
    RUN_TEST(test_delta_pulses_with_end_points);
    RUN_TEST(test_second_aileron_channel);
    RUN_TEST(test_rc_to_q14_values_and_rounding);
    RUN_TEST(test_rc_reversed_and_unipolar);
    RUN_TEST(test_rc_bad_pulses_and_calibrations);
    RUN_TEST(test_rc_full_pulse_range_is_bounded);
    RUN_TEST(test_manual_pass_through_vtail);
    RUN_TEST(test_manual_pass_through_failures_are_neutral);
    return UNITY_END();
}
