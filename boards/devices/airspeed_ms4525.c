/*
 * airspeed_ms4525.c - the MS4525DO driver (see airspeed_ms4525.h).
 */
#include "airspeed_ms4525.h"

#include <stddef.h>

#include "helical/math/q14.h"

static void count(uint16_t *c)
{
    if (*c != UINT16_MAX) {
        (*c)++;
    }
}

int32_t ms4525_counts_to_mpa(uint16_t counts)
{
    const int64_t full = (int64_t)MS4525_COUNTS_FULL;
    const int64_t bridge = (int64_t)counts & full; /* the status bits are not pressure */
    const int64_t half_counts = 2 * bridge - full;
    const int64_t scaled = half_counts * MS4525_MPA_PER_HALF_COUNT_Q16 + 32768;
    // cppcheck-suppress misra-c2012-10.1 ; ASR: rounded floor of a signed pressure
    const int64_t mpa = scaled >> 16;
    return (int32_t)mpa; /* |mpa| <= 16383 * 526.1 */
}

int16_t ms4525_airspeed_cm_s(int32_t dp_mpa)
{
    if (dp_mpa <= 0) {
        return 0; /* no negative airspeed: ports swapped, noise at rest */
    }
    const uint64_t q = (uint64_t)dp_mpa;
    const uint64_t v2 = (q * MS4525_V2_CM2_S2_PER_MPA_Q16 + 32768u) >> 16;
    if (v2 > UINT32_MAX) {
        return INT16_MAX;
    }
    const uint32_t v = q_isqrt32_round((uint32_t)v2);
    if (v > (uint32_t)INT16_MAX) {
        return INT16_MAX;
    }
    return (int16_t)v;
}

ms4525_status_t ms4525_init(ms4525_t *m, const i2c_bus_t *bus, uint8_t addr7)
{
    if (m == NULL || bus == NULL || bus->write_read == NULL) {
        return MS4525_ERR_NULL;
    }
    m->bus = *bus;
    m->addr7 = addr7;
    m->present = 0u;
    m->backoff_len = 0u;
    m->backoff_left = 0u;
    m->dp_mpa = 0;
    m->airspeed_cm_s = 0;
    m->temp_cdeg = 0;
    m->absent = 0u;
    m->stale = 0u;
    m->faults = 0u;
    m->bus_errors = 0u;
    m->zero_errors = 0u;
    ms4525_rezero(m);
    return MS4525_OK;
}

void ms4525_rezero(ms4525_t *m)
{
    if (m == NULL) {
        return;
    }
    m->zeroed = 0u;
    m->zero_n = 0u;
    m->zero_sum = 0u;
}

/* After a NACK: skip 1, 2, 4 .. MS4525_BACKOFF_MAX calls. */
static void back_off(ms4525_t *m)
{
    if (m->backoff_len == 0u) {
        m->backoff_len = 1u;
    } else if (m->backoff_len < MS4525_BACKOFF_MAX) {
        m->backoff_len = (uint8_t)(m->backoff_len * 2u);
    } else {
        /* at the cap */
    }
    m->backoff_left = m->backoff_len;
}

/* One more at-rest sample into the zero average. */
static ms4525_status_t add_zero_sample(ms4525_t *m, uint16_t counts)
{
    m->zero_sum += counts;
    m->zero_n++;
    if (m->zero_n < MS4525_ZERO_SAMPLES) {
        return MS4525_NO_DATA;
    }
    /* the mean against 8191.5, both in Q5 */
    const int32_t mid_q5 = (int32_t)MS4525_COUNTS_FULL * (int32_t)MS4525_ZERO_SAMPLES / 2;
    const int32_t dev_q5 = (int32_t)m->zero_sum - mid_q5;
    const int32_t lim_q5 = MS4525_ZERO_MAX_COUNTS * (int32_t)MS4525_ZERO_SAMPLES;
    if (dev_q5 > lim_q5 || dev_q5 < -lim_q5) {
        count(&m->zero_errors);
        ms4525_rezero(m);
        return MS4525_ERR_ZERO;
    }
    m->zeroed = 1u;
    return MS4525_NO_DATA; /* the next sample is the first airspeed */
}

ms4525_status_t ms4525_update(ms4525_t *m)
{
    if (m == NULL) {
        return MS4525_ERR_NULL;
    }
    if (m->backoff_left > 0u) {
        m->backoff_left--;
        return MS4525_ABSENT;
    }
    uint8_t raw[MS4525_READ_LEN] = {0u, 0u, 0u, 0u};
    const i2c_bus_status_t st =
        i2c_bus_write_read(&m->bus, m->addr7, NULL, 0u, raw, (uint16_t)MS4525_READ_LEN);
    if (st == I2C_BUS_ERR_NACK) {
        m->present = 0u;
        count(&m->absent);
        back_off(m);
        return MS4525_ABSENT;
    }
    if (st != I2C_BUS_OK) {
        count(&m->bus_errors);
        return MS4525_ERR_BUS;
    }
    m->present = 1u;
    m->backoff_len = 0u;
    const uint8_t status = (uint8_t)(raw[0] >> 6);
    if (status == 2u) {
        count(&m->stale);
        return MS4525_NO_DATA;
    }
    if (status != 0u) {
        count(&m->faults);
        return MS4525_ERR_FAULT;
    }
    const uint16_t hi = (uint16_t)(raw[0] & 0x3Fu);
    const uint16_t counts = (uint16_t)((uint16_t)(hi << 8) | raw[1]);
    const uint16_t t_hi = raw[2];
    const uint16_t t_counts = (uint16_t)((uint16_t)(t_hi << 3) | (uint16_t)(raw[3] >> 5));
    /* T = counts * 200 / 2047 - 50 degC, in 0.01 degC, rounded */
    const int32_t t_cdeg = ((int32_t)t_counts * 20000 + 1023) / 2047 - 5000;
    m->temp_cdeg = (int16_t)t_cdeg; /* -5000 .. 15000 */
    if (!m->zeroed) {
        return add_zero_sample(m, counts);
    }
    /* (counts - zero) in Q5, scaled by the half-count factor: 2 / 32 = >> 4 */
    const int64_t diff_q5 = (int64_t)counts * (int64_t)MS4525_ZERO_SAMPLES - (int64_t)m->zero_sum;
    const int64_t dp_scaled = diff_q5 * MS4525_MPA_PER_HALF_COUNT_Q16 + INT64_C(524288);
    // cppcheck-suppress misra-c2012-10.1 ; ASR: rounded floor of a signed pressure
    const int64_t dp = dp_scaled >> 20;
    m->dp_mpa = (int32_t)dp; /* |dp| < 2^14 counts * 1053 mPa */
    m->airspeed_cm_s = ms4525_airspeed_cm_s(m->dp_mpa);
    return MS4525_OK;
}
