/*
 * icm42688p.c - the ICM-42688-P's reset, configuration and burst read (see
 * icm42688p.h for the sequence and its sources).
 */
#include "icm42688p.h"

#include <stddef.h>

/* The invalid-sample mark: the data registers hold -32768 (0x8000) for a
 * sensor that is off or has no sample yet (DS 14.x INTF_CONFIG0). */
#define ICM42688P_INVALID_SAMPLE (-32768)

uint8_t icm42688p_filter_bw(uint8_t lpf)
{
    /* UI filter bandwidth codes per imu_lpf_t (DS 14.x GYRO_ACCEL_CONFIG0:
     * 1 = max(400 Hz, ODR) / 4, 4 = ODR / 10, 6 = ODR / 20, 7 = ODR / 40). */
    static const uint8_t k_filter_bw[IMU_LPF_COUNT] = {1u, 4u, 6u, 7u};
    if (lpf >= (uint8_t)IMU_LPF_COUNT) {
        return 0xFFu;
    }
    const uint8_t bw = k_filter_bw[lpf];
    return (uint8_t)(bw << 4) | bw;
}

imu_status_t icm42688p_probe(const imu_spi_bus_t *bus)
{
    imu_chip_t chip = IMU_CHIP_NONE;
    const imu_status_t st = imu_spi_detect(bus, &chip, NULL);
    if (st != IMU_OK) {
        return st;
    }
    return (chip == IMU_CHIP_ICM42688P) ? IMU_OK : IMU_ERR_WRONG_ID;
}

/* After a soft reset INT_STATUS reads RESET_DONE_INT (its reset value 0x10,
 * cleared by the read). */
static imu_status_t wait_reset_done(const imu_spi_bus_t *bus)
{
    bus->delay_us(bus->ctx, ICM42688P_RESET_WAIT_US);
    for (uint8_t poll = 0u; poll < ICM42688P_RESET_POLLS; ++poll) {
        uint8_t status = 0u;
        const imu_status_t st = imu_spi_read_regs(bus, ICM42688P_INT_STATUS, &status, 1u);
        if (st != IMU_OK) {
            return st;
        }
        if ((status & ICM42688P_INT_RESET_DONE) != 0u) {
            return IMU_OK;
        }
        bus->delay_us(bus->ctx, ICM42688P_RESET_POLL_US);
    }
    return IMU_ERR_RESET_TIMEOUT;
}

imu_status_t icm42688p_init(const imu_spi_bus_t *bus, uint8_t lpf)
{
    if (bus == NULL || bus->xfer == NULL || bus->delay_us == NULL) {
        return IMU_ERR_NULL;
    }
    const uint8_t bw = icm42688p_filter_bw(lpf);
    if (bw == 0xFFu) {
        return IMU_ERR_RANGE;
    }
    /* Everything is set while the sensors are off; PWR_MGMT0 comes last. */
    const imu_reg_value_t config[] = {
        {ICM42688P_INTF_CONFIG0, ICM42688P_INTF0_VALUE},
        {ICM42688P_INT_CONFIG, ICM42688P_INT1_PULSE_PP_HIGH},
        {ICM42688P_INT_CONFIG1, ICM42688P_INT_CONFIG1_VALUE},
        {ICM42688P_INT_SOURCE0, ICM42688P_UI_DRDY_INT1_EN},
        {ICM42688P_GYRO_CONFIG0, ICM42688P_GYRO_2000DPS_1KHZ},
        {ICM42688P_ACCEL_CONFIG0, ICM42688P_ACCEL_16G_1KHZ},
        {ICM42688P_GYRO_ACCEL_CONFIG0, bw},
        {ICM42688P_PWR_MGMT0, ICM42688P_PWR_LN_BOTH},
    };
    const uint8_t n_config = (uint8_t)(sizeof config / sizeof config[0]);

    imu_status_t st = imu_spi_set_clock(bus, IMU_ICM42688P_SCK_HZ);
    if (st == IMU_OK) {
        st = imu_spi_write_reg(bus, ICM42688P_DEVICE_CONFIG, ICM42688P_SOFT_RESET);
    }
    if (st == IMU_OK) {
        st = wait_reset_done(bus);
    }
    if (st == IMU_OK) {
        st = imu_spi_write_seq(bus, config, n_config);
    }
    if (st == IMU_OK) {
        /* DS PWR_MGMT0: no register write for 200 us after a sensor leaves OFF
         * (reads are fine, but the wait keeps the rule simple) */
        bus->delay_us(bus->ctx, ICM42688P_POWER_ON_WAIT_US);
        st = imu_spi_verify_seq(bus, config, n_config);
    }
    if (st == IMU_OK) {
        bus->delay_us(bus->ctx, ICM42688P_STARTUP_WAIT_US);
    }
    return st;
}

imu_status_t icm42688p_read_raw(const imu_spi_bus_t *bus, int16_t accel[3], int16_t gyro[3],
                                int16_t *temp)
{
    if (accel == NULL || gyro == NULL || temp == NULL) {
        return IMU_ERR_NULL;
    }
    uint8_t b[ICM42688P_BURST_BYTES];
    const imu_status_t st = imu_spi_read_regs(bus, ICM42688P_TEMP_DATA1, b, ICM42688P_BURST_BYTES);
    if (st != IMU_OK) {
        return st;
    }
    if (imu_burst_is_blank(b, ICM42688P_BURST_BYTES) != 0u) {
        return IMU_ERR_DATA;
    }
    /* DS 14.x: TEMP_DATA1/0, ACCEL_DATA_X1 .. GYRO_DATA_Z0, high byte first
     * (SENSOR_DATA_ENDIAN = 1) */
    int16_t a[3];
    int16_t g[3];
    uint8_t invalid = 0u;
    for (uint8_t i = 0u; i < 3u; ++i) {
        a[i] = imu_be16(&b[2u + 2u * i]);
        g[i] = imu_be16(&b[8u + 2u * i]);
        if (a[i] == ICM42688P_INVALID_SAMPLE && g[i] == ICM42688P_INVALID_SAMPLE) {
            invalid++;
        }
    }
    if (invalid == 3u) {
        return IMU_ERR_DATA;
    }
    for (uint8_t i = 0u; i < 3u; ++i) {
        accel[i] = a[i];
        gyro[i] = g[i];
    }
    *temp = imu_be16(&b[0]);
    return IMU_OK;
}

int16_t icm42688p_temp_cdeg(int16_t raw)
{
    /* 100 / 132.48 = 625 / 828 */
    const int32_t r = raw;
    const int32_t cdeg = imu_div_round(r * 625, 828) + 2500;
    return (int16_t)cdeg; /* within [-22234, 27233] for every raw */
}
