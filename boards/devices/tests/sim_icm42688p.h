/*
 * sim_icm42688p.h - a simulated ICM-42688-P on SPI for the host tests: the
 * bank-0 register map answering frames the way DS-000347 describes:
 *   - first byte: bit 7 = 1 read, 0 write; bits 6:0 the register; auto-
 *     increment on every further byte;
 *   - bank-0 reset values (DS section 14) for the registers the driver uses:
 *     INT_STATUS 0x10 (RESET_DONE), INTF_CONFIG0 0x30, INTF_CONFIG1 0x91,
 *     PWR_MGMT0 0x00, GYRO_CONFIG0 0x06, ACCEL_CONFIG0 0x06, GYRO_CONFIG1
 *     0x16, GYRO_ACCEL_CONFIG0 0x11, ACCEL_CONFIG1 0x0D, INT_CONFIG1 0x10,
 *     INT_SOURCE0 0x10, WHO_AM_I 0x47, the data registers 0x80 0x00;
 *   - DEVICE_CONFIG bit 0 (soft reset) restores them; for 1 ms the chip is
 *     busy (reads 0x00, writes dropped);
 *   - INT_STATUS clears when read;
 *   - REG_BANK_SEL (0x76) switches banks; banks 1-4 are not modelled (reads
 *     0, writes counted as foreign and dropped);
 *   - for 200 us after PWR_MGMT0 turns a sensor on from off, writes are
 *     dropped (counted);
 *   - a sensor that is off reads -32768 (the invalid-sample mark); on, the
 *     physical value set by the test converted with the range in
 *     GYRO_CONFIG0 / ACCEL_CONFIG0 (16.4 * 2^FS_SEL LSB per deg/s;
 *     2048 * 2^FS_SEL LSB/g), rounded, clamped to int16; temperature
 *     (T - 25) * 132.48; byte order from INTF_CONFIG0 bit 4 (1 = big-endian);
 *   - SCK above 24 MHz counts a violation.
 */
#ifndef HT_SIM_ICM42688P_H
#define HT_SIM_ICM42688P_H

#include <stdint.h>

#include "sim_mpu6000.h" /* SIM_LOG_MAX */

typedef struct {
    uint8_t regs[128]; /* bank 0 */
    uint8_t bank;
    double rate_rad_s[3];
    double accel_g[3];
    double temp_c;
    uint64_t busy_until_us;
    uint64_t no_write_until_us;
    uint32_t reset_busy_us;   /* how long a soft reset keeps the chip busy (1 ms) */
    uint8_t ignore_write_reg; /* nonzero: writes to this register are lost (a fault) */
    uint16_t clock_violations;
    uint16_t dropped_writes;
    uint16_t foreign_writes; /* writes to banks 1-4 */
    uint16_t resets;
    uint16_t log_n;
    uint8_t log_reg[SIM_LOG_MAX];
    uint8_t log_val[SIM_LOG_MAX];
} sim_icm42688p_t;

void sim_icm42688p_init(sim_icm42688p_t *s);
void sim_icm42688p_set_motion(sim_icm42688p_t *s, const double rate_rad_s[3],
                              const double accel_g[3]);
int16_t sim_icm42688p_gyro_counts(const sim_icm42688p_t *s, double rate_rad_s);
int16_t sim_icm42688p_accel_counts(const sim_icm42688p_t *s, double accel_g);
int sim_icm42688p_frame(void *chip, const uint8_t *tx, uint8_t *rx, uint16_t n, uint32_t sck_hz,
                        uint64_t now_us);

#endif /* HT_SIM_ICM42688P_H */
