/*
 * icm42688p.h - the TDK InvenSense ICM-42688-P on SPI: bank-0 registers and
 * the driver's steps (imu_spi.c calls them; tests call them directly).
 *
 * Source: ICM-42688-P datasheet DS-000347 rev 1.x: section 3 (table 1 gyro:
 * 16.4 LSB per deg/s at +/-2000, table 2 accel: 2048 LSB/g at +/-16 g), the SPI
 * interface section (read bit, 24 MHz, modes 0 and 3), 13/14 (bank-0 register map,
 * reset values, fields). Only bank 0 is used; the FIFO is not (data is read
 * from the registers at data-ready).
 */
#ifndef HT_ICM42688P_H
#define HT_ICM42688P_H

#include <stdint.h>

#include "imu_spi_bus.h"

/* ICM42688P_WHO_AM_I_VALUE: imu_spi_bus.h (imu_spi_detect names the chip by it). */

/* Bank-0 registers (DS section 13) */
#define ICM42688P_DEVICE_CONFIG      0x11u /* SOFT_RESET_CONFIG bit 0 */
#define ICM42688P_INT_CONFIG         0x14u /* INT1 mode/drive/polarity bits 2:0 */
#define ICM42688P_TEMP_DATA1         0x1Du /* 14 bytes: temp, accel X, Y, Z, gyro X, Y, Z */
#define ICM42688P_INT_STATUS         0x2Du /* RESET_DONE_INT bit 4, DATA_RDY_INT bit 3 */
#define ICM42688P_INTF_CONFIG0       0x4Cu /* reset 0x30 */
#define ICM42688P_PWR_MGMT0          0x4Eu /* reset 0x00: sensors off */
#define ICM42688P_GYRO_CONFIG0       0x4Fu /* GYRO_FS_SEL 7:5, GYRO_ODR 3:0; reset 0x06 */
#define ICM42688P_ACCEL_CONFIG0      0x50u /* ACCEL_FS_SEL 7:5, ACCEL_ODR 3:0; reset 0x06 */
#define ICM42688P_GYRO_ACCEL_CONFIG0 0x52u /* ACCEL_UI_FILT_BW 7:4, GYRO_UI_FILT_BW 3:0 */
#define ICM42688P_INT_CONFIG1        0x64u /* reset 0x10 */
#define ICM42688P_INT_SOURCE0        0x65u /* reset 0x10 */
#define ICM42688P_REG_BANK_SEL       0x76u

/* Values written (DS section 14) */
#define ICM42688P_SOFT_RESET     0x01u
#define ICM42688P_INT_RESET_DONE 0x10u /* INT_STATUS bit 4 */
#define ICM42688P_INTF0_VALUE                                                                      \
    0x33u                                  /* FIFO_COUNT_ENDIAN and SENSOR_DATA_ENDIAN kept 1      \
                                              (big-endian, the reset value), UI_SIFS_CFG 11:       \
                                              I2C off */
#define ICM42688P_INT1_PULSE_PP_HIGH 0x03u /* INT1 pulsed, push-pull, active high */
#define ICM42688P_INT_CONFIG1_VALUE                                                                \
    0x00u                                 /* INT_ASYNC_RESET 0 (DS: must be changed from           \
                                             its reset 1 for proper INT pin operation);            \
                                             100 us pulse, de-assert on (ODR < 4 kHz) */
#define ICM42688P_UI_DRDY_INT1_EN   0x08u /* INT_SOURCE0 bit 3; reset-done routing off */
#define ICM42688P_GYRO_2000DPS_1KHZ 0x06u /* GYRO_FS_SEL 000, GYRO_ODR 0110 */
#define ICM42688P_ACCEL_16G_1KHZ    0x06u /* ACCEL_FS_SEL 000, ACCEL_ODR 0110 */
#define ICM42688P_PWR_LN_BOTH                                                                      \
    0x0Fu /* GYRO_MODE 11, ACCEL_MODE 11: low noise,                                               \
             temperature sensor on */

/* Waits (DS 14.x DEVICE_CONFIG: 1 ms after a soft reset; PWR_MGMT0: 200
 * us without register writes after a sensor leaves OFF; table 1: gyro start-up
 * 30 ms). */
#define ICM42688P_RESET_WAIT_US    1000u
#define ICM42688P_RESET_POLL_US    1000u
#define ICM42688P_RESET_POLLS      10u
#define ICM42688P_POWER_ON_WAIT_US 200u
#define ICM42688P_STARTUP_WAIT_US  30000u
#define ICM42688P_BURST_BYTES      14u

/* GYRO_ACCEL_CONFIG0 for an imu_lpf_t (the same bandwidth code in both
 * nibbles, table in imu_spi_bus.h); 0xFF when out of range. */
uint8_t icm42688p_filter_bw(uint8_t lpf);

/* WHO_AM_I at 1 MHz: IMU_OK for 0x47, else as imu_spi_detect. */
imu_status_t icm42688p_probe(const imu_spi_bus_t *bus);

/*
 * Reset and configure (24 MHz):
 *   DEVICE_CONFIG = 0x01, wait 1 ms, poll INT_STATUS until RESET_DONE (10 x 1 ms)
 *   INTF_CONFIG0 = 0x33, INT_CONFIG = 0x03, INT_CONFIG1 = 0x00,
 *   INT_SOURCE0 = 0x08, GYRO_CONFIG0 = 0x06, ACCEL_CONFIG0 = 0x06,
 *   GYRO_ACCEL_CONFIG0 = bw << 4 | bw, PWR_MGMT0 = 0x0F, wait 200 us,
 *   read every one of those back, wait 30 ms (gyro start-up)
 */
imu_status_t icm42688p_init(const imu_spi_bus_t *bus, uint8_t lpf);

/* The 14-byte burst from TEMP_DATA1 (big-endian), raw counts in chip axes. */
imu_status_t icm42688p_read_raw(const imu_spi_bus_t *bus, int16_t accel[3], int16_t gyro[3],
                                int16_t *temp);

/* Die temperature: TEMP_DATA / 132.48 + 25 degC (DS 14.x), in 0.01 degC. */
int16_t icm42688p_temp_cdeg(int16_t raw);

#endif /* HT_ICM42688P_H */
