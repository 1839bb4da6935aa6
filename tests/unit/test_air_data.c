/*
 * test_air_data.c - true airspeed from indicated airspeed, pressure altitude
 * and temperature (helical/estimator/air_data.h) against the ICAO standard
 * atmosphere in double, written here from its formulas:
 *   - every metre of pressure altitude from -1 000 m to 20 000 m (21 001
 *     points): TAS / IAS within 1e-4 of 1 / sqrt(sigma);
 *   - the static temperature from -80 to +85 degC every 0.5 degC at 0, 1 500,
 *     3 000, 11 000 m: within 1.5e-4 of sqrt((p0 / p)(T / T0));
 *   - the edges: altitudes beyond the range clamped, a temperature out of
 *     range or not valid -> the ISA's, IAS <= 0 -> 0, saturation at INT16_MAX,
 *     the documented figures (7.6 % at 1 500 m, 16.1 % at 3 000 m).
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>

#include "helical/estimator/air_data.h"
#include "unity.h"

void setUp(void) {}

void tearDown(void) {}

static double isa_theta(double h)
{
    return (h <= 11000.0) ? 1.0 - 0.0065 * h / 288.15 : 216.65 / 288.15;
}

static double isa_delta(double h)
{
    const double n = 9.80665 / (287.05287 * 0.0065);
    if (h <= 11000.0) {
        return pow(isa_theta(h), n);
    }
    return pow(216.65 / 288.15, n) * exp(-9.80665 * (h - 11000.0) / (287.05287 * 216.65));
}

/* TAS / IAS = 1 / sqrt(sigma), sigma = delta (T0 / T) */
static double ref_ratio(double h, double t_k)
{
    return 1.0 / sqrt(isa_delta(h) * 288.15 / t_k);
}

static void test_isa_every_metre(void)
{
    double worst = 0.0;
    for (int h = -1000; h <= 20000; ++h) {
        const double want = ref_ratio(h, 288.15 * isa_theta(h));
        const double got = ht_tas_per_ias_q14(h * 100, 0, 0u) / 16384.0;
        const double err = fabs(got / want - 1.0);
        worst = (err > worst) ? err : worst;
        TEST_ASSERT_TRUE_MESSAGE(err < 1e-4, "TAS / IAS off the ISA");
    }
    printf("air data: worst ISA TAS/IAS error %.2e over -1000..20000 m\n", worst);
}

static void test_measured_temperature(void)
{
    static const int32_t alts_m[4] = {0, 1500, 3000, 11000};
    double worst = 0.0;
    for (int a = 0; a < 4; ++a) {
        for (int t = -8000; t <= 8500; t += 50) {
            const double want = ref_ratio(alts_m[a], 273.15 + t / 100.0);
            const double got = ht_tas_per_ias_q14(alts_m[a] * 100, (int16_t)t, 1u) / 16384.0;
            const double err = fabs(got / want - 1.0);
            worst = (err > worst) ? err : worst;
            TEST_ASSERT_TRUE_MESSAGE(err < 1.5e-4, "TAS / IAS off with a measured temperature");
        }
    }
    printf("air data: worst TAS/IAS error with a measured temperature %.2e\n", worst);
}

static void test_edges_and_figures(void)
{
    /* beyond the range: the end's value */
    TEST_ASSERT_EQUAL_UINT32(ht_tas_per_ias_q14(-100000, 0, 0u),
                             ht_tas_per_ias_q14(INT32_MIN, 0, 0u));
    TEST_ASSERT_EQUAL_UINT32(ht_tas_per_ias_q14(2000000, 0, 0u),
                             ht_tas_per_ias_q14(INT32_MAX, 0, 0u));
    TEST_ASSERT_EQUAL_UINT32(16384u, ht_tas_per_ias_q14(0, 0, 0u)); /* sea level: 1 */
    /* a temperature out of range or not valid: the ISA's */
    TEST_ASSERT_EQUAL_UINT32(ht_tas_per_ias_q14(300000, 0, 0u),
                             ht_tas_per_ias_q14(300000, 8501, 1u));
    TEST_ASSERT_EQUAL_UINT32(ht_tas_per_ias_q14(300000, 0, 0u),
                             ht_tas_per_ias_q14(300000, -8001, 1u));
    TEST_ASSERT_EQUAL_UINT32(ht_tas_per_ias_q14(300000, 0, 0u),
                             ht_tas_per_ias_q14(300000, 4000, 0u));
    /* the ISA temperature given as measured: the same within a count */
    TEST_ASSERT_UINT32_WITHIN(1u, ht_tas_per_ias_q14(300000, 0, 0u),
                              ht_tas_per_ias_q14(300000, -450, 1u)); /* 15 - 19.5 = -4.5 degC */
    /* IAS: negative or 0 -> 0; saturation */
    TEST_ASSERT_EQUAL_INT16(0, ht_true_airspeed_cm_s(-5, 300000, 0, 0u));
    TEST_ASSERT_EQUAL_INT16(0, ht_true_airspeed_cm_s(0, 300000, 0, 0u));
    TEST_ASSERT_EQUAL_INT16(INT16_MAX, ht_true_airspeed_cm_s(INT16_MAX, 2000000, 8500, 1u));
    TEST_ASSERT_EQUAL_INT16(1500, ht_true_airspeed_cm_s(1500, 0, 0, 0u));
    /* the header's figures: 7.6 % at 1 500 m, 16.1 % at 3 000 m */
    TEST_ASSERT_INT16_WITHIN(1, 10760, ht_true_airspeed_cm_s(10000, 150000, 0, 0u));
    TEST_ASSERT_INT16_WITHIN(1, 11607, ht_true_airspeed_cm_s(10000, 300000, 0, 0u));
    /* rounding: IAS x ratio to the nearest cm/s, every IAS at 3 000 m */
    const uint32_t f = ht_tas_per_ias_q14(300000, 0, 0u);
    for (int v = 1; v <= INT16_MAX; ++v) {
        const double want = floor(v * (double)f / 16384.0 + 0.5);
        const int16_t got = ht_true_airspeed_cm_s((int16_t)v, 300000, 0, 0u);
        TEST_ASSERT_EQUAL_INT32((want > INT16_MAX) ? INT16_MAX : (int32_t)want, got);
    }
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_isa_every_metre);
    RUN_TEST(test_measured_temperature);
    RUN_TEST(test_edges_and_figures);
    return UNITY_END();
}
