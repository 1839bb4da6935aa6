/*
 * sim_icm42688p.c - see sim_icm42688p.h. Host test code: float allowed.
 */
#include "sim_icm42688p.h"

#include <math.h>
#include <string.h>

#define REG_DEVICE_CONFIG    0x11u
#define REG_DATA_FIRST       0x1Du /* TEMP_DATA1 */
#define REG_DATA_LAST        0x2Au /* GYRO_DATA_Z0 */
#define REG_INT_STATUS       0x2Du
#define REG_INTF_CONFIG0     0x4Cu
#define REG_PWR_MGMT0        0x4Eu
#define REG_GYRO_CONFIG0     0x4Fu
#define REG_ACCEL_CONFIG0    0x50u
#define REG_WHO_AM_I         0x75u
#define REG_BANK_SEL         0x76u
#define SOFT_RESET_BUSY_US   1000u
#define POWER_ON_NO_WRITE_US 200u
#define SIM_PI               3.14159265358979323846

static int16_t clamp16(double v)
{
    const double r = floor(v + 0.5);
    if (r > 32767.0) {
        return 32767;
    }
    if (r < -32768.0) {
        return -32768;
    }
    return (int16_t)r;
}

static void reset_values(sim_icm42688p_t *s)
{
    memset(s->regs, 0, sizeof s->regs);
    for (unsigned r = REG_DATA_FIRST; r <= REG_DATA_LAST; r += 2u) {
        s->regs[r] = 0x80u; /* -32768, high byte first */
    }
    s->regs[0x13] = 0x05u; /* DRIVE_CONFIG */
    s->regs[REG_INT_STATUS] = 0x10u;
    s->regs[REG_INTF_CONFIG0] = 0x30u;
    s->regs[0x4D] = 0x91u; /* INTF_CONFIG1 */
    s->regs[REG_GYRO_CONFIG0] = 0x06u;
    s->regs[REG_ACCEL_CONFIG0] = 0x06u;
    s->regs[0x51] = 0x16u; /* GYRO_CONFIG1 */
    s->regs[0x52] = 0x11u; /* GYRO_ACCEL_CONFIG0 */
    s->regs[0x53] = 0x0Du; /* ACCEL_CONFIG1 */
    s->regs[0x64] = 0x10u; /* INT_CONFIG1 */
    s->regs[0x65] = 0x10u; /* INT_SOURCE0 */
    s->regs[REG_WHO_AM_I] = 0x47u;
    s->bank = 0u;
}

void sim_icm42688p_init(sim_icm42688p_t *s)
{
    memset(s, 0, sizeof *s);
    reset_values(s);
    s->accel_g[2] = 1.0;
    s->temp_c = 25.0;
    s->reset_busy_us = SOFT_RESET_BUSY_US;
}

void sim_icm42688p_set_motion(sim_icm42688p_t *s, const double rate_rad_s[3],
                              const double accel_g[3])
{
    for (int i = 0; i < 3; ++i) {
        s->rate_rad_s[i] = rate_rad_s[i];
        s->accel_g[i] = accel_g[i];
    }
}

int16_t sim_icm42688p_gyro_counts(const sim_icm42688p_t *s, double rate_rad_s)
{
    const unsigned fs = (s->regs[REG_GYRO_CONFIG0] >> 5) & 7u;
    return clamp16(rate_rad_s * (180.0 / SIM_PI) * 16.4 * (double)(1u << fs));
}

int16_t sim_icm42688p_accel_counts(const sim_icm42688p_t *s, double accel_g)
{
    const unsigned fs = (s->regs[REG_ACCEL_CONFIG0] >> 5) & 3u;
    return clamp16(accel_g * 2048.0 * (double)(1u << fs));
}

static void put16(const sim_icm42688p_t *s, uint8_t *p, int16_t v)
{
    const uint16_t u = (uint16_t)v;
    const uint8_t hi = (uint8_t)(u >> 8);
    const uint8_t lo = (uint8_t)(u & 0xFFu);
    if ((s->regs[REG_INTF_CONFIG0] & 0x10u) != 0u) {
        p[0] = hi; /* SENSOR_DATA_ENDIAN = 1: big-endian */
        p[1] = lo;
    } else {
        p[0] = lo;
        p[1] = hi;
    }
}

static void latch_data(sim_icm42688p_t *s)
{
    uint8_t *d = &s->regs[REG_DATA_FIRST];
    const uint8_t pwr = s->regs[REG_PWR_MGMT0];
    const int accel_on = (pwr & 0x03u) != 0u;
    const int gyro_on = (pwr & 0x0Cu) != 0u;
    const int temp_on = (pwr & 0x20u) == 0u && (accel_on || gyro_on);
    put16(s, &d[0], temp_on ? clamp16((s->temp_c - 25.0) * 132.48) : (int16_t)-32768);
    for (int i = 0; i < 3; ++i) {
        put16(s, &d[2 + 2 * i],
              accel_on ? sim_icm42688p_accel_counts(s, s->accel_g[i]) : (int16_t)-32768);
        put16(s, &d[8 + 2 * i],
              gyro_on ? sim_icm42688p_gyro_counts(s, s->rate_rad_s[i]) : (int16_t)-32768);
    }
    if (accel_on || gyro_on) {
        s->regs[REG_INT_STATUS] |= 0x08u; /* DATA_RDY_INT */
    }
}

static void log_write(sim_icm42688p_t *s, uint8_t reg, uint8_t v)
{
    if (s->log_n < SIM_LOG_MAX) {
        s->log_reg[s->log_n] = reg;
        s->log_val[s->log_n] = v;
    }
    s->log_n++;
}

static void write_reg(sim_icm42688p_t *s, uint8_t reg, uint8_t v, uint64_t now_us)
{
    if (reg == REG_BANK_SEL) {
        s->bank = v & 0x07u;
        log_write(s, reg, v);
        return;
    }
    if (s->bank != 0u) {
        s->foreign_writes++;
        return;
    }
    if (now_us < s->no_write_until_us) {
        s->dropped_writes++;
        return;
    }
    if (reg == REG_WHO_AM_I || reg == REG_INT_STATUS ||
        (reg >= REG_DATA_FIRST && reg <= REG_DATA_LAST)) {
        return; /* read-only */
    }
    if (s->ignore_write_reg != 0u && reg == s->ignore_write_reg) {
        return;
    }
    log_write(s, reg, v);
    if (reg == REG_DEVICE_CONFIG && (v & 0x01u) != 0u) {
        reset_values(s);
        s->resets++;
        s->busy_until_us = now_us + s->reset_busy_us;
        return;
    }
    if (reg == REG_PWR_MGMT0) {
        const uint8_t old = s->regs[reg];
        const int turns_on = ((old & 0x03u) == 0u && (v & 0x03u) != 0u) ||
                             ((old & 0x0Cu) == 0u && (v & 0x0Cu) != 0u);
        if (turns_on) {
            s->no_write_until_us = now_us + POWER_ON_NO_WRITE_US;
        }
    }
    s->regs[reg] = v;
}

int sim_icm42688p_frame(void *chip, const uint8_t *tx, uint8_t *rx, uint16_t n, uint32_t sck_hz,
                        uint64_t now_us)
{
    sim_icm42688p_t *s = (sim_icm42688p_t *)chip;
    if (n == 0u) {
        return 0;
    }
    memset(rx, 0, n);
    const int read = (tx[0] & 0x80u) != 0u;
    uint8_t reg = tx[0] & 0x7Fu;
    if (now_us < s->busy_until_us) {
        if (!read) {
            s->dropped_writes++;
        }
        return 0;
    }
    if (sck_hz > 24000000u || sck_hz == 0u) {
        s->clock_violations++;
    }
    if (read && s->bank == 0u) {
        latch_data(s);
    }
    for (uint16_t i = 1u; i < n; ++i) {
        if (read) {
            if (reg == REG_BANK_SEL) {
                rx[i] = s->bank;
            } else if (s->bank == 0u) {
                rx[i] = s->regs[reg];
                if (reg == REG_INT_STATUS) {
                    s->regs[reg] = 0u; /* cleared on read */
                }
            }
        } else {
            write_reg(s, reg, tx[i], now_us);
        }
        reg = (uint8_t)((reg + 1u) & 0x7Fu);
    }
    return 0;
}
