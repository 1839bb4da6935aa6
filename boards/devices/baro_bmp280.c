/*
 * baro_bmp280.c - the BMP280 driver (see baro_bmp280.h).
 */
#include "baro_bmp280.h"

#include <stddef.h>

#include "baro_altitude.h"

static void count(uint16_t *c)
{
    if (*c != UINT16_MAX) {
        (*c)++;
    }
}

static uint16_t le_u16(const uint8_t *p)
{
    const uint16_t lo = p[0];
    const uint16_t hi = p[1];
    return (uint16_t)(lo | (uint16_t)(hi << 8));
}

static int16_t le_s16(const uint8_t *p)
{
    const uint16_t u = le_u16(p);
    /* two's complement without an implementation-defined conversion */
    const int32_t s = (u >= 0x8000u) ? ((int32_t)u - 65536) : (int32_t)u;
    return (int16_t)s;
}

void bmp280_parse_calib(const uint8_t raw[BMP280_CALIB_LEN], bmp280_calib_t *cal)
{
    if (raw == NULL || cal == NULL) {
        return;
    }
    cal->t1 = le_u16(&raw[0]);
    cal->t2 = le_s16(&raw[2]);
    cal->t3 = le_s16(&raw[4]);
    cal->p1 = le_u16(&raw[6]);
    cal->p2 = le_s16(&raw[8]);
    cal->p3 = le_s16(&raw[10]);
    cal->p4 = le_s16(&raw[12]);
    cal->p5 = le_s16(&raw[14]);
    cal->p6 = le_s16(&raw[16]);
    cal->p7 = le_s16(&raw[18]);
    cal->p8 = le_s16(&raw[20]);
    cal->p9 = le_s16(&raw[22]);
}

/*
 * Temperature (datasheet 3.11.3): a linear term in adc_t / 8 - 2 dig_T1 and
 * a quadratic term in adc_t / 16 - dig_T1, summed as t_fine. The products
 * are formed in 64 bits so that no calibration can overflow them; where the
 * datasheet's 32-bit products do not overflow the bits are the same.
 */
static int32_t t_fine_of(const bmp280_calib_t *c, int32_t adc_t)
{
    const int64_t t1 = (int64_t)c->t1;
    const int64_t adc = (int64_t)adc_t;
    // cppcheck-suppress misra-c2012-10.1 ; ASR+: adc_t >= 0 (checked by the caller)
    const int64_t lin_arg = (adc >> 3) - 2 * t1;
    // cppcheck-suppress misra-c2012-10.1 ; ASR: floor of a signed value (datasheet)
    const int64_t lin = (lin_arg * (int64_t)c->t2) >> 11;
    // cppcheck-suppress misra-c2012-10.1 ; ASR+: adc_t >= 0 (checked by the caller)
    const int64_t quad_arg = (adc >> 4) - t1;
    // cppcheck-suppress misra-c2012-10.1 ; ASR: floor of a signed value (datasheet)
    const int64_t quad = (((quad_arg * quad_arg) >> 12) * (int64_t)c->t3) >> 14;
    const int64_t sum = lin + quad;
    if (sum > INT32_MAX || sum < INT32_MIN) {
        return INT32_MIN; /* refused by the range check below */
    }
    return (int32_t)sum;
}

#define P_SCALE_2_12 INT64_C(4096)            /* the datasheet's << 12 */
#define P_SCALE_2_17 INT64_C(131072)          /* << 17 */
#define P_SCALE_2_31 INT64_C(2147483648)      /* << 31 */
#define P_SCALE_2_35 INT64_C(34359738368)     /* << 35 */
#define P_ONE_2_47   INT64_C(140737488355328) /* 1 << 47 */
/* 2^36 = 1 MPa in the formula's Pa * 2^16: below it the dig_P9 term
 * (2^23)^2 * 2^15 and the dig_P8 term 2^15 * 2^36 stay inside 64 bits. */
#define P_LIMIT_2_36 INT64_C(68719476736)
/* floor(INT64_MAX / 3125): the largest magnitude that may be scaled by 3125 */
#define P_NUM_LIMIT INT64_C(2951479051793528)

/*
 * Pressure (datasheet 3.11.3, the 64-bit formula): offset and sensitivity as
 * polynomials in dt = t_fine - 128000, the pressure as (2^20 - adc_p)
 * scaled by 3125 / sensitivity, then a quadratic correction (dig_P7..P9).
 * Left shifts of possibly negative values are written as multiplications
 * (a left shift of a negative value is undefined in C); the two products
 * that could leave 64 bits with a hostile calibration are checked first.
 */
static bmp280_status_t press_q24_8_of(const bmp280_calib_t *c, int32_t t_fine, int32_t adc_p,
                                      uint32_t *out)
{
    const int64_t dt = (int64_t)t_fine - 128000;
    int64_t off = dt * dt * (int64_t)c->p6;
    off += dt * (int64_t)c->p5 * P_SCALE_2_17;
    off += (int64_t)c->p4 * P_SCALE_2_35;
    // cppcheck-suppress misra-c2012-10.1 ; ASR: floor of a signed value (datasheet)
    const int64_t sens_sq = (dt * dt * (int64_t)c->p3) >> 8;
    const int64_t sens_poly = sens_sq + dt * (int64_t)c->p2 * P_SCALE_2_12;
    const int64_t sens_base = P_ONE_2_47 + sens_poly;
    if (sens_base <= 0 || c->p1 == 0u) {
        return BMP280_ERR_RANGE;
    }
    /* For a t_fine within -40..85 degC |poly| < 2^46, so the product is
     * below 2^48 * 2^16 and fits in uint64. */
    const uint64_t sens_prod = (uint64_t)sens_base * (uint64_t)c->p1;
    const int64_t sens = (int64_t)(sens_prod >> 33);
    if (sens == 0) {
        return BMP280_ERR_RANGE; /* the datasheet's division-by-zero guard */
    }
    const int64_t inv = 1048576 - (int64_t)adc_p;
    const int64_t num = inv * P_SCALE_2_31 - off;
    if (num > P_NUM_LIMIT || num < -P_NUM_LIMIT) {
        return BMP280_ERR_RANGE;
    }
    int64_t p = (num * 3125) / sens; /* Pa * 2^16 here */
    if (p < 0 || p > P_LIMIT_2_36) {
        return BMP280_ERR_RANGE; /* negative or above 1 MPa: not air */
    }
    // cppcheck-suppress misra-c2012-10.1 ; ASR+: p >= 0 here (checked above)
    const int64_t p_hi = p >> 13;
    // cppcheck-suppress misra-c2012-10.1 ; ASR: floor of a signed value (datasheet)
    const int64_t corr9 = ((int64_t)c->p9 * p_hi * p_hi) >> 25;
    // cppcheck-suppress misra-c2012-10.1 ; ASR: floor of a signed value (datasheet)
    const int64_t corr8 = ((int64_t)c->p8 * p) >> 19;
    const int64_t p_sum = p + corr9 + corr8;
    // cppcheck-suppress misra-c2012-10.1 ; ASR: floor of a signed value (datasheet)
    p = (p_sum >> 8) + (int64_t)c->p7 * 16;
    if (p <= 0 || p > (int64_t)UINT32_MAX) {
        return BMP280_ERR_RANGE;
    }
    *out = (uint32_t)p;
    return BMP280_OK;
}

bmp280_status_t bmp280_compensate(const bmp280_calib_t *cal, int32_t adc_t, int32_t adc_p,
                                  bmp280_reading_t *out)
{
    if (cal == NULL || out == NULL) {
        return BMP280_ERR_NULL;
    }
    if (adc_t < 0 || adc_t > 0xFFFFF || adc_p < 0 || adc_p > 0xFFFFF) {
        return BMP280_ERR_RANGE; /* 20-bit values only */
    }
    const int32_t t_fine = t_fine_of(cal, adc_t);
    if (t_fine < BMP280_T_FINE_MIN || t_fine > BMP280_T_FINE_MAX) {
        return BMP280_ERR_RANGE;
    }
    uint32_t p = 0u;
    const bmp280_status_t st = press_q24_8_of(cal, t_fine, adc_p, &p);
    if (st != BMP280_OK) {
        return st;
    }
    out->t_fine = t_fine;
    // cppcheck-suppress misra-c2012-10.1 ; ASR: t_fine < 0 below 0 degC (datasheet)
    out->temp_cdeg = (t_fine * 5 + 128) >> 8; /* T = t_fine / 5120 in 0.01 degC */
    out->press_q24_8 = p;
    return BMP280_OK;
}

static bmp280_status_t from_bus(i2c_bus_status_t st)
{
    if (st == I2C_BUS_OK) {
        return BMP280_OK;
    }
    return (st == I2C_BUS_ERR_NACK) ? BMP280_ERR_ABSENT : BMP280_ERR_BUS;
}

static bmp280_status_t read_regs(const bmp280_t *b, uint8_t reg, uint8_t *rx, uint16_t n)
{
    return from_bus(i2c_bus_write_read(&b->bus, b->addr7, &reg, 1u, rx, n));
}

static bmp280_status_t write_reg(const bmp280_t *b, uint8_t reg, uint8_t value)
{
    const uint8_t tx[2] = {reg, value};
    return from_bus(i2c_bus_write_read(&b->bus, b->addr7, tx, 2u, NULL, 0u));
}

/* After the soft reset the chip copies its NVM (im_update = 1) and may not
 * answer at all for the 2 ms start-up: a NACK here is "not yet". */
static bmp280_status_t wait_nvm_copied(const bmp280_t *b)
{
    for (uint32_t i = 0u; i < BMP280_RESET_POLLS; ++i) {
        uint8_t status = 0xFFu;
        const bmp280_status_t st = read_regs(b, BMP280_REG_STATUS, &status, 1u);
        if (st == BMP280_OK && (status & BMP280_STATUS_IM_UPD) == 0u) {
            return BMP280_OK;
        }
        if (st == BMP280_ERR_BUS) {
            return st;
        }
    }
    return BMP280_ERR_TIMEOUT;
}

bmp280_status_t bmp280_init(bmp280_t *b, const i2c_bus_t *bus, uint8_t addr7)
{
    if (b == NULL || bus == NULL || bus->write_read == NULL) {
        return BMP280_ERR_NULL;
    }
    b->ready = 0u;
    b->bus = *bus;
    b->addr7 = addr7;
    b->last_adc_p = (uint32_t)BMP280_ADC_SKIPPED;
    b->last_adc_t = (uint32_t)BMP280_ADC_SKIPPED;
    b->alt_cm = 0;
    b->reading.t_fine = 0;
    b->reading.temp_cdeg = 0;
    b->reading.press_q24_8 = 0u;
    b->bus_errors = 0u;
    b->stale = 0u;
    b->range_errors = 0u;

    uint8_t id = 0u;
    bmp280_status_t st = read_regs(b, BMP280_REG_ID, &id, 1u);
    if (st != BMP280_OK) {
        return st;
    }
    if (id != BMP280_CHIP_ID) {
        return BMP280_ERR_CHIP_ID;
    }
    st = write_reg(b, BMP280_REG_RESET, BMP280_RESET_WORD);
    if (st != BMP280_OK) {
        return st;
    }
    st = wait_nvm_copied(b);
    if (st != BMP280_OK) {
        return st;
    }
    uint8_t raw[BMP280_CALIB_LEN];
    st = read_regs(b, BMP280_REG_CALIB, raw, (uint16_t)BMP280_CALIB_LEN);
    if (st != BMP280_OK) {
        return st;
    }
    bmp280_parse_calib(raw, &b->cal);
    if (b->cal.t1 == 0u || b->cal.p1 == 0u) {
        return BMP280_ERR_CALIB;
    }
    st = write_reg(b, BMP280_REG_CONFIG, BMP280_CONFIG_VALUE);
    if (st == BMP280_OK) {
        st = write_reg(b, BMP280_REG_CTRL_MEAS, BMP280_CTRL_MEAS_VALUE);
    }
    if (st != BMP280_OK) {
        return st;
    }
    uint8_t back[2] = {0u, 0u};
    st = read_regs(b, BMP280_REG_CTRL_MEAS, back, 2u);
    if (st != BMP280_OK) {
        return st;
    }
    if (back[0] != BMP280_CTRL_MEAS_VALUE || back[1] != BMP280_CONFIG_VALUE) {
        return BMP280_ERR_CONFIG;
    }
    b->ready = 1u;
    return BMP280_OK;
}

/* 20-bit value from msb, lsb and xlsb[7:4] (datasheet 4.3.6, 4.3.7). */
static uint32_t adc20(const uint8_t *p)
{
    const uint32_t msb = p[0];
    const uint32_t lsb = p[1];
    const uint32_t xlsb = p[2];
    return (msb << 12) | (lsb << 4) | (xlsb >> 4);
}

bmp280_status_t bmp280_read(bmp280_t *b)
{
    if (b == NULL) {
        return BMP280_ERR_NULL;
    }
    if (!b->ready) {
        return BMP280_ERR_NOT_READY;
    }
    uint8_t raw[BMP280_DATA_LEN];
    const bmp280_status_t st = read_regs(b, BMP280_REG_DATA, raw, (uint16_t)BMP280_DATA_LEN);
    if (st != BMP280_OK) {
        count(&b->bus_errors);
        return st;
    }
    const uint32_t adc_p = adc20(&raw[0]);
    const uint32_t adc_t = adc20(&raw[3]);
    if (adc_p == (uint32_t)BMP280_ADC_SKIPPED || adc_t == (uint32_t)BMP280_ADC_SKIPPED ||
        (adc_p == b->last_adc_p && adc_t == b->last_adc_t)) {
        count(&b->stale);
        return BMP280_NO_DATA;
    }
    b->last_adc_p = adc_p;
    b->last_adc_t = adc_t;
    bmp280_reading_t r;
    const bmp280_status_t cst = bmp280_compensate(&b->cal, (int32_t)adc_t, (int32_t)adc_p, &r);
    if (cst != BMP280_OK) {
        count(&b->range_errors);
        return cst;
    }
    b->reading = r;
    b->alt_cm = baro_altitude_cm(r.press_q24_8, NULL);
    return BMP280_OK;
}
