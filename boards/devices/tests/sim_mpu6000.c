/*
 * sim_mpu6000.c - see sim_mpu6000.h. Host test code: float allowed.
 */
#include "sim_mpu6000.h"

#include <math.h>
#include <string.h>

#define REG_GYRO_CONFIG       0x1Bu
#define REG_ACCEL_CONFIG      0x1Cu
#define REG_INT_STATUS        0x3Au
#define REG_DATA_FIRST        0x3Bu
#define REG_DATA_LAST         0x48u
#define REG_SIGNAL_PATH_RESET 0x68u
#define REG_PWR_MGMT_1        0x6Bu
#define REG_WHO_AM_I          0x75u
#define RESET_BUSY_US         100000u
#define SIM_PI                3.14159265358979323846

static const double k_gyro_lsb_per_dps[4] = {131.0, 65.5, 32.8, 16.4};
static const double k_accel_lsb_per_g[4] = {16384.0, 8192.0, 4096.0, 2048.0};

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

static void reset_values(sim_mpu6000_t *s)
{
    memset(s->regs, 0, sizeof s->regs);
    s->regs[REG_PWR_MGMT_1] = 0x40u;
    s->regs[REG_WHO_AM_I] = 0x68u;
}

void sim_mpu6000_init(sim_mpu6000_t *s)
{
    memset(s, 0, sizeof *s);
    reset_values(s);
    s->accel_g[2] = 1.0;
    s->temp_c = 25.0;
    s->reset_busy_us = RESET_BUSY_US;
}

void sim_mpu6000_set_motion(sim_mpu6000_t *s, const double rate_rad_s[3], const double accel_g[3])
{
    for (int i = 0; i < 3; ++i) {
        s->rate_rad_s[i] = rate_rad_s[i];
        s->accel_g[i] = accel_g[i];
    }
}

int16_t sim_mpu6000_gyro_counts(const sim_mpu6000_t *s, double rate_rad_s)
{
    const unsigned fs = (s->regs[REG_GYRO_CONFIG] >> 3) & 3u;
    return clamp16(rate_rad_s * (180.0 / SIM_PI) * k_gyro_lsb_per_dps[fs]);
}

int16_t sim_mpu6000_accel_counts(const sim_mpu6000_t *s, double accel_g)
{
    const unsigned fs = (s->regs[REG_ACCEL_CONFIG] >> 3) & 3u;
    return clamp16(accel_g * k_accel_lsb_per_g[fs]);
}

static void put16(uint8_t *p, int16_t v)
{
    const uint16_t u = (uint16_t)v;
    p[0] = (uint8_t)(u >> 8);
    p[1] = (uint8_t)(u & 0xFFu);
}

/* The data registers, latched at the start of a frame (the chip's sample). */
static void latch_data(sim_mpu6000_t *s)
{
    uint8_t *d = &s->regs[REG_DATA_FIRST];
    if ((s->regs[REG_PWR_MGMT_1] & 0x40u) != 0u) {
        return; /* asleep: no new samples */
    }
    for (int i = 0; i < 3; ++i) {
        put16(&d[2 * i], sim_mpu6000_accel_counts(s, s->accel_g[i]));
        put16(&d[8 + 2 * i], sim_mpu6000_gyro_counts(s, s->rate_rad_s[i]));
    }
    put16(&d[6], clamp16((s->temp_c - 36.53) * 340.0));
    s->regs[REG_INT_STATUS] = 0x01u; /* DATA_RDY_INT */
}

static void log_write(sim_mpu6000_t *s, uint8_t reg, uint8_t v)
{
    if (s->log_n < SIM_LOG_MAX) {
        s->log_reg[s->log_n] = reg;
        s->log_val[s->log_n] = v;
    }
    s->log_n++;
}

static void write_reg(sim_mpu6000_t *s, uint8_t reg, uint8_t v, uint64_t now_us)
{
    if (reg == REG_WHO_AM_I || (reg >= REG_INT_STATUS && reg <= REG_DATA_LAST)) {
        return; /* read-only */
    }
    if (s->ignore_write_reg != 0u && reg == s->ignore_write_reg) {
        return;
    }
    log_write(s, reg, v);
    if (reg == REG_PWR_MGMT_1 && (v & 0x80u) != 0u) {
        reset_values(s); /* DEVICE_RESET: every register, the bit clears itself */
        s->resets++;
        s->busy_until_us = now_us + s->reset_busy_us;
        return;
    }
    if (reg == REG_SIGNAL_PATH_RESET) {
        memset(&s->regs[REG_DATA_FIRST], 0, REG_DATA_LAST - REG_DATA_FIRST + 1u);
        s->busy_until_us = now_us + s->reset_busy_us;
        return; /* the reset bits are not stored */
    }
    s->regs[reg] = v;
}

int sim_mpu6000_frame(void *chip, const uint8_t *tx, uint8_t *rx, uint16_t n, uint32_t sck_hz,
                      uint64_t now_us)
{
    sim_mpu6000_t *s = (sim_mpu6000_t *)chip;
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
    if (read) {
        latch_data(s);
    }
    for (uint16_t i = 1u; i < n; ++i) {
        const int fast_ok = read && reg >= REG_INT_STATUS && reg <= REG_DATA_LAST;
        if (sck_hz > 20000000u || (sck_hz > 1000000u && !fast_ok) || sck_hz == 0u) {
            s->clock_violations++;
        }
        if (read) {
            rx[i] = s->regs[reg];
            if (reg == REG_INT_STATUS) {
                s->regs[reg] = 0u; /* INT_RD_CLEAR-style: read clears */
            }
        } else {
            write_reg(s, reg, tx[i], now_us);
        }
        reg = (uint8_t)((reg + 1u) & 0x7Fu);
    }
    return 0;
}
