/*
 * test_baro_bmp280.c - the BMP280 driver: its compensation against the
 * datasheet's worked example and the double-precision formula, and its
 * bus protocol against the simulated chip (sim_bmp280.c).
 *
 * Worked example (BMP280 datasheet BST-BMP280-DS001, section 3.12, table
 * "compensation computation example"):
 *   dig_T1..T3 = 27504, 26435, -1000
 *   dig_P1..P9 = 36477, -10685, 3024, 2855, 140, -7, 15500, -14600, 6000
 *   adc_T = 519888 -> t_fine = 128422, T = 2508 (25.08 degC)
 *   adc_P = 415148 -> 100653.27 Pa (double); the table prints 25767236 for
 *   the 64-bit integer code, but the published 64-bit formula, executed
 *   exactly, gives 25767233 (100653.254 Pa): the printed figure is 3/256 Pa
 *   (0.012 Pa) off. The test demands the formula's 25767233 exactly, which
 *   is within 0.02 Pa of the printed one.
 * Those bytes at 0x88..0x9F, little-endian: 27504 = 0x6B70 -> 70 6B,
 *   26435 = 0x6743 -> 43 67, -1000 = 0xFC18 -> 18 FC, 36477 = 0x8E7D -> 7D 8E, ...
 * Registers written by init: config 0xF5 = 0x08 (t_sb 000, filter 010 = 4),
 *   ctrl_meas 0xF4 = 0x33 (osrs_t 001 = x1, osrs_p 100 = x8, mode 11 = normal).
 * Integer against double over the operating range (same t_fine): pressure
 *   within 0.02 Pa; temperature within 0.008 degC (t_fine drops adc_T's low 3
 *   bits, one unit of adc_T >> 3 being dig_T2 / 2048 = 12.9 t_fine = 0.0025
 *   degC, and the result is rounded to 0.01 degC).
 * Sim round trip tolerances: one ADC code is about 0.16 Pa and 0.0003 degC
 *   at these trimming values: pressure within 0.5 Pa, temperature within
 *   0.011 degC, altitude within 0.6 Pa * dh/dp (8.4 cm/Pa at sea level,
 *   28 cm/Pa at 300 hPa) + the table's 6 cm.
 */
#include "unity.h"

#include "baro_altitude.h"
#include "baro_bmp280.h"
#include "sim_bmp280.h"

#include <math.h>
#include <string.h>

static sim_bmp280_t sim;
static bmp280_t baro;
static i2c_bus_t bus;

void setUp(void)
{
    sim_bmp280_init(&sim, BMP280_ADDR_SDO_LOW, &sim_bmp280_example_cal);
    bus = sim_bmp280_bus(&sim);
    memset(&baro, 0, sizeof baro);
}

void tearDown(void) {}

static void test_datasheet_example(void)
{
    bmp280_reading_t r;
    TEST_ASSERT_EQUAL(BMP280_OK, bmp280_compensate(&sim_bmp280_example_cal, 519888, 415148, &r));
    TEST_ASSERT_EQUAL_INT32(128422, r.t_fine);
    TEST_ASSERT_EQUAL_INT32(2508, r.temp_cdeg);
    TEST_ASSERT_EQUAL_UINT32(25767233u, r.press_q24_8);
    TEST_ASSERT_UINT32_WITHIN(5u, 25767236u, r.press_q24_8);
    /* and the double formula, independently */
    double tf = 0.0;
    TEST_ASSERT_DOUBLE_WITHIN(0.005, 25.08,
                              sim_bmp280_ref_temp_c(&sim_bmp280_example_cal, 519888, &tf));
    TEST_ASSERT_DOUBLE_WITHIN(0.01, 100653.27,
                              sim_bmp280_ref_press_pa(&sim_bmp280_example_cal, 415148, tf));
}

static void test_parse_calib_little_endian(void)
{
    const uint8_t raw[BMP280_CALIB_LEN] = {0x70, 0x6B, 0x43, 0x67, 0x18, 0xFC, 0x7D, 0x8E,
                                           0x43, 0xD6, 0xD0, 0x0B, 0x27, 0x0B, 0x8C, 0x00,
                                           0xF9, 0xFF, 0x8C, 0x3C, 0xF8, 0xC6, 0x70, 0x17};
    bmp280_calib_t c;
    memset(&c, 0, sizeof c);
    bmp280_parse_calib(raw, &c);
    TEST_ASSERT_EQUAL_UINT16(27504u, c.t1);
    TEST_ASSERT_EQUAL_INT16(26435, c.t2);
    TEST_ASSERT_EQUAL_INT16(-1000, c.t3);
    TEST_ASSERT_EQUAL_UINT16(36477u, c.p1);
    TEST_ASSERT_EQUAL_INT16(-10685, c.p2);
    TEST_ASSERT_EQUAL_INT16(3024, c.p3);
    TEST_ASSERT_EQUAL_INT16(2855, c.p4);
    TEST_ASSERT_EQUAL_INT16(140, c.p5);
    TEST_ASSERT_EQUAL_INT16(-7, c.p6);
    TEST_ASSERT_EQUAL_INT16(15500, c.p7);
    TEST_ASSERT_EQUAL_INT16(-14600, c.p8);
    TEST_ASSERT_EQUAL_INT16(6000, c.p9);
    /* the simulated chip holds the same bytes */
    TEST_ASSERT_EQUAL_HEX8_ARRAY(raw, &sim.reg[0x88], BMP280_CALIB_LEN);
    bmp280_parse_calib(NULL, &c); /* harmless */
    bmp280_parse_calib(raw, NULL);
}

static void test_compensation_matches_double_reference(void)
{
    /* a grid over the operating range: every 20-bit code region the chip
     * can produce between about 250 and 1150 hPa, -40 and 85 degC */
    double worst_pa = 0.0;
    double worst_c = 0.0;
    for (int32_t adc_t = 380000; adc_t <= 680000; adc_t += 9973) {
        for (int32_t adc_p = 150000; adc_p <= 800000; adc_p += 7919) {
            bmp280_reading_t r;
            const bmp280_status_t st = bmp280_compensate(&sim_bmp280_example_cal, adc_t, adc_p, &r);
            double tf = 0.0;
            const double t_ref = sim_bmp280_ref_temp_c(&sim_bmp280_example_cal, adc_t, &tf);
            if (t_ref < -40.0 || t_ref > 85.0) {
                TEST_ASSERT_EQUAL(BMP280_ERR_RANGE, st);
                continue;
            }
            TEST_ASSERT_EQUAL(BMP280_OK, st);
            /* the integer code uses the integer t_fine, as the datasheet's does */
            const double p_ref =
                sim_bmp280_ref_press_pa(&sim_bmp280_example_cal, adc_p, (double)r.t_fine);
            const double dp = fabs((double)r.press_q24_8 / 256.0 - p_ref);
            const double dt = fabs((double)r.temp_cdeg / 100.0 - t_ref);
            worst_pa = (dp > worst_pa) ? dp : worst_pa;
            worst_c = (dt > worst_c) ? dt : worst_c;
        }
    }
    /* measured: 0.0092 Pa and 0.0063 degC */
    TEST_ASSERT_TRUE(worst_pa < 0.02);
    TEST_ASSERT_TRUE(worst_c < 0.008);
}

static void test_compensation_refuses_bad_input(void)
{
    bmp280_reading_t r;
    r.press_q24_8 = 7u;
    TEST_ASSERT_EQUAL(BMP280_ERR_NULL, bmp280_compensate(NULL, 519888, 415148, &r));
    TEST_ASSERT_EQUAL(BMP280_ERR_NULL,
                      bmp280_compensate(&sim_bmp280_example_cal, 519888, 415148, NULL));
    TEST_ASSERT_EQUAL(BMP280_ERR_RANGE, bmp280_compensate(&sim_bmp280_example_cal, -1, 415148, &r));
    TEST_ASSERT_EQUAL(BMP280_ERR_RANGE,
                      bmp280_compensate(&sim_bmp280_example_cal, 519888, 0x100000, &r));
    /* adc_T 0xFFFFF is about +240 degC: outside the operating range */
    TEST_ASSERT_EQUAL(BMP280_ERR_RANGE,
                      bmp280_compensate(&sim_bmp280_example_cal, 0xFFFFF, 415148, &r));
    bmp280_calib_t c = sim_bmp280_example_cal;
    c.p1 = 0u; /* the datasheet's division-by-zero case */
    TEST_ASSERT_EQUAL(BMP280_ERR_RANGE, bmp280_compensate(&c, 519888, 415148, &r));
    /* hostile trimming values: no overflow (UBSan watches), a status */
    c = sim_bmp280_example_cal;
    c.p1 = 65535u;
    c.p2 = 32767;
    c.p3 = 32767;
    c.p4 = -32768;
    c.p6 = -32768;
    c.p9 = 32767;
    c.p8 = 32767;
    (void)bmp280_compensate(&c, 519888, 0, &r);
    (void)bmp280_compensate(&c, 380000, 0xFFFFF, &r);
    c.p4 = 32767;
    c.p6 = 32767;
    r.press_q24_8 = 7u;
    TEST_ASSERT_EQUAL(BMP280_ERR_RANGE, bmp280_compensate(&c, 519888, 0xFFFFF, &r));
    TEST_ASSERT_EQUAL_UINT32(7u, r.press_q24_8); /* nothing written on a refusal */
}

static void test_init_talks_to_the_chip(void)
{
    sim.nvm_busy = 5u; /* im_update shown for 5 status reads after the reset */
    TEST_ASSERT_EQUAL(BMP280_OK, bmp280_init(&baro, &bus, BMP280_ADDR_SDO_LOW));
    TEST_ASSERT_EQUAL_UINT8(1u, baro.ready);
    TEST_ASSERT_EQUAL_UINT32(1u, sim.resets);
    TEST_ASSERT_EQUAL_HEX8(0x33u, sim.reg[0xF4]);
    TEST_ASSERT_EQUAL_HEX8(0x08u, sim.reg[0xF5]);
    TEST_ASSERT_EQUAL_MEMORY(&sim_bmp280_example_cal, &baro.cal, sizeof baro.cal);
    TEST_ASSERT_EQUAL_UINT16(0u, sim.nvm_left);
}

static void test_init_failures(void)
{
    sim.absent = 1u;
    TEST_ASSERT_EQUAL(BMP280_ERR_ABSENT, bmp280_init(&baro, &bus, BMP280_ADDR_SDO_LOW));
    sim.absent = 0u;
    /* the other address: nobody there */
    TEST_ASSERT_EQUAL(BMP280_ERR_ABSENT, bmp280_init(&baro, &bus, BMP280_ADDR_SDO_HIGH));
    sim.chip_id = 0x60u; /* a BME280 */
    TEST_ASSERT_EQUAL(BMP280_ERR_CHIP_ID, bmp280_init(&baro, &bus, BMP280_ADDR_SDO_LOW));
    TEST_ASSERT_EQUAL_UINT32(0u, sim.resets); /* nothing else done */
    sim.chip_id = 0x58u;
    sim.nvm_busy = 1000u; /* the NVM copy never ends */
    TEST_ASSERT_EQUAL(BMP280_ERR_TIMEOUT, bmp280_init(&baro, &bus, BMP280_ADDR_SDO_LOW));
    TEST_ASSERT_EQUAL_UINT16(1000u - BMP280_RESET_POLLS, sim.nvm_left);
    sim.nvm_busy = 0u;
    sim.fail_next = I2C_BUS_ERR_TIMEOUT;
    TEST_ASSERT_EQUAL(BMP280_ERR_BUS, bmp280_init(&baro, &bus, BMP280_ADDR_SDO_LOW));
    TEST_ASSERT_EQUAL_UINT8(0u, baro.ready);
    TEST_ASSERT_EQUAL(BMP280_ERR_NULL, bmp280_init(NULL, &bus, BMP280_ADDR_SDO_LOW));
    TEST_ASSERT_EQUAL(BMP280_ERR_NULL, bmp280_init(&baro, NULL, BMP280_ADDR_SDO_LOW));
}

static void test_init_refuses_a_blank_trimming_block(void)
{
    memset(&sim.reg[0x88], 0, BMP280_CALIB_LEN);
    TEST_ASSERT_EQUAL(BMP280_ERR_CALIB, bmp280_init(&baro, &bus, BMP280_ADDR_SDO_LOW));
    TEST_ASSERT_EQUAL_UINT8(0u, baro.ready);
}

static void test_init_checks_the_configuration(void)
{
    /* A chip that missed the reset and still runs in normal mode from an
     * earlier boot ignores the config write (datasheet 5.4.6): the
     * read-back must catch it rather than fly with another filter. */
    sim.ignore_reset = 1u;
    sim.reg[0xF4] = 0x27u;
    sim.reg[0xF5] = 0xA0u;
    TEST_ASSERT_EQUAL(BMP280_ERR_CONFIG, bmp280_init(&baro, &bus, BMP280_ADDR_SDO_LOW));
    TEST_ASSERT_EQUAL_HEX8(0xA0u, sim.reg[0xF5]);
    TEST_ASSERT_EQUAL_UINT8(0u, baro.ready);
    /* with the reset taken, the chip sleeps when config is written */
    sim.ignore_reset = 0u;
    TEST_ASSERT_EQUAL(BMP280_OK, bmp280_init(&baro, &bus, BMP280_ADDR_SDO_LOW));
    TEST_ASSERT_EQUAL_HEX8(0x08u, sim.reg[0xF5]);
}

static void read_and_check(double p_pa, double t_c)
{
    sim_bmp280_set(&sim, p_pa, t_c);
    TEST_ASSERT_EQUAL(BMP280_OK, bmp280_read(&baro));
    TEST_ASSERT_DOUBLE_WITHIN(0.5, p_pa, (double)baro.reading.press_q24_8 / 256.0);
    TEST_ASSERT_DOUBLE_WITHIN(0.011, t_c, (double)baro.reading.temp_cdeg / 100.0);
    /* dh/dp = -R T / (g p) <= R T0 / (g p): 8.4 cm/Pa at sea level, 28 at 300 hPa */
    const double n = 287.05287 * 0.0065 / 9.80665;
    const double h_ref = 100.0 * 44330.769 * (1.0 - pow(p_pa / 101325.0, n));
    const double cm_per_pa = 100.0 * 287.05287 * 288.15 / (9.80665 * p_pa);
    TEST_ASSERT_DOUBLE_WITHIN(0.5 * cm_per_pa * 1.2 + BARO_ALT_ERROR_BOUND_CM, h_ref,
                              (double)baro.alt_cm);
}

static void test_reads_back_the_air(void)
{
    TEST_ASSERT_EQUAL(BMP280_OK, bmp280_init(&baro, &bus, BMP280_ADDR_SDO_LOW));
    read_and_check(101325.0, 25.0);
    TEST_ASSERT_INT32_WITHIN(11, 0, baro.alt_cm);
    read_and_check(89874.56, 8.5); /* ISA 1000 m */
    TEST_ASSERT_INT32_WITHIN(11, 100000, baro.alt_cm);
    read_and_check(30000.0, -39.9); /* the ends of both ranges */
    read_and_check(110000.0, 84.9);
    read_and_check(95000.0, -12.34);
}

static void test_no_new_result(void)
{
    /* before init the chip sleeps: data registers say "no result" */
    TEST_ASSERT_EQUAL(BMP280_ERR_NOT_READY, bmp280_read(&baro));
    TEST_ASSERT_EQUAL(BMP280_OK, bmp280_init(&baro, &bus, BMP280_ADDR_SDO_LOW));
    TEST_ASSERT_EQUAL(BMP280_OK, bmp280_read(&baro));
    const uint32_t p = baro.reading.press_q24_8;
    TEST_ASSERT_EQUAL(BMP280_NO_DATA, bmp280_read(&baro)); /* the same raw pair again */
    TEST_ASSERT_EQUAL_UINT16(1u, baro.stale);
    TEST_ASSERT_EQUAL_UINT32(p, baro.reading.press_q24_8);
    sim.reg[0xF4] = 0x00u; /* put it to sleep behind the driver's back */
    sim_bmp280_set(&sim, 90000.0, 20.0);
    TEST_ASSERT_EQUAL(BMP280_NO_DATA, bmp280_read(&baro)); /* 0x80000: no result */
    TEST_ASSERT_EQUAL_UINT16(2u, baro.stale);
    sim.reg[0xF4] = 0x23u; /* temperature only: pressure skipped */
    sim_bmp280_set(&sim, 91000.0, 20.0);
    TEST_ASSERT_EQUAL(BMP280_NO_DATA, bmp280_read(&baro));
    sim.reg[0xF4] = 0x33u;
    sim_bmp280_set(&sim, 92000.0, 20.0);
    TEST_ASSERT_EQUAL(BMP280_OK, bmp280_read(&baro));
    TEST_ASSERT_DOUBLE_WITHIN(0.5, 92000.0, (double)baro.reading.press_q24_8 / 256.0);
}

static void test_bus_failure_keeps_the_last_reading(void)
{
    TEST_ASSERT_EQUAL(BMP280_OK, bmp280_init(&baro, &bus, BMP280_ADDR_SDO_LOW));
    TEST_ASSERT_EQUAL(BMP280_OK, bmp280_read(&baro));
    const int32_t alt = baro.alt_cm;
    sim_bmp280_set(&sim, 80000.0, 0.0);
    sim.fail_next = I2C_BUS_ERR_ARLO;
    TEST_ASSERT_EQUAL(BMP280_ERR_BUS, bmp280_read(&baro));
    TEST_ASSERT_EQUAL_UINT16(1u, baro.bus_errors);
    TEST_ASSERT_EQUAL_INT32(alt, baro.alt_cm);
    sim.absent = 1u;
    TEST_ASSERT_EQUAL(BMP280_ERR_ABSENT, bmp280_read(&baro));
    TEST_ASSERT_EQUAL_UINT16(2u, baro.bus_errors);
    sim.absent = 0u;
    TEST_ASSERT_EQUAL(BMP280_OK, bmp280_read(&baro));
    TEST_ASSERT_TRUE(baro.alt_cm > alt + 150000); /* 800 hPa: about 1950 m */
    TEST_ASSERT_EQUAL(BMP280_ERR_NULL, bmp280_read(NULL));
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_datasheet_example);
    RUN_TEST(test_parse_calib_little_endian);
    RUN_TEST(test_compensation_matches_double_reference);
    RUN_TEST(test_compensation_refuses_bad_input);
    RUN_TEST(test_init_talks_to_the_chip);
    RUN_TEST(test_init_failures);
    RUN_TEST(test_init_refuses_a_blank_trimming_block);
    RUN_TEST(test_init_checks_the_configuration);
    RUN_TEST(test_reads_back_the_air);
    RUN_TEST(test_no_new_result);
    RUN_TEST(test_bus_failure_keeps_the_last_reading);
    return UNITY_END();
}
