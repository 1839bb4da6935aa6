/* Unit tests of the upset guard (include/helical/law/upset_guard.h): parameter
 * checks, engage / hold / release with hysteresis, the measured pitch ratio
 * against a double reference, and INT16 extremes of the tilt row. */
#include "unity.h"

#include "helical/law/upset_guard.h"

#include <math.h>
#include <stddef.h>

static ht_upset_guard_params_t prm;
static ht_upset_guard_state_t st;

void setUp(void)
{
    const ht_upset_guard_params_t d = HT_UPSET_GUARD_PARAMS_DEFAULT;
    prm = d;
    ht_upset_guard_reset(&st);
}

void tearDown(void) {}

/* The tilt row of roll phi, pitch theta (deg), Q14 (control-law.md axes:
 * X = -sin(phi) cos(theta), Y = -sin(theta), Z = cos(phi) cos(theta)). */
static void tilt(double phi_deg, double theta_deg, q14_t r[3])
{
    const double d2r = 3.14159265358979323846 / 180.0;
    const double v[3] = {-sin(phi_deg * d2r) * cos(theta_deg * d2r), -sin(theta_deg * d2r),
                         cos(phi_deg * d2r) * cos(theta_deg * d2r)};
    for (int i = 0; i < 3; ++i) {
        r[i] = (q14_t)lround(v[i] * 16384.0);
    }
}

static q16_t step_att(double phi, double theta, uint8_t inv, q16_t pitch)
{
    q14_t r[3];
    tilt(phi, theta, r);
    return ht_upset_guard_step(&prm, &st, r[0], r[1], r[2], inv, pitch);
}

static void test_defaults_accepted_and_each_bad_field_refused(void)
{
    TEST_ASSERT_EQUAL_INT(HT_UG_OK, ht_upset_guard_check(&prm));
    TEST_ASSERT_EQUAL_INT(HT_UG_ERR_NULL, ht_upset_guard_check(NULL));
    ht_upset_guard_params_t p = prm;
    p.engage_sin = (q14_t)(Q14_ONE + 1);
    TEST_ASSERT_EQUAL_INT(HT_UG_ERR_PARAM, ht_upset_guard_check(&p));
    p = prm;
    p.release_sin = 0;
    TEST_ASSERT_EQUAL_INT(HT_UG_ERR_PARAM, ht_upset_guard_check(&p));
    p = prm;
    p.release_sin = p.engage_sin; /* no hysteresis */
    TEST_ASSERT_EQUAL_INT(HT_UG_ERR_PARAM, ht_upset_guard_check(&p));
    p = prm;
    p.release_cos_bank = 0;
    TEST_ASSERT_EQUAL_INT(HT_UG_ERR_PARAM, ht_upset_guard_check(&p));
    p = prm;
    p.release_cos_bank = (q14_t)(Q14_ONE + 1);
    TEST_ASSERT_EQUAL_INT(HT_UG_ERR_PARAM, ht_upset_guard_check(&p));
    p = prm;
    p.engage_sin = Q14_ONE; /* the edges are valid */
    p.release_sin = 1;
    p.release_cos_bank = Q14_ONE;
    TEST_ASSERT_EQUAL_INT(HT_UG_OK, ht_upset_guard_check(&p));
    /* unchecked bad parameters: the pitch passes through, disengaged */
    st.engaged = 1u;
    p.release_sin = 0;
    TEST_ASSERT_EQUAL_INT32(1234, ht_upset_guard_step(&p, &st, 0, 16000, -3000, 0u, 1234));
    TEST_ASSERT_EQUAL_UINT8(0u, st.engaged);
    TEST_ASSERT_EQUAL_INT32(77, ht_upset_guard_step(&prm, NULL, 0, 16000, -3000, 0u, 77));
}

static void test_pass_through_outside_the_upset(void)
{
    const double att[][2] = {{0, 0}, {0, -80}, {60, -70}, {180, 0}, {180, -50}, {120, -55}};
    for (unsigned i = 0; i < sizeof att / sizeof att[0]; ++i) {
        TEST_ASSERT_EQUAL_INT32(Q16_ONE / 4, step_att(att[i][0], att[i][1], 0u, Q16_ONE / 4));
        TEST_ASSERT_EQUAL_UINT8(0u, st.engaged);
    }
    /* commanded inverted: never engages */
    TEST_ASSERT_EQUAL_INT32(Q16_ONE / 4, step_att(180, -80, 1u, Q16_ONE / 4));
    TEST_ASSERT_EQUAL_UINT8(0u, st.engaged);
}

static void test_engages_inverted_nose_low_with_the_measured_ratio(void)
{
    const double att[][2] = {{180, -80}, {-136, -74}, {107, -61}, {150, -85}, {-170, -65}};
    for (unsigned i = 0; i < sizeof att / sizeof att[0]; ++i) {
        ht_upset_guard_reset(&st);
        const q16_t r = step_att(att[i][0], att[i][1], 0u, Q16_ONE / 4);
        TEST_ASSERT_EQUAL_UINT8(1u, st.engaged);
        const double ref = tan(att[i][1] * 3.14159265358979323846 / 180.0) * 65536.0;
        TEST_ASSERT_FLOAT_WITHIN(fabs(ref) * 0.01 + 64.0, ref, (double)r);
    }
}

static void test_release_upright_or_nose_up_with_hysteresis(void)
{
    (void)step_att(180, -80, 0u, 0);
    TEST_ASSERT_EQUAL_UINT8(1u, st.engaged);
    /* rolling: still engaged through knife edge and at 50 deg of bank */
    (void)step_att(90, -75, 0u, 0);
    TEST_ASSERT_EQUAL_UINT8(1u, st.engaged);
    (void)step_att(50, -75, 0u, 0);
    TEST_ASSERT_EQUAL_UINT8(1u, st.engaged);
    /* inside the hysteresis band (nose 45 deg down, inverted): held */
    (void)step_att(170, -45, 0u, 0);
    TEST_ASSERT_EQUAL_UINT8(1u, st.engaged);
    /* upright within 45 deg of bank: released, pitch passes through */
    TEST_ASSERT_EQUAL_INT32(Q16_ONE / 4, step_att(40, -75, 0u, Q16_ONE / 4));
    TEST_ASSERT_EQUAL_UINT8(0u, st.engaged);
    /* nose back above 30 deg down, still inverted: released */
    (void)step_att(180, -80, 0u, 0);
    TEST_ASSERT_EQUAL_UINT8(1u, st.engaged);
    TEST_ASSERT_EQUAL_INT32(-5, step_att(175, -25, 0u, -5));
    TEST_ASSERT_EQUAL_UINT8(0u, st.engaged);
    /* the command turning inverted releases */
    (void)step_att(180, -80, 0u, 0);
    TEST_ASSERT_EQUAL_INT32(9, step_att(180, -80, 1u, 9));
    TEST_ASSERT_EQUAL_UINT8(0u, st.engaged);
}

static void test_int16_extremes_and_vertical_fuselage(void)
{
    /* fuselage straight down (X = Z = 0) cannot engage (Z not < 0) ... */
    TEST_ASSERT_EQUAL_INT32(3, ht_upset_guard_step(&prm, &st, 0, Q14_ONE, 0, 0u, 3));
    TEST_ASSERT_EQUAL_UINT8(0u, st.engaged);
    /* ... but once engaged it gives the clamped ratio, finite */
    (void)ht_upset_guard_step(&prm, &st, 0, 16000, -100, 0u, 0);
    TEST_ASSERT_EQUAL_UINT8(1u, st.engaged);
    TEST_ASSERT_EQUAL_INT32(-HT_UG_RATIO_MAX, ht_upset_guard_step(&prm, &st, 0, Q14_ONE, 0, 0u, 0));
    TEST_ASSERT_EQUAL_INT32(-HT_UG_RATIO_MAX,
                            ht_upset_guard_step(&prm, &st, 0, INT16_MAX, -1, 0u, 0));
    /* every INT16 extreme combination: a bounded result, never a trap */
    const q14_t v[] = {INT16_MIN, -16384, -1, 0, 1, 16384, INT16_MAX};
    const unsigned n = (unsigned)(sizeof v / sizeof v[0]);
    for (unsigned i = 0; i < n; ++i) {
        for (unsigned j = 0; j < n; ++j) {
            for (unsigned k = 0; k < n; ++k) {
                for (uint8_t e = 0u; e < 2u; ++e) {
                    st.engaged = e;
                    const q16_t r = ht_upset_guard_step(&prm, &st, v[i], v[j], v[k], 0u, 42);
                    TEST_ASSERT_TRUE(r == 42 || (r >= -HT_UG_RATIO_MAX && r <= HT_UG_RATIO_MAX));
                    TEST_ASSERT_TRUE(st.engaged <= 1u);
                }
            }
        }
    }
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_defaults_accepted_and_each_bad_field_refused);
    RUN_TEST(test_pass_through_outside_the_upset);
    RUN_TEST(test_engages_inverted_nose_low_with_the_measured_ratio);
    RUN_TEST(test_release_upright_or_nose_up_with_hysteresis);
    RUN_TEST(test_int16_extremes_and_vertical_fuselage);
    return UNITY_END();
}
