/*
 * sim_ms4525.c - the simulated MS4525DO (see sim_ms4525.h). Host test code.
 */
#include "sim_ms4525.h"

#include <math.h>
#include <string.h>

void sim_ms4525_init(sim_ms4525_t *s, uint8_t addr7)
{
    memset(s, 0, sizeof *s);
    s->addr7 = addr7;
    s->auto_update = 1u;
    s->fail_next = I2C_BUS_OK;
    sim_ms4525_set(s, 0.0, 20.0);
}

static uint16_t clamp_counts(double c, double full)
{
    const double r = floor(c + 0.5);
    if (r < 0.0) {
        return 0u;
    }
    return (uint16_t)((r > full) ? full : r);
}

void sim_ms4525_set(sim_ms4525_t *s, double dp_pa, double temp_c)
{
    s->dp_pa = dp_pa;
    s->temp_c = temp_c;
    const double p_psi = (dp_pa + s->zero_error_pa) / SIM_MS4525_PA_PER_PSI;
    /* type A, Pmin = -1 psi, Pmax = +1 psi */
    const double counts = 0.8 * 16383.0 * (p_psi + 1.0) / 2.0 + 0.1 * 16383.0;
    s->counts_p = clamp_counts(counts, 16383.0);
    s->counts_t = clamp_counts((temp_c + 50.0) * 2047.0 / 200.0, 2047.0);
    s->fresh = 1u;
}

i2c_bus_status_t sim_ms4525_write_read(void *ctx, uint8_t addr7, const uint8_t *tx, uint16_t ntx,
                                       uint8_t *rx, uint16_t nrx)
{
    sim_ms4525_t *s = (sim_ms4525_t *)ctx;
    (void)tx;
    s->transactions++;
    if (s->fail_next != I2C_BUS_OK) {
        const i2c_bus_status_t st = s->fail_next;
        s->fail_next = I2C_BUS_OK;
        return st;
    }
    if (s->absent || addr7 != s->addr7) {
        return I2C_BUS_ERR_NACK;
    }
    if (ntx > 0u) {
        return I2C_BUS_ERR_DATA_NACK; /* the part has no writable registers */
    }
    if (s->auto_update) {
        s->fresh = 1u;
    }
    unsigned status = s->fresh ? 0u : 2u;
    if (s->fault) {
        status = 3u;
    }
    uint8_t pkt[4];
    pkt[0] = (uint8_t)((status << 6) | ((s->counts_p >> 8) & 0x3Fu));
    pkt[1] = (uint8_t)(s->counts_p & 0xFFu);
    pkt[2] = (uint8_t)((s->counts_t >> 3) & 0xFFu);
    pkt[3] = (uint8_t)(((s->counts_t & 0x7u) << 5) | 0x1Fu);
    for (uint16_t i = 0u; i < nrx; ++i) {
        rx[i] = (i < 4u) ? pkt[i] : 0xFFu;
    }
    if (nrx >= 2u) {
        s->fresh = 0u; /* the bridge data has been fetched */
        s->reads++;
    }
    return I2C_BUS_OK;
}

i2c_bus_t sim_ms4525_bus(sim_ms4525_t *s)
{
    i2c_bus_t b;
    b.ctx = s;
    b.write_read = sim_ms4525_write_read;
    return b;
}
