/*
 * sim_ms4525.h - a simulated MS4525DO-DS5AI001DP (I2C, 0x28, +/-1 psi,
 * output type A) on the I2C bus seam, for host tests.
 *
 * A plain read returns the datasheet's Read_DF packet (section 1.6.1):
 * status[7:6] and the 14-bit bridge counts, then the 11-bit temperature
 * with the undetermined low 5 bits of byte 3 set to ones (so a driver that
 * forgets the mask reads a wrong temperature). Status 00 for a measurement
 * not fetched before, 10 (stale) for one already fetched, 11 on a fault.
 * The counts come from the type A transfer function inverted in double
 * precision: counts = 0.8 * 16383 * (P + 1 psi) / (2 psi) + 0.1 * 16383.
 */
#ifndef HT_SIM_MS4525_H
#define HT_SIM_MS4525_H

#include <stdint.h>

#include "i2c_bus.h"

#define SIM_MS4525_PA_PER_PSI 6894.757293168

typedef struct {
    uint8_t addr7;
    uint8_t absent;      /* NACK every transaction */
    uint8_t fault;       /* status 11 */
    uint8_t auto_update; /* every read finds a new measurement (the default) */
    uint8_t fresh;       /* a measurement not yet fetched */
    i2c_bus_status_t fail_next;
    double dp_pa;         /* the true differential pressure */
    double zero_error_pa; /* the part's own offset, which the driver must remove */
    double temp_c;
    uint16_t counts_p, counts_t;
    unsigned reads, transactions;
} sim_ms4525_t;

void sim_ms4525_init(sim_ms4525_t *s, uint8_t addr7);

/* Set the air (differential pressure in Pa, temperature in degC); a new
 * measurement becomes available. */
void sim_ms4525_set(sim_ms4525_t *s, double dp_pa, double temp_c);

i2c_bus_status_t sim_ms4525_write_read(void *ctx, uint8_t addr7, const uint8_t *tx, uint16_t ntx,
                                       uint8_t *rx, uint16_t nrx);
i2c_bus_t sim_ms4525_bus(sim_ms4525_t *s);

#endif /* HT_SIM_MS4525_H */
