/*
 * test_imu_decimate.c - the IMU's 1 kHz -> 200 Hz boxcar average.
 *
 * Worked values:
 *   gyro X samples 10, 20, 30, 40, 51 (Q16): sum 151, / 5 = 30.2 -> 30
 *   gyro Y -1, -2 (Q16): sum -3, / 2 = -1.5 -> -2 (half away from zero)
 *   accel Z five times -65536 (-1 g level): -65536
 *   64 full-scale gyro samples 2285406: sum 146265984 < 2^31, mean 2285406
 */
#include "unity.h"

#include "imu_decimate.h"

#include <string.h>

static imu_decimate_t d;

void setUp(void)
{
    memset(&d, 0, sizeof d);
}

void tearDown(void) {}

static ht_imu_sample_t sample(q16_t gx, q16_t gy, q16_t az)
{
    ht_imu_sample_t s;
    memset(&s, 0, sizeof s);
    s.gyro_rad_s[0] = gx;
    s.gyro_rad_s[1] = gy;
    s.accel_g[2] = az;
    return s;
}

static void test_five_samples_mean(void)
{
    const q16_t gx[5] = {10, 20, 30, 40, 51};
    for (unsigned i = 0u; i < 5u; ++i) {
        const ht_imu_sample_t s = sample(gx[i], 0, -65536);
        imu_decimate_add(&d, &s);
    }
    ht_imu_sample_t out;
    memset(&out, 0x55, sizeof out);
    TEST_ASSERT_EQUAL_UINT16(5u, imu_decimate_take(&d, &out));
    TEST_ASSERT_EQUAL_INT32(30, out.gyro_rad_s[0]);
    TEST_ASSERT_EQUAL_INT32(0, out.gyro_rad_s[2]);
    TEST_ASSERT_EQUAL_INT32(-65536, out.accel_g[2]);
    TEST_ASSERT_EQUAL_UINT16(0u, d.n);
}

static void test_negative_halves_round_away(void)
{
    ht_imu_sample_t s = sample(0, -1, 0);
    imu_decimate_add(&d, &s);
    s = sample(0, -2, 0);
    imu_decimate_add(&d, &s);
    ht_imu_sample_t out;
    TEST_ASSERT_EQUAL_UINT16(2u, imu_decimate_take(&d, &out));
    TEST_ASSERT_EQUAL_INT32(-2, out.gyro_rad_s[1]);
}

static void test_empty_window_leaves_output(void)
{
    ht_imu_sample_t out = sample(7, 8, 9);
    TEST_ASSERT_EQUAL_UINT16(0u, imu_decimate_take(&d, &out));
    TEST_ASSERT_EQUAL_INT32(7, out.gyro_rad_s[0]);
    TEST_ASSERT_EQUAL_UINT16(0u, imu_decimate_take(NULL, &out));
}

static void test_full_scale_window_does_not_overflow(void)
{
    const ht_imu_sample_t s = sample(2285406, -2285406, -1048576);
    for (unsigned i = 0u; i < IMU_DECIMATE_MAX + 3u; ++i) {
        imu_decimate_add(&d, &s);
    }
    TEST_ASSERT_EQUAL_UINT16(3u, d.dropped);
    ht_imu_sample_t out;
    TEST_ASSERT_EQUAL_UINT16(IMU_DECIMATE_MAX, imu_decimate_take(&d, &out));
    TEST_ASSERT_EQUAL_INT32(2285406, out.gyro_rad_s[0]);
    TEST_ASSERT_EQUAL_INT32(-2285406, out.gyro_rad_s[1]);
    TEST_ASSERT_EQUAL_INT32(-1048576, out.accel_g[2]);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_five_samples_mean);
    RUN_TEST(test_negative_halves_round_away);
    RUN_TEST(test_empty_window_leaves_output);
    RUN_TEST(test_full_scale_window_does_not_overflow);
    return UNITY_END();
}
