/*
 * imu_spi.h - SPI IMUs (MPU-6000, ICM-42688-P) behind one interface: detect
 * the chip by WHO_AM_I, reset and configure it, read one sample at data-ready
 * and hand it on in the estimator's formats and axes (ht_imu_sample_t,
 * include/helical/estimator/dcm.h: gyro Q16 rad/s, specific force Q16 g, library body
 * axes X out the left wing, Y forward, Z down).
 *
 * The chips are reached through a bus interface (imu_spi_bus_t, in
 * imu_spi_bus.h with the status codes, alignments, filters, detection and
 * the register helpers the chip drivers share), so the same code runs on the STM32 SPI driver
 * (boards/stm32f4/stm32f4_spi.h) and on the simulated chips of the host tests
 * (boards/devices/tests/sim_*.h). Every wait is a call of the bus's delay_us with a fixed count,
 * every poll has a fixed number of tries: nothing here spins on real time or hangs.
 *
 * Both chips are configured alike: gyro +/-2000 deg/s (16.4 LSB per deg/s),
 * accelerometer +/-16 g (2048 LSB/g), 1 kHz output rate, the chosen low-pass
 * filter, data-ready on the INT pin (push-pull, active high, pulsed). The
 * sample is one burst read of the data registers when the INT pin says
 * data-ready (the caller's EXTI): the ICM-42688-P's FIFO is not used.
 * docs/drivers/imu.md has the register values and their sources.
 *
 * Integer only; no float, malloc, recursion or global state: the caller owns
 * imu_spi_bus_t and imu_spi_t.
 */
#ifndef HT_IMU_SPI_H
#define HT_IMU_SPI_H

#include <stdint.h>

#include "helical/estimator/dcm.h"
#include "imu_spi_bus.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct {
    uint8_t align_mpu6000;   /* imu_align_t when the MPU-6000 is found */
    uint8_t align_icm42688p; /* imu_align_t when the ICM-42688-P is found (the board
                                variants may place the two chips differently) */
    uint8_t lpf;             /* imu_lpf_t */
} imu_spi_config_t;

/* Driver state, owned by the caller. Counters saturate at UINT16_MAX. */
typedef struct {
    const imu_spi_bus_t *bus;
    uint8_t chip;         /* imu_chip_t found by the last init */
    uint8_t align;        /* imu_align_t in use */
    uint8_t ready;        /* 1 after a successful init */
    uint16_t read_errors; /* reads that returned IMU_ERR_BUS or IMU_ERR_DATA */
    int16_t temp_cdeg;    /* the last good sample's die temperature, 0.01 degC */
} imu_spi_t;

/*
 * Detect the chip, reset it and configure it (see the chip's header), then
 * read every configured register back. imu->ready only on IMU_OK. Takes
 * about 230 ms on the MPU-6000, 35 ms on the ICM-42688-P (the bus's
 * delay_us). cfg out of range: IMU_ERR_RANGE before any bus access.
 */
imu_status_t imu_spi_init(imu_spi_t *imu, const imu_spi_bus_t *bus, const imu_spi_config_t *cfg);

/*
 * One sample: a burst read of the data registers, scaled and rotated into
 * body axes. On IMU_ERR_BUS or IMU_ERR_DATA read_errors counts it and *out
 * is left as it was.
 */
imu_status_t imu_spi_read(imu_spi_t *imu, ht_imu_sample_t *out);

#ifdef __cplusplus
}
#endif

#endif /* HT_IMU_SPI_H */
