/*
 * imu_spi.c - the SPI IMUs' dispatch (see imu_spi.h): detect the chip, then
 * run its driver (mpu6000.c, icm42688p.c); the common register access,
 * detection, scaling and alignment are in imu_spi_bus.c.
 */
#include "imu_spi.h"

#include <stddef.h>

#include "icm42688p.h"
#include "mpu6000.h"

static void count(uint16_t *c)
{
    if (*c != UINT16_MAX) {
        (*c)++;
    }
}

imu_status_t imu_spi_init(imu_spi_t *imu, const imu_spi_bus_t *bus, const imu_spi_config_t *cfg)
{
    if (imu == NULL || cfg == NULL || !imu_spi_bus_ok(bus)) {
        return IMU_ERR_NULL;
    }
    imu->ready = 0u;
    if (cfg->align_mpu6000 >= (uint8_t)IMU_ALIGN_COUNT ||
        cfg->align_icm42688p >= (uint8_t)IMU_ALIGN_COUNT || cfg->lpf >= (uint8_t)IMU_LPF_COUNT) {
        return IMU_ERR_RANGE;
    }
    imu->bus = bus;
    imu->chip = (uint8_t)IMU_CHIP_NONE;
    imu->read_errors = 0u;
    imu->temp_cdeg = 0;
    imu_chip_t chip = IMU_CHIP_NONE;
    imu_status_t st = imu_spi_detect(bus, &chip, NULL);
    if (st != IMU_OK) {
        return st;
    }
    if (chip == IMU_CHIP_MPU6000) {
        st = mpu6000_init(bus, cfg->lpf);
        imu->align = cfg->align_mpu6000;
    } else {
        st = icm42688p_init(bus, cfg->lpf);
        imu->align = cfg->align_icm42688p;
    }
    if (st != IMU_OK) {
        return st;
    }
    imu->chip = (uint8_t)chip;
    imu->ready = 1u;
    return IMU_OK;
}

imu_status_t imu_spi_read(imu_spi_t *imu, ht_imu_sample_t *out)
{
    if (imu == NULL || out == NULL) {
        return IMU_ERR_NULL;
    }
    if (!imu->ready) {
        return IMU_ERR_NOT_READY;
    }
    int16_t accel[3] = {0, 0, 0};
    int16_t gyro[3] = {0, 0, 0};
    int16_t temp = 0;
    imu_status_t st;
    if (imu->chip == (uint8_t)IMU_CHIP_MPU6000) {
        st = mpu6000_read_raw(imu->bus, accel, gyro, &temp);
    } else {
        st = icm42688p_read_raw(imu->bus, accel, gyro, &temp);
    }
    if (st != IMU_OK) {
        count(&imu->read_errors);
        return st;
    }
    q16_t accel_q16[3];
    q16_t gyro_q16[3];
    for (uint8_t i = 0u; i < 3u; ++i) {
        accel_q16[i] = imu_accel_q16_from_raw(accel[i]);
        gyro_q16[i] = imu_gyro_q16_from_raw(gyro[i]);
    }
    imu_align_apply(imu->align, accel_q16, out->accel_g);
    imu_align_apply(imu->align, gyro_q16, out->gyro_rad_s);
    if (imu->chip == (uint8_t)IMU_CHIP_MPU6000) {
        imu->temp_cdeg = mpu6000_temp_cdeg(temp);
    } else {
        imu->temp_cdeg = icm42688p_temp_cdeg(temp);
    }
    return IMU_OK;
}
