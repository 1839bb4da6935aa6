/*
 * test_fw_link_joint.c - a parameter set from the ground station against
 * the joint rule of the configuration (helical/guidance/config_check.h) and
 * against the flight state, on a flying firmware step (issue 33, items 1-3
 * and 12):
 *   - each combination issue 33 found accepted in flight (the inverted
 *     switch on a stick or the mode switch, its threshold at 800 us, the
 *     mode switch on the aileron, a mode input the 6-channel receiver does
 *     not have, an arrival radius beyond half the spacing of the flown
 *     list) is refused whole: the row keeps its value, the running modes are
 *     the old ones, the refusal's text names the rule; with centred sticks
 *     in fly-by-wire the law is never asked for inverted flight;
 *   - ALT_MAX_INTEGRAL lowered in flight: the integrators are within the
 *     new bound from the next control step.
 * The set goes through fw_link_param_set, the function PARAM_SET calls.
 */
#include "unity.h"

#include "link/fw_link.h"
#include "link/fw_link_param_table.h"

#include <string.h>

static fw_config_t cfg;
static fw_t fw;
static fw_link_t lk;
static fw_inputs_t in;
static fw_output_t out;
static uint32_t samples;

static const ht_waypoint_t square[4] = {
    {200, -200, 100}, {200, 200, 100}, {-200, 200, 100}, {-200, -200, 100}};

void setUp(void)
{
    fw_config_default(&cfg);
    cfg.modes.rc_channels = 6u; /* a 6-channel receiver */
    cfg.waypoints = square;
    cfg.waypoint_count = 4u;
    TEST_ASSERT_EQUAL_INT(1, fw_init(&fw, &cfg));
    TEST_ASSERT_EQUAL_INT(0, fw_link_init(&lk, &fw, &cfg, 1u, 1u));
    memset(&in, 0, sizeof in);
    memset(&out, 0, sizeof out);
    in.sensors.imu_fresh = 1u;
    in.sensors.imu.accel_g[2] = -Q16_ONE; /* level */
    in.sensors.airspeed_fresh = 1u;
    in.sensors.airspeed_cm_s = 1500;
    in.sensors.baro_fresh = 1u;
    in.sensors.baro_alt_cm = 50000;
    in.rc_count = 6u;
    for (unsigned i = 0u; i < 6u; ++i) {
        in.rc_us[i] = 1500u; /* every channel centred, the inverted switch too */
    }
    in.rc_us[2] = 1000u;
    in.rc_us[4] = 1500u; /* the mode switch: fly-by-wire */
    in.rc_fresh = 1u;
    samples = 0u;
}

void tearDown(void) {}

static void steps(unsigned k)
{
    for (unsigned j = 0u; j < k; ++j) {
        int ran = 0;
        while (ran == 0) {
            ++samples;
            ran = fw_step(&fw, &in, &out);
        }
    }
}

static uint16_t index_of(const char *id)
{
    const int32_t i = fw_link_param_find(id);
    TEST_ASSERT_TRUE_MESSAGE(i >= 0, id);
    return (uint16_t)i;
}

static int32_t value_of(const char *id)
{
    int32_t raw = 0;
    TEST_ASSERT_EQUAL_INT(0, fw_link_param_get(&lk, index_of(id), &raw, NULL));
    return raw;
}

static void test_each_unsafe_combination_is_refused_whole(void)
{
    static const struct {
        const char *id;
        int32_t raw;
        const char *why;
    } cases[] = {
        {"FBW_INVERTD_INPT", 0, "joint.inverted_input is a stick channel"},
        {"FBW_INVERTD_INPT", 3, "joint.inverted_input is a stick channel"},
        {"FBW_INVERTD_INPT", 4, "joint.inverted_input is the mode_input"},
        {"FBW_INVERTD_INPT", 15, "joint.inverted_input is not a receiver channel"},
        {"FBW_INVRTD_THRSH", 800, "joint.inverted_threshold_us not in (centre, full]"},
        {"FBW_INVRTD_THRSH", 1500, "joint.inverted_threshold_us not in (centre, full]"},
        {"MOD_MODE_INPUT", 0, "joint.mode_input is a stick channel"},
        {"MOD_MODE_INPUT", 15, "joint.mode_input is not a receiver channel"},
        {"NAV_ARRIVAL_RADS", 200, "joint.arrival_radius_m not below half a leg"},
    };
    steps(40u);
    TEST_ASSERT_EQUAL_UINT8(HT_MODE_FBW, out.modes.mode);
    for (unsigned i = 0u; i < sizeof cases / sizeof cases[0]; ++i) {
        char id[17];
        const uint16_t index = index_of(cases[i].id);
        TEST_ASSERT_EQUAL_INT(0, fw_link_param_id(index, id));
        const int32_t before = value_of(id);
        const ht_modes_t modes_before = fw.modes;
        TEST_ASSERT_EQUAL_INT_MESSAGE(2, fw_link_param_set(&lk, index, cases[i].raw), id);
        TEST_ASSERT_EQUAL_INT32_MESSAGE(before, value_of(id), id);
        TEST_ASSERT_EQUAL_MEMORY_MESSAGE(&modes_before, &fw.modes, sizeof modes_before, id);
        TEST_ASSERT_EQUAL_STRING_MESSAGE(cases[i].why, lk.param_refusal, id);
        TEST_ASSERT_TRUE(strlen(lk.param_refusal) <= 49u);
        steps(20u);
        TEST_ASSERT_EQUAL_UINT8_MESSAGE(0u, out.modes.law_in.inverted, id);
        TEST_ASSERT_EQUAL_UINT8_MESSAGE(HT_MODE_FBW, out.modes.mode, id);
        TEST_ASSERT_EQUAL_UINT8_MESSAGE(0u, out.modes.failsafe, id);
    }
    /* a safe value of the same rows is applied, and the text cleared */
    TEST_ASSERT_EQUAL_INT(0, fw_link_param_set(&lk, index_of("NAV_ARRIVAL_RADS"), 199));
    TEST_ASSERT_EQUAL_STRING("", lk.param_refusal);
    TEST_ASSERT_EQUAL_INT(0, fw_link_param_set(&lk, index_of("FBW_INVRTD_THRSH"), 1501));
    /* out of its row: named by the row */
    TEST_ASSERT_EQUAL_INT(1, fw_link_param_set(&lk, index_of("MOD_MODE_INPUT"), 16));
    TEST_ASSERT_EQUAL_STRING("MOD_MODE_INPUT out of range", lk.param_refusal);
    steps(4u);
    TEST_ASSERT_EQUAL_UINT8(1u, fw.ready);
}

static void test_alt_max_integral_lowered_in_flight_clamps_at_once(void)
{
    /* the integrators as a long climb leaves them: at the old bound */
    const int32_t old_q20 = cfg.modes.alt.max_integral_pitch * 16;
    fw.modes_state.alt.integral_q20[0] = old_q20;
    fw.modes_state.alt.integral_q20[1] = -old_q20;
    in.rc_us[4] = 1800u; /* waypoint mode: the altitude hold runs */
    steps(2u);
    const q16_t lower = 3277; /* 0.05 */
    TEST_ASSERT_EQUAL_INT(0, fw_link_param_set(&lk, index_of("ALT_MAX_INTEGRAL"), lower));
    steps(1u);
    const int32_t bound_q20 = (int32_t)lower * 16;
    TEST_ASSERT_INT32_WITHIN(bound_q20, 0, fw.modes_state.alt.integral_q20[0]);
    TEST_ASSERT_INT32_WITHIN(bound_q20, 0, fw.modes_state.alt.integral_q20[1]);
    TEST_ASSERT_TRUE(fw.modes_state.alt.integral_q20[1] == -bound_q20); /* not reset: clamped */
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_each_unsafe_combination_is_refused_whole);
    RUN_TEST(test_alt_max_integral_lowered_in_flight_clamps_at_once);
    return UNITY_END();
}
