/*
 * mpu6000.h - the InvenSense MPU-6000 on SPI: registers and the driver's
 * steps (imu_spi.c calls them; tests call them directly).
 *
 * Sources: "MPU-6000 and MPU-6050 Register Map and Descriptions" RM-MPU-6000A-00
 * rev 4.2 (section 3 register map, sections 4.x per register, reset values in
 * section 3: 0x00 except PWR_MGMT_1 = 0x40 and WHO_AM_I = 0x68) and "Product
 * Specification" PS-MPU-6000A-00 rev 3.4 (sections 6.1/6.2 gyro and
 * accelerometer specifications: sensitivities, start-up time; the SPI
 * interface section: clock limits; the orientation-of-axes figure).
 */
#ifndef HT_MPU6000_H
#define HT_MPU6000_H

#include <stdint.h>

#include "imu_spi_bus.h"

/* MPU6000_WHO_AM_I_VALUE: imu_spi_bus.h (imu_spi_detect names the chip by it). */

/* Registers (RM section 3, register map) */
#define MPU6000_SMPLRT_DIV        0x19u /* sample rate = gyro output rate / (1 + div) */
#define MPU6000_CONFIG            0x1Au /* DLPF_CFG bits 2:0, EXT_SYNC_SET 5:3 */
#define MPU6000_GYRO_CONFIG       0x1Bu /* FS_SEL bits 4:3 */
#define MPU6000_ACCEL_CONFIG      0x1Cu /* AFS_SEL bits 4:3 */
#define MPU6000_INT_PIN_CFG       0x37u
#define MPU6000_INT_ENABLE        0x38u
#define MPU6000_INT_STATUS        0x3Au
#define MPU6000_ACCEL_XOUT_H      0x3Bu /* 14 bytes: accel X, Y, Z, temp, gyro X, Y, Z */
#define MPU6000_SIGNAL_PATH_RESET 0x68u
#define MPU6000_USER_CTRL         0x6Au
#define MPU6000_PWR_MGMT_1        0x6Bu

/* Values written (RM section 4, each register's description) */
#define MPU6000_PWR1_DEVICE_RESET 0x80u /* bit 7, clears itself when the reset is done */
#define MPU6000_PWR1_SLEEP        0x40u /* bit 6, set after reset */
#define MPU6000_PWR1_CLK_PLL_ZG                                                                    \
    0x03u /* CLKSEL 3: PLL on the Z gyro (RM, PWR_MGMT_1 notes recommend a                         \
             gyro reference over the 8 MHz oscillator) */
#define MPU6000_SPR_RESET_ALL   0x07u /* GYRO_RESET | ACCEL_RESET | TEMP_RESET */
#define MPU6000_USER_I2C_IF_DIS 0x10u /* bit 4: SPI only (PS SPI section: disable I2C on SPI) */
#define MPU6000_SMPLRT_1KHZ     0x00u /* 1 kHz / (1 + 0) with the DLPF on */
#define MPU6000_FS_2000DPS      0x18u /* FS_SEL 3: +/-2000 deg/s, 16.4 LSB per deg/s */
#define MPU6000_AFS_16G         0x18u /* AFS_SEL 3: +/-16 g, 2048 LSB/g */
#define MPU6000_INT_PIN_PULSE                                                                      \
    0x10u /* active high, push-pull, 50 us pulse (LATCH_INT_EN 0),                                 \
             INT_RD_CLEAR 1: any read clears the status */
#define MPU6000_INT_DATA_RDY_EN 0x01u

/* Waits (RM PWR_MGMT_1 notes: 100 ms after DEVICE_RESET and after SIGNAL_PATH_RESET on
 * SPI; PS 6.1: gyro start-up time 30 ms from sleep). */
#define MPU6000_RESET_WAIT_US   100000u
#define MPU6000_RESET_POLL_US   10000u
#define MPU6000_RESET_POLLS     10u
#define MPU6000_STARTUP_WAIT_US 30000u
#define MPU6000_BURST_BYTES     14u

/* DLPF_CFG for an imu_lpf_t (table in imu_spi_bus.h); 0xFF when out of range. */
uint8_t mpu6000_dlpf_cfg(uint8_t lpf);

/* WHO_AM_I at 1 MHz: IMU_OK for 0x68, else as imu_spi_detect. */
imu_status_t mpu6000_probe(const imu_spi_bus_t *bus);

/*
 * Reset and configure (1 MHz for every register access, then the bus goes to
 * 20 MHz for the data reads):
 *   PWR_MGMT_1 = 0x80, wait 100 ms, poll until DEVICE_RESET reads 0 (10 x 10 ms)
 *   SIGNAL_PATH_RESET = 0x07, wait 100 ms
 *   USER_CTRL = 0x10, PWR_MGMT_1 = 0x03, SMPLRT_DIV = 0x00, CONFIG = DLPF_CFG,
 *   GYRO_CONFIG = 0x18, ACCEL_CONFIG = 0x18, INT_PIN_CFG = 0x10, INT_ENABLE = 0x01
 *   read every one of those back, wait 30 ms (gyro start-up)
 */
imu_status_t mpu6000_init(const imu_spi_bus_t *bus, uint8_t lpf);

/* The 14-byte burst from ACCEL_XOUT_H (big-endian), raw counts in chip axes. */
imu_status_t mpu6000_read_raw(const imu_spi_bus_t *bus, int16_t accel[3], int16_t gyro[3],
                              int16_t *temp);

/* Die temperature: TEMP_OUT / 340 + 36.53 degC (RM, TEMP_OUT registers 65-66), in 0.01 degC. */
int16_t mpu6000_temp_cdeg(int16_t raw);

#endif /* HT_MPU6000_H */
