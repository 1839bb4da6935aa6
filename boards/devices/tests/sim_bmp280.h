/*
 * sim_bmp280.h - a simulated BMP280 on the I2C bus seam, for host tests.
 *
 * It answers as the datasheet (BST-BMP280-DS001) describes: a write sets
 * the register pointer and then writes (register, value) pairs (section
 * 5.2.1); a read returns registers from the pointer on, auto-incrementing
 * (5.2.2). Registers: the 24-byte trimming block at 0x88 (little-endian),
 * id 0xD0, reset 0xE0, status 0xF3, ctrl_meas 0xF4, config 0xF5 (ignored
 * while in normal mode, 5.4.6), data 0xF7..0xFC (0x80000 until a mode
 * with measurements is set or when a measurement is skipped).
 *
 * The physical state (pressure in Pa, temperature in degC) is turned into
 * raw ADC values by inverting the datasheet's double-precision compensation
 * (section 8.1) numerically, so the driver's integer code is checked
 * against an independent floating-point reference.
 */
#ifndef HT_SIM_BMP280_H
#define HT_SIM_BMP280_H

#include <stdint.h>

#include "baro_bmp280.h"
#include "i2c_bus.h"

typedef struct {
    uint8_t addr7;
    uint8_t chip_id;      /* 0x58; a test may make it another chip */
    uint8_t absent;       /* NACK every transaction */
    uint8_t ignore_reset; /* the reset command has no effect */
    uint16_t nvm_busy;    /* status reads showing im_update after a reset */
    uint16_t nvm_left;
    i2c_bus_status_t fail_next; /* returned once by the next transaction */
    bmp280_calib_t cal;
    uint8_t reg[256];
    uint8_t ptr;
    double pressure_pa, temp_c;
    int32_t adc_p, adc_t;
    unsigned transactions, resets;
} sim_bmp280_t;

void sim_bmp280_init(sim_bmp280_t *s, uint8_t addr7, const bmp280_calib_t *cal);

/* Set the air the chip sits in; computes adc_p/adc_t. */
void sim_bmp280_set(sim_bmp280_t *s, double pressure_pa, double temp_c);

i2c_bus_status_t sim_bmp280_write_read(void *ctx, uint8_t addr7, const uint8_t *tx, uint16_t ntx,
                                       uint8_t *rx, uint16_t nrx);
i2c_bus_t sim_bmp280_bus(sim_bmp280_t *s);

/* The double-precision reference (datasheet section 8.1): the temperature
 * in degC and t_fine from adc_t; the pressure in Pa from adc_p and t_fine. */
double sim_bmp280_ref_temp_c(const bmp280_calib_t *c, int32_t adc_t, double *t_fine);
double sim_bmp280_ref_press_pa(const bmp280_calib_t *c, int32_t adc_p, double t_fine);

/* The datasheet's worked example's trimming values (section 3.12). */
extern const bmp280_calib_t sim_bmp280_example_cal;

#endif /* HT_SIM_BMP280_H */
