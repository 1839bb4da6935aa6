/* Unit tests of the altitude and airspeed holds (include/helical/guidance/holds.h). */
#include "unity.h"

#include "helical/guidance/holds.h"

#include <stddef.h>

static ht_alt_hold_params_t alt;
static ht_alt_hold_state_t alt_s;
static ht_speed_hold_params_t spd;
static ht_speed_hold_state_t spd_s;

void setUp(void)
{
    alt.kp_pitch_per_m = 655; /* ~0.01 per m */
    alt.ki_pitch_per_m_s = 0;
    alt.kd_pitch_per_m_s = 0;
    alt.max_pitch = Q16_FROM_REAL(0.3);
    alt.max_integral_pitch = Q16_FROM_REAL(0.2);
    alt.max_error_cm = 100000;
    alt.integral_band_cm = 100000;
    alt.rate_hz = 40;
    alt.protect_cm_s = 0;
    alt.protect_valid_cm_s = 0;
    alt.kv_pitch_per_m_s = 0;
    alt.protect_tau_ms = 0;
    ht_alt_hold_reset(&alt_s);

    spd.throttle_trim = Q14_FROM_REAL(0.5);
    spd.throttle_min = 0;
    spd.throttle_max = Q14_ONE;
    spd.kp_throttle_per_m_s = Q16_FROM_REAL(0.1);
    spd.ki_throttle_per_m = 0;
    spd.kff_throttle_per_pitch = 0;
    spd.max_integral_throttle = Q14_FROM_REAL(0.5);
    spd.rate_hz = 40;
    ht_speed_hold_reset(&spd_s);
}

void tearDown(void) {}

/* --- altitude hold ------------------------------------------------------- */

static void test_alt_check_accepts_valid_and_rejects_each_bad_field(void)
{
    TEST_ASSERT_EQUAL_INT(HT_HOLD_OK, ht_alt_hold_check(&alt));
    TEST_ASSERT_EQUAL_INT(HT_HOLD_ERR_NULL, ht_alt_hold_check(NULL));
    ht_alt_hold_params_t b;
    b = alt;
    b.kp_pitch_per_m = -1;
    TEST_ASSERT_EQUAL_INT(HT_HOLD_ERR_PARAM, ht_alt_hold_check(&b));
    b = alt;
    b.ki_pitch_per_m_s = 64 * Q16_ONE + 1;
    TEST_ASSERT_EQUAL_INT(HT_HOLD_ERR_PARAM, ht_alt_hold_check(&b));
    b = alt;
    b.kd_pitch_per_m_s = 64 * Q16_ONE;
    TEST_ASSERT_EQUAL_INT(HT_HOLD_OK, ht_alt_hold_check(&b)); /* edge is allowed */
    b = alt;
    b.max_pitch = 0;
    TEST_ASSERT_EQUAL_INT(HT_HOLD_ERR_PARAM, ht_alt_hold_check(&b));
    b = alt;
    b.max_pitch = 4 * Q16_ONE + 1;
    TEST_ASSERT_EQUAL_INT(HT_HOLD_ERR_PARAM, ht_alt_hold_check(&b));
    b = alt;
    b.max_integral_pitch = -1;
    TEST_ASSERT_EQUAL_INT(HT_HOLD_ERR_PARAM, ht_alt_hold_check(&b));
    b = alt;
    b.max_error_cm = 99;
    TEST_ASSERT_EQUAL_INT(HT_HOLD_ERR_PARAM, ht_alt_hold_check(&b));
    b = alt;
    b.max_error_cm = 1000001;
    TEST_ASSERT_EQUAL_INT(HT_HOLD_ERR_PARAM, ht_alt_hold_check(&b));
    b = alt;
    b.integral_band_cm = -1;
    TEST_ASSERT_EQUAL_INT(HT_HOLD_ERR_PARAM, ht_alt_hold_check(&b));
    b = alt;
    b.integral_band_cm = b.max_error_cm + 1;
    TEST_ASSERT_EQUAL_INT(HT_HOLD_ERR_PARAM, ht_alt_hold_check(&b));
    b = alt;
    b.rate_hz = 0;
    TEST_ASSERT_EQUAL_INT(HT_HOLD_ERR_PARAM, ht_alt_hold_check(&b));
    b = alt;
    b.rate_hz = 1001;
    TEST_ASSERT_EQUAL_INT(HT_HOLD_ERR_PARAM, ht_alt_hold_check(&b));
}

static void test_alt_null_and_bad_params_give_zero_and_keep_state(void)
{
    TEST_ASSERT_EQUAL_INT32(0, ht_alt_hold_step(NULL, &alt_s, 1000, 0, 0, 0));
    TEST_ASSERT_EQUAL_INT32(0, ht_alt_hold_step(&alt, NULL, 1000, 0, 0, 0));
    ht_alt_hold_params_t b = alt;
    b.rate_hz = 0;
    b.ki_pitch_per_m_s = Q16_ONE;
    alt_s.integral_q20[0] = 77;
    TEST_ASSERT_EQUAL_INT32(0, ht_alt_hold_step(&b, &alt_s, 1000, 0, 0, 0));
    TEST_ASSERT_EQUAL_INT32(77, alt_s.integral_q20[0]);
}

static void test_alt_proportional_exact_value_and_sign(void)
{
    /* 10 m low: 655 * 10 = 6550 (Q16), climb. */
    TEST_ASSERT_EQUAL_INT32(6550, ht_alt_hold_step(&alt, &alt_s, 101000, 100000, 0, 0));
    /* 10 m high: exact mirror. */
    TEST_ASSERT_EQUAL_INT32(-6550, ht_alt_hold_step(&alt, &alt_s, 100000, 101000, 0, 0));
    /* 1 cm: 0.01 m -> Q8 round(2.56) = 3 -> round(655 * 3 / 256) = 8 */
    TEST_ASSERT_EQUAL_INT32(8, ht_alt_hold_step(&alt, &alt_s, 1, 0, 0, 0));
    TEST_ASSERT_EQUAL_INT32(-8, ht_alt_hold_step(&alt, &alt_s, 0, 1, 0, 0));
    TEST_ASSERT_EQUAL_INT32(0, ht_alt_hold_step(&alt, &alt_s, 5000, 5000, 0, 0));
}

static void test_alt_same_request_upright_and_inverted(void)
{
    /* The pitch ratio is earth-frame: the core keeps its sign when inverted. */
    q16_t up = ht_alt_hold_step(&alt, &alt_s, 2000, 0, 0, 0);
    q16_t inv = ht_alt_hold_step(&alt, &alt_s, 2000, 0, 0, 1);
    TEST_ASSERT_TRUE(up > 0);
    TEST_ASSERT_EQUAL_INT32(up, inv);
}

static void test_alt_saturates_at_max_pitch_over_whole_input_range(void)
{
    TEST_ASSERT_EQUAL_INT32(alt.max_pitch,
                            ht_alt_hold_step(&alt, &alt_s, INT32_MAX, INT32_MIN, 0, 0));
    TEST_ASSERT_EQUAL_INT32(-alt.max_pitch,
                            ht_alt_hold_step(&alt, &alt_s, INT32_MIN, INT32_MAX, 0, 0));
    TEST_ASSERT_EQUAL_INT32(0, ht_alt_hold_step(&alt, &alt_s, 0, 0, INT32_MIN, 0)); /* no kd */
    alt.kd_pitch_per_m_s = 64 * Q16_ONE;
    alt.kp_pitch_per_m = 64 * Q16_ONE;
    alt.ki_pitch_per_m_s = 64 * Q16_ONE;
    TEST_ASSERT_EQUAL_INT32(-alt.max_pitch, ht_alt_hold_step(&alt, &alt_s, 0, 0, INT32_MAX, 0));
    TEST_ASSERT_EQUAL_INT32(alt.max_pitch, ht_alt_hold_step(&alt, &alt_s, 0, 0, INT32_MIN, 1));
    TEST_ASSERT_EQUAL_INT32(alt.max_pitch,
                            ht_alt_hold_step(&alt, &alt_s, INT32_MAX, INT32_MIN, INT32_MIN, 0));
    TEST_ASSERT_EQUAL_INT32(-alt.max_pitch,
                            ht_alt_hold_step(&alt, &alt_s, INT32_MIN, INT32_MAX, INT32_MAX, 1));
}

static void test_alt_just_below_saturation_is_not_clamped(void)
{
    alt.max_pitch = 6550;
    TEST_ASSERT_EQUAL_INT32(6550, ht_alt_hold_step(&alt, &alt_s, 1000, 0, 0, 0));
    alt.max_pitch = 6549;
    TEST_ASSERT_EQUAL_INT32(6549, ht_alt_hold_step(&alt, &alt_s, 1000, 0, 0, 0));
}

static void test_alt_vertical_speed_damps(void)
{
    alt.kp_pitch_per_m = 0;
    alt.kd_pitch_per_m_s = Q16_FROM_REAL(0.05);
    /* climbing 2 m/s -> -0.1 */
    q16_t d = ht_alt_hold_step(&alt, &alt_s, 0, 0, 200, 0);
    TEST_ASSERT_INT32_WITHIN(2, -6554, d);
    TEST_ASSERT_EQUAL_INT32(-d, ht_alt_hold_step(&alt, &alt_s, 0, 0, -200, 0));
}

static void test_alt_integral_accumulates_exactly_per_orientation(void)
{
    alt.kp_pitch_per_m = 0;
    alt.ki_pitch_per_m_s = 655; /* ~0.01 per m s */
    /* 1 m error: per step round(655 * 256 / 16 / 40) = round(262.0) = 262 (Q20) */
    for (int i = 0; i < 40; ++i) {
        (void)ht_alt_hold_step(&alt, &alt_s, 100, 0, 0, 0);
    }
    TEST_ASSERT_EQUAL_INT32(262 * 40, alt_s.integral_q20[0]);
    TEST_ASSERT_EQUAL_INT32(0, alt_s.integral_q20[1]);
    /* the inverted integrator is separate, and the upright one is kept */
    q16_t out = ht_alt_hold_step(&alt, &alt_s, 0, 100, 0, 1);
    TEST_ASSERT_EQUAL_INT32(-262, alt_s.integral_q20[1]);
    TEST_ASSERT_EQUAL_INT32(262 * 40, alt_s.integral_q20[0]);
    TEST_ASSERT_EQUAL_INT32(-16, out); /* round(-262 / 16) = -16 (ties to +inf) */
    out = ht_alt_hold_step(&alt, &alt_s, 0, 0, 0, 0);
    TEST_ASSERT_EQUAL_INT32(655, out); /* 10480 / 16 */
    ht_alt_hold_reset(&alt_s);
    TEST_ASSERT_EQUAL_INT32(0, alt_s.integral_q20[0]);
    TEST_ASSERT_EQUAL_INT32(0, alt_s.integral_q20[1]);
}

static void test_alt_integrates_only_inside_the_band(void)
{
    alt.kp_pitch_per_m = 0;
    alt.ki_pitch_per_m_s = 655;
    alt.integral_band_cm = 500;
    (void)ht_alt_hold_step(&alt, &alt_s, 501, 0, 0, 0); /* 5.01 m: outside */
    TEST_ASSERT_EQUAL_INT32(0, alt_s.integral_q20[0]);
    (void)ht_alt_hold_step(&alt, &alt_s, 0, 501, 0, 0);
    TEST_ASSERT_EQUAL_INT32(0, alt_s.integral_q20[0]);
    (void)ht_alt_hold_step(&alt, &alt_s, 500, 0, 0, 0);   /* exactly on the edge: inside */
    TEST_ASSERT_EQUAL_INT32(1310, alt_s.integral_q20[0]); /* round(655*1280/16/40) */
    (void)ht_alt_hold_step(&alt, &alt_s, 0, 500, 0, 0);
    TEST_ASSERT_EQUAL_INT32(0, alt_s.integral_q20[0]);
}

static void test_alt_integral_rounding_is_symmetric(void)
{
    alt.kp_pitch_per_m = 0;
    alt.ki_pitch_per_m_s = 5; /* per step 5*3/16 ~ 1 (Q20) -> /40: 0.025, rounds to 0 */
    (void)ht_alt_hold_step(&alt, &alt_s, 1, 0, 0, 0);
    TEST_ASSERT_EQUAL_INT32(0, alt_s.integral_q20[0]);
    /* exact tie of the division: q_mul32 = 20, 20 / 40 = 0.5 -> away from zero */
    alt.ki_pitch_per_m_s = 20; /* 20 * 256 (1 m) >> 4 = 320 -> 320 / 40 = 8 */
    alt.rate_hz = 640;         /* 320 / 640 = 0.5 exactly */
    (void)ht_alt_hold_step(&alt, &alt_s, 100, 0, 0, 0);
    TEST_ASSERT_EQUAL_INT32(1, alt_s.integral_q20[0]);
    (void)ht_alt_hold_step(&alt, &alt_s, 0, 100, 0, 1);
    TEST_ASSERT_EQUAL_INT32(-1, alt_s.integral_q20[1]);
}

static void test_alt_integral_clamped_and_no_windup_when_saturated(void)
{
    alt.kp_pitch_per_m = 0;
    alt.ki_pitch_per_m_s = Q16_ONE;
    alt.max_pitch = Q16_FROM_REAL(0.5);
    alt.max_integral_pitch = Q16_FROM_REAL(0.2);
    for (int i = 0; i < 1000; ++i) {
        (void)ht_alt_hold_step(&alt, &alt_s, 100000, 0, 0, 0);
    }
    TEST_ASSERT_EQUAL_INT32(alt.max_integral_pitch * 16, alt_s.integral_q20[0]);
    /* Now P saturates the output: the integral must not grow further. */
    ht_alt_hold_reset(&alt_s);
    alt.kp_pitch_per_m = Q16_ONE;
    for (int i = 0; i < 1000; ++i) {
        TEST_ASSERT_EQUAL_INT32(alt.max_pitch, ht_alt_hold_step(&alt, &alt_s, 100000, 0, 0, 0));
    }
    TEST_ASSERT_EQUAL_INT32(0, alt_s.integral_q20[0]);
    /* but it may unwind in the other direction */
    alt.kp_pitch_per_m = 0;
    (void)ht_alt_hold_step(&alt, &alt_s, 0, 100, 0, 0);
    TEST_ASSERT_TRUE(alt_s.integral_q20[0] < 0);
}

/* --- altitude hold: airspeed protection ---------------------------------- */

/* protect below 40 m/s, 0.01 pitch ratio per m/s, readings below 15 m/s invalid */
static void use_protection(uint16_t tau_ms)
{
    alt.protect_cm_s = 4000;
    alt.protect_valid_cm_s = 1500;
    alt.kv_pitch_per_m_s = 655;
    alt.protect_tau_ms = tau_ms;
}

static void test_alt_protection_check_rejects_each_bad_field(void)
{
    use_protection(1000);
    TEST_ASSERT_EQUAL_INT(HT_HOLD_OK, ht_alt_hold_check(&alt));
    ht_alt_hold_params_t b;
    b = alt;
    b.protect_cm_s = -1;
    TEST_ASSERT_EQUAL_INT(HT_HOLD_ERR_PARAM, ht_alt_hold_check(&b));
    b = alt;
    b.protect_cm_s = 32768;
    TEST_ASSERT_EQUAL_INT(HT_HOLD_ERR_PARAM, ht_alt_hold_check(&b));
    b = alt;
    b.protect_valid_cm_s = -1;
    TEST_ASSERT_EQUAL_INT(HT_HOLD_ERR_PARAM, ht_alt_hold_check(&b));
    b = alt;
    b.protect_valid_cm_s = b.protect_cm_s + 1;
    TEST_ASSERT_EQUAL_INT(HT_HOLD_ERR_PARAM, ht_alt_hold_check(&b));
    b = alt;
    b.kv_pitch_per_m_s = -1;
    TEST_ASSERT_EQUAL_INT(HT_HOLD_ERR_PARAM, ht_alt_hold_check(&b));
    b = alt;
    b.kv_pitch_per_m_s = 64 * Q16_ONE + 1;
    TEST_ASSERT_EQUAL_INT(HT_HOLD_ERR_PARAM, ht_alt_hold_check(&b));
    b = alt;
    b.protect_tau_ms = 60001u;
    TEST_ASSERT_EQUAL_INT(HT_HOLD_ERR_PARAM, ht_alt_hold_check(&b));
    /* the edges are accepted */
    b = alt;
    b.protect_cm_s = 32767;
    b.protect_valid_cm_s = 32767;
    b.kv_pitch_per_m_s = 64 * Q16_ONE;
    b.protect_tau_ms = 60000u;
    TEST_ASSERT_EQUAL_INT(HT_HOLD_OK, ht_alt_hold_check(&b));
    /* a bad protection field refuses the step too (and ht_alt_hold_step) */
    b.protect_valid_cm_s = -1;
    TEST_ASSERT_EQUAL_INT32(0, ht_alt_hold_step_v(&b, &alt_s, 100000, 0, 0, 0, 3000));
    TEST_ASSERT_EQUAL_INT32(0, ht_alt_hold_step(&b, &alt_s, 100000, 0, 0, 0));
    TEST_ASSERT_EQUAL_INT32(0, ht_alt_hold_step_v(&alt, NULL, 100000, 0, 0, 0, 3000));
    TEST_ASSERT_EQUAL_INT32(0, ht_alt_hold_step_v(NULL, &alt_s, 100000, 0, 0, 0, 3000));
}

static void test_alt_protection_off_is_the_plain_step(void)
{
    /* protect 0: ht_alt_hold_step_v == ht_alt_hold_step, state for state */
    alt.ki_pitch_per_m_s = Q16_FROM_REAL(0.01);
    alt.kd_pitch_per_m_s = Q16_FROM_REAL(0.02);
    ht_alt_hold_state_t s2;
    ht_alt_hold_reset(&s2);
    const int32_t alts[] = {0, 5000, -30000, 100000, 2500, -100, 7, 0};
    const int16_t speeds[] = {0, 1000, 3000, 5000, INT16_MIN, INT16_MAX, 1499, 1500};
    for (int i = 0; i < 8; ++i) {
        const q16_t a = ht_alt_hold_step(&alt, &alt_s, 0, alts[i], 150 * i - 300, 0);
        const q16_t b = ht_alt_hold_step_v(&alt, &s2, 0, alts[i], 150 * i - 300, 0, speeds[i]);
        TEST_ASSERT_EQUAL_INT32(a, b);
        TEST_ASSERT_EQUAL_INT32(alt_s.integral_q20[0], s2.integral_q20[0]);
    }
}

static void test_alt_protection_ceiling_exact_values(void)
{
    use_protection(0); /* no filter */
    /* 100 m low: the hold asks max_pitch (19661) at or above 40 m/s */
    TEST_ASSERT_EQUAL_INT32(alt.max_pitch, ht_alt_hold_step_v(&alt, &alt_s, 10000, 0, 0, 0, 4000));
    TEST_ASSERT_EQUAL_INT32(alt.max_pitch,
                            ht_alt_hold_step_v(&alt, &alt_s, 10000, 0, 0, 0, INT16_MAX));
    /* 1 cm/s below: 0.01 m/s -> Q8 3 -> round(655 * 3 / 256) = 8 */
    TEST_ASSERT_EQUAL_INT32(alt.max_pitch - 8,
                            ht_alt_hold_step_v(&alt, &alt_s, 10000, 0, 0, 0, 3999));
    /* 10 m/s below: 655 * 10 = 6550 */
    TEST_ASSERT_EQUAL_INT32(alt.max_pitch - 6550,
                            ht_alt_hold_step_v(&alt, &alt_s, 10000, 0, 0, 0, 3000));
    /* 25 m/s below (the valid edge, 15 m/s): 16375 */
    TEST_ASSERT_EQUAL_INT32(alt.max_pitch - 16375,
                            ht_alt_hold_step_v(&alt, &alt_s, 10000, 0, 0, 0, 1500));
    /* steep: the ceiling stops at -max_pitch (descend for airspeed) */
    alt.kv_pitch_per_m_s = 64 * Q16_ONE;
    TEST_ASSERT_EQUAL_INT32(-alt.max_pitch, ht_alt_hold_step_v(&alt, &alt_s, 10000, 0, 0, 0, 2000));
    /* the extreme: protect 32767, every reading valid, airspeed 0 */
    alt.protect_cm_s = 32767;
    alt.protect_valid_cm_s = 0;
    TEST_ASSERT_EQUAL_INT32(-alt.max_pitch,
                            ht_alt_hold_step_v(&alt, &alt_s, INT32_MAX, INT32_MIN, 0, 0, 0));
}

static void test_alt_protection_only_cuts_the_climb_demand(void)
{
    use_protection(0);
    /* 10 m high: -6550 asked, below the ceiling at 30 m/s (13111): unchanged */
    TEST_ASSERT_EQUAL_INT32(-6550, ht_alt_hold_step_v(&alt, &alt_s, 100000, 101000, 0, 0, 3000));
    /* 10 m low: +6550, below the ceiling: unchanged */
    TEST_ASSERT_EQUAL_INT32(6550, ht_alt_hold_step_v(&alt, &alt_s, 101000, 100000, 0, 0, 3000));
    /* the same inverted */
    TEST_ASSERT_EQUAL_INT32(6550, ht_alt_hold_step_v(&alt, &alt_s, 101000, 100000, 0, 1, 3000));
    /* 30 m low: 19650 asked, cut to 13111 */
    TEST_ASSERT_EQUAL_INT32(13111, ht_alt_hold_step_v(&alt, &alt_s, 103000, 100000, 0, 0, 3000));
    TEST_ASSERT_EQUAL_INT32(13111, ht_alt_hold_step_v(&alt, &alt_s, 103000, 100000, 0, 1, 3000));
}

static void test_alt_protection_ignores_a_failed_sensor(void)
{
    use_protection(0);
    /* below protect_valid (15 m/s): a dead pitot, not a stall */
    TEST_ASSERT_EQUAL_INT32(alt.max_pitch, ht_alt_hold_step_v(&alt, &alt_s, 10000, 0, 0, 0, 0));
    TEST_ASSERT_EQUAL_INT32(alt.max_pitch, ht_alt_hold_step_v(&alt, &alt_s, 10000, 0, 0, 0, 1499));
    TEST_ASSERT_EQUAL_INT32(alt.max_pitch,
                            ht_alt_hold_step_v(&alt, &alt_s, 10000, 0, 0, 0, INT16_MIN));
}

static void test_alt_protection_no_windup_against_the_ceiling(void)
{
    use_protection(0);
    alt.kp_pitch_per_m = 0;
    alt.ki_pitch_per_m_s = Q16_FROM_REAL(0.01); /* 10 m: 0.0025 (164 Q16) per step */
    alt.integral_band_cm = 100000;
    /* 10 m low at 15 m/s: the ceiling is 19661 - 16375 = 3286 (0.05); without
     * it the integral would reach max_integral (0.2) in 80 steps */
    for (int i = 0; i < 400; ++i) {
        (void)ht_alt_hold_step_v(&alt, &alt_s, 1000, 0, 0, 0, 1500);
    }
    /* the integral stops where the output meets the ceiling (within one step) */
    const int32_t i_q16 = alt_s.integral_q20[0] / 16;
    TEST_ASSERT_TRUE(i_q16 >= 3286);
    TEST_ASSERT_TRUE(i_q16 < 3286 + 165);
    TEST_ASSERT_TRUE(i_q16 < alt.max_integral_pitch);
    TEST_ASSERT_EQUAL_INT32(3286, ht_alt_hold_step_v(&alt, &alt_s, 1000, 0, 0, 0, 1500));
    /* it unwinds at once when the error reverses */
    const int32_t before = alt_s.integral_q20[0];
    (void)ht_alt_hold_step_v(&alt, &alt_s, 0, 1000, 0, 0, 1500);
    TEST_ASSERT_TRUE(alt_s.integral_q20[0] < before);
}

static void test_alt_protection_filter(void)
{
    use_protection(1000); /* 1 s at 40 Hz: 1/40 of the difference per step */
    /* the first reading is taken as it is */
    TEST_ASSERT_EQUAL_INT32(alt.max_pitch, ht_alt_hold_step_v(&alt, &alt_s, 10000, 0, 0, 0, 5000));
    TEST_ASSERT_EQUAL_INT32(5000 * 256, alt_s.airspeed_q8);
    TEST_ASSERT_EQUAL_UINT8(1u, alt_s.airspeed_valid);
    /* a one-step dip to 20 m/s moves the filter by 30 / 40 m/s: no cut */
    TEST_ASSERT_EQUAL_INT32(alt.max_pitch, ht_alt_hold_step_v(&alt, &alt_s, 10000, 0, 0, 0, 2000));
    TEST_ASSERT_EQUAL_INT32(5000 * 256 - 3000 * 256 / 40, alt_s.airspeed_q8);
    /* an invalid reading leaves it alone */
    (void)ht_alt_hold_step_v(&alt, &alt_s, 10000, 0, 0, 0, 0);
    TEST_ASSERT_EQUAL_INT32(5000 * 256 - 3000 * 256 / 40, alt_s.airspeed_q8);
    /* a lasting 30 m/s: the filter settles there and the ceiling with it */
    for (int i = 0; i < 40 * 20; ++i) {
        (void)ht_alt_hold_step_v(&alt, &alt_s, 10000, 0, 0, 0, 3000);
    }
    TEST_ASSERT_INT32_WITHIN(20 * 256, 3000 * 256, alt_s.airspeed_q8);
    TEST_ASSERT_INT32_WITHIN(150, alt.max_pitch - 6550,
                             ht_alt_hold_step_v(&alt, &alt_s, 10000, 0, 0, 0, 3000));
    /* reset forgets it */
    ht_alt_hold_reset(&alt_s);
    TEST_ASSERT_EQUAL_UINT8(0u, alt_s.airspeed_valid);
    TEST_ASSERT_EQUAL_INT32(0, alt_s.airspeed_q8);
    /* a time constant shorter than a step: n = 1, no filtering */
    alt.protect_tau_ms = 10u;
    (void)ht_alt_hold_step_v(&alt, &alt_s, 10000, 0, 0, 0, 5000);
    TEST_ASSERT_EQUAL_INT32(alt.max_pitch - 6550,
                            ht_alt_hold_step_v(&alt, &alt_s, 10000, 0, 0, 0, 3000));
}

static void test_alt_protection_survives_a_corrupt_state(void)
{
    use_protection(1000);
    alt_s.airspeed_valid = 1u;
    alt_s.airspeed_q8 = INT32_MIN; /* the state is the caller's */
    q16_t out = ht_alt_hold_step_v(&alt, &alt_s, 10000, 0, 0, 0, 3000);
    TEST_ASSERT_TRUE(out >= -alt.max_pitch && out <= alt.max_pitch);
    alt_s.airspeed_q8 = INT32_MAX;
    out = ht_alt_hold_step_v(&alt, &alt_s, 10000, 0, 0, 0, 3000);
    TEST_ASSERT_EQUAL_INT32(alt.max_pitch, out); /* reads as fast: no cut */
}

/* --- airspeed hold ------------------------------------------------------- */

static void test_speed_check_rejects_each_bad_field(void)
{
    TEST_ASSERT_EQUAL_INT(HT_HOLD_OK, ht_speed_hold_check(&spd));
    TEST_ASSERT_EQUAL_INT(HT_HOLD_ERR_NULL, ht_speed_hold_check(NULL));
    ht_speed_hold_params_t b;
    b = spd;
    b.throttle_trim = -1;
    TEST_ASSERT_EQUAL_INT(HT_HOLD_ERR_PARAM, ht_speed_hold_check(&b));
    b = spd;
    b.throttle_trim = Q14_ONE + 1;
    TEST_ASSERT_EQUAL_INT(HT_HOLD_ERR_PARAM, ht_speed_hold_check(&b));
    b = spd;
    b.throttle_min = Q14_FROM_REAL(0.6);
    b.throttle_max = Q14_FROM_REAL(0.5);
    TEST_ASSERT_EQUAL_INT(HT_HOLD_ERR_PARAM, ht_speed_hold_check(&b));
    b = spd;
    b.kp_throttle_per_m_s = -1;
    TEST_ASSERT_EQUAL_INT(HT_HOLD_ERR_PARAM, ht_speed_hold_check(&b));
    b = spd;
    b.kff_throttle_per_pitch = 64 * Q16_ONE + 1;
    TEST_ASSERT_EQUAL_INT(HT_HOLD_ERR_PARAM, ht_speed_hold_check(&b));
    b = spd;
    b.max_integral_throttle = Q14_ONE + 1;
    TEST_ASSERT_EQUAL_INT(HT_HOLD_ERR_PARAM, ht_speed_hold_check(&b));
    b = spd;
    b.rate_hz = 0;
    TEST_ASSERT_EQUAL_INT(HT_HOLD_ERR_PARAM, ht_speed_hold_check(&b));
    TEST_ASSERT_EQUAL_INT16(0, ht_speed_hold_step(&b, &spd_s, 5000, 4000, 0));
    TEST_ASSERT_EQUAL_INT16(0, ht_speed_hold_step(&spd, NULL, 5000, 4000, 0));
}

static void test_speed_trim_at_target_and_proportional(void)
{
    TEST_ASSERT_EQUAL_INT16(Q14_FROM_REAL(0.5), ht_speed_hold_step(&spd, &spd_s, 5000, 5000, 0));
    /* 1 m/s slow: +0.1 -> 0.6 within one LSB */
    TEST_ASSERT_INT16_WITHIN(1, Q14_FROM_REAL(0.6),
                             ht_speed_hold_step(&spd, &spd_s, 5000, 4900, 0));
    TEST_ASSERT_INT16_WITHIN(1, Q14_FROM_REAL(0.4),
                             ht_speed_hold_step(&spd, &spd_s, 5000, 5100, 0));
}

static void test_speed_pitch_feed_forward(void)
{
    spd.kff_throttle_per_pitch = Q16_FROM_REAL(1.0);
    TEST_ASSERT_INT16_WITHIN(1, Q14_FROM_REAL(0.6),
                             ht_speed_hold_step(&spd, &spd_s, 5000, 5000, Q16_FROM_REAL(0.1)));
    TEST_ASSERT_INT16_WITHIN(1, Q14_FROM_REAL(0.4),
                             ht_speed_hold_step(&spd, &spd_s, 5000, 5000, Q16_FROM_REAL(-0.1)));
}

static void test_speed_clamps_to_limits_over_whole_range(void)
{
    spd.throttle_min = Q14_FROM_REAL(0.1);
    spd.throttle_max = Q14_FROM_REAL(0.9);
    spd.kp_throttle_per_m_s = 64 * Q16_ONE;
    spd.kff_throttle_per_pitch = 64 * Q16_ONE;
    TEST_ASSERT_EQUAL_INT16(spd.throttle_max,
                            ht_speed_hold_step(&spd, &spd_s, INT16_MAX, INT16_MIN, INT32_MAX));
    TEST_ASSERT_EQUAL_INT16(spd.throttle_min,
                            ht_speed_hold_step(&spd, &spd_s, INT16_MIN, INT16_MAX, INT32_MIN));
    /* opposite saturated terms cancel: still within the limits */
    q14_t th = ht_speed_hold_step(&spd, &spd_s, INT16_MAX, INT16_MIN, INT32_MIN);
    TEST_ASSERT_TRUE(th >= spd.throttle_min && th <= spd.throttle_max);
}

static void test_speed_integral_and_antiwindup(void)
{
    spd.kp_throttle_per_m_s = 0;
    spd.ki_throttle_per_m = Q16_FROM_REAL(0.04);
    /* 1 m/s slow for 1 s -> +0.04 */
    q14_t th = 0;
    for (int i = 0; i < 40; ++i) {
        th = ht_speed_hold_step(&spd, &spd_s, 5000, 4900, 0);
    }
    TEST_ASSERT_INT16_WITHIN(2, Q14_FROM_REAL(0.54), th);
    /* Saturated at max: the integral stops growing. */
    ht_speed_hold_reset(&spd_s);
    spd.throttle_trim = Q14_ONE;
    for (int i = 0; i < 400; ++i) {
        TEST_ASSERT_EQUAL_INT16(Q14_ONE, ht_speed_hold_step(&spd, &spd_s, 5000, 4000, 0));
    }
    TEST_ASSERT_EQUAL_INT32(0, spd_s.integral_q20);
    /* clamp of the integral itself */
    spd.throttle_trim = Q14_FROM_REAL(0.5);
    spd.max_integral_throttle = Q14_FROM_REAL(0.25);
    spd.ki_throttle_per_m = Q16_ONE;
    for (int i = 0; i < 4000; ++i) {
        (void)ht_speed_hold_step(&spd, &spd_s, 5000, 4000, 0);
    }
    TEST_ASSERT_EQUAL_INT32(Q14_FROM_REAL(0.25) * 64, spd_s.integral_q20);
    TEST_ASSERT_EQUAL_INT16(Q14_FROM_REAL(0.75), ht_speed_hold_step(&spd, &spd_s, 5000, 5000, 0));
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_alt_check_accepts_valid_and_rejects_each_bad_field);
    RUN_TEST(test_alt_null_and_bad_params_give_zero_and_keep_state);
    RUN_TEST(test_alt_proportional_exact_value_and_sign);
    RUN_TEST(test_alt_same_request_upright_and_inverted);
    RUN_TEST(test_alt_saturates_at_max_pitch_over_whole_input_range);
    RUN_TEST(test_alt_just_below_saturation_is_not_clamped);
    RUN_TEST(test_alt_vertical_speed_damps);
    RUN_TEST(test_alt_integral_accumulates_exactly_per_orientation);
    RUN_TEST(test_alt_integrates_only_inside_the_band);
    RUN_TEST(test_alt_integral_rounding_is_symmetric);
    RUN_TEST(test_alt_integral_clamped_and_no_windup_when_saturated);
    RUN_TEST(test_alt_protection_check_rejects_each_bad_field);
    RUN_TEST(test_alt_protection_off_is_the_plain_step);
    RUN_TEST(test_alt_protection_ceiling_exact_values);
    RUN_TEST(test_alt_protection_only_cuts_the_climb_demand);
    RUN_TEST(test_alt_protection_ignores_a_failed_sensor);
    RUN_TEST(test_alt_protection_no_windup_against_the_ceiling);
    RUN_TEST(test_alt_protection_filter);
    RUN_TEST(test_alt_protection_survives_a_corrupt_state);
    RUN_TEST(test_speed_check_rejects_each_bad_field);
    RUN_TEST(test_speed_trim_at_target_and_proportional);
    RUN_TEST(test_speed_pitch_feed_forward);
    RUN_TEST(test_speed_clamps_to_limits_over_whole_range);
    RUN_TEST(test_speed_integral_and_antiwindup);
    return UNITY_END();
}
