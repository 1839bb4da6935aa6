/*
 * test_mpu6000.c - the MPU-6000 driver against the simulated chip
 * (sim_mpu6000.h): reset and configuration, the burst read, scaling,
 * saturation, alignment, failures.
 *
 * Configuration expected, worked from RM-MPU-6000A-00 rev 4.2:
 *   PWR_MGMT_1 (0x6B) = 0x80   DEVICE_RESET (bit 7); then 100 ms, poll 0x40
 *   SIGNAL_PATH_RESET (0x68) = 0x07   GYRO|ACCEL|TEMP_RESET; then 100 ms
 *   USER_CTRL (0x6A) = 0x10    I2C_IF_DIS (bit 4)
 *   PWR_MGMT_1 (0x6B) = 0x03   SLEEP 0, CLKSEL 3 (PLL, Z gyro)
 *   SMPLRT_DIV (0x19) = 0x00   1 kHz / (1 + 0)
 *   CONFIG (0x1A) = 1/2/3/4    DLPF_CFG per filter (188/98/42/20 Hz gyro)
 *   GYRO_CONFIG (0x1B) = 0x18  FS_SEL 3 (bits 4:3): +/-2000 deg/s
 *   ACCEL_CONFIG (0x1C) = 0x18 AFS_SEL 3: +/-16 g
 *   INT_PIN_CFG (0x37) = 0x10  active high, push-pull, 50 us pulse, read clears
 *   INT_ENABLE (0x38) = 0x01   DATA_RDY_EN
 *   time: 100 + 100 + 30 ms = 230000 us of delay_us; SCK 1 MHz, then 20 MHz.
 * Data: 14 bytes from ACCEL_XOUT_H (0x3B), big-endian: accel X, Y, Z, temp,
 * gyro X, Y, Z. At 16.4 LSB per deg/s, 2 rad/s = 114.59 deg/s = 1879.3 ->
 * 1879 counts -> 1879 * 69.745060 = 131051.0 Q16 (2 rad/s = 131072: the
 * count's quantum is 69.7 Q16). At 2048 LSB/g, -1 g = -2048 -> -65536.
 * Saturation: 40 rad/s -> 32767 -> 2285336; -40 -> -32768 -> -2285406;
 * 20 g -> 32767 -> 1048544; -20 g -> -32768 -> -1048576.
 */
#include "unity.h"

#include "imu_spi.h"
#include "imu_test_util.h"
#include "mpu6000.h"
#include "sim_bus.h"
#include "sim_mpu6000.h"

#include <math.h>
#include <string.h>

static sim_bus_t sb;
static sim_mpu6000_t mpu;
static imu_spi_t imu;

void setUp(void)
{
    sim_mpu6000_init(&mpu);
    sim_bus_init(&sb, &mpu, sim_mpu6000_frame);
    memset(&imu, 0, sizeof imu);
}

void tearDown(void) {}

static void init_ok(uint8_t align)
{
    const imu_spi_config_t cfg = {align, IMU_ALIGN_YAW0, IMU_LPF_MEDIUM};
    TEST_ASSERT_EQUAL(IMU_OK, imu_spi_init(&imu, &sb.bus, &cfg));
    TEST_ASSERT_EQUAL_UINT8(1u, imu.ready);
    TEST_ASSERT_EQUAL(IMU_CHIP_MPU6000, imu.chip);
}

static void test_init_writes_exactly(void)
{
    init_ok(IMU_ALIGN_FLIP_YAW0);
    const uint8_t want_reg[] = {0x6Bu, 0x68u, 0x6Au, 0x6Bu, 0x19u,
                                0x1Au, 0x1Bu, 0x1Cu, 0x37u, 0x38u};
    const uint8_t want_val[] = {0x80u, 0x07u, 0x10u, 0x03u, 0x00u,
                                0x02u, 0x18u, 0x18u, 0x10u, 0x01u};
    TEST_ASSERT_EQUAL_UINT16(sizeof want_reg, mpu.log_n);
    TEST_ASSERT_EQUAL_HEX8_ARRAY(want_reg, mpu.log_reg, sizeof want_reg);
    TEST_ASSERT_EQUAL_HEX8_ARRAY(want_val, mpu.log_val, sizeof want_val);
    TEST_ASSERT_EQUAL_UINT16(1u, mpu.resets);
    TEST_ASSERT_EQUAL_UINT16(0u, mpu.dropped_writes);   /* every wait long enough */
    TEST_ASSERT_EQUAL_UINT16(0u, mpu.clock_violations); /* registers at 1 MHz */
    TEST_ASSERT_EQUAL_UINT64(230000u, sb.now_us);
    TEST_ASSERT_EQUAL_UINT32(20000000u, sb.sck_hz);
    /* the chip holds them (read back by the driver too) */
    TEST_ASSERT_EQUAL_HEX8(0x03u, mpu.regs[0x6B]);
    TEST_ASSERT_EQUAL_HEX8(0x18u, mpu.regs[0x1B]);
}

static void test_filter_choices(void)
{
    const uint8_t dlpf[IMU_LPF_COUNT] = {1u, 2u, 3u, 4u};
    for (uint8_t f = 0u; f < (uint8_t)IMU_LPF_COUNT; ++f) {
        setUp();
        TEST_ASSERT_EQUAL_HEX8(dlpf[f], mpu6000_dlpf_cfg(f));
        TEST_ASSERT_EQUAL(IMU_OK, mpu6000_init(&sb.bus, f));
        TEST_ASSERT_EQUAL_HEX8(dlpf[f], mpu.regs[0x1A]);
    }
    setUp();
    TEST_ASSERT_EQUAL_HEX8(0xFFu, mpu6000_dlpf_cfg(IMU_LPF_COUNT));
    TEST_ASSERT_EQUAL(IMU_ERR_RANGE, mpu6000_init(&sb.bus, IMU_LPF_COUNT));
    TEST_ASSERT_EQUAL_UINT32(0u, sb.frames);
    TEST_ASSERT_EQUAL(IMU_ERR_NULL, mpu6000_init(NULL, IMU_LPF_WIDE));
}

/* Read one sample of a motion given in chip axes with the identity
 * alignment (FLIP_YAW0) and check every axis within 1 LSB of the exact
 * product of the count the chip put out, and within half a count of the
 * physical value (unless saturated). */
static void check_motion(const double rate[3], const double accel[3])
{
    sim_mpu6000_set_motion(&mpu, rate, accel);
    ht_imu_sample_t s;
    memset(&s, 0, sizeof s);
    TEST_ASSERT_EQUAL(IMU_OK, imu_spi_read(&imu, &s));
    for (int i = 0; i < 3; ++i) {
        const int16_t gc = sim_mpu6000_gyro_counts(&mpu, rate[i]);
        const int16_t ac = sim_mpu6000_accel_counts(&mpu, accel[i]);
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
    const double rate2[3] = {34.8, -34.8, 0.001}; /* near full scale, 1994 deg/s */
    const double accel2[3] = {15.9, -15.9, 0.3};
    check_motion(rate2, accel2);
    const double rate3[3] = {-0.01, 0.02, -7.5};
    const double accel3[3] = {1.2, -0.7, 2.5};
    check_motion(rate3, accel3);
    TEST_ASSERT_EQUAL_UINT16(0u, mpu.clock_violations); /* data at 20 MHz is allowed */
    TEST_ASSERT_EQUAL_UINT16(0u, imu.read_errors);
    TEST_ASSERT_INT16_WITHIN(1, 2500, imu.temp_cdeg); /* the sim's 25 degC */
}

static void test_saturation_exact(void)
{
    init_ok(IMU_ALIGN_FLIP_YAW0);
    const double rate[3] = {40.0, -40.0, 2.0};
    const double accel[3] = {20.0, -20.0, -1.0};
    sim_mpu6000_set_motion(&mpu, rate, accel);
    ht_imu_sample_t s;
    TEST_ASSERT_EQUAL(IMU_OK, imu_spi_read(&imu, &s));
    TEST_ASSERT_EQUAL_INT32(2285336, s.gyro_rad_s[0]);
    TEST_ASSERT_EQUAL_INT32(-2285406, s.gyro_rad_s[1]);
    TEST_ASSERT_EQUAL_INT32(131051, s.gyro_rad_s[2]);
    TEST_ASSERT_EQUAL_INT32(1048544, s.accel_g[0]);
    TEST_ASSERT_EQUAL_INT32(-1048576, s.accel_g[1]);
    TEST_ASSERT_EQUAL_INT32(-65536, s.accel_g[2]);
}

/* Every alignment through the whole chain: a body-axes truth turned into
 * what the chip would read (the independent model), read back in body axes. */
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
        sim_mpu6000_set_motion(&mpu, chip_rate, chip_accel);
        ht_imu_sample_t s;
        TEST_ASSERT_EQUAL(IMU_OK, imu_spi_read(&imu, &s));
        for (int i = 0; i < 3; ++i) {
            TEST_ASSERT_INT32_WITHIN(36, (int32_t)lround(body_rate[i] * 65536.0), s.gyro_rad_s[i]);
            TEST_ASSERT_INT32_WITHIN(17, (int32_t)lround(body_accel[i] * 65536.0), s.accel_g[i]);
        }
    }
}

/* The sim decodes the frame: a burst one register off, or read with the
 * bytes swapped, does not give the motion back (so a driver doing either
 * fails the tests above). */
static void test_sim_decodes_address_and_byte_order(void)
{
    init_ok(IMU_ALIGN_FLIP_YAW0);
    const double rate[3] = {0.5, -1.0, 2.0};
    const double accel[3] = {0.0, 0.0, -1.0};
    sim_mpu6000_set_motion(&mpu, rate, accel);
    uint8_t b[14];
    TEST_ASSERT_EQUAL(IMU_OK, imu_spi_read_regs(&sb.bus, 0x3Bu, b, 14u));
    const int16_t gx = sim_mpu6000_gyro_counts(&mpu, rate[0]);
    const int16_t az = sim_mpu6000_accel_counts(&mpu, accel[2]);
    TEST_ASSERT_EQUAL_INT16(gx, imu_be16(&b[8]));
    TEST_ASSERT_EQUAL_INT16(az, imu_be16(&b[4]));
    const uint8_t swapped[2] = {b[9], b[8]};
    TEST_ASSERT_NOT_EQUAL(gx, imu_be16(swapped));
    TEST_ASSERT_EQUAL(IMU_OK, imu_spi_read_regs(&sb.bus, 0x3Cu, b, 14u));
    TEST_ASSERT_NOT_EQUAL(gx, imu_be16(&b[8]));
    TEST_ASSERT_NOT_EQUAL(az, imu_be16(&b[4]));
    /* and a register write at the data clock is caught (the burst from 0x3C
     * already reached 0x49, outside the 20 MHz registers) */
    const uint16_t before = mpu.clock_violations;
    TEST_ASSERT_EQUAL(IMU_OK, imu_spi_write_reg(&sb.bus, 0x19u, 0x00u));
    TEST_ASSERT_EQUAL_UINT16(before + 1u, mpu.clock_violations);
}

static void test_sleep_blocks_data(void)
{
    /* after reset the chip sleeps: its data registers hold their reset 0 */
    TEST_ASSERT_EQUAL(IMU_OK, imu_spi_set_clock(&sb.bus, 20000000u));
    int16_t a[3];
    int16_t g[3];
    int16_t t;
    TEST_ASSERT_EQUAL(IMU_ERR_DATA, mpu6000_read_raw(&sb.bus, a, g, &t));
    /* awake it samples; put back to sleep it keeps the last sample */
    init_ok(IMU_ALIGN_FLIP_YAW0);
    const double rate1[3] = {0.5, -1.0, 2.0};
    const double accel1[3] = {0.0, 0.0, -1.0};
    sim_mpu6000_set_motion(&mpu, rate1, accel1);
    ht_imu_sample_t s;
    TEST_ASSERT_EQUAL(IMU_OK, imu_spi_read(&imu, &s));
    mpu.regs[0x6B] |= 0x40u;
    const double rate2[3] = {-3.0, 3.0, -3.0};
    sim_mpu6000_set_motion(&mpu, rate2, accel1);
    ht_imu_sample_t s2;
    TEST_ASSERT_EQUAL(IMU_OK, imu_spi_read(&imu, &s2));
    TEST_ASSERT_EQUAL_INT32(s.gyro_rad_s[0], s2.gyro_rad_s[0]);
    TEST_ASSERT_EQUAL(IMU_ERR_NULL, mpu6000_read_raw(&sb.bus, NULL, g, &t));
}

static void test_read_errors_counted(void)
{
    init_ok(IMU_ALIGN_FLIP_YAW0);
    ht_imu_sample_t s;
    sb.fail_frame = sb.frames + 1u;
    TEST_ASSERT_EQUAL(IMU_ERR_BUS, imu_spi_read(&imu, &s));
    TEST_ASSERT_EQUAL_UINT16(1u, imu.read_errors);
    sb.stuck_miso = 0xFF; /* the chip went away */
    TEST_ASSERT_EQUAL(IMU_ERR_DATA, imu_spi_read(&imu, &s));
    sb.stuck_miso = 0x00;
    TEST_ASSERT_EQUAL(IMU_ERR_DATA, imu_spi_read(&imu, &s));
    TEST_ASSERT_EQUAL_UINT16(3u, imu.read_errors);
    imu.read_errors = UINT16_MAX;
    TEST_ASSERT_EQUAL(IMU_ERR_DATA, imu_spi_read(&imu, &s));
    TEST_ASSERT_EQUAL_UINT16(UINT16_MAX, imu.read_errors);
    sb.stuck_miso = -1;
    TEST_ASSERT_EQUAL(IMU_OK, imu_spi_read(&imu, &s));
}

static void test_reset_never_done(void)
{
    mpu.reset_busy_us = 10000000u; /* the chip stays in reset */
    const imu_spi_config_t cfg = {IMU_ALIGN_YAW0, IMU_ALIGN_YAW0, IMU_LPF_MEDIUM};
    TEST_ASSERT_EQUAL(IMU_ERR_RESET_TIMEOUT, imu_spi_init(&imu, &sb.bus, &cfg));
    TEST_ASSERT_EQUAL_UINT8(0u, imu.ready);
    /* bounded: probe, reset write, 10 polls; 100 ms + 10 x 10 ms */
    TEST_ASSERT_EQUAL_UINT32(12u, sb.frames);
    TEST_ASSERT_EQUAL_UINT64(200000u, sb.now_us);
}

static void test_config_not_taken(void)
{
    mpu.ignore_write_reg = 0x1Bu; /* GYRO_CONFIG writes get lost */
    const imu_spi_config_t cfg = {IMU_ALIGN_YAW0, IMU_ALIGN_YAW0, IMU_LPF_MEDIUM};
    TEST_ASSERT_EQUAL(IMU_ERR_CONFIG, imu_spi_init(&imu, &sb.bus, &cfg));
    TEST_ASSERT_EQUAL_UINT8(0u, imu.ready);
    /* a bus failure in the middle of the configuration */
    setUp();
    sb.fail_frame = 6u;
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
    RUN_TEST(test_sim_decodes_address_and_byte_order);
    RUN_TEST(test_sleep_blocks_data);
    RUN_TEST(test_read_errors_counted);
    RUN_TEST(test_reset_never_done);
    RUN_TEST(test_config_not_taken);
    return UNITY_END();
}
