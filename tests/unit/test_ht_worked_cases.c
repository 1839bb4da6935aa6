/*
 * The worked cases: control-law.md's checks and the source text's Eq. A.14 to
 * A.17, each in both pitch modes where the text compares them.
 */
#include <math.h>

#include "ht_test_support.h"
#include "unity.h"

/* One LSB of Q14 is 6.1e-5; the expected values below are exact math, so the
 * core may be off by its rounding (about an LSB) and the text's own rounding
 * of the quoted figures (3 digits). */
#define TOL_Q14 (2.0 / 16384.0)

static ht_controller_t ctl_default;

void setUp(void)
{
    const ht_params_t p = HT_PARAMS_DEFAULT;
    TEST_ASSERT_EQUAL_INT(HT_OK, ht_init(&ctl_default, &p, NULL));
}
void tearDown(void) {}

static ht_input_t level_input(void)
{
    ht_input_t in = {0};
    in.z = Q14_ONE;
    in.airspeed_cm_s = 1500;
    return in;
}

static double q14(q14_t v)
{
    return v / 16384.0;
}

static void step_mode(ht_pitch_mode_t mode, const ht_input_t *in, ht_output_t *out)
{
    ht_params_t p = HT_PARAMS_DEFAULT;
    p.pitch_mode = (uint8_t)mode;
    ht_controller_t ctl;
    TEST_ASSERT_EQUAL_INT(HT_OK, ht_init(&ctl, &p, NULL));
    ht_step(&ctl, in, out);
}

/* control-law.md: level, S = 15 m/s, turn rate 0.5 rad/s -> roll right. */
static void test_spec_turn_rate_half_rad_s(void)
{
    ht_input_t in = level_input();
    in.turn_rate_rad_s = Q11_FROM_REAL(0.5);
    ht_output_t out;
    ht_step(&ctl_default, &in, &out);
    double ratio = 0.5 * 15.0 / 9.80665;
    double expect = ratio / sqrt(ratio * ratio + 1.0); /* 0.6075 */
    TEST_ASSERT_DOUBLE_WITHIN(TOL_Q14, -expect, q14(out.tilt_x));
    TEST_ASSERT_DOUBLE_WITHIN(TOL_Q14, -expect, q14(out.roll_error));
    TEST_ASSERT_DOUBLE_WITHIN(TOL_Q14, expect, q14(out.aileron));
    TEST_ASSERT_DOUBLE_WITHIN(0.001, 0.607, q14(out.aileron));
}

/* control-law.md: pitch 0.2 -> nose up. */
static void test_spec_pitch_point_two(void)
{
    ht_input_t in = level_input();
    in.pitch_ratio = Q16_FROM_REAL(0.2);
    ht_output_t out;
    ht_step(&ctl_default, &in, &out);
    double expect = 0.2 / sqrt(1.04); /* 0.1961 */
    TEST_ASSERT_DOUBLE_WITHIN(TOL_Q14, -expect, q14(out.tilt_y));
    TEST_ASSERT_DOUBLE_WITHIN(TOL_Q14, -expect, q14(out.pitch_error));
    TEST_ASSERT_DOUBLE_WITHIN(TOL_Q14, expect, q14(out.elevator));
    TEST_ASSERT_EQUAL_INT(0, out.aileron);
    TEST_ASSERT_EQUAL_INT(0, out.rudder);
}

/* control-law.md: inverted target, R = [0, 0.1, -0.995] (nose low) -> push. */
static void test_spec_inverted_nose_low_pushes(void)
{
    ht_input_t in = level_input();
    in.inverted = 1;
    in.y = Q14_FROM_REAL(0.1);
    in.z = Q14_FROM_REAL(-0.995);
    ht_output_t out;
    ht_step(&ctl_default, &in, &out);
    /* pe = 0*a - 0.1*1 = -0.1; body x = pe/a * -Z = -0.1 * 0.995/0.995 = -0.1 */
    TEST_ASSERT_DOUBLE_WITHIN(TOL_Q14, -0.1, q14(out.elevator));
    TEST_ASSERT_DOUBLE_WITHIN(TOL_Q14, -1.0, q14(out.tilt_z));
}

/* control-law.md: R = [1, 0.1, 0] (90 deg left bank, nose low), level target:
 * aileron +1 (roll right), rudder +0.1 holds the nose up (Eq. A.16). */
static void test_spec_knife_edge_rudder_holds_nose(void)
{
    ht_input_t in = level_input();
    in.x = Q14_ONE;
    in.y = Q14_FROM_REAL(0.1);
    in.z = 0;
    ht_output_t out;
    ht_step(&ctl_default, &in, &out);
    TEST_ASSERT_EQUAL_INT(Q14_ONE, out.aileron);
    TEST_ASSERT_DOUBLE_WITHIN(TOL_Q14, 0.1, q14(out.rudder));
    TEST_ASSERT_DOUBLE_WITHIN(TOL_Q14, 0.0, q14(out.elevator));
    TEST_ASSERT_TRUE((out.flags & HT_F_ROLL_BEYOND_90) != 0);
}

/* Eq. A.14: level target, pitch only: both methods give [Y, 0, 0]; inverted
 * flips the sign. */
static void check_pitch_only(int inverted, double y)
{
    ht_input_t in = level_input();
    in.inverted = (uint8_t)inverted;
    in.y = Q14_FROM_REAL(y);
    double z = sqrt(1.0 - y * y);
    in.z = ts_fix16(inverted ? -z : z, 14);
    double sign = inverted ? -1.0 : 1.0;
    for (int mode = 0; mode < 2; mode++) {
        ht_output_t out;
        step_mode((ht_pitch_mode_t)mode, &in, &out);
        TEST_ASSERT_DOUBLE_WITHIN(TOL_Q14, sign * y, q14(out.pitch_body_x));
        TEST_ASSERT_DOUBLE_WITHIN(TOL_Q14, 0.0, q14(out.pitch_body_z));
    }
}

static void test_eq_a14_pitch_only_normal_and_inverted(void)
{
    check_pitch_only(0, 0.2);
    check_pitch_only(0, -0.3);
    check_pitch_only(1, 0.2);
    check_pitch_only(1, -0.3);
}

/* Eq. A.15 and A.16: target inverted level, half-way through the roll (Z = 0,
 * X close to 1): the tilt cross product uses the elevator ([-Y, 0, 0]), the
 * earth-frame method the rudder ([0, 0, -Y]). */
static void test_eq_a15_a16_half_way_roll_to_inverted(void)
{
    const double y = 0.15;
    ht_input_t in = level_input();
    in.inverted = 1;
    in.x = Q14_FROM_REAL(0.988686);
    in.y = Q14_FROM_REAL(y);
    in.z = 0;
    ht_output_t cross, earth;
    step_mode(HT_PITCH_TILT_CROSS, &in, &cross);
    step_mode(HT_PITCH_EARTH_FRAME, &in, &earth);
    TEST_ASSERT_DOUBLE_WITHIN(TOL_Q14, -y, q14(cross.pitch_body_x));
    TEST_ASSERT_DOUBLE_WITHIN(TOL_Q14, 0.0, q14(cross.pitch_body_z));
    TEST_ASSERT_DOUBLE_WITHIN(TOL_Q14, 0.0, q14(earth.pitch_body_x));
    TEST_ASSERT_DOUBLE_WITHIN(TOL_Q14, -y, q14(earth.pitch_body_z));
    /* and so the earth-frame method raises the nose with the rudder (the
     * aircraft turns against e: rudder = -kp * e_z = +Y, nose right, which is
     * up in a left knife edge), the cross product with the elevator */
    TEST_ASSERT_DOUBLE_WITHIN(TOL_Q14, 0.0, q14(earth.elevator));
    TEST_ASSERT_DOUBLE_WITHIN(TOL_Q14, y, q14(earth.rudder));
    TEST_ASSERT_DOUBLE_WITHIN(TOL_Q14, -y, q14(cross.elevator));
    TEST_ASSERT_DOUBLE_WITHIN(TOL_Q14, 0.0, q14(cross.rudder));
}

/* Eq. A.17: in a turn with the roll already right, target pitch 0, actual
 * pitch Y: both methods give Y * [Zt, 0, -Xt]. */
static void test_eq_a17_turn_with_roll_right(void)
{
    ht_input_t in = level_input();
    in.turn_rate_rad_s = Q11_FROM_REAL(0.5);
    ht_output_t target;
    ht_step(&ctl_default, &in, &target);
    double xt = q14(target.tilt_x), zt = q14(target.tilt_z);
    const double y = -0.12; /* nose up */
    double c = sqrt(1.0 - y * y);
    in.x = ts_fix16(xt * c, 14);
    in.y = ts_fix16(y, 14);
    in.z = ts_fix16(zt * c, 14);
    for (int mode = 0; mode < 2; mode++) {
        ht_output_t out;
        step_mode((ht_pitch_mode_t)mode, &in, &out);
        TEST_ASSERT_DOUBLE_WITHIN(2 * TOL_Q14, y * zt, q14(out.pitch_body_x));
        TEST_ASSERT_DOUBLE_WITHIN(2 * TOL_Q14, -y * xt, q14(out.pitch_body_z));
        TEST_ASSERT_DOUBLE_WITHIN(2 * TOL_Q14, 0.0, q14(out.roll_error));
    }
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_spec_turn_rate_half_rad_s);
    RUN_TEST(test_spec_pitch_point_two);
    RUN_TEST(test_spec_inverted_nose_low_pushes);
    RUN_TEST(test_spec_knife_edge_rudder_holds_nose);
    RUN_TEST(test_eq_a14_pitch_only_normal_and_inverted);
    RUN_TEST(test_eq_a15_a16_half_way_roll_to_inverted);
    RUN_TEST(test_eq_a17_turn_with_roll_right);
    return UNITY_END();
}
