/*
 * imu_spi_bus.h - what the SPI IMU drivers share (imu_spi.h's base): the bus
 * interface, the status codes, the alignments and filters, chip detection
 * by WHO_AM_I and the common register access, scaling and alignment. The
 * chip drivers (mpu6000.c, icm42688p.c) use only this; the dispatcher
 * (imu_spi.c: imu_spi_init, imu_spi_read) uses them and this.
 *
 * Integer only; no float, malloc, recursion or global state: the caller owns
 * imu_spi_bus_t.
 */
#ifndef HT_IMU_SPI_BUS_H
#define HT_IMU_SPI_BUS_H

#include <stdint.h>

#include "helical/estimator/dcm.h"

#ifdef __cplusplus
extern "C" {
#endif

/*
 * The bus: one chip select, one chip. xfer exchanges n bytes full duplex
 * inside one chip-select frame (tx[i] out while rx[i] comes in) and returns
 * 0 on success. set_clock sets the SCK to at most max_hz and returns 0 (NULL
 * when the bus has one fixed clock low enough for every access, 1 MHz).
 * delay_us waits at least us microseconds (the board's timer).
 */
typedef struct {
    void *ctx;
    int (*xfer)(void *ctx, const uint8_t *tx, uint8_t *rx, uint16_t n);
    int (*set_clock)(void *ctx, uint32_t max_hz);
    void (*delay_us)(void *ctx, uint32_t us);
} imu_spi_bus_t;

typedef enum {
    IMU_CHIP_NONE = 0,
    IMU_CHIP_MPU6000 = 1,  /* WHO_AM_I 0x68 */
    IMU_CHIP_ICM42688P = 2 /* WHO_AM_I 0x47 */
} imu_chip_t;

typedef enum {
    IMU_OK = 0,
    IMU_ERR_NULL = 1,          /* a NULL pointer or a bus without xfer/delay_us */
    IMU_ERR_RANGE = 2,         /* an alignment or filter out of range: nothing written */
    IMU_ERR_BUS = 3,           /* the bus reported an error (an SPI timeout) */
    IMU_ERR_NO_DEVICE = 4,     /* WHO_AM_I read 0x00 or 0xFF: MISO floats or is stuck,
                                  nothing answers */
    IMU_ERR_WRONG_ID = 5,      /* something answered with another WHO_AM_I */
    IMU_ERR_RESET_TIMEOUT = 6, /* the chip did not report its reset done in time */
    IMU_ERR_CONFIG = 7,        /* a configuration register read back wrong */
    IMU_ERR_NOT_READY = 8,     /* imu_spi_read before a successful imu_spi_init */
    IMU_ERR_DATA = 9           /* a burst with no data in it (all 0x00, all 0xFF, or the
                                  ICM-42688-P's invalid-sample mark -32768 on all six axes) */
} imu_status_t;

/*
 * How the chip sits on the board: the chip's own axes (datasheets' figure
 * "orientation of axes of sensitivity": X and Y in the package plane, Z out
 * of its top) to the library's body axes. YAWn: the chip top up, its +Y axis
 * turned n degrees clockwise (seen from above) from the nose; YAW0 is +Y
 * forward, +X toward the right wing. FLIP_YAWn: the same chip then turned
 * upside down about the fuselage axis (top down, mounted under the board).
 * Each is an exact permutation with sign changes (body = M sensor):
 *   YAW0       ( -x,  y, -z )      FLIP_YAW0    (  x,  y,  z )
 *   YAW90      ( -y, -x, -z )      FLIP_YAW90   (  y, -x,  z )
 *   YAW180     (  x, -y, -z )      FLIP_YAW180  ( -x, -y,  z )
 *   YAW270     (  y,  x, -z )      FLIP_YAW270  ( -y,  x,  z )
 * (a chip at rest top up reads specific force +1 g on its Z: body (0, 0, -1)).
 */
typedef enum {
    IMU_ALIGN_YAW0 = 0,
    IMU_ALIGN_YAW90 = 1,
    IMU_ALIGN_YAW180 = 2,
    IMU_ALIGN_YAW270 = 3,
    IMU_ALIGN_FLIP_YAW0 = 4,
    IMU_ALIGN_FLIP_YAW90 = 5,
    IMU_ALIGN_FLIP_YAW180 = 6,
    IMU_ALIGN_FLIP_YAW270 = 7,
    IMU_ALIGN_COUNT = 8
} imu_align_t;

/*
 * The low-pass filter, nominal -3 dB bandwidths at the 1 kHz output rate
 * (gyro / accelerometer where they differ):
 *              MPU-6000 DLPF_CFG          ICM-42688-P UI filter BW (2nd order)
 *   WIDE       1: 188 / 184 Hz            1: max(400 Hz, ODR) / 4 = 250 Hz
 *   MEDIUM     2:  98 /  94 Hz            4: ODR / 10 = 100 Hz
 *   NARROW     3:  42 /  44 Hz            6: ODR / 20 =  50 Hz
 *   NARROWEST  4:  20 /  21 Hz            7: ODR / 40 =  25 Hz
 */
typedef enum {
    IMU_LPF_WIDE = 0,
    IMU_LPF_MEDIUM = 1,
    IMU_LPF_NARROW = 2,
    IMU_LPF_NARROWEST = 3,
    IMU_LPF_COUNT = 4
} imu_lpf_t;

/* The SPI clock limits (datasheets: MPU-6000 PS SPI interface section and
 * register map section 1: 1 MHz for every register, 20 MHz for reading the sensor and
 * interrupt registers only; ICM-42688-P DS-000347 SPI interface section: 24 MHz). */
#define IMU_MPU6000_SCK_REG_HZ  1000000u
#define IMU_MPU6000_SCK_DATA_HZ 20000000u
#define IMU_ICM42688P_SCK_HZ    24000000u

/* Both chips keep WHO_AM_I at register 0x75 (the ICM-42688-P in bank 0, its
 * bank after reset). */
#define IMU_REG_WHO_AM_I 0x75u
/* The first byte of a transaction: bit 7 = 1 reads, 0 writes; bits 6:0 the
 * register; the chip then auto-increments the register on every byte. */
#define IMU_SPI_READ 0x80u

/* What each chip answers at WHO_AM_I. */
#define MPU6000_WHO_AM_I_VALUE   0x68u
#define ICM42688P_WHO_AM_I_VALUE 0x47u

/*
 * Read WHO_AM_I once at 1 MHz and name the chip: IMU_OK with *chip set,
 * IMU_ERR_NO_DEVICE (0x00 or 0xFF), IMU_ERR_WRONG_ID (*chip = NONE and
 * *who_am_i, may be NULL, says what answered), IMU_ERR_BUS, IMU_ERR_NULL.
 */
imu_status_t imu_spi_detect(const imu_spi_bus_t *bus, imu_chip_t *chip, uint8_t *who_am_i);

/* 1 when the bus can be used: not NULL, with xfer and delay_us. */
int imu_spi_bus_ok(const imu_spi_bus_t *bus);

/* Read n (1..15) registers from reg on: one frame of n + 1 bytes. */
imu_status_t imu_spi_read_regs(const imu_spi_bus_t *bus, uint8_t reg, uint8_t *data, uint8_t n);

/* Write one register: one frame of 2 bytes. */
imu_status_t imu_spi_write_reg(const imu_spi_bus_t *bus, uint8_t reg, uint8_t value);

/* One register and the value the driver writes there. */
typedef struct {
    uint8_t reg;
    uint8_t value;
} imu_reg_value_t;

/* Write each register of seq in order; stop at the first bus error. */
imu_status_t imu_spi_write_seq(const imu_spi_bus_t *bus, const imu_reg_value_t *seq, uint8_t n);

/* Read each register of seq back: IMU_ERR_CONFIG at the first that differs. */
imu_status_t imu_spi_verify_seq(const imu_spi_bus_t *bus, const imu_reg_value_t *seq, uint8_t n);

/* Set the bus clock (nothing when the bus has no set_clock). */
imu_status_t imu_spi_set_clock(const imu_spi_bus_t *bus, uint32_t max_hz);

/* A big-endian 16-bit two's-complement value from p[0] (high), p[1] (low). */
int16_t imu_be16(const uint8_t *p);

/*
 * 1 when a burst of n bytes holds one value throughout, 0x00 or 0xFF: a chip
 * that is asleep, gone or held in reset returns that; a live one never does
 * (gravity alone moves an axis). Both chips' reads refuse such a burst.
 */
uint8_t imu_burst_is_blank(const uint8_t *b, uint8_t n);

/*
 * Counts to Q16 at +/-2000 deg/s (16.4 LSB per deg/s) and +/-16 g (2048
 * LSB/g), both chips' nominal sensitivities:
 *   gyro:  raw * (65536 pi / (180 * 16.4)) = raw * 69.74506, held as
 *          69 + 48828 / 65536 and rounded once to nearest (ties up); error
 *          under 0.62 LSB of Q16 over the whole int16 range
 *          (-32768 -> -2285406 = -34.872 rad/s, 32767 -> 2285336);
 *   accel: raw * 32 exactly (-32768 -> -16 g, 32767 -> 15.9995 g).
 */
q16_t imu_gyro_q16_from_raw(int16_t raw);
q16_t imu_accel_q16_from_raw(int16_t raw);

/* out = M in for the alignment (table above); an align out of range gives
 * zeros. in and out must not overlap. */
void imu_align_apply(uint8_t align, const q16_t in[3], q16_t out[3]);

/* a / b rounded to nearest, halves away from zero; b > 0. */
int32_t imu_div_round(int32_t a, int32_t b);

#ifdef __cplusplus
}
#endif

#endif /* HT_IMU_SPI_BUS_H */
