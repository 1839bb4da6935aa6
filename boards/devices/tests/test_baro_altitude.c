/*
 * test_baro_altitude.c - the integer pressure-altitude table against the
 * double-precision ISA formula.
 *
 * Reference (ICAO Doc 7488 / ISO 2533 troposphere):
 *   h = 44330.77 m * (1 - (p / 101325 Pa)^0.1902631),
 *   0.1902631 = R L / g0 = 287.05287 * 0.0065 / 9.80665, 44330.77 = 288.15 / 0.0065.
 * Standard-atmosphere points (the same formula, as tabulated):
 *   101325 Pa -> 0 m; 89874.56 Pa -> 1000 m; 54019.89 Pa -> 5000 m;
 *   30742.43 Pa -> 9000 m; 107477.51 Pa -> -500 m.
 * Bound: the chord error of linear interpolation over a 256 Pa step is at
 * most (256 Pa)^2 / 8 * max|h''|, h'' = 0.8097 * 8434.4 m / p0^2 * (p/p0)^-1.8097,
 * which at 300 hPa is 6.0e-6 m/Pa^2 -> 4.9 cm; plus the table's and the
 * result's 0.5 cm roundings: the test demands < 6 cm everywhere in
 * 300..1101.28 hPa (it measures 5.3 cm, at 301 hPa).
 */
#include "unity.h"

#include "baro_altitude.h"

#include <math.h>
#include <stddef.h>

void setUp(void) {}
void tearDown(void) {}

static double isa_alt_cm(double p_pa)
{
    const double n = 287.05287 * 0.0065 / 9.80665;
    return 100.0 * (288.15 / 0.0065) * (1.0 - pow(p_pa / 101325.0, n));
}

static uint32_t q8(double p_pa)
{
    return (uint32_t)lround(p_pa * 256.0);
}

static void test_every_node_is_the_rounded_formula(void)
{
    for (uint32_t i = 0u; i < BARO_ALT_TABLE_NODES; ++i) {
        const double p = (double)(BARO_ALT_TABLE_BASE_PA + i * BARO_ALT_TABLE_STEP_PA);
        TEST_ASSERT_DOUBLE_WITHIN(0.5, isa_alt_cm(p), (double)baro_alt_table_cm[i]);
    }
}

static void test_sweep_within_bound_and_monotonic(void)
{
    double worst = 0.0;
    int32_t prev = INT32_MAX;
    for (uint32_t p = BARO_ALT_P_MIN_Q8; p <= BARO_ALT_P_MAX_Q8; p += 97u) {
        uint8_t clamped = 9u;
        const int32_t h = baro_altitude_cm(p, &clamped);
        TEST_ASSERT_EQUAL_UINT8(0u, clamped);
        const double err = fabs((double)h - isa_alt_cm((double)p / 256.0));
        if (err > worst) {
            worst = err;
        }
        TEST_ASSERT_TRUE(h <= prev); /* more pressure, lower */
        prev = h;
    }
    TEST_ASSERT_TRUE(worst < (double)BARO_ALT_ERROR_BOUND_CM);
    TEST_ASSERT_TRUE(worst > 3.0); /* the bound is not loose by an order */
}

static void test_standard_atmosphere_points(void)
{
    TEST_ASSERT_INT32_WITHIN(1, 0, baro_altitude_cm(q8(101325.0), NULL));
    TEST_ASSERT_INT32_WITHIN(2, 100000, baro_altitude_cm(q8(89874.56), NULL));
    TEST_ASSERT_INT32_WITHIN(3, 500000, baro_altitude_cm(q8(54019.89), NULL));
    TEST_ASSERT_INT32_WITHIN(6, 900000, baro_altitude_cm(q8(30742.43), NULL));
    TEST_ASSERT_INT32_WITHIN(2, -50000, baro_altitude_cm(q8(107477.51), NULL));
}

static void test_interpolation_rounds_to_nearest(void)
{
    /* a quarter step above the first node: 916395 + (910705 - 916395) / 4
     * = 916395 - 1422.5, the tie rounded toward +infinity: 914973 */
    TEST_ASSERT_EQUAL_INT32(914973, baro_altitude_cm(BARO_ALT_P_MIN_Q8 + 64u * 256u, NULL));
    /* half a step: 916395 - 2845 exactly */
    TEST_ASSERT_EQUAL_INT32(913550, baro_altitude_cm(BARO_ALT_P_MIN_Q8 + 128u * 256u, NULL));
}

static void test_clamps_outside_the_table(void)
{
    uint8_t clamped = 0u;
    TEST_ASSERT_EQUAL_INT32(916395, baro_altitude_cm(BARO_ALT_P_MIN_Q8, &clamped));
    TEST_ASSERT_EQUAL_UINT8(0u, clamped);
    TEST_ASSERT_EQUAL_INT32(916395, baro_altitude_cm(BARO_ALT_P_MIN_Q8 - 1u, &clamped));
    TEST_ASSERT_EQUAL_UINT8(1u, clamped);
    TEST_ASSERT_EQUAL_INT32(916395, baro_altitude_cm(0u, &clamped));
    TEST_ASSERT_EQUAL_UINT8(1u, clamped);
    TEST_ASSERT_EQUAL_INT32(-70828, baro_altitude_cm(BARO_ALT_P_MAX_Q8, &clamped));
    TEST_ASSERT_EQUAL_UINT8(0u, clamped);
    TEST_ASSERT_EQUAL_INT32(-70828, baro_altitude_cm(BARO_ALT_P_MAX_Q8 + 1u, &clamped));
    TEST_ASSERT_EQUAL_UINT8(1u, clamped);
    TEST_ASSERT_EQUAL_INT32(-70828, baro_altitude_cm(UINT32_MAX, &clamped));
    TEST_ASSERT_EQUAL_UINT8(1u, clamped);
    /* the limits themselves: 300 hPa and 1101.28 hPa */
    TEST_ASSERT_EQUAL_UINT32(7680000u, BARO_ALT_P_MIN_Q8);
    TEST_ASSERT_EQUAL_UINT32(28192768u, BARO_ALT_P_MAX_Q8);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_every_node_is_the_rounded_formula);
    RUN_TEST(test_sweep_within_bound_and_monotonic);
    RUN_TEST(test_standard_atmosphere_points);
    RUN_TEST(test_interpolation_rounds_to_nearest);
    RUN_TEST(test_clamps_outside_the_table);
    return UNITY_END();
}
