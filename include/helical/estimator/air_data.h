/*
 * air_data.h - true airspeed from the pitot's indicated airspeed and the
 * baro: the density correction the law (tan(bank) = turn rate x V / g) and
 * the estimator's centripetal term need (src/estimator/air_data.c).
 *
 * A pitot measures the dynamic pressure q; its driver gives the indicated
 * airspeed IAS = sqrt(2 q / rho0) (sea-level density, boards/devices/
 * airspeed_ms4525.h). The true airspeed is TAS = IAS / sqrt(sigma), sigma =
 * rho / rho0 = (p / p0) (T0 / T). The static pressure p is the baro's, given
 * on the board seam as its ISA pressure altitude (a one-to-one function of
 * p); the temperature T is the baro's own when the board has one, else the
 * ISA temperature at that pressure altitude. At 1 500 m TAS is 7.6 % above
 * IAS, at 3 000 m 16.1 %.
 *
 * The firmware step (firmware/fw_step.c) makes the pitot's reading true
 * here, once per reading; every consumer then sees the true airspeed.
 * Integer only, no state.
 */
#ifndef HELICAL_AIR_DATA_H
#define HELICAL_AIR_DATA_H

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* The lookup's range: pressure altitudes outside it are clamped to it. */
#define HT_AIR_ALT_MIN_CM ((int32_t)-100000) /* -1 000 m */
#define HT_AIR_ALT_MAX_CM ((int32_t)2000000) /* 20 000 m */
/* A temperature outside this range is not believed: the ISA's is used. */
#define HT_AIR_TEMP_MIN_CDEG (-8000) /* -80 degC */
#define HT_AIR_TEMP_MAX_CDEG 8500    /* +85 degC, the baro's rated top */

/* TAS / IAS in Q14 (16384 = 1) at the pressure altitude, with the static
 * temperature temp_cdeg when temp_valid != 0 (and within the range above),
 * else the ISA's: 1 / sqrt(sigma), piecewise linear over 250 m nodes of the
 * ICAO standard atmosphere (scripts/gen_tas_table.py), within 1e-4 of the
 * formula. */
uint32_t ht_tas_per_ias_q14(int32_t pressure_alt_cm, int16_t temp_cdeg, uint8_t temp_valid);

/* The true airspeed of an indicated airspeed (cm/s; negative reads as 0),
 * rounded, saturated at INT16_MAX. */
int16_t ht_true_airspeed_cm_s(int16_t ias_cm_s, int32_t pressure_alt_cm, int16_t temp_cdeg,
                              uint8_t temp_valid);

#ifdef __cplusplus
}
#endif

#endif /* HELICAL_AIR_DATA_H */
