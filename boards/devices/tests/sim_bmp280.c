/*
 * sim_bmp280.c - the simulated BMP280 (see sim_bmp280.h). Host test code:
 * floating point is fine here.
 */
#include "sim_bmp280.h"

#include <math.h>
#include <stddef.h>
#include <string.h>

const bmp280_calib_t sim_bmp280_example_cal = {27504u, 26435, -1000, 36477u, -10685, 3024,
                                               2855,   140,   -7,    15500,  -14600, 6000};

#define ADC_NONE 0x80000

double sim_bmp280_ref_temp_c(const bmp280_calib_t *c, int32_t adc_t, double *t_fine)
{
    const double a = (double)adc_t / 16384.0 - (double)c->t1 / 1024.0;
    const double b = (double)adc_t / 131072.0 - (double)c->t1 / 8192.0;
    const double tf = a * (double)c->t2 + b * b * (double)c->t3;
    if (t_fine != NULL) {
        *t_fine = tf;
    }
    return tf / 5120.0;
}

double sim_bmp280_ref_press_pa(const bmp280_calib_t *c, int32_t adc_p, double t_fine)
{
    const double dt = t_fine / 2.0 - 64000.0;
    double off = dt * dt * (double)c->p6 / 32768.0 + dt * (double)c->p5 * 2.0;
    off = off / 4.0 + (double)c->p4 * 65536.0;
    const double s = ((double)c->p3 * dt * dt / 524288.0 + (double)c->p2 * dt) / 524288.0;
    const double sens = (1.0 + s / 32768.0) * (double)c->p1;
    if (sens == 0.0) {
        return 0.0;
    }
    double p = 1048576.0 - (double)adc_p;
    p = (p - off / 4096.0) * 6250.0 / sens;
    const double c9 = (double)c->p9 * p * p / 2147483648.0;
    const double c8 = p * (double)c->p8 / 32768.0;
    return p + (c9 + c8 + (double)c->p7) / 16.0;
}

/* The 20-bit code whose reference value is nearest to target; f is
 * monotonic in the code (rising when rising != 0). */
static int32_t invert(double (*f)(const sim_bmp280_t *, int32_t), const sim_bmp280_t *s,
                      double target, int rising)
{
    int32_t lo = 0;
    int32_t hi = 0xFFFFF;
    while (hi - lo > 1) {
        const int32_t mid = lo + (hi - lo) / 2;
        const double v = f(s, mid);
        if ((v < target) == (rising != 0)) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    return (fabs(f(s, lo) - target) <= fabs(f(s, hi) - target)) ? lo : hi;
}

static double temp_of(const sim_bmp280_t *s, int32_t adc_t)
{
    return sim_bmp280_ref_temp_c(&s->cal, adc_t, NULL);
}

static double press_of(const sim_bmp280_t *s, int32_t adc_p)
{
    double tf = 0.0;
    (void)sim_bmp280_ref_temp_c(&s->cal, s->adc_t, &tf);
    return sim_bmp280_ref_press_pa(&s->cal, adc_p, tf);
}

static void put20(uint8_t *r, int32_t v)
{
    const uint32_t u = (uint32_t)v;
    r[0] = (uint8_t)((u >> 12) & 0xFFu);
    r[1] = (uint8_t)((u >> 4) & 0xFFu);
    r[2] = (uint8_t)((u & 0xFu) << 4);
}

/* The data registers as the chip shows them for its current mode. */
static void refresh_data(sim_bmp280_t *s)
{
    const uint8_t ctrl = s->reg[0xF4];
    const int measuring = (ctrl & 0x03u) != 0u;
    const int osrs_p = (ctrl >> 2) & 0x07u;
    const int osrs_t = (ctrl >> 5) & 0x07u;
    put20(&s->reg[0xF7], (measuring && osrs_p != 0) ? s->adc_p : ADC_NONE);
    put20(&s->reg[0xFA], (measuring && osrs_t != 0) ? s->adc_t : ADC_NONE);
}

static void power_on_reset(sim_bmp280_t *s)
{
    s->reg[0xF3] = 0u;
    s->reg[0xF4] = 0u;
    s->reg[0xF5] = 0u;
    s->nvm_left = s->nvm_busy;
    refresh_data(s);
}

static void put16(uint8_t *r, uint16_t v)
{
    r[0] = (uint8_t)(v & 0xFFu); /* LSB first (datasheet table 17) */
    r[1] = (uint8_t)(v >> 8);
}

void sim_bmp280_init(sim_bmp280_t *s, uint8_t addr7, const bmp280_calib_t *cal)
{
    memset(s, 0, sizeof *s);
    s->addr7 = addr7;
    s->chip_id = 0x58u;
    s->fail_next = I2C_BUS_OK;
    s->cal = *cal;
    uint8_t *r = &s->reg[0x88];
    put16(&r[0], cal->t1);
    put16(&r[2], (uint16_t)cal->t2);
    put16(&r[4], (uint16_t)cal->t3);
    put16(&r[6], cal->p1);
    put16(&r[8], (uint16_t)cal->p2);
    put16(&r[10], (uint16_t)cal->p3);
    put16(&r[12], (uint16_t)cal->p4);
    put16(&r[14], (uint16_t)cal->p5);
    put16(&r[16], (uint16_t)cal->p6);
    put16(&r[18], (uint16_t)cal->p7);
    put16(&r[20], (uint16_t)cal->p8);
    put16(&r[22], (uint16_t)cal->p9);
    sim_bmp280_set(s, 101325.0, 25.0);
    power_on_reset(s);
}

void sim_bmp280_set(sim_bmp280_t *s, double pressure_pa, double temp_c)
{
    s->pressure_pa = pressure_pa;
    s->temp_c = temp_c;
    s->adc_t = invert(temp_of, s, temp_c, 1);
    s->adc_p = invert(press_of, s, pressure_pa, 0);
    refresh_data(s);
}

static void write_reg(sim_bmp280_t *s, uint8_t reg, uint8_t value)
{
    if (reg == 0xE0u) {
        if (value == 0xB6u && !s->ignore_reset) {
            s->resets++;
            power_on_reset(s);
        }
    } else if (reg == 0xF4u) {
        s->reg[0xF4] = value;
        refresh_data(s);
    } else if (reg == 0xF5u) {
        if ((s->reg[0xF4] & 0x03u) != 0x03u) { /* ignored in normal mode */
            s->reg[0xF5] = value;
        }
    } else {
        /* read-only or reserved: no effect */
    }
}

static uint8_t read_reg(sim_bmp280_t *s, uint8_t reg)
{
    if (reg == 0xD0u) {
        return s->chip_id;
    }
    if (reg == 0xF3u) {
        if (s->nvm_left > 0u) {
            s->nvm_left--;
            return 0x01u; /* im_update */
        }
        return 0x00u;
    }
    return s->reg[reg];
}

i2c_bus_status_t sim_bmp280_write_read(void *ctx, uint8_t addr7, const uint8_t *tx, uint16_t ntx,
                                       uint8_t *rx, uint16_t nrx)
{
    sim_bmp280_t *s = (sim_bmp280_t *)ctx;
    s->transactions++;
    if (s->fail_next != I2C_BUS_OK) {
        const i2c_bus_status_t st = s->fail_next;
        s->fail_next = I2C_BUS_OK;
        return st;
    }
    if (s->absent || addr7 != s->addr7) {
        return I2C_BUS_ERR_NACK;
    }
    if (ntx == 1u) {
        s->ptr = tx[0]; /* the register pointer for the read that follows */
    } else {
        /* (register, value) pairs; an odd last byte is dropped */
        for (uint16_t i = 0u; (uint16_t)(i + 1u) < ntx; i = (uint16_t)(i + 2u)) {
            write_reg(s, tx[i], tx[i + 1u]);
        }
    }
    for (uint16_t i = 0u; i < nrx; ++i) {
        rx[i] = read_reg(s, s->ptr);
        s->ptr = (uint8_t)(s->ptr + 1u);
    }
    return I2C_BUS_OK;
}

i2c_bus_t sim_bmp280_bus(sim_bmp280_t *s)
{
    i2c_bus_t b;
    b.ctx = s;
    b.write_read = sim_bmp280_write_read;
    return b;
}
