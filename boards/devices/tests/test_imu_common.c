/*
 * test_imu_common.c - the chip-independent part of the SPI IMU driver:
 * register frames, big-endian decoding, scaling, board alignment,
 * detection (chips, nothing, a stranger) and argument checks.
 *
 * Worked values:
 *   gyro: 65536 pi / (180 * 16.4) = 69.745060 Q16 per count
 *     -32768 -> -2285406.115 -> -2285406;  32767 -> 2285336.370 -> 2285336
 *     164 counts = 10 deg/s = 0.1745329 rad/s = 11438.19 -> 11438
 *     1 -> 69.745 -> 70;  -1 -> -69.745 -> -70
 *   accel: 65536 / 2048 = 32 exactly: -32768 -> -1048576 (-16 g),
 *     32767 -> 1048544, 2048 -> 65536 (1 g)
 *   temperature: MPU-6000 T = raw / 340 + 36.53: raw 0 -> 3653 cdeg,
 *     raw -3920 -> 24.9994 -> 2500;  ICM-42688-P T = raw / 132.48 + 25:
 *     raw 0 -> 2500, raw 1325 -> 35.0015 -> 3500, raw -32768 -> -22234
 *   WHO_AM_I: MPU-6000 0x68, ICM-42688-P 0x47 (register 0x75); frame
 *     [0xF5, 0x00]: 0x75 | 0x80 (read).
 */
#include "unity.h"

#include "icm42688p.h"
#include "imu_spi.h"
#include "imu_test_util.h"
#include "mpu6000.h"
#include "sim_bus.h"
#include "sim_icm42688p.h"
#include "sim_mpu6000.h"

#include <math.h>
#include <string.h>

static sim_bus_t sb;
static sim_mpu6000_t mpu;
static sim_icm42688p_t icm;

void setUp(void)
{
    sim_mpu6000_init(&mpu);
    sim_icm42688p_init(&icm);
    sim_bus_init(&sb, &mpu, sim_mpu6000_frame);
}

void tearDown(void) {}

static void test_be16(void)
{
    const uint8_t a[2] = {0x80u, 0x00u};
    const uint8_t b[2] = {0x7Fu, 0xFFu};
    const uint8_t c[2] = {0xFFu, 0xFFu};
    const uint8_t d[2] = {0x01u, 0x02u};
    TEST_ASSERT_EQUAL_INT16(-32768, imu_be16(a));
    TEST_ASSERT_EQUAL_INT16(32767, imu_be16(b));
    TEST_ASSERT_EQUAL_INT16(-1, imu_be16(c));
    TEST_ASSERT_EQUAL_INT16(258, imu_be16(d));
}

static void test_gyro_scale(void)
{
    TEST_ASSERT_EQUAL_INT32(-2285406, imu_gyro_q16_from_raw(-32768));
    TEST_ASSERT_EQUAL_INT32(2285336, imu_gyro_q16_from_raw(32767));
    TEST_ASSERT_EQUAL_INT32(0, imu_gyro_q16_from_raw(0));
    TEST_ASSERT_EQUAL_INT32(70, imu_gyro_q16_from_raw(1));
    TEST_ASSERT_EQUAL_INT32(-70, imu_gyro_q16_from_raw(-1));
    TEST_ASSERT_EQUAL_INT32(11438, imu_gyro_q16_from_raw(164));
    /* every count within 1 LSB (the bound is 0.62) of the exact product */
    double worst = 0.0;
    for (int32_t r = -32768; r <= 32767; ++r) {
        const double err =
            fabs((double)imu_gyro_q16_from_raw((int16_t)r) - gyro_q16_exact((int16_t)r));
        if (err > worst) {
            worst = err;
        }
    }
    TEST_ASSERT_TRUE(worst < 0.62);
}

static void test_accel_scale(void)
{
    TEST_ASSERT_EQUAL_INT32(-1048576, imu_accel_q16_from_raw(-32768));
    TEST_ASSERT_EQUAL_INT32(1048544, imu_accel_q16_from_raw(32767));
    TEST_ASSERT_EQUAL_INT32(65536, imu_accel_q16_from_raw(2048));
    TEST_ASSERT_EQUAL_INT32(-65536, imu_accel_q16_from_raw(-2048));
    TEST_ASSERT_EQUAL_INT32(0, imu_accel_q16_from_raw(0));
}

/* The driver's table against the independent physical model, every value. */
static void test_alignment_every_value(void)
{
    const double body[3] = {0.25, -1.5, 3.0};
    for (unsigned a = 0u; a < (unsigned)IMU_ALIGN_COUNT; ++a) {
        double chip[3];
        chip_from_body(a, body, chip);
        q16_t in[3];
        for (int i = 0; i < 3; ++i) {
            in[i] = (q16_t)lround(chip[i] * 65536.0);
        }
        q16_t out[3] = {0, 0, 0};
        imu_align_apply((uint8_t)a, in, out);
        for (int i = 0; i < 3; ++i) {
            TEST_ASSERT_INT32_WITHIN_MESSAGE(0, (int32_t)lround(body[i] * 65536.0), out[i],
                                             "alignment");
        }
    }
    /* each is a rotation: level at rest the chip reads +1 g on the axis out of
     * its top when it is mounted top up, -1 g when top down: body (0, 0, -1) */
    const q16_t up[3] = {0, 0, Q16_ONE};
    const q16_t down[3] = {0, 0, -Q16_ONE};
    for (uint8_t a = 0u; a < (uint8_t)IMU_ALIGN_COUNT; ++a) {
        q16_t out[3];
        imu_align_apply(a, a < 4u ? up : down, out);
        TEST_ASSERT_EQUAL_INT32(0, out[0]);
        TEST_ASSERT_EQUAL_INT32(0, out[1]);
        TEST_ASSERT_EQUAL_INT32(-Q16_ONE, out[2]);
    }
    /* exact at the extremes: negating the most negative Q16 count is safe */
    const q16_t big[3] = {-1048576, 2285336, -2285406};
    q16_t out[3];
    imu_align_apply(IMU_ALIGN_YAW90, big, out);
    TEST_ASSERT_EQUAL_INT32(-2285336, out[0]);
    TEST_ASSERT_EQUAL_INT32(1048576, out[1]);
    TEST_ASSERT_EQUAL_INT32(2285406, out[2]);
    imu_align_apply(IMU_ALIGN_COUNT, big, out); /* out of range: zeros */
    TEST_ASSERT_EQUAL_INT32(0, out[0]);
    TEST_ASSERT_EQUAL_INT32(0, out[1]);
    TEST_ASSERT_EQUAL_INT32(0, out[2]);
}

static void test_div_round_and_temperature(void)
{
    TEST_ASSERT_EQUAL_INT32(3, imu_div_round(5, 2));
    TEST_ASSERT_EQUAL_INT32(-3, imu_div_round(-5, 2));
    TEST_ASSERT_EQUAL_INT32(2, imu_div_round(7, 4));
    TEST_ASSERT_EQUAL_INT32(-2, imu_div_round(-7, 4));
    TEST_ASSERT_EQUAL_INT16(3653, mpu6000_temp_cdeg(0));
    TEST_ASSERT_EQUAL_INT16(2500, mpu6000_temp_cdeg(-3920));
    TEST_ASSERT_EQUAL_INT16(-5985, mpu6000_temp_cdeg(-32768));
    TEST_ASSERT_EQUAL_INT16(2500, icm42688p_temp_cdeg(0));
    TEST_ASSERT_EQUAL_INT16(3500, icm42688p_temp_cdeg(1325));
    TEST_ASSERT_EQUAL_INT16(-22234, icm42688p_temp_cdeg(-32768));
}

static void test_register_frames(void)
{
    uint8_t v = 0u;
    TEST_ASSERT_EQUAL(IMU_OK, imu_spi_set_clock(&sb.bus, 1000000u));
    TEST_ASSERT_EQUAL(IMU_OK, imu_spi_read_regs(&sb.bus, 0x75u, &v, 1u));
    TEST_ASSERT_EQUAL_HEX8(0x68u, v);
    TEST_ASSERT_EQUAL(IMU_OK, imu_spi_write_reg(&sb.bus, 0x19u, 0x07u));
    TEST_ASSERT_EQUAL_HEX8(0x07u, mpu.regs[0x19]);
    TEST_ASSERT_EQUAL(IMU_OK, imu_spi_read_regs(&sb.bus, 0x19u, &v, 1u));
    TEST_ASSERT_EQUAL_HEX8(0x07u, v);
    /* auto-increment across registers */
    uint8_t two[2] = {0u, 0u};
    TEST_ASSERT_EQUAL(IMU_OK, imu_spi_read_regs(&sb.bus, 0x6Bu, two, 2u));
    TEST_ASSERT_EQUAL_HEX8(0x40u, two[0]); /* PWR_MGMT_1 reset value */
    TEST_ASSERT_EQUAL_HEX8(0x00u, two[1]); /* PWR_MGMT_2 */
    TEST_ASSERT_EQUAL_UINT16(0u, mpu.clock_violations);
    /* argument checks: no frame */
    const uint32_t frames = sb.frames;
    uint8_t buf[16];
    TEST_ASSERT_EQUAL(IMU_ERR_RANGE, imu_spi_read_regs(&sb.bus, 0x3Bu, buf, 0u));
    TEST_ASSERT_EQUAL(IMU_ERR_RANGE, imu_spi_read_regs(&sb.bus, 0x3Bu, buf, 16u));
    TEST_ASSERT_EQUAL(IMU_ERR_RANGE, imu_spi_read_regs(&sb.bus, 0x80u, buf, 1u));
    TEST_ASSERT_EQUAL(IMU_ERR_RANGE, imu_spi_write_reg(&sb.bus, 0x80u, 0u));
    TEST_ASSERT_EQUAL(IMU_ERR_NULL, imu_spi_read_regs(NULL, 0x3Bu, buf, 1u));
    TEST_ASSERT_EQUAL(IMU_ERR_NULL, imu_spi_read_regs(&sb.bus, 0x3Bu, NULL, 1u));
    TEST_ASSERT_EQUAL(IMU_ERR_NULL, imu_spi_write_reg(NULL, 0x19u, 0u));
    TEST_ASSERT_EQUAL(IMU_ERR_NULL, imu_spi_write_seq(&sb.bus, NULL, 1u));
    TEST_ASSERT_EQUAL(IMU_ERR_NULL, imu_spi_verify_seq(&sb.bus, NULL, 1u));
    TEST_ASSERT_EQUAL_UINT32(frames, sb.frames);
    /* a bus error is reported */
    sb.fail_frame = sb.frames + 1u;
    TEST_ASSERT_EQUAL(IMU_ERR_BUS, imu_spi_read_regs(&sb.bus, 0x75u, &v, 1u));
    sb.fail_clock = 1;
    TEST_ASSERT_EQUAL(IMU_ERR_BUS, imu_spi_set_clock(&sb.bus, 1000000u));
    /* a bus without set_clock is fine */
    sb.bus.set_clock = NULL;
    TEST_ASSERT_EQUAL(IMU_OK, imu_spi_set_clock(&sb.bus, 1000000u));
}

static void test_detect_each_chip(void)
{
    imu_chip_t chip = IMU_CHIP_NONE;
    uint8_t who = 0u;
    TEST_ASSERT_EQUAL(IMU_OK, imu_spi_detect(&sb.bus, &chip, &who));
    TEST_ASSERT_EQUAL(IMU_CHIP_MPU6000, chip);
    TEST_ASSERT_EQUAL_HEX8(0x68u, who);
    TEST_ASSERT_EQUAL_UINT32(1000000u, sb.sck_hz);
    TEST_ASSERT_EQUAL_UINT16(0u, mpu.clock_violations);
    TEST_ASSERT_EQUAL(IMU_OK, mpu6000_probe(&sb.bus));
    TEST_ASSERT_EQUAL(IMU_ERR_WRONG_ID, icm42688p_probe(&sb.bus));

    sim_bus_init(&sb, &icm, sim_icm42688p_frame);
    TEST_ASSERT_EQUAL(IMU_OK, imu_spi_detect(&sb.bus, &chip, &who));
    TEST_ASSERT_EQUAL(IMU_CHIP_ICM42688P, chip);
    TEST_ASSERT_EQUAL_HEX8(0x47u, who);
    TEST_ASSERT_EQUAL(IMU_OK, icm42688p_probe(&sb.bus));
    TEST_ASSERT_EQUAL(IMU_ERR_WRONG_ID, mpu6000_probe(&sb.bus));
    TEST_ASSERT_EQUAL_UINT16(0u, icm.clock_violations);
}

static void test_detect_nothing(void)
{
    imu_chip_t chip = IMU_CHIP_MPU6000;
    /* no chip, MISO pulled up */
    sim_bus_init(&sb, NULL, NULL);
    TEST_ASSERT_EQUAL(IMU_ERR_NO_DEVICE, imu_spi_detect(&sb.bus, &chip, NULL));
    TEST_ASSERT_EQUAL(IMU_CHIP_NONE, chip);
    TEST_ASSERT_EQUAL_UINT32(1u, sb.frames); /* one try, no wait, no hang */
    TEST_ASSERT_EQUAL(IMU_ERR_NO_DEVICE, mpu6000_probe(&sb.bus));
    TEST_ASSERT_EQUAL(IMU_ERR_NO_DEVICE, icm42688p_probe(&sb.bus));
    /* MISO stuck low */
    sb.stuck_miso = 0x00;
    TEST_ASSERT_EQUAL(IMU_ERR_NO_DEVICE, imu_spi_detect(&sb.bus, &chip, NULL));
    /* MISO stuck high with a chip on the bus (broken line) */
    sim_bus_init(&sb, &mpu, sim_mpu6000_frame);
    sb.stuck_miso = 0xFF;
    TEST_ASSERT_EQUAL(IMU_ERR_NO_DEVICE, imu_spi_detect(&sb.bus, &chip, NULL));
    /* the whole init gives up at once too */
    imu_spi_t imu;
    memset(&imu, 0, sizeof imu);
    const imu_spi_config_t cfg = {IMU_ALIGN_YAW0, IMU_ALIGN_YAW0, IMU_LPF_MEDIUM};
    sb.frames = 0u;
    TEST_ASSERT_EQUAL(IMU_ERR_NO_DEVICE, imu_spi_init(&imu, &sb.bus, &cfg));
    TEST_ASSERT_EQUAL_UINT32(1u, sb.frames);
    TEST_ASSERT_EQUAL_UINT32(0u, sb.delays);
    TEST_ASSERT_EQUAL_UINT8(0u, imu.ready);
    ht_imu_sample_t s;
    TEST_ASSERT_EQUAL(IMU_ERR_NOT_READY, imu_spi_read(&imu, &s));
}

static void test_detect_stranger_and_errors(void)
{
    imu_chip_t chip = IMU_CHIP_MPU6000;
    uint8_t who = 0u;
    mpu.regs[0x75] = 0x70u; /* another InvenSense part answering */
    TEST_ASSERT_EQUAL(IMU_ERR_WRONG_ID, imu_spi_detect(&sb.bus, &chip, &who));
    TEST_ASSERT_EQUAL(IMU_CHIP_NONE, chip);
    TEST_ASSERT_EQUAL_HEX8(0x70u, who);
    imu_spi_t imu;
    memset(&imu, 0, sizeof imu);
    const imu_spi_config_t cfg = {IMU_ALIGN_YAW0, IMU_ALIGN_YAW0, IMU_LPF_MEDIUM};
    TEST_ASSERT_EQUAL(IMU_ERR_WRONG_ID, imu_spi_init(&imu, &sb.bus, &cfg));
    TEST_ASSERT_EQUAL_UINT8(0u, imu.ready);
    TEST_ASSERT_EQUAL_UINT16(0u, mpu.log_n); /* nothing written to a stranger */
    /* bus errors */
    sb.fail_frame = sb.frames + 1u;
    TEST_ASSERT_EQUAL(IMU_ERR_BUS, imu_spi_detect(&sb.bus, &chip, &who));
    sb.fail_clock = 1;
    TEST_ASSERT_EQUAL(IMU_ERR_BUS, imu_spi_detect(&sb.bus, &chip, &who));
    TEST_ASSERT_EQUAL(IMU_ERR_NULL, imu_spi_detect(NULL, &chip, &who));
    TEST_ASSERT_EQUAL(IMU_ERR_NULL, imu_spi_detect(&sb.bus, NULL, &who));
}

static void test_init_refuses_bad_config(void)
{
    imu_spi_t imu;
    memset(&imu, 0, sizeof imu);
    imu_spi_config_t cfg = {IMU_ALIGN_COUNT, IMU_ALIGN_YAW0, IMU_LPF_MEDIUM};
    TEST_ASSERT_EQUAL(IMU_ERR_RANGE, imu_spi_init(&imu, &sb.bus, &cfg));
    cfg.align_mpu6000 = IMU_ALIGN_YAW0;
    cfg.align_icm42688p = IMU_ALIGN_COUNT;
    TEST_ASSERT_EQUAL(IMU_ERR_RANGE, imu_spi_init(&imu, &sb.bus, &cfg));
    cfg.align_icm42688p = IMU_ALIGN_YAW0;
    cfg.lpf = IMU_LPF_COUNT;
    TEST_ASSERT_EQUAL(IMU_ERR_RANGE, imu_spi_init(&imu, &sb.bus, &cfg));
    TEST_ASSERT_EQUAL_UINT32(0u, sb.frames); /* refused before any bus access */
    TEST_ASSERT_EQUAL(IMU_ERR_NULL, imu_spi_init(NULL, &sb.bus, &cfg));
    TEST_ASSERT_EQUAL(IMU_ERR_NULL, imu_spi_init(&imu, NULL, &cfg));
    TEST_ASSERT_EQUAL(IMU_ERR_NULL, imu_spi_init(&imu, &sb.bus, NULL));
    imu_spi_bus_t no_delay = sb.bus;
    no_delay.delay_us = NULL;
    cfg.lpf = IMU_LPF_MEDIUM;
    TEST_ASSERT_EQUAL(IMU_ERR_NULL, imu_spi_init(&imu, &no_delay, &cfg));
    ht_imu_sample_t s;
    TEST_ASSERT_EQUAL(IMU_ERR_NULL, imu_spi_read(NULL, &s));
    TEST_ASSERT_EQUAL(IMU_ERR_NULL, imu_spi_read(&imu, NULL));
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_be16);
    RUN_TEST(test_gyro_scale);
    RUN_TEST(test_accel_scale);
    RUN_TEST(test_alignment_every_value);
    RUN_TEST(test_div_round_and_temperature);
    RUN_TEST(test_register_frames);
    RUN_TEST(test_detect_each_chip);
    RUN_TEST(test_detect_nothing);
    RUN_TEST(test_detect_stranger_and_errors);
    RUN_TEST(test_init_refuses_bad_config);
    return UNITY_END();
}
