/*
 * airspeed_ms4525.h - the TE (Measurement Specialties) MS4525DO differential
 * pressure sensor over I2C (bus seam i2c_bus.h), as a pitot airspeed.
 *
 * Facts from the MS4525DO datasheet (MEAS, rev. January 2011 and later):
 *   I2C address by interface code: 0x28 ("I"), 0x36 ("J"), 0x46 ("K")
 *   section 1.6.1 (Read_DF4): a plain 4-byte read returns
 *     byte 0: status[7:6], bridge[13:8]; byte 1: bridge[7:0]
 *     byte 2: temperature[10:3];         byte 3: temperature[2:0] in bits 7:5,
 *     bits 4:0 undetermined ("should be masked off")
 *   status: 00 normal, 01 reserved (command mode), 10 stale (already
 *     fetched), 11 fault (diagnostic)
 *   output type A: 10 % .. 90 % of 2^14 - 1 = 16383 counts over Pmin .. Pmax:
 *     P = (counts - 0.1 * 16383) * (Pmax - Pmin) / (0.8 * 16383) + Pmin
 *   temperature: T = counts * 200 / 2047 - 50 degC
 * For the 001PD (differential, +/-1 psi; 1 psi = 6894.757 Pa) the pressure
 * reduces to P = (2 counts - 16383) * 6894.757 Pa / 13106.4, zero at 8191.5.
 *
 * Airspeed: the indicated airspeed of the incompressible Bernoulli relation,
 * v = sqrt(2 q / rho0), rho0 = 1.225 kg/m^3 (ISA sea level), from the
 * offset-corrected differential pressure q. Below 0.3 Mach the
 * compressibility error is under 2 %. No density correction (that would be
 * true airspeed): the firmware's seam takes the pitot's indicated speed.
 *
 * Start-up: the first MS4525_ZERO_SAMPLES good readings (the pitot at rest)
 * are averaged as the zero offset; until then nothing is fresh. A zero more
 * than MS4525_ZERO_MAX_COUNTS from the transfer function's 8191.5 is refused
 * and the averaging starts again (wind over the pitot, a wrong part).
 *
 * An absent sensor (address NACK) is a normal, optional state: the driver
 * then skips the bus for a doubling number of calls (1, 2, 4 .. 64) before
 * probing again, so a missing pitot costs one transaction per 64 ticks.
 */
#ifndef HT_AIRSPEED_MS4525_H
#define HT_AIRSPEED_MS4525_H

#include <stdint.h>

#include "i2c_bus.h"

#define MS4525_ADDR_I 0x28u
#define MS4525_ADDR_J 0x36u
#define MS4525_ADDR_K 0x46u

#define MS4525_READ_LEN        4u
#define MS4525_COUNTS_FULL     16383u /* 2^14 - 1 */
#define MS4525_ZERO_SAMPLES    32u    /* a power of two: the mean is a shift */
#define MS4525_ZERO_SHIFT      5u
#define MS4525_ZERO_MAX_COUNTS 655 /* 5 % of the 13106-count span: 690 Pa */
#define MS4525_BACKOFF_MAX     64u

/* 6894.757293 Pa / 13106.4 per half count, in mPa, Q16: 526.06034 * 65536 */
#define MS4525_MPA_PER_HALF_COUNT_Q16 34475891
/* 2 / rho0 in (cm/s)^2 per mPa: 2 / 1.225 * 10 = 16.3265306, Q16 */
#define MS4525_V2_CM2_S2_PER_MPA_Q16 1069976u

typedef enum {
    MS4525_OK = 0, /* a fresh airspeed */
    MS4525_ERR_NULL = 1,
    MS4525_ABSENT = 2,    /* no sensor answered (now or backing off): not an error */
    MS4525_NO_DATA = 3,   /* stale data, or still averaging the zero */
    MS4525_ERR_FAULT = 4, /* status 11 (fault) or 01 (command mode) */
    MS4525_ERR_BUS = 5,   /* any bus failure other than an absent sensor */
    MS4525_ERR_ZERO = 6   /* the zero average was implausible: averaging restarted */
} ms4525_status_t;

/* Driver state, owned by the caller. Counters saturate at UINT16_MAX. */
typedef struct {
    i2c_bus_t bus;
    uint8_t addr7;
    uint8_t present;     /* the last transaction was acknowledged */
    uint8_t zeroed;      /* zero_sum holds a full, accepted average */
    uint8_t zero_n;      /* samples in zero_sum while averaging */
    uint32_t zero_sum;   /* sum of MS4525_ZERO_SAMPLES raw counts (the zero in Q5) */
    uint8_t backoff_len; /* calls skipped after the latest NACK */
    uint8_t backoff_left;
    int32_t dp_mpa;        /* offset-corrected differential pressure */
    int16_t airspeed_cm_s; /* indicated airspeed, 0 when dp <= 0 */
    int16_t temp_cdeg;
    uint16_t absent, stale, faults, bus_errors, zero_errors;
} ms4525_t;

/* The datasheet's transfer function, without the zero offset: mPa from the
 * 14-bit bridge counts of a 001PD, rounded. */
int32_t ms4525_counts_to_mpa(uint16_t counts);

/* Indicated airspeed in cm/s from a differential pressure in mPa (<= 0 gives
 * 0; saturates at INT16_MAX). */
int16_t ms4525_airspeed_cm_s(int32_t dp_mpa);

/* Set up the state; no bus traffic (the first update probes). */
ms4525_status_t ms4525_init(ms4525_t *m, const i2c_bus_t *bus, uint8_t addr7);

/* Start averaging the zero again (the pitot must be at rest). */
void ms4525_rezero(ms4525_t *m);

/* One 4-byte read (or one skipped call while backing off). MS4525_OK: a
 * fresh airspeed in m->airspeed_cm_s (and m->dp_mpa, m->temp_cdeg). */
ms4525_status_t ms4525_update(ms4525_t *m);

#endif /* HT_AIRSPEED_MS4525_H */
