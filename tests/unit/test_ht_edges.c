/*
 * Boundaries of the control law: a vertical fuselage, INT16_MIN/INT32_MIN
 * inputs, zero, negative and huge airspeed, exactly opposite target and
 * actual tilt, the tilt limit, bad parameters and NULL pointers.
 */
#include <math.h>

#include "ht_test_support.h"
#include "unity.h"

#define TOL_Q14 (2.0 / 16384.0)

static ht_controller_t ctl;

void setUp(void)
{
    const ht_params_t p = HT_PARAMS_DEFAULT;
    TEST_ASSERT_EQUAL_INT(HT_OK, ht_init(&ctl, &p, NULL));
}
void tearDown(void) {}

static void assert_bounded(const ht_output_t *o)
{
    TEST_ASSERT_TRUE(o->aileron >= -Q14_ONE && o->aileron <= Q14_ONE);
    TEST_ASSERT_TRUE(o->elevator >= -Q14_ONE && o->elevator <= Q14_ONE);
    TEST_ASSERT_TRUE(o->rudder >= -Q14_ONE && o->rudder <= Q14_ONE);
    /* the target tilt is a unit vector whatever the inputs */
    double n = sqrt((double)o->tilt_x * o->tilt_x + (double)o->tilt_y * o->tilt_y +
                    (double)o->tilt_z * o->tilt_z) /
               16384.0;
    TEST_ASSERT_DOUBLE_WITHIN(3.0 / 16384.0, 1.0, n);
}

/* X = Z = 0: the projection direction is defined as [-1, 0, 0]. */
static void test_vertical_fuselage_is_finite_and_documented(void)
{
    const q14_t ys[2] = {Q14_ONE, -Q14_ONE};
    for (int k = 0; k < 2; k++) {
        ht_input_t in = {0};
        in.y = ys[k];
        in.airspeed_cm_s = 1500;
        in.pitch_ratio = Q16_FROM_REAL(0.3);
        ht_output_t out;
        ht_step(&ctl, &in, &out);
        TEST_ASSERT_TRUE((out.flags & HT_F_FUSELAGE_VERTICAL) != 0);
        TEST_ASSERT_EQUAL_INT(-out.pitch_error, out.pitch_body_x);
        TEST_ASSERT_EQUAL_INT(0, out.pitch_body_z);
        assert_bounded(&out);
        /* and the reference, which documents the same choice, agrees */
        ht_ref_params_t rp;
        ht_ref_input_t ri;
        ht_ref_output_t ro;
        ht_ref_params_from_controller(&ctl, &rp);
        ht_ref_input_from_fixed(&in, &ri);
        ht_ref_step(&rp, &ri, &ro);
        TEST_ASSERT_DOUBLE_WITHIN(TOL_Q14, ro.pitch_error, out.pitch_error / 16384.0);
        TEST_ASSERT_DOUBLE_WITHIN(TOL_Q14, ro.elevator, out.elevator / 16384.0);
    }
}

/* A fuselage one LSB away from vertical still has a direction. */
static void test_nearly_vertical_fuselage_uses_the_tiny_direction(void)
{
    ht_input_t in = {0};
    in.x = 1; /* 6e-5: the smallest left bank there is */
    in.y = Q14_ONE;
    in.airspeed_cm_s = 1500;
    ht_output_t out;
    ht_step(&ctl, &in, &out);
    TEST_ASSERT_FALSE((out.flags & HT_F_FUSELAGE_VERTICAL) != 0);
    TEST_ASSERT_EQUAL_INT(0, out.pitch_body_x);
    TEST_ASSERT_EQUAL_INT(out.pitch_error, out.pitch_body_z);
}

/* Every field at its most negative value, and at its most positive. */
static void test_extreme_inputs_give_bounded_outputs(void)
{
    ht_input_t lo = {INT16_MIN,
                     INT16_MIN,
                     INT16_MIN,
                     INT16_MIN,
                     INT32_MIN,
                     INT16_MIN,
                     {INT16_MIN, INT16_MIN, INT16_MIN},
                     1,
                     INT16_MIN,
                     INT16_MIN};
    ht_input_t hi = {INT16_MAX,
                     INT16_MAX,
                     INT16_MAX,
                     INT16_MAX,
                     INT32_MAX,
                     INT16_MAX,
                     {INT16_MAX, INT16_MAX, INT16_MAX},
                     0,
                     INT16_MAX,
                     INT16_MAX};
    for (int set = 0; set < ts_gain_set_count; set++) {
        ht_controller_t c;
        TEST_ASSERT_EQUAL_INT(HT_OK, ht_init(&c, &ts_gain_sets[set].params, NULL));
        ht_output_t out;
        ht_step(&c, &lo, &out);
        assert_bounded(&out);
        TEST_ASSERT_TRUE((out.flags & HT_F_AIRSPEED_FLOORED) != 0);
        TEST_ASSERT_TRUE((out.flags & HT_F_TILT_LIMITED) != 0);
        /* pitch ratio -32768: target nose straight down (tilt_y = +1) */
        TEST_ASSERT_INT_WITHIN(1, Q14_ONE, out.tilt_y);
        ht_step(&c, &hi, &out);
        assert_bounded(&out);
        TEST_ASSERT_INT_WITHIN(1, -Q14_ONE, out.tilt_y);
    }
}

/* Field by field: the struct has padding, so memcmp would compare garbage. */
static void assert_same_outputs(const ht_output_t *a, const ht_output_t *b)
{
    TEST_ASSERT_EQUAL_INT(a->turn_rate_used_rad_s, b->turn_rate_used_rad_s);
    TEST_ASSERT_EQUAL_INT32(a->tilt_ratio, b->tilt_ratio);
    const q14_t va[] = {a->tilt_x,       a->tilt_y,       a->tilt_z,       a->rate_x_rad_s,
                        a->rate_y_rad_s, a->rate_z_rad_s, a->roll_dot,     a->roll_cross,
                        a->roll_error,   a->pitch_error,  a->pitch_body_x, a->pitch_body_z,
                        a->aileron,      a->elevator,     a->rudder};
    const q14_t vb[] = {b->tilt_x,       b->tilt_y,       b->tilt_z,       b->rate_x_rad_s,
                        b->rate_y_rad_s, b->rate_z_rad_s, b->roll_dot,     b->roll_cross,
                        b->roll_error,   b->pitch_error,  b->pitch_body_x, b->pitch_body_z,
                        b->aileron,      b->elevator,     b->rudder};
    TEST_ASSERT_EQUAL_INT16_ARRAY(va, vb, sizeof va / sizeof va[0]);
}

/* Zero and negative airspeed use v_min; the result equals the v_min result. */
static void test_zero_and_negative_airspeed_use_v_min(void)
{
    ht_input_t in = {0};
    in.z = Q14_ONE;
    in.turn_rate_rad_s = Q11_FROM_REAL(0.5);
    in.gyro_rad_s[1] = Q11_FROM_REAL(0.2);
    ht_output_t at_min, at_zero, at_neg;
    in.airspeed_cm_s = 500;
    ht_step(&ctl, &in, &at_min);
    in.airspeed_cm_s = 0;
    ht_step(&ctl, &in, &at_zero);
    in.airspeed_cm_s = -3000;
    ht_step(&ctl, &in, &at_neg);
    assert_same_outputs(&at_min, &at_zero);
    assert_same_outputs(&at_min, &at_neg);
    TEST_ASSERT_TRUE((at_zero.flags & HT_F_AIRSPEED_FLOORED) != 0);
    TEST_ASSERT_FALSE((at_min.flags & HT_F_AIRSPEED_FLOORED) != 0);
}

/* Huge airspeed: the tilt limit holds the bank at max_tilt, the turn rate used
 * falls to max_tilt * g / S, and the feed-forward scale v_ref / S is small. */
static void test_huge_airspeed_limits_tilt(void)
{
    ht_input_t in = {0};
    in.z = Q14_ONE;
    in.turn_rate_rad_s = Q11_FROM_REAL(1.0);
    in.airspeed_cm_s = INT16_MAX;
    ht_output_t out;
    ht_step(&ctl, &in, &out);
    TEST_ASSERT_TRUE((out.flags & HT_F_TILT_LIMITED) != 0);
    TEST_ASSERT_EQUAL_INT32(4 * Q16_ONE, out.tilt_ratio);
    double omega = 4.0 * 9.80665 / 327.67;
    TEST_ASSERT_DOUBLE_WITHIN(0.51 / 2048.0, omega, out.turn_rate_used_rad_s / 2048.0);
    TEST_ASSERT_DOUBLE_WITHIN(TOL_Q14, -4.0 / sqrt(17.0), out.tilt_x / 16384.0);
}

/* The tilt limit at 15 m/s: 10 rad/s asks ratio 15.3, gets 4 at 2.615 rad/s. */
static void test_tilt_limit_sets_turn_rate_used(void)
{
    ht_input_t in = {0};
    in.z = Q14_ONE;
    in.turn_rate_rad_s = Q11_FROM_REAL(-10.0);
    in.airspeed_cm_s = 1500;
    ht_output_t out;
    ht_step(&ctl, &in, &out);
    TEST_ASSERT_EQUAL_INT32(-4 * Q16_ONE, out.tilt_ratio);
    TEST_ASSERT_DOUBLE_WITHIN(0.51 / 2048.0, -4.0 * 9.80665 / 15.0,
                              out.turn_rate_used_rad_s / 2048.0);
    /* Eq. 3 with the actual row [0, 0, 1]: all of it about body Z */
    TEST_ASSERT_EQUAL_INT(out.turn_rate_used_rad_s, out.rate_z_rad_s);
}

/* Exactly opposite: level target, inverted actual. roll_dot = -1, cross = 0,
 * so roll_error = sign(0) = +1 and the aileron is -kp: a full roll left. */
static void test_exactly_opposite_tilt_rolls_deterministically(void)
{
    ht_input_t in = {0};
    in.z = -Q14_ONE;
    in.airspeed_cm_s = 1500;
    ht_output_t out;
    ht_step(&ctl, &in, &out);
    TEST_ASSERT_EQUAL_INT(-Q14_ONE, out.roll_dot);
    TEST_ASSERT_EQUAL_INT(0, out.roll_cross);
    TEST_ASSERT_EQUAL_INT(Q14_ONE, out.roll_error);
    TEST_ASSERT_EQUAL_INT(-Q14_ONE, out.aileron);
    TEST_ASSERT_EQUAL_INT(0, out.elevator);
    /* and the other way round: inverted target, upright actual */
    in.z = Q14_ONE;
    in.inverted = 1;
    ht_step(&ctl, &in, &out);
    TEST_ASSERT_EQUAL_INT(Q14_ONE, out.roll_error);
    TEST_ASSERT_EQUAL_INT(-Q14_ONE, out.aileron);
}

/* Opposite in pitch: nose straight down, target nose straight up: the pitch
 * error saturates at -1 (pull). */
static void test_opposite_pitch_saturates(void)
{
    ht_input_t in = {0};
    in.y = Q14_ONE;
    in.z = 1;
    in.airspeed_cm_s = 1500;
    in.pitch_ratio = INT32_MAX;
    ht_output_t out;
    ht_step(&ctl, &in, &out);
    TEST_ASSERT_TRUE((out.flags & HT_F_PITCH_BEYOND_90) != 0);
    TEST_ASSERT_EQUAL_INT(-Q14_ONE, out.pitch_error);
    TEST_ASSERT_EQUAL_INT(Q14_ONE, out.elevator);
}

static void test_surface_saturation_flag(void)
{
    ht_input_t in = {0};
    in.z = Q14_ONE;
    in.airspeed_cm_s = 1500;
    ht_output_t out;
    ht_step(&ctl, &in, &out);
    TEST_ASSERT_EQUAL_UINT8(0, out.flags);
    in.gyro_rad_s[1] = Q11_FROM_REAL(3.0);
    ht_params_t p = HT_PARAMS_DEFAULT;
    p.kd_aileron = Q16_FROM_REAL(1.0);
    ht_controller_t c;
    TEST_ASSERT_EQUAL_INT(HT_OK, ht_init(&c, &p, NULL));
    ht_step(&c, &in, &out);
    TEST_ASSERT_EQUAL_INT(-Q14_ONE, out.aileron);
    TEST_ASSERT_TRUE((out.flags & HT_F_SURFACE_SATURATED) != 0);
}

static void test_null_and_uninitialised_give_zero_surfaces(void)
{
    ht_input_t in = {0};
    in.z = Q14_ONE;
    in.turn_rate_rad_s = Q11_FROM_REAL(1.0);
    ht_output_t out;
    out.aileron = 123;
    ht_step(NULL, &in, &out);
    TEST_ASSERT_EQUAL_INT(0, out.aileron);
    out.aileron = 123;
    ht_step(&ctl, NULL, &out);
    TEST_ASSERT_EQUAL_INT(0, out.aileron);
    ht_step(&ctl, &in, NULL); /* nothing to write: must not crash */
    ht_controller_t zeroed = {0};
    out.aileron = 123;
    ht_step(&zeroed, &in, &out);
    TEST_ASSERT_EQUAL_INT(0, out.aileron);
    TEST_ASSERT_EQUAL_INT(HT_ERR_NULL, ht_init(NULL, NULL, NULL));
}

/* Each parameter out of range is refused, naming the field, and leaves the
 * controller unusable. */
static void check_refused(ht_params_t p, ht_param_id_t field, const char *name)
{
    ht_controller_t c;
    ht_param_id_t bad = HT_P_NONE;
    TEST_ASSERT_EQUAL_INT(HT_ERR_PARAM, ht_init(&c, &p, &bad));
    TEST_ASSERT_EQUAL_INT(field, bad);
    TEST_ASSERT_EQUAL_STRING(name, ht_param_name(bad));
    TEST_ASSERT_EQUAL_UINT8(0, c.ready);
}

static void test_bad_parameters_are_refused_by_name(void)
{
    const ht_params_t d = HT_PARAMS_DEFAULT;
    ht_params_t p;
    p = d;
    p.kp_aileron = -1;
    check_refused(p, HT_P_KP_AILERON, "kp_aileron");
    p = d;
    p.kp_rudder = 64 * Q16_ONE + 1;
    check_refused(p, HT_P_KP_RUDDER, "kp_rudder");
    p = d;
    p.kff_elevator = -Q16_ONE;
    check_refused(p, HT_P_KFF_ELEVATOR, "kff_elevator");
    p = d;
    p.kd_rudder = INT32_MIN;
    check_refused(p, HT_P_KD_RUDDER, "kd_rudder");
    p = d;
    p.v_min_cm_s = 0;
    check_refused(p, HT_P_V_MIN, "v_min");
    p = d;
    p.v_min_cm_s = -500;
    check_refused(p, HT_P_V_MIN, "v_min");
    p = d;
    p.v_ref_cm_s = 499;
    check_refused(p, HT_P_V_REF, "v_ref");
    p = d;
    p.v_ref_cm_s = 40000;
    check_refused(p, HT_P_V_REF, "v_ref");
    p = d;
    p.schedule = 2;
    check_refused(p, HT_P_SCHEDULE, "schedule");
    p = d;
    p.max_tilt = 0;
    check_refused(p, HT_P_MAX_TILT, "max_tilt");
    p = d;
    p.max_tilt = 8 * Q16_ONE + 1;
    check_refused(p, HT_P_MAX_TILT, "max_tilt");
    p = d;
    p.pitch_mode = 7;
    check_refused(p, HT_P_PITCH_MODE, "pitch_mode");
    /* the limits themselves are accepted */
    p = d;
    p.kp_aileron = 64 * Q16_ONE;
    p.max_tilt = 8 * Q16_ONE;
    p.v_min_cm_s = 100;
    p.v_ref_cm_s = 3200; /* the largest scale, 32 */
    ht_controller_t c;
    TEST_ASSERT_EQUAL_INT(HT_OK, ht_init(&c, &p, NULL));
    p.v_min_cm_s = 1024;
    p.v_ref_cm_s = INT16_MAX;
    TEST_ASSERT_EQUAL_INT(HT_OK, ht_init(&c, &p, NULL));
    TEST_ASSERT_EQUAL_STRING("", ht_param_name(HT_P_COUNT));
}

/* v_ref / v_min <= 32: at the bound accepted, one cm/s beyond refused. */
static void test_scale_limit_is_exact(void)
{
    ht_params_t p = HT_PARAMS_DEFAULT;
    p.v_min_cm_s = 500;
    p.v_ref_cm_s = 16000;
    ht_controller_t c;
    TEST_ASSERT_EQUAL_INT(HT_OK, ht_init(&c, &p, NULL));
    p.v_ref_cm_s = 16001;
    check_refused(p, HT_P_V_REF, "v_ref");
    /* 32767 needs v_min >= 1024 (1023 * 32 = 32736) */
    p.v_ref_cm_s = INT16_MAX;
    p.v_min_cm_s = 1023;
    check_refused(p, HT_P_V_REF, "v_ref");
}

/* Per axis kff * v_ref / v_min + kd * s_p,max <= 512, exactly (the products
 * reach 2^37): at the bound accepted, one Q16 LSB beyond refused, named by
 * the gain that carries it (kff if kff alone exceeds it, else kd). */
static void test_rate_gain_limit_is_exact(void)
{
    const ht_params_t d = HT_PARAMS_DEFAULT;
    ht_params_t p = d;
    ht_controller_t c;
    /* scheduled, scale 32: (kff + kd) * 32 <= 512 */
    p.schedule = 1;
    p.v_min_cm_s = 1000;
    p.v_ref_cm_s = 32000;
    p.kff_rudder = 10 * Q16_ONE;
    p.kd_rudder = 6 * Q16_ONE;
    TEST_ASSERT_EQUAL_INT(HT_OK, ht_init(&c, &p, NULL));
    p.kd_rudder += 1;
    check_refused(p, HT_P_KD_RUDDER, "kd_rudder");
    p.kd_rudder = 0;
    p.kff_rudder = 16 * Q16_ONE;
    TEST_ASSERT_EQUAL_INT(HT_OK, ht_init(&c, &p, NULL));
    p.kff_rudder += 1;
    check_refused(p, HT_P_KFF_RUDDER, "kff_rudder");
    /* unscheduled: kd is not scaled, kff * 32 + kd <= 512 */
    p = d;
    p.v_min_cm_s = 1000;
    p.v_ref_cm_s = 32000;
    p.kd_aileron = 64 * Q16_ONE;
    p.kff_aileron = 14 * Q16_ONE;
    TEST_ASSERT_EQUAL_INT(HT_OK, ht_init(&c, &p, NULL));
    p.kff_aileron += 1;
    check_refused(p, HT_P_KD_AILERON, "kd_aileron");
    /* scale 4, scheduled: every gain at 64 is exactly 512 */
    p = d;
    p.schedule = 1;
    p.v_min_cm_s = 8000;
    p.v_ref_cm_s = 32000;
    p.kp_elevator = p.kff_elevator = p.kd_elevator = 64 * Q16_ONE;
    TEST_ASSERT_EQUAL_INT(HT_OK, ht_init(&c, &p, NULL));
    p.v_ref_cm_s = 32001;
    check_refused(p, HT_P_KD_ELEVATOR, "kd_elevator");
    /* the corner: every gain 64, scale 327, is refused */
    p = d;
    p.kp_aileron = p.kp_elevator = p.kp_rudder = 64 * Q16_ONE;
    p.kff_aileron = p.kff_elevator = p.kff_rudder = 64 * Q16_ONE;
    p.kd_aileron = p.kd_elevator = p.kd_rudder = 64 * Q16_ONE;
    p.schedule = 1;
    p.v_min_cm_s = 100;
    p.v_ref_cm_s = INT16_MAX;
    check_refused(p, HT_P_V_REF, "v_ref");
    p.v_ref_cm_s = 3200;
    check_refused(p, HT_P_KFF_AILERON, "kff_aileron");
}

/* The largest parameters with the largest inputs still give bounded output
 * (the Q20 sum saturates instead of wrapping): every gain 64 at the largest
 * scale that allows it (4, scheduled). */
static void test_largest_gains_do_not_wrap(void)
{
    ht_params_t p = HT_PARAMS_DEFAULT;
    p.kp_aileron = p.kp_elevator = p.kp_rudder = 64 * Q16_ONE;
    p.kff_aileron = p.kff_elevator = p.kff_rudder = 64 * Q16_ONE;
    p.kd_aileron = p.kd_elevator = p.kd_rudder = 64 * Q16_ONE;
    p.v_min_cm_s = 8192;
    p.v_ref_cm_s = INT16_MAX;
    p.schedule = 1;
    p.max_tilt = 8 * Q16_ONE;
    ht_controller_t c;
    TEST_ASSERT_EQUAL_INT(HT_OK, ht_init(&c, &p, NULL));
    ht_input_t in = {
        INT16_MIN, INT16_MAX, INT16_MIN, INT16_MAX, INT32_MIN, 0, {INT16_MIN, INT16_MAX, INT16_MIN},
        1,         INT16_MIN, INT16_MAX};
    ht_output_t out;
    ht_step(&c, &in, &out);
    assert_bounded(&out);
    /* and they are the double law's (here the damping of the +16 rad/s roll
     * gyro dominates: full left aileron) */
    ht_ref_params_t rp;
    ht_ref_input_t ri;
    ht_ref_output_t ro;
    ht_ref_params_from_controller(&c, &rp);
    ht_ref_input_from_fixed(&in, &ri);
    ht_ref_step(&rp, &ri, &ro);
    TEST_ASSERT_EQUAL_INT(-Q14_ONE, out.aileron);
    TEST_ASSERT_DOUBLE_WITHIN(TOL_Q14, ro.aileron, out.aileron / 16384.0);
    TEST_ASSERT_DOUBLE_WITHIN(TOL_Q14, ro.elevator, out.elevator / 16384.0);
    TEST_ASSERT_DOUBLE_WITHIN(TOL_Q14, ro.rudder, out.rudder / 16384.0);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_vertical_fuselage_is_finite_and_documented);
    RUN_TEST(test_nearly_vertical_fuselage_uses_the_tiny_direction);
    RUN_TEST(test_extreme_inputs_give_bounded_outputs);
    RUN_TEST(test_zero_and_negative_airspeed_use_v_min);
    RUN_TEST(test_huge_airspeed_limits_tilt);
    RUN_TEST(test_tilt_limit_sets_turn_rate_used);
    RUN_TEST(test_exactly_opposite_tilt_rolls_deterministically);
    RUN_TEST(test_opposite_pitch_saturates);
    RUN_TEST(test_surface_saturation_flag);
    RUN_TEST(test_null_and_uninitialised_give_zero_surfaces);
    RUN_TEST(test_bad_parameters_are_refused_by_name);
    RUN_TEST(test_scale_limit_is_exact);
    RUN_TEST(test_rate_gain_limit_is_exact);
    RUN_TEST(test_largest_gains_do_not_wrap);
    return UNITY_END();
}
