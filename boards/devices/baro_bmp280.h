/*
 * baro_bmp280.h - the Bosch BMP280 barometer over I2C (bus seam i2c_bus.h).
 *
 * Facts from the BMP280 datasheet (BST-BMP280-DS001, rev. 1.19/1.26):
 *   section 5.2: I2C address 0x76 (SDO to GND) or 0x77 (SDO to VDDIO);
 *                writes are (register, value) pairs, reads auto-increment
 *   section 4.3: registers: id 0xD0 = 0x58, reset 0xE0 (0xB6 resets),
 *                status 0xF3 (bit 3 measuring, bit 0 im_update), ctrl_meas
 *                0xF4 (osrs_t[7:5], osrs_p[4:2], mode[1:0]), config 0xF5
 *                (t_sb[7:5], filter[4:2]), data 0xF7..0xFC (press msb, lsb,
 *                xlsb[7:4], temp msb, lsb, xlsb[7:4]); 0x80000 = no result
 *   section 3.11.2: the 24-byte trimming block 0x88..0x9F, little-endian:
 *                dig_T1 (u16), dig_T2, dig_T3, dig_P1 (u16), dig_P2..dig_P9
 *   section 3.11.3: the integer compensation (temperature with t_fine in
 *                32 bits; pressure with 64-bit intermediates, in Q24.8 Pa)
 *   section 3.8.1: measurement time typ = 1 + 2 * osrs_t + 2 * osrs_p + 0.5 ms,
 *                max = 1.25 + 2.3 * osrs_t + 2.3 * osrs_p + 0.575 ms
 *   section 3.3.3: IIR filter coefficient 4 reaches 75 % of a step in 5 samples
 *
 * Configuration chosen here (the datasheet's "high resolution" setting,
 * section 3.4): pressure x8, temperature x1, IIR filter coefficient 4,
 * normal mode with t_standby 0.5 ms: a result every 19.5 + 0.5 = 20.0 ms
 * typical (50 Hz), 22.5 + 0.5 = 23.0 ms at most (43.5 Hz), so a 40 Hz
 * control loop sees a new one on nearly every tick. The filter's 4 keeps
 * the lag at a few samples (about 0.1 s) while taking out most of the
 * sample noise.
 *
 * Nothing here blocks except the bus transactions themselves; the reset
 * wait polls im_update at most BMP280_RESET_POLLS times.
 */
#ifndef HT_BARO_BMP280_H
#define HT_BARO_BMP280_H

#include <stdint.h>

#include "i2c_bus.h"

#define BMP280_ADDR_SDO_LOW  0x76u
#define BMP280_ADDR_SDO_HIGH 0x77u

#define BMP280_REG_CALIB     0x88u
#define BMP280_CALIB_LEN     24u
#define BMP280_REG_ID        0xD0u
#define BMP280_CHIP_ID       0x58u
#define BMP280_REG_RESET     0xE0u
#define BMP280_RESET_WORD    0xB6u
#define BMP280_REG_STATUS    0xF3u
#define BMP280_STATUS_IM_UPD 0x01u /* the NVM is being copied (after a reset) */
#define BMP280_REG_CTRL_MEAS 0xF4u
#define BMP280_REG_CONFIG    0xF5u
#define BMP280_REG_DATA      0xF7u
#define BMP280_DATA_LEN      6u
#define BMP280_ADC_SKIPPED   0x80000 /* the data registers' value with no result */

/* ctrl_meas = osrs_t x1 (001 << 5) | osrs_p x8 (100 << 2) | normal (11) */
#define BMP280_CTRL_MEAS_VALUE 0x33u
/* config = t_sb 0.5 ms (000 << 5) | filter 4 (010 << 2) | spi3w off */
#define BMP280_CONFIG_VALUE 0x08u

#define BMP280_RESET_POLLS 200u /* status reads while the NVM copies (2 ms start-up) */

/* The operating range (datasheet table 1): a t_fine outside it is refused
 * rather than fed to the pressure formula. t_fine = T * 5120. */
#define BMP280_T_FINE_MIN (-40 * 5120)
#define BMP280_T_FINE_MAX (85 * 5120)

typedef enum {
    BMP280_OK = 0,
    BMP280_ERR_NULL = 1,
    BMP280_ERR_ABSENT = 2,  /* the address was not acknowledged */
    BMP280_ERR_CHIP_ID = 3, /* something answered, but not a BMP280 */
    BMP280_ERR_BUS = 4,     /* any other bus failure */
    BMP280_ERR_TIMEOUT = 5, /* im_update never cleared after the reset */
    BMP280_ERR_CALIB = 6,   /* an implausible trimming block (dig_T1 or dig_P1 zero) */
    BMP280_ERR_CONFIG = 7,  /* ctrl_meas/config did not read back as written */
    BMP280_ERR_NOT_READY = 8,
    BMP280_ERR_RANGE = 9, /* raw values outside what the compensation accepts */
    BMP280_NO_DATA = 10   /* no new result since the previous read (or none yet) */
} bmp280_status_t;

typedef struct {
    uint16_t t1;
    int16_t t2, t3;
    uint16_t p1;
    int16_t p2, p3, p4, p5, p6, p7, p8, p9;
} bmp280_calib_t;

typedef struct {
    int32_t t_fine;       /* the datasheet's fine temperature, T * 5120 */
    int32_t temp_cdeg;    /* 0.01 degC */
    uint32_t press_q24_8; /* Pa * 256 */
} bmp280_reading_t;

/* Driver state, owned by the caller. Counters saturate at UINT16_MAX. */
typedef struct {
    i2c_bus_t bus;
    uint8_t addr7;
    uint8_t ready;
    bmp280_calib_t cal;
    uint32_t last_adc_p, last_adc_t; /* the previous raw pair: unchanged = no new result */
    bmp280_reading_t reading;        /* the latest good reading */
    int32_t alt_cm;                  /* its ISA pressure altitude (baro_altitude.h) */
    uint16_t bus_errors, stale, range_errors;
} bmp280_t;

/* dig_T1..dig_P9 from the 24 bytes at 0x88, little-endian. */
void bmp280_parse_calib(const uint8_t raw[BMP280_CALIB_LEN], bmp280_calib_t *cal);

/*
 * The datasheet's integer compensation (section 3.11.3): t_fine and the
 * temperature in 0.01 degC from adc_t; the pressure in Q24.8 Pa from adc_p
 * with 64-bit intermediates (the 64-bit variant, not the 32-bit one:
 * resolution 1/256 Pa, the datasheet's "accuracy 0.0001 Pa" variant).
 * Intermediates are formed so that no operation can overflow or shift a
 * negative value left for any 20-bit input and any calibration: BMP280_OK,
 * or BMP280_ERR_RANGE (a temperature outside -40..85 degC, or a pressure the
 * formula cannot represent), BMP280_ERR_NULL.
 */
bmp280_status_t bmp280_compensate(const bmp280_calib_t *cal, int32_t adc_t, int32_t adc_p,
                                  bmp280_reading_t *out);

/*
 * Probe (chip id), soft reset, wait for the NVM copy, read the trimming
 * block, write config then ctrl_meas (config first: the datasheet, section
 * 5.4.6, says writes to config in normal mode may be ignored) and read both
 * back. The bus struct is copied.
 */
bmp280_status_t bmp280_init(bmp280_t *b, const i2c_bus_t *bus, uint8_t addr7);

/*
 * One burst read of 0xF7..0xFC, compensated. BMP280_OK: a new result, in
 * b->reading and b->alt_cm. BMP280_NO_DATA: the raw values did not change
 * since the previous read, or say "no result" (0x80000); the previous
 * reading is kept. Bus and range failures are counted and returned.
 */
bmp280_status_t bmp280_read(bmp280_t *b);

#endif /* HT_BARO_BMP280_H */
