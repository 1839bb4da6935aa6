/*
 * sim_mpu6000.h - a simulated MPU-6000 on SPI for the host tests: a register
 * map that answers frames the way RM-MPU-6000A-00 rev 4.2 and
 * PS-MPU-6000A-00 rev 3.4 describe:
 *   - first byte: bit 7 = 1 read, 0 write; bits 6:0 the register; the
 *     register auto-increments on every further byte (reads and writes);
 *   - reset values 0x00 except PWR_MGMT_1 = 0x40 (asleep), WHO_AM_I = 0x68;
 *   - PWR_MGMT_1 bit 7 (DEVICE_RESET) restores them and the chip is busy for
 *     100 ms: reads give 0x00, writes are dropped (counted); likewise for
 *     100 ms after SIGNAL_PATH_RESET (the register map's SPI sequence);
 *   - while SLEEP (PWR_MGMT_1 bit 6) is set the data registers stay 0;
 *   - awake, ACCEL_XOUT_H..GYRO_ZOUT_L (0x3B..0x48) hold the physical values
 *     set by the test, converted with the sensitivity of the range then in
 *     GYRO_CONFIG / ACCEL_CONFIG (131/65.5/32.8/16.4 LSB per deg/s,
 *     16384/8192/4096/2048 LSB/g), rounded, clamped to int16, high byte
 *     first; the temperature as (T - 36.53) * 340;
 *   - SCK above 1 MHz is allowed only for reads of 0x3A..0x48 (sensor and
 *     interrupt status), up to 20 MHz: anything else counts a violation;
 *   - WHO_AM_I and the data registers are read-only.
 * Axes are the chip's (X, Y in the package plane, Z out of the top).
 */
#ifndef HT_SIM_MPU6000_H
#define HT_SIM_MPU6000_H

#include <stdint.h>

#define SIM_LOG_MAX 64u

typedef struct {
    uint8_t regs[128];
    double rate_rad_s[3]; /* chip axes */
    double accel_g[3];    /* specific force, chip axes */
    double temp_c;
    uint64_t busy_until_us;
    uint32_t reset_busy_us;   /* how long a reset keeps the chip busy (100 ms) */
    uint8_t ignore_write_reg; /* nonzero: writes to this register are lost (a fault) */
    uint16_t clock_violations;
    uint16_t dropped_writes; /* writes while busy */
    uint16_t resets;         /* DEVICE_RESET seen */
    uint16_t log_n;          /* register writes accepted, in order */
    uint8_t log_reg[SIM_LOG_MAX];
    uint8_t log_val[SIM_LOG_MAX];
} sim_mpu6000_t;

/* Power-on state: reset values, at rest top up (0, 0, +1 g), 25 degC. */
void sim_mpu6000_init(sim_mpu6000_t *s);

void sim_mpu6000_set_motion(sim_mpu6000_t *s, const double rate_rad_s[3], const double accel_g[3]);

/* The count the chip would put out for a rate / specific force now. */
int16_t sim_mpu6000_gyro_counts(const sim_mpu6000_t *s, double rate_rad_s);
int16_t sim_mpu6000_accel_counts(const sim_mpu6000_t *s, double accel_g);

/* sim_frame_fn for sim_bus_t (chip = sim_mpu6000_t *). */
int sim_mpu6000_frame(void *chip, const uint8_t *tx, uint8_t *rx, uint16_t n, uint32_t sck_hz,
                      uint64_t now_us);

#endif /* HT_SIM_MPU6000_H */
