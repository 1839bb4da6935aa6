/*
 * mpu6000.c - the MPU-6000's reset, configuration and burst read (see
 * mpu6000.h for the sequence and its sources).
 */
#include "mpu6000.h"

#include <stddef.h>

uint8_t mpu6000_dlpf_cfg(uint8_t lpf)
{
    /* DLPF_CFG per imu_lpf_t (RM, CONFIG register 26 table: 1 -> 188 Hz gyro, 2 -> 98,
     * 3 -> 42, 4 -> 20; any of 1..6 makes the gyro output rate 1 kHz). */
    static const uint8_t k_dlpf_cfg[IMU_LPF_COUNT] = {1u, 2u, 3u, 4u};
    if (lpf >= (uint8_t)IMU_LPF_COUNT) {
        return 0xFFu;
    }
    return k_dlpf_cfg[lpf];
}

imu_status_t mpu6000_probe(const imu_spi_bus_t *bus)
{
    imu_chip_t chip = IMU_CHIP_NONE;
    const imu_status_t st = imu_spi_detect(bus, &chip, NULL);
    if (st != IMU_OK) {
        return st;
    }
    return (chip == IMU_CHIP_MPU6000) ? IMU_OK : IMU_ERR_WRONG_ID;
}

/* After DEVICE_RESET the chip reads PWR_MGMT_1 = 0x40: reset bit cleared by
 * the chip, asleep (the reset value). Anything else: not done (or not reset). */
static imu_status_t wait_reset_done(const imu_spi_bus_t *bus)
{
    bus->delay_us(bus->ctx, MPU6000_RESET_WAIT_US);
    for (uint8_t poll = 0u; poll < MPU6000_RESET_POLLS; ++poll) {
        uint8_t pwr = 0u;
        const imu_status_t st = imu_spi_read_regs(bus, MPU6000_PWR_MGMT_1, &pwr, 1u);
        if (st != IMU_OK) {
            return st;
        }
        if ((pwr & (MPU6000_PWR1_DEVICE_RESET | MPU6000_PWR1_SLEEP)) == MPU6000_PWR1_SLEEP) {
            return IMU_OK;
        }
        bus->delay_us(bus->ctx, MPU6000_RESET_POLL_US);
    }
    return IMU_ERR_RESET_TIMEOUT;
}

imu_status_t mpu6000_init(const imu_spi_bus_t *bus, uint8_t lpf)
{
    if (bus == NULL || bus->xfer == NULL || bus->delay_us == NULL) {
        return IMU_ERR_NULL;
    }
    const uint8_t dlpf = mpu6000_dlpf_cfg(lpf);
    if (dlpf == 0xFFu) {
        return IMU_ERR_RANGE;
    }
    /* I2C off first, so the SPI alone talks to the chip; then wake on the
     * gyro PLL; then rate, filter, ranges and the data-ready pulse. */
    const imu_reg_value_t config[] = {
        {MPU6000_USER_CTRL, MPU6000_USER_I2C_IF_DIS}, {MPU6000_PWR_MGMT_1, MPU6000_PWR1_CLK_PLL_ZG},
        {MPU6000_SMPLRT_DIV, MPU6000_SMPLRT_1KHZ},    {MPU6000_CONFIG, dlpf},
        {MPU6000_GYRO_CONFIG, MPU6000_FS_2000DPS},    {MPU6000_ACCEL_CONFIG, MPU6000_AFS_16G},
        {MPU6000_INT_PIN_CFG, MPU6000_INT_PIN_PULSE}, {MPU6000_INT_ENABLE, MPU6000_INT_DATA_RDY_EN},
    };
    const uint8_t n_config = (uint8_t)(sizeof config / sizeof config[0]);

    /* every register access at 1 MHz (PS, SPI interface: 1 MHz for all registers) */
    imu_status_t st = imu_spi_set_clock(bus, IMU_MPU6000_SCK_REG_HZ);
    if (st == IMU_OK) {
        st = imu_spi_write_reg(bus, MPU6000_PWR_MGMT_1, MPU6000_PWR1_DEVICE_RESET);
    }
    if (st == IMU_OK) {
        st = wait_reset_done(bus);
    }
    if (st == IMU_OK) {
        /* RM, PWR_MGMT_1 register 107 notes: on SPI, DEVICE_RESET then SIGNAL_PATH_RESET, 100 ms
         * each */
        st = imu_spi_write_reg(bus, MPU6000_SIGNAL_PATH_RESET, MPU6000_SPR_RESET_ALL);
    }
    if (st == IMU_OK) {
        bus->delay_us(bus->ctx, MPU6000_RESET_WAIT_US);
        st = imu_spi_write_seq(bus, config, n_config);
    }
    if (st == IMU_OK) {
        st = imu_spi_verify_seq(bus, config, n_config);
    }
    if (st == IMU_OK) {
        bus->delay_us(bus->ctx, MPU6000_STARTUP_WAIT_US);
        /* from now on only sensor registers are read: 20 MHz allowed */
        st = imu_spi_set_clock(bus, IMU_MPU6000_SCK_DATA_HZ);
    }
    return st;
}

imu_status_t mpu6000_read_raw(const imu_spi_bus_t *bus, int16_t accel[3], int16_t gyro[3],
                              int16_t *temp)
{
    if (accel == NULL || gyro == NULL || temp == NULL) {
        return IMU_ERR_NULL;
    }
    uint8_t b[MPU6000_BURST_BYTES];
    const imu_status_t st = imu_spi_read_regs(bus, MPU6000_ACCEL_XOUT_H, b, MPU6000_BURST_BYTES);
    if (st != IMU_OK) {
        return st;
    }
    if (imu_burst_is_blank(b, MPU6000_BURST_BYTES) != 0u) {
        return IMU_ERR_DATA;
    }
    /* RM, registers 59-72: ACCEL_XOUT_H .. GYRO_ZOUT_L, high byte first */
    for (size_t i = 0u; i < 3u; ++i) {
        accel[i] = imu_be16(&b[2u * i]);
        gyro[i] = imu_be16(&b[8u + (2u * i)]);
    }
    *temp = imu_be16(&b[6]);
    return IMU_OK;
}

int16_t mpu6000_temp_cdeg(int16_t raw)
{
    /* 100 / 340 = 5 / 17 */
    const int32_t r = raw;
    const int32_t cdeg = imu_div_round(r * 5, 17) + 3653;
    return (int16_t)cdeg; /* within [-5985, 13290] for every raw */
}
