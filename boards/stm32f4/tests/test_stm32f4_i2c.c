/*
 * test_stm32f4_i2c.c - the I2C master on a fake register block.
 *
 * Expected values, worked from RM0090 (27.6.2 CR2, 27.6.8 CCR, 27.6.9 TRISE)
 * and DS8626 table 53 (Sm: tLOW >= 4.7 us, tHIGH >= 4.0 us; Fm: tLOW >= 1.3 us,
 * tHIGH >= 0.6 us; tr <= 1000 ns Sm, <= 300 ns Fm):
 *   16 MHz (HSI), 100 kHz: FREQ = 16 = 0x10; CCR = 16e6 / (2 * 100e3) = 80 = 0x50
 *                          (tHIGH = tLOW = 80 * 62.5 ns = 5.0 us); TRISE = 16 + 1 = 0x11
 *   42 MHz, 100 kHz:       FREQ = 0x2A; CCR = 42e6 / 200e3 = 210 = 0xD2; TRISE = 43 = 0x2B
 *   42 MHz, 400 kHz:       CCR = 42e6 / (3 * 400e3) = 35 -> F/S | 35 = 0x8023
 *                          (tHIGH = 35 / 42 MHz = 833 ns, tLOW = 1667 ns, SCL = 400.0 kHz);
 *                          TRISE = floor(42 * 300 / 1000) + 1 = 12 + 1 = 13 = 0x0D
 *   16 MHz, 400 kHz:       16e6 / 1.2e6 = 13.3 -> rounded up to 14: F/S | 14 = 0x800E
 *                          (SCL = 16e6 / 42 = 381 kHz, never above 400); TRISE = 4 + 1 = 5
 *   2 MHz, 100 kHz:        CCR = 10 = 0xA, TRISE = 3 (the lowest Sm clock)
 *   CR1 after init = PE = 0x0001; OAR1 = bit 14 = 0x4000 (RM0090 27.6.3).
 * A fake block keeps what was written and never changes a flag by itself, so
 * each test sets SR1/SR2 as the hardware would, and DR reads back the last
 * byte the driver wrote (so a read returns the address byte it sent).
 */
#include "unity.h"

#include "stm32f4_i2c.h"

#include <string.h>

static stm32_i2c_regs_t regs;
static stm32_i2c_t i2c;

#define ALL_EVENTS (I2C_SR1_SB | I2C_SR1_ADDR | I2C_SR1_BTF | I2C_SR1_RXNE | I2C_SR1_TXE)

void setUp(void)
{
    memset((void *)&regs, 0, sizeof regs);
    memset(&i2c, 0, sizeof i2c);
}

void tearDown(void) {}

static void init_16mhz_sm(void)
{
    TEST_ASSERT_EQUAL(I2C_BUS_OK,
                      stm32_i2c_init(&i2c, &regs, 16000000u, STM32_I2C_STANDARD_100KHZ, 100u));
}

static void test_init_standard_16mhz(void)
{
    regs.CR1 = I2C_CR1_ACK | I2C_CR1_STOP; /* left over: init clears them */
    regs.CR2 = 0x0700u;                    /* interrupts left enabled: init disables them */
    regs.CCR = 0x1234u;
    regs.FLTR = 0xABu; /* reserved on the F405: never written */
    init_16mhz_sm();
    TEST_ASSERT_EQUAL_HEX32(0x0001u, regs.CR1);
    TEST_ASSERT_EQUAL_HEX32(0x10u, regs.CR2);
    TEST_ASSERT_EQUAL_HEX32(0x50u, regs.CCR);
    TEST_ASSERT_EQUAL_HEX32(0x11u, regs.TRISE);
    TEST_ASSERT_EQUAL_HEX32(0x4000u, regs.OAR1);
    TEST_ASSERT_EQUAL_HEX32(0xABu, regs.FLTR);
    TEST_ASSERT_EQUAL_UINT8(1u, i2c.ready);
    TEST_ASSERT_EQUAL_UINT32(100u, i2c.spin_limit);
}

static void test_init_other_clocks(void)
{
    TEST_ASSERT_EQUAL(I2C_BUS_OK,
                      stm32_i2c_init(&i2c, &regs, 42000000u, STM32_I2C_STANDARD_100KHZ, 10u));
    TEST_ASSERT_EQUAL_HEX32(0x2Au, regs.CR2);
    TEST_ASSERT_EQUAL_HEX32(0xD2u, regs.CCR);
    TEST_ASSERT_EQUAL_HEX32(0x2Bu, regs.TRISE);
    TEST_ASSERT_EQUAL(I2C_BUS_OK,
                      stm32_i2c_init(&i2c, &regs, 42000000u, STM32_I2C_FAST_400KHZ, 10u));
    TEST_ASSERT_EQUAL_HEX32(0x2Au, regs.CR2);
    TEST_ASSERT_EQUAL_HEX32(0x8023u, regs.CCR);
    TEST_ASSERT_EQUAL_HEX32(0x0Du, regs.TRISE);
    TEST_ASSERT_EQUAL(I2C_BUS_OK,
                      stm32_i2c_init(&i2c, &regs, 16000000u, STM32_I2C_FAST_400KHZ, 10u));
    TEST_ASSERT_EQUAL_HEX32(0x800Eu, regs.CCR);
    TEST_ASSERT_EQUAL_HEX32(0x05u, regs.TRISE);
    TEST_ASSERT_EQUAL(I2C_BUS_OK,
                      stm32_i2c_init(&i2c, &regs, 2000000u, STM32_I2C_STANDARD_100KHZ, 0u));
    TEST_ASSERT_EQUAL_HEX32(0x02u, regs.CR2);
    TEST_ASSERT_EQUAL_HEX32(0x0Au, regs.CCR);
    TEST_ASSERT_EQUAL_HEX32(0x03u, regs.TRISE);
    TEST_ASSERT_EQUAL_UINT32(1u, i2c.spin_limit); /* 0 is read as 1 */
    TEST_ASSERT_EQUAL(I2C_BUS_OK,
                      stm32_i2c_init(&i2c, &regs, 4000000u, STM32_I2C_FAST_400KHZ, 10u));
    TEST_ASSERT_EQUAL_HEX32(0x8004u, regs.CCR); /* 4e6 / 1.2e6 = 3.3 -> 4 */
    TEST_ASSERT_EQUAL_HEX32(0x02u, regs.TRISE); /* floor(1.2) + 1 */
}

static void test_init_refuses_without_writing(void)
{
    regs.CR1 = 0x1234u;
    TEST_ASSERT_EQUAL(I2C_BUS_ERR_NULL,
                      stm32_i2c_init(NULL, &regs, 16000000u, STM32_I2C_STANDARD_100KHZ, 10u));
    TEST_ASSERT_EQUAL(I2C_BUS_ERR_NULL,
                      stm32_i2c_init(&i2c, NULL, 16000000u, STM32_I2C_STANDARD_100KHZ, 10u));
    /* not a whole MHz */
    TEST_ASSERT_EQUAL(I2C_BUS_ERR_RANGE,
                      stm32_i2c_init(&i2c, &regs, 16500000u, STM32_I2C_STANDARD_100KHZ, 10u));
    /* below 2 MHz (Sm) and 4 MHz (Fm), above 42 MHz */
    TEST_ASSERT_EQUAL(I2C_BUS_ERR_RANGE,
                      stm32_i2c_init(&i2c, &regs, 1000000u, STM32_I2C_STANDARD_100KHZ, 10u));
    TEST_ASSERT_EQUAL(I2C_BUS_ERR_RANGE,
                      stm32_i2c_init(&i2c, &regs, 3000000u, STM32_I2C_FAST_400KHZ, 10u));
    TEST_ASSERT_EQUAL(I2C_BUS_ERR_RANGE,
                      stm32_i2c_init(&i2c, &regs, 43000000u, STM32_I2C_STANDARD_100KHZ, 10u));
    TEST_ASSERT_EQUAL(I2C_BUS_ERR_RANGE,
                      stm32_i2c_init(&i2c, &regs, 43000000u, STM32_I2C_FAST_400KHZ, 10u));
    TEST_ASSERT_EQUAL(I2C_BUS_ERR_RANGE,
                      stm32_i2c_init(&i2c, &regs, 16000000u, (stm32_i2c_speed_t)2, 10u));
    TEST_ASSERT_EQUAL_HEX32(0x1234u, regs.CR1);
    TEST_ASSERT_EQUAL_HEX32(0x0u, regs.CCR);
    TEST_ASSERT_EQUAL_UINT8(0u, i2c.ready);
}

static void test_bad_arguments(void)
{
    uint8_t b = 0u;
    TEST_ASSERT_EQUAL(I2C_BUS_ERR_NULL, stm32_i2c_write_read(NULL, 0x76u, &b, 1u, NULL, 0u));
    TEST_ASSERT_EQUAL(I2C_BUS_ERR_NOT_READY, stm32_i2c_write_read(&i2c, 0x76u, &b, 1u, NULL, 0u));
    init_16mhz_sm();
    regs.SR1 = ALL_EVENTS;
    regs.DR = 0x5Au;
    TEST_ASSERT_EQUAL(I2C_BUS_ERR_NULL, stm32_i2c_write_read(&i2c, 0x76u, NULL, 1u, NULL, 0u));
    TEST_ASSERT_EQUAL(I2C_BUS_ERR_NULL, stm32_i2c_write_read(&i2c, 0x76u, &b, 1u, NULL, 1u));
    TEST_ASSERT_EQUAL(I2C_BUS_ERR_RANGE, stm32_i2c_write_read(&i2c, 0x80u, &b, 1u, NULL, 0u));
    TEST_ASSERT_EQUAL_HEX32(0x5Au, regs.DR); /* nothing sent */
    TEST_ASSERT_EQUAL_HEX32(I2C_CR1_PE, regs.CR1);
}

static void test_probe_sends_the_write_address(void)
{
    init_16mhz_sm();
    regs.SR1 = I2C_SR1_SB | I2C_SR1_ADDR; /* no TXE/BTF: a probe must not wait for them */
    TEST_ASSERT_EQUAL(I2C_BUS_OK, stm32_i2c_write_read(&i2c, 0x76u, NULL, 0u, NULL, 0u));
    TEST_ASSERT_EQUAL_HEX32(0xECu, regs.DR); /* 0x76 << 1 | W */
    TEST_ASSERT_EQUAL_HEX32(I2C_CR1_PE | I2C_CR1_START | I2C_CR1_STOP, regs.CR1);
}

static void test_register_write(void)
{
    const uint8_t tx[2] = {0xF4u, 0x33u};
    init_16mhz_sm();
    regs.SR1 = ALL_EVENTS;
    TEST_ASSERT_EQUAL(I2C_BUS_OK, stm32_i2c_write_read(&i2c, 0x76u, tx, 2u, NULL, 0u));
    TEST_ASSERT_EQUAL_HEX32(0x33u, regs.DR); /* the last byte after the address and 0xF4 */
    TEST_ASSERT_EQUAL_HEX32(I2C_CR1_PE | I2C_CR1_START | I2C_CR1_STOP, regs.CR1);
    TEST_ASSERT_EQUAL_UINT16(0u, i2c.recoveries);
}

static void test_write_then_read_one_byte(void)
{
    const uint8_t reg = 0xD0u;
    uint8_t rx = 0u;
    init_16mhz_sm();
    regs.SR1 = ALL_EVENTS;
    TEST_ASSERT_EQUAL(I2C_BUS_OK, stm32_i2c_write_read(&i2c, 0x76u, &reg, 1u, &rx, 1u));
    /* the repeated START's address, 0x76 << 1 | R, was the last byte written */
    TEST_ASSERT_EQUAL_HEX8(0xEDu, rx);
    /* one byte: NACKed (ACK clear), STOP requested, no POS */
    TEST_ASSERT_EQUAL_HEX32(I2C_CR1_PE | I2C_CR1_START | I2C_CR1_STOP, regs.CR1);
}

static void test_read_two_bytes(void)
{
    uint8_t rx[2] = {0u, 0u};
    init_16mhz_sm();
    regs.SR1 = ALL_EVENTS;
    regs.CR1 |= I2C_CR1_ACK; /* whatever was left: the two-byte closing clears it */
    TEST_ASSERT_EQUAL(I2C_BUS_OK, stm32_i2c_write_read(&i2c, 0x28u, NULL, 0u, rx, 2u));
    TEST_ASSERT_EQUAL_HEX8(0x51u, rx[0]); /* 0x28 << 1 | R */
    TEST_ASSERT_EQUAL_HEX8(0x51u, rx[1]);
    TEST_ASSERT_EQUAL_HEX32(I2C_CR1_PE | I2C_CR1_START | I2C_CR1_STOP, regs.CR1); /* POS cleared */
}

static void test_read_many_bytes(void)
{
    uint8_t rx[6];
    memset(rx, 0, sizeof rx);
    init_16mhz_sm();
    regs.SR1 = ALL_EVENTS;
    TEST_ASSERT_EQUAL(I2C_BUS_OK, stm32_i2c_write_read(&i2c, 0x28u, NULL, 0u, rx, 6u));
    for (unsigned i = 0; i < 6u; ++i) {
        TEST_ASSERT_EQUAL_HEX8(0x51u, rx[i]);
    }
    /* ACK was cleared for the last byte, STOP requested */
    TEST_ASSERT_EQUAL_HEX32(I2C_CR1_PE | I2C_CR1_START | I2C_CR1_STOP, regs.CR1);
    rx[0] = 0u;
    rx[3] = 0u;
    TEST_ASSERT_EQUAL(I2C_BUS_OK, stm32_i2c_write_read(&i2c, 0x28u, NULL, 0u, rx, 4u));
    TEST_ASSERT_EQUAL_HEX8(0x51u, rx[0]);
    TEST_ASSERT_EQUAL_HEX8(0x51u, rx[3]);
}

static void test_address_nack_is_absent_not_reset(void)
{
    uint8_t rx[4];
    init_16mhz_sm();
    regs.CCR = 0x0777u; /* a reset + reconfigure would rewrite 0x50 */
    regs.SR1 = I2C_SR1_SB | I2C_SR1_AF;
    TEST_ASSERT_EQUAL(I2C_BUS_ERR_NACK, stm32_i2c_write_read(&i2c, 0x28u, NULL, 0u, rx, 4u));
    TEST_ASSERT_EQUAL_HEX32(0x51u, regs.DR); /* only the address went out */
    TEST_ASSERT_EQUAL_HEX32(0u, regs.CR1 & I2C_CR1_ACK);
    TEST_ASSERT_EQUAL_HEX32(I2C_CR1_STOP, regs.CR1 & I2C_CR1_STOP);
    TEST_ASSERT_EQUAL_HEX32(0u, regs.SR1 & I2C_SR1_AF); /* AF cleared (rc_w0) */
    TEST_ASSERT_EQUAL_HEX32(I2C_SR1_BERR | I2C_SR1_ARLO,
                            regs.SR1 & (I2C_SR1_BERR | I2C_SR1_ARLO)); /* written 1: unchanged */
    TEST_ASSERT_EQUAL_HEX32(0x0777u, regs.CCR);
    TEST_ASSERT_EQUAL_UINT16(1u, i2c.nacks);
    TEST_ASSERT_EQUAL_UINT16(0u, i2c.recoveries);
}

static void test_data_nack(void)
{
    const uint8_t tx[2] = {0xE0u, 0xB6u};
    init_16mhz_sm();
    /* ADDR proves the address was acknowledged; AF then belongs to the data */
    regs.SR1 = I2C_SR1_SB | I2C_SR1_ADDR | I2C_SR1_TXE | I2C_SR1_AF;
    TEST_ASSERT_EQUAL(I2C_BUS_ERR_DATA_NACK, stm32_i2c_write_read(&i2c, 0x76u, tx, 2u, NULL, 0u));
    TEST_ASSERT_EQUAL_HEX32(0xECu, regs.DR); /* no data byte written */
    TEST_ASSERT_EQUAL_UINT16(1u, i2c.data_nacks);
    TEST_ASSERT_EQUAL_UINT16(0u, i2c.nacks);
    TEST_ASSERT_EQUAL_HEX32(I2C_CR1_STOP, regs.CR1 & I2C_CR1_STOP);
}

static void assert_recovered(void)
{
    TEST_ASSERT_EQUAL_HEX32(I2C_CR1_PE, regs.CR1); /* SWRST released, re-enabled */
    TEST_ASSERT_EQUAL_HEX32(0x50u, regs.CCR);      /* the saved timing written back */
    TEST_ASSERT_EQUAL_HEX32(0x11u, regs.TRISE);
    TEST_ASSERT_EQUAL_HEX32(0x10u, regs.CR2);
    TEST_ASSERT_EQUAL_UINT16(1u, i2c.recoveries);
}

static void test_bus_error_recovers(void)
{
    const uint8_t tx = 0xF7u;
    init_16mhz_sm();
    regs.CCR = 0x0777u;
    regs.TRISE = 0u;
    regs.SR1 = I2C_SR1_SB | I2C_SR1_BERR;
    TEST_ASSERT_EQUAL(I2C_BUS_ERR_BUS, stm32_i2c_write_read(&i2c, 0x76u, &tx, 1u, NULL, 0u));
    TEST_ASSERT_EQUAL_UINT16(1u, i2c.bus_errors);
    assert_recovered();
}

static void test_arbitration_lost_recovers(void)
{
    uint8_t rx[3];
    init_16mhz_sm();
    regs.CCR = 0x0777u;
    regs.SR1 = I2C_SR1_SB | I2C_SR1_ADDR | I2C_SR1_ARLO;
    TEST_ASSERT_EQUAL(I2C_BUS_ERR_ARLO, stm32_i2c_write_read(&i2c, 0x76u, NULL, 0u, rx, 3u));
    TEST_ASSERT_EQUAL_UINT16(1u, i2c.arb_lost);
    assert_recovered();
}

static void test_timeouts_recover(void)
{
    const uint8_t tx[2] = {0x11u, 0x22u};
    init_16mhz_sm();
    regs.CCR = 0x0777u;
    regs.SR1 = 0u; /* SB never comes */
    regs.DR = 0x5Au;
    TEST_ASSERT_EQUAL(I2C_BUS_ERR_TIMEOUT, stm32_i2c_write_read(&i2c, 0x76u, tx, 2u, NULL, 0u));
    TEST_ASSERT_EQUAL_HEX32(0x5Au, regs.DR); /* no address sent */
    TEST_ASSERT_EQUAL_UINT16(1u, i2c.timeouts);
    assert_recovered();
    /* BTF never comes after the bytes went out */
    regs.SR1 = I2C_SR1_SB | I2C_SR1_ADDR | I2C_SR1_TXE;
    TEST_ASSERT_EQUAL(I2C_BUS_ERR_TIMEOUT, stm32_i2c_write_read(&i2c, 0x76u, tx, 2u, NULL, 0u));
    TEST_ASSERT_EQUAL_HEX32(0x22u, regs.DR);
    TEST_ASSERT_EQUAL_UINT16(2u, i2c.timeouts);
    /* RXNE never comes for the only byte */
    regs.SR1 = I2C_SR1_SB | I2C_SR1_ADDR;
    uint8_t rx = 0u;
    TEST_ASSERT_EQUAL(I2C_BUS_ERR_TIMEOUT, stm32_i2c_write_read(&i2c, 0x76u, NULL, 0u, &rx, 1u));
    TEST_ASSERT_EQUAL_UINT16(3u, i2c.timeouts);
    TEST_ASSERT_EQUAL_UINT16(3u, i2c.recoveries);
}

static void test_stuck_busy_recovers(void)
{
    const uint8_t tx = 0xF7u;
    init_16mhz_sm();
    regs.CCR = 0x0777u;
    regs.SR1 = ALL_EVENTS;
    regs.SR2 = I2C_SR2_BUSY; /* SDA held low: BUSY never drops */
    regs.DR = 0x5Au;
    TEST_ASSERT_EQUAL(I2C_BUS_ERR_BUSY, stm32_i2c_write_read(&i2c, 0x76u, &tx, 1u, NULL, 0u));
    TEST_ASSERT_EQUAL_HEX32(0x5Au, regs.DR); /* no START, no address */
    TEST_ASSERT_EQUAL_UINT16(1u, i2c.busy);
    assert_recovered();
    stm32_i2c_recover(NULL); /* harmless */
}

static void test_counters_saturate(void)
{
    init_16mhz_sm();
    i2c.nacks = UINT16_MAX;
    regs.SR1 = I2C_SR1_SB | I2C_SR1_AF;
    TEST_ASSERT_EQUAL(I2C_BUS_ERR_NACK, stm32_i2c_write_read(&i2c, 0x28u, NULL, 0u, NULL, 0u));
    TEST_ASSERT_EQUAL_UINT16(UINT16_MAX, i2c.nacks);
}

static void test_bus_seam(void)
{
    const uint8_t reg = 0xD0u;
    uint8_t rx = 0u;
    init_16mhz_sm();
    const i2c_bus_t bus = stm32_i2c_bus(&i2c);
    TEST_ASSERT_EQUAL_PTR(&i2c, bus.ctx);
    regs.SR1 = ALL_EVENTS;
    TEST_ASSERT_EQUAL(I2C_BUS_OK, i2c_bus_write_read(&bus, 0x77u, &reg, 1u, &rx, 1u));
    TEST_ASSERT_EQUAL_HEX8(0xEFu, rx); /* 0x77 << 1 | R */
    TEST_ASSERT_EQUAL(I2C_BUS_ERR_NULL, i2c_bus_write_read(NULL, 0x77u, &reg, 1u, &rx, 1u));
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_init_standard_16mhz);
    RUN_TEST(test_init_other_clocks);
    RUN_TEST(test_init_refuses_without_writing);
    RUN_TEST(test_bad_arguments);
    RUN_TEST(test_probe_sends_the_write_address);
    RUN_TEST(test_register_write);
    RUN_TEST(test_write_then_read_one_byte);
    RUN_TEST(test_read_two_bytes);
    RUN_TEST(test_read_many_bytes);
    RUN_TEST(test_address_nack_is_absent_not_reset);
    RUN_TEST(test_data_nack);
    RUN_TEST(test_bus_error_recovers);
    RUN_TEST(test_arbitration_lost_recovers);
    RUN_TEST(test_timeouts_recover);
    RUN_TEST(test_stuck_busy_recovers);
    RUN_TEST(test_counters_saturate);
    RUN_TEST(test_bus_seam);
    return UNITY_END();
}
