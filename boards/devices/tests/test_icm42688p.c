/*
 * test_icm42688p.c - the ICM-42688-P driver against the simulated chip
 * (sim_icm42688p.h): reset and configuration, the burst read, scaling,
 * saturation, alignment, invalid samples, byte order, failures.
 *
 * Configuration expected, worked from DS-000347 (bank-0 register map):
 *   DEVICE_CONFIG (0x11) = 0x01   SOFT_RESET_CONFIG; 1 ms; INT_STATUS bit 4
 *   INTF_CONFIG0 (0x4C) = 0x33    endian bits 5:4 kept 1 (big), UI_SIFS_CFG 11
 *   INT_CONFIG (0x14) = 0x03      INT1 pulsed (bit 2 = 0), push-pull (bit 1),
 *                                 active high (bit 0)
 *   INT_CONFIG1 (0x64) = 0x00     INT_ASYNC_RESET (bit 4) cleared
 *   INT_SOURCE0 (0x65) = 0x08     UI_DRDY_INT1_EN (bit 3)
 *   GYRO_CONFIG0 (0x4F) = 0x06    GYRO_FS_SEL 000 (+/-2000 deg/s), ODR 0110 (1 kHz)
 *   ACCEL_CONFIG0 (0x50) = 0x06   ACCEL_FS_SEL 000 (+/-16 g), ODR 0110 (1 kHz)
 *   GYRO_ACCEL_CONFIG0 (0x52) = 0x11/0x44/0x66/0x77 per filter
 *   PWR_MGMT0 (0x4E) = 0x0F       gyro and accel low noise; then 200 us
 *   time: 1 ms + 200 us + 30 ms = 31200 us of delay_us; SCK 24 MHz.
 * (GYRO_CONFIG0 and ACCEL_CONFIG0 reset to 0x06 already: the write log, not
 * the data, proves they are set.)
 * Data: 14 bytes from TEMP_DATA1 (0x1D), big-endian: temp, accel X, Y, Z,
 * gyro X, Y, Z; a sensor that is off reads -32768. Same nominal scale as the
 * MPU-6000: 2 rad/s -> 1879 counts -> 131051 Q16; 40 rad/s -> 32767 ->
 * 2285336; -40 -> -32768 -> -2285406; +/-20 g -> 1048544 / -1048576.
 */
#include "unity.h"

#include "icm42688p.h"
#include "imu_spi.h"
#include "imu_test_util.h"
#include "sim_bus.h"
#include "sim_icm42688p.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static sim_bus_t sb;
static sim_icm42688p_t icm;
static imu_spi_t imu;

void setUp(void)
{
    sim_icm42688p_init(&icm);
    sim_bus_init(&sb, &icm, sim_icm42688p_frame);
    memset(&imu, 0, sizeof imu);
}

void tearDown(void) {}

static void init_ok(uint8_t align)
{
    const imu_spi_config_t cfg = {IMU_ALIGN_YAW0, align, IMU_LPF_MEDIUM};
    TEST_ASSERT_EQUAL(IMU_OK, imu_spi_init(&imu, &sb.bus, &cfg));
    TEST_ASSERT_EQUAL_UINT8(1u, imu.ready);
    TEST_ASSERT_EQUAL(IMU_CHIP_ICM42688P, imu.chip);
}

static void test_init_writes_exactly(void)
{
    init_ok(IMU_ALIGN_FLIP_YAW0);
    const uint8_t want_reg[] = {0x11u, 0x4Cu, 0x14u, 0x64u, 0x65u, 0x4Fu, 0x50u, 0x52u, 0x4Eu};
    const uint8_t want_val[] = {0x01u, 0x33u, 0x03u, 0x00u, 0x08u, 0x06u, 0x06u, 0x44u, 0x0Fu};
    TEST_ASSERT_EQUAL_UINT16(sizeof want_reg, icm.log_n);
    TEST_ASSERT_EQUAL_HEX8_ARRAY(want_reg, icm.log_reg, sizeof want_reg);
    TEST_ASSERT_EQUAL_HEX8_ARRAY(want_val, icm.log_val, sizeof want_val);
    TEST_ASSERT_EQUAL_UINT16(1u, icm.resets);
    TEST_ASSERT_EQUAL_UINT16(0u, icm.dropped_writes);
    TEST_ASSERT_EQUAL_UINT16(0u, icm.foreign_writes);
    TEST_ASSERT_EQUAL_UINT16(0u, icm.clock_violations);
    TEST_ASSERT_EQUAL_UINT64(31200u, sb.now_us);
    TEST_ASSERT_EQUAL_UINT32(24000000u, sb.sck_hz);
    TEST_ASSERT_EQUAL_HEX8(0x0Fu, icm.regs[0x4E]);
    TEST_ASSERT_EQUAL_HEX8(0x00u, icm.regs[0x64]);
}

static void test_filter_choices(void)
{
    const uint8_t bw[IMU_LPF_COUNT] = {0x11u, 0x44u, 0x66u, 0x77u};
    for (uint8_t f = 0u; f < (uint8_t)IMU_LPF_COUNT; ++f) {
        setUp();
        TEST_ASSERT_EQUAL_HEX8(bw[f], icm42688p_filter_bw(f));
        TEST_ASSERT_EQUAL(IMU_OK, icm42688p_init(&sb.bus, f));
        TEST_ASSERT_EQUAL_HEX8(bw[f], icm.regs[0x52]);
    }
    setUp();
    TEST_ASSERT_EQUAL_HEX8(0xFFu, icm42688p_filter_bw(IMU_LPF_COUNT));
    TEST_ASSERT_EQUAL(IMU_ERR_RANGE, icm42688p_init(&sb.bus, IMU_LPF_COUNT));
    TEST_ASSERT_EQUAL_UINT32(0u, sb.frames);
    TEST_ASSERT_EQUAL(IMU_ERR_NULL, icm42688p_init(NULL, IMU_LPF_WIDE));
}

static void check_motion(const double rate[3], const double accel[3])
{
    sim_icm42688p_set_motion(&icm, rate, accel);
    ht_imu_sample_t s;
    memset(&s, 0, sizeof s);
    TEST_ASSERT_EQUAL(IMU_OK, imu_spi_read(&imu, &s));
    for (int i = 0; i < 3; ++i) {
        const int16_t gc = sim_icm42688p_gyro_counts(&icm, rate[i]);
        const int16_t ac = sim_icm42688p_accel_counts(&icm, accel[i]);
        TEST_ASSERT_INT32_WITHIN(1, (int32_t)lround(gyro_q16_exact(gc)), s.gyro_rad_s[i]);
        TEST_ASSERT_EQUAL_INT32((int32_t)ac * 32, s.accel_g[i]);
        if (gc != 32767 && gc != -32768) {
            TEST_ASSERT_INT32_WITHIN(36, (int32_t)lround(rate[i] * 65536.0), s.gyro_rad_s[i]);
        }
        if (ac != 32767 && ac != -32768) {
            TEST_ASSERT_INT32_WITHIN(17, (int32_t)lround(accel[i] * 65536.0), s.accel_g[i]);
        }
    }
}

static void test_burst_read_values(void)
{
    init_ok(IMU_ALIGN_FLIP_YAW0);
    const double rate1[3] = {0.5, -1.0, 2.0};
    const double accel1[3] = {0.0, 0.0, -1.0};
    check_motion(rate1, accel1);
    const double rate2[3] = {34.8, -34.8, 0.001};
    const double accel2[3] = {15.9, -15.9, 0.3};
    check_motion(rate2, accel2);
    const double rate3[3] = {-0.01, 0.02, -7.5};
    const double accel3[3] = {1.2, -0.7, 2.5};
    check_motion(rate3, accel3);
    TEST_ASSERT_EQUAL_UINT16(0u, icm.clock_violations);
    TEST_ASSERT_EQUAL_UINT16(0u, imu.read_errors);
    icm.temp_c = 35.0;
    ht_imu_sample_t s;
    TEST_ASSERT_EQUAL(IMU_OK, imu_spi_read(&imu, &s));
    TEST_ASSERT_INT16_WITHIN(1, 3500, imu.temp_cdeg);
}

static void test_saturation_exact(void)
{
    init_ok(IMU_ALIGN_FLIP_YAW0);
    const double rate[3] = {40.0, -40.0, 2.0};
    const double accel[3] = {20.0, -20.0, -1.0};
    sim_icm42688p_set_motion(&icm, rate, accel);
    ht_imu_sample_t s;
    TEST_ASSERT_EQUAL(IMU_OK, imu_spi_read(&imu, &s));
    TEST_ASSERT_EQUAL_INT32(2285336, s.gyro_rad_s[0]);
    TEST_ASSERT_EQUAL_INT32(-2285406, s.gyro_rad_s[1]);
    TEST_ASSERT_EQUAL_INT32(131051, s.gyro_rad_s[2]);
    TEST_ASSERT_EQUAL_INT32(1048544, s.accel_g[0]);
    TEST_ASSERT_EQUAL_INT32(-1048576, s.accel_g[1]);
    TEST_ASSERT_EQUAL_INT32(-65536, s.accel_g[2]);
}

static void test_alignment_through_the_chain(void)
{
    const double body_rate[3] = {0.5, -1.0, 2.0};
    const double body_accel[3] = {0.1, 0.2, -1.0};
    for (unsigned a = 0u; a < (unsigned)IMU_ALIGN_COUNT; ++a) {
        setUp();
        init_ok((uint8_t)a);
        double chip_rate[3];
        double chip_accel[3];
        chip_from_body(a, body_rate, chip_rate);
        chip_from_body(a, body_accel, chip_accel);
        sim_icm42688p_set_motion(&icm, chip_rate, chip_accel);
        ht_imu_sample_t s;
        TEST_ASSERT_EQUAL(IMU_OK, imu_spi_read(&imu, &s));
        for (int i = 0; i < 3; ++i) {
            TEST_ASSERT_INT32_WITHIN(36, (int32_t)lround(body_rate[i] * 65536.0), s.gyro_rad_s[i]);
            TEST_ASSERT_INT32_WITHIN(17, (int32_t)lround(body_accel[i] * 65536.0), s.accel_g[i]);
        }
    }
}

/* The alignment is taken per chip: the MPU-6000 entry does not apply here. */
static void test_alignment_per_chip(void)
{
    const imu_spi_config_t cfg = {IMU_ALIGN_YAW90, IMU_ALIGN_YAW270, IMU_LPF_WIDE};
    TEST_ASSERT_EQUAL(IMU_OK, imu_spi_init(&imu, &sb.bus, &cfg));
    TEST_ASSERT_EQUAL_UINT8(IMU_ALIGN_YAW270, imu.align);
}

static void test_byte_order_and_address_matter(void)
{
    init_ok(IMU_ALIGN_FLIP_YAW0);
    const double rate[3] = {0.5, -1.0, 2.0};
    const double accel[3] = {0.0, 0.0, -1.0};
    sim_icm42688p_set_motion(&icm, rate, accel);
    /* a burst one register off does not give the motion back */
    uint8_t b[14];
    TEST_ASSERT_EQUAL(IMU_OK, imu_spi_read_regs(&sb.bus, 0x1Eu, b, 14u));
    const int16_t gx = sim_icm42688p_gyro_counts(&icm, rate[0]);
    TEST_ASSERT_NOT_EQUAL(gx, imu_be16(&b[8]));
    TEST_ASSERT_EQUAL(IMU_OK, imu_spi_read_regs(&sb.bus, 0x1Du, b, 14u));
    TEST_ASSERT_EQUAL_INT16(gx, imu_be16(&b[8]));
    /* the chip switched to little-endian: the driver's sample is wrong, so a
     * driver that cleared SENSOR_DATA_ENDIAN would fail check_motion */
    icm.regs[0x4C] &= (uint8_t)~0x10u;
    ht_imu_sample_t s;
    TEST_ASSERT_EQUAL(IMU_OK, imu_spi_read(&imu, &s));
    TEST_ASSERT_TRUE(labs((long)s.gyro_rad_s[0] - lround(rate[0] * 65536.0)) > 1000);
    TEST_ASSERT_TRUE(labs((long)s.accel_g[2] + 65536L) > 1000);
}

static void test_sensors_off_is_no_data(void)
{
    init_ok(IMU_ALIGN_FLIP_YAW0);
    icm.regs[0x4E] = 0x00u; /* both sensors off: -32768 everywhere */
    ht_imu_sample_t s;
    memset(&s, 0x5A, sizeof s);
    TEST_ASSERT_EQUAL(IMU_ERR_DATA, imu_spi_read(&imu, &s));
    TEST_ASSERT_EQUAL_UINT16(1u, imu.read_errors);
    TEST_ASSERT_EQUAL_HEX32(0x5A5A5A5Au, (uint32_t)s.accel_g[2]);
    /* one sensor saturated at -32768 on all its axes is still data */
    icm.regs[0x4E] = 0x0Fu;
    const double rate[3] = {-40.0, -40.0, -40.0};
    const double accel[3] = {0.0, 0.0, 1.0};
    sim_icm42688p_set_motion(&icm, rate, accel);
    TEST_ASSERT_EQUAL(IMU_OK, imu_spi_read(&imu, &s));
    TEST_ASSERT_EQUAL_INT32(-2285406, s.gyro_rad_s[2]);
}

static void test_sim_enforces_power_on_wait(void)
{
    /* the 200 us rule the driver honours: a write right after PWR_MGMT0
     * turns the sensors on is lost */
    TEST_ASSERT_EQUAL(IMU_OK, imu_spi_set_clock(&sb.bus, 24000000u));
    TEST_ASSERT_EQUAL(IMU_OK, imu_spi_write_reg(&sb.bus, 0x4Eu, 0x0Fu));
    TEST_ASSERT_EQUAL(IMU_OK, imu_spi_write_reg(&sb.bus, 0x52u, 0x77u));
    TEST_ASSERT_EQUAL_UINT16(1u, icm.dropped_writes);
    TEST_ASSERT_EQUAL_HEX8(0x11u, icm.regs[0x52]);
    sb.bus.delay_us(sb.bus.ctx, 200u);
    TEST_ASSERT_EQUAL(IMU_OK, imu_spi_write_reg(&sb.bus, 0x52u, 0x77u));
    TEST_ASSERT_EQUAL_HEX8(0x77u, icm.regs[0x52]);
    /* and the clock limit */
    TEST_ASSERT_EQUAL(IMU_OK, imu_spi_set_clock(&sb.bus, 25000000u));
    uint8_t v;
    TEST_ASSERT_EQUAL(IMU_OK, imu_spi_read_regs(&sb.bus, 0x75u, &v, 1u));
    TEST_ASSERT_EQUAL_UINT16(1u, icm.clock_violations);
}

static void test_reset_never_done(void)
{
    icm.reset_busy_us = 10000000u;
    const imu_spi_config_t cfg = {IMU_ALIGN_YAW0, IMU_ALIGN_YAW0, IMU_LPF_MEDIUM};
    TEST_ASSERT_EQUAL(IMU_ERR_RESET_TIMEOUT, imu_spi_init(&imu, &sb.bus, &cfg));
    TEST_ASSERT_EQUAL_UINT8(0u, imu.ready);
    TEST_ASSERT_EQUAL_UINT32(12u, sb.frames); /* probe, reset, 10 polls */
    TEST_ASSERT_EQUAL_UINT64(11000u, sb.now_us);
}

static void test_config_not_taken(void)
{
    icm.ignore_write_reg = 0x64u; /* INT_CONFIG1 keeps its reset 0x10 */
    const imu_spi_config_t cfg = {IMU_ALIGN_YAW0, IMU_ALIGN_YAW0, IMU_LPF_MEDIUM};
    TEST_ASSERT_EQUAL(IMU_ERR_CONFIG, imu_spi_init(&imu, &sb.bus, &cfg));
    TEST_ASSERT_EQUAL_UINT8(0u, imu.ready);
    setUp();
    sb.fail_frame = 5u;
    TEST_ASSERT_EQUAL(IMU_ERR_BUS, imu_spi_init(&imu, &sb.bus, &cfg));
    TEST_ASSERT_EQUAL_UINT8(0u, imu.ready);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_init_writes_exactly);
    RUN_TEST(test_filter_choices);
    RUN_TEST(test_burst_read_values);
    RUN_TEST(test_saturation_exact);
    RUN_TEST(test_alignment_through_the_chain);
    RUN_TEST(test_alignment_per_chip);
    RUN_TEST(test_byte_order_and_address_matter);
    RUN_TEST(test_sensors_off_is_no_data);
    RUN_TEST(test_sim_enforces_power_on_wait);
    RUN_TEST(test_reset_never_done);
    RUN_TEST(test_config_not_taken);
    return UNITY_END();
}
