/*
 * imu_spi_bus.c - the SPI IMUs' common register access, chip detection,
 * scaling and board alignment (see imu_spi_bus.h); the chips' own steps are
 * in mpu6000.c and icm42688p.c, the dispatch in imu_spi.c.
 */
#include "imu_spi_bus.h"

#include <stddef.h>
#include <string.h>

#include "helical/math/q14.h"

/* 65536 pi / (180 * 16.4) = 69.745060: Q16 rad/s per count at 16.4 LSB per
 * deg/s, as 69 + 48828 / 65536 (|raw * 48828| < 2^31 for every int16). */
#define IMU_GYRO_K_INT      69
#define IMU_GYRO_K_FRAC_Q16 48828
/* 65536 / 2048: Q16 g per count at 2048 LSB/g. */
#define IMU_ACCEL_K 32

#define IMU_MAX_BURST 15u

int imu_spi_bus_ok(const imu_spi_bus_t *bus)
{
    return bus != NULL && bus->xfer != NULL && bus->delay_us != NULL;
}

imu_status_t imu_spi_read_regs(const imu_spi_bus_t *bus, uint8_t reg, uint8_t *data, uint8_t n)
{
    if (!imu_spi_bus_ok(bus) || data == NULL) {
        return IMU_ERR_NULL;
    }
    if (n == 0u || n > IMU_MAX_BURST || reg > 0x7Fu) {
        return IMU_ERR_RANGE;
    }
    uint8_t tx[IMU_MAX_BURST + 1u];
    uint8_t rx[IMU_MAX_BURST + 1u];
    (void)memset(tx, 0, sizeof tx);
    (void)memset(rx, 0, sizeof rx);
    tx[0] = reg | IMU_SPI_READ; /* the rest are dummies: the chip ignores MOSI now */
    const uint32_t len32 = (uint32_t)n + 1u;
    if (bus->xfer(bus->ctx, tx, rx, (uint16_t)len32) != 0) {
        return IMU_ERR_BUS;
    }
    for (uint8_t i = 0u; i < n; ++i) {
        data[i] = rx[i + 1u]; /* rx[0] came while the address went out */
    }
    return IMU_OK;
}

imu_status_t imu_spi_write_reg(const imu_spi_bus_t *bus, uint8_t reg, uint8_t value)
{
    if (!imu_spi_bus_ok(bus)) {
        return IMU_ERR_NULL;
    }
    if (reg > 0x7Fu) {
        return IMU_ERR_RANGE;
    }
    const uint8_t tx[2] = {reg, value}; /* bit 7 clear: write */
    uint8_t rx[2] = {0u, 0u};
    if (bus->xfer(bus->ctx, tx, rx, 2u) != 0) {
        return IMU_ERR_BUS;
    }
    return IMU_OK;
}

imu_status_t imu_spi_write_seq(const imu_spi_bus_t *bus, const imu_reg_value_t *seq, uint8_t n)
{
    if (seq == NULL) {
        return IMU_ERR_NULL;
    }
    for (uint8_t i = 0u; i < n; ++i) {
        const imu_status_t st = imu_spi_write_reg(bus, seq[i].reg, seq[i].value);
        if (st != IMU_OK) {
            return st;
        }
    }
    return IMU_OK;
}

imu_status_t imu_spi_verify_seq(const imu_spi_bus_t *bus, const imu_reg_value_t *seq, uint8_t n)
{
    if (seq == NULL) {
        return IMU_ERR_NULL;
    }
    for (uint8_t i = 0u; i < n; ++i) {
        uint8_t v = 0u;
        const imu_status_t st = imu_spi_read_regs(bus, seq[i].reg, &v, 1u);
        if (st != IMU_OK) {
            return st;
        }
        if (v != seq[i].value) {
            return IMU_ERR_CONFIG;
        }
    }
    return IMU_OK;
}

imu_status_t imu_spi_set_clock(const imu_spi_bus_t *bus, uint32_t max_hz)
{
    if (!imu_spi_bus_ok(bus)) {
        return IMU_ERR_NULL;
    }
    if (bus->set_clock != NULL && bus->set_clock(bus->ctx, max_hz) != 0) {
        return IMU_ERR_BUS;
    }
    return IMU_OK;
}

uint8_t imu_burst_is_blank(const uint8_t *b, uint8_t n)
{
    uint8_t all_00 = 1u;
    uint8_t all_ff = 1u;
    for (uint8_t i = 0u; i < n; ++i) {
        if (b[i] != 0x00u) {
            all_00 = 0u;
        }
        if (b[i] != 0xFFu) {
            all_ff = 0u;
        }
    }
    return ((all_00 != 0u) || (all_ff != 0u)) ? 1u : 0u;
}

int16_t imu_be16(const uint8_t *p)
{
    const uint32_t u = ((uint32_t)p[0] << 8) | (uint32_t)p[1];
    const int32_t s = (u >= 0x8000u) ? (int32_t)u - 65536 : (int32_t)u;
    return (int16_t)s;
}

q16_t imu_gyro_q16_from_raw(int16_t raw)
{
    const int32_t r = raw;
    const int32_t frac_q16 = r * IMU_GYRO_K_FRAC_Q16;
    /* one rounding, to nearest with ties up (q14.h's convention): the integer
     * part r * 69 is exact */
    return r * IMU_GYRO_K_INT + q_rshift_round(frac_q16, 16u);
}

q16_t imu_accel_q16_from_raw(int16_t raw)
{
    const int32_t r = raw;
    return r * IMU_ACCEL_K;
}

void imu_align_apply(uint8_t align, const q16_t in[3], q16_t out[3])
{
    /* For each alignment and body axis: the chip axis it takes and its sign
     * (the table in imu_spi_bus.h). */
    static const uint8_t k_align_src[IMU_ALIGN_COUNT][3] = {
        {0u, 1u, 2u}, {1u, 0u, 2u}, {0u, 1u, 2u}, {1u, 0u, 2u},
        {0u, 1u, 2u}, {1u, 0u, 2u}, {0u, 1u, 2u}, {1u, 0u, 2u},
    };
    static const int8_t k_align_sign[IMU_ALIGN_COUNT][3] = {
        {-1, 1, -1}, {-1, -1, -1}, {1, -1, -1}, {1, 1, -1},
        {1, 1, 1},   {1, -1, 1},   {-1, -1, 1}, {-1, 1, 1},
    };
    if (in == NULL || out == NULL) {
        return;
    }
    for (uint8_t i = 0u; i < 3u; ++i) {
        if (align >= (uint8_t)IMU_ALIGN_COUNT) {
            out[i] = 0;
        } else {
            const q16_t v = in[k_align_src[align][i]];
            out[i] = (k_align_sign[align][i] < 0) ? -v : v; /* |v| < 2^22: no overflow */
        }
    }
}

int32_t imu_div_round(int32_t a, int32_t b)
{
    if (a >= 0) {
        return (a + b / 2) / b;
    }
    return -((-a + b / 2) / b);
}

imu_status_t imu_spi_detect(const imu_spi_bus_t *bus, imu_chip_t *chip, uint8_t *who_am_i)
{
    if (!imu_spi_bus_ok(bus) || chip == NULL) {
        return IMU_ERR_NULL;
    }
    *chip = IMU_CHIP_NONE;
    /* 1 MHz: the slowest limit of either chip for a register read */
    imu_status_t st = imu_spi_set_clock(bus, IMU_MPU6000_SCK_REG_HZ);
    uint8_t who = 0u;
    if (st == IMU_OK) {
        st = imu_spi_read_regs(bus, IMU_REG_WHO_AM_I, &who, 1u);
    }
    if (st != IMU_OK) {
        return st;
    }
    if (who_am_i != NULL) {
        *who_am_i = who;
    }
    if (who == MPU6000_WHO_AM_I_VALUE) {
        *chip = IMU_CHIP_MPU6000;
        return IMU_OK;
    }
    if (who == ICM42688P_WHO_AM_I_VALUE) {
        *chip = IMU_CHIP_ICM42688P;
        return IMU_OK;
    }
    /* A missing chip leaves MISO to its pull-up or pull-down (or a short):
     * every bit reads the same. */
    if (who == 0x00u || who == 0xFFu) {
        return IMU_ERR_NO_DEVICE;
    }
    return IMU_ERR_WRONG_ID;
}
