/*
 * hold_params.h - the holds' parameters (params.def HT_PARAMS_ALT,
 * HT_PARAMS_SPEED): the structs, their ids, defaults, names, rows and range
 * checks (src/guidance/hold_params.c). The holds themselves: holds.h.
 */
#ifndef HELICAL_HOLD_PARAMS_H
#define HELICAL_HOLD_PARAMS_H

#include <stdint.h>

#include "helical/params.h"
#include "helical/math/q14.h"

#ifdef __cplusplus
extern "C" {
#endif

/* --- altitude hold ------------------------------------------------------- */

/* The parameters: the rows of params.def HT_PARAMS_ALT (names, units,
 * ranges, defaults), then the step rate.
 *
 * Airspeed protection (ht_alt_hold_step_v; protect_cm_s = 0: off). Below
 * protect_cm_s the climb demand is cut: the pitch ratio is limited to
 *   ceiling = max_pitch - kv * (protect - airspeed), at least -max_pitch,
 * so when the aircraft cannot hold its altitude at the pitch asked for (a
 * downdraft beyond its climb, full throttle) it gives up altitude for
 * airspeed instead of slowing into the stall. An airspeed below
 * protect_valid_cm_s is taken as a failed sensor (a dead pitot reads 0), not
 * a stall: no protection then, and the reading is not filtered. The airspeed
 * the ceiling uses is low-pass filtered (first order, time constant
 * protect_tau_ms; 0 = none) so that the short airspeed dips of horizontal
 * gusts and one-sample spikes do not pitch the nose down. */
typedef struct {
    HT_PARAMS_ALT(HT_PARAM_X_FIELD)
    uint16_t rate_hz; /* step rate, [1, 1000]: the control rate */
} ht_alt_hold_params_t;

/* HT_ALT_P_<ID> of each row, in table order; HT_ALT_P_RATE_HZ is rate_hz,
 * which is not a row. */
#define HT_PARAM_X_ALT_ID(id, name, field, unit, fmt, lo, hi, def, desc) HT_ALT_P_##id,
typedef enum {
    HT_ALT_P_NONE = 0,
    HT_PARAMS_ALT(HT_PARAM_X_ALT_ID) HT_ALT_P_COUNT
} ht_alt_param_id_t;
#define HT_ALT_P_RATE_HZ HT_ALT_P_COUNT /* not a row: the step rate */

/* The table's defaults, at the step rate rate_hz. */
void ht_alt_hold_params_default(ht_alt_hold_params_t *p, uint16_t rate_hz);

/* "alt_kp", ..., "rate_hz" (HT_ALT_P_RATE_HZ), or "" for anything else. */
const char *ht_alt_hold_param_name(ht_alt_param_id_t id);

/* The table's row of a parameter, or NULL (also for HT_ALT_P_RATE_HZ). */
const ht_param_info_t *ht_alt_hold_param_info(ht_alt_param_id_t id);

/* The first parameter out of range: each row's own bounds in table order,
 * then the joint limits (integral_band <= max_error names
 * HT_ALT_P_INTEGRAL_BAND, protect_valid <= protect HT_ALT_P_PROTECT_VALID),
 * then rate_hz. HT_ALT_P_NONE when all are in range. p must not be NULL. */
ht_alt_param_id_t ht_alt_hold_first_bad(const ht_alt_hold_params_t *p);

/* --- airspeed hold ------------------------------------------------------- */

typedef struct {
    HT_PARAMS_SPEED(HT_PARAM_X_FIELD)
    uint16_t rate_hz; /* step rate, [1, 1000]: the control rate */
} ht_speed_hold_params_t;

/* HT_SPEED_P_<ID> of each row, in table order; HT_SPEED_P_RATE_HZ is
 * rate_hz, which is not a row. */
#define HT_PARAM_X_SPEED_ID(id, name, field, unit, fmt, lo, hi, def, desc) HT_SPEED_P_##id,
typedef enum {
    HT_SPEED_P_NONE = 0,
    HT_PARAMS_SPEED(HT_PARAM_X_SPEED_ID) HT_SPEED_P_COUNT
} ht_speed_param_id_t;
#define HT_SPEED_P_RATE_HZ HT_SPEED_P_COUNT /* not a row: the step rate */

void ht_speed_hold_params_default(ht_speed_hold_params_t *p, uint16_t rate_hz);
const char *ht_speed_hold_param_name(ht_speed_param_id_t id);
const ht_param_info_t *ht_speed_hold_param_info(ht_speed_param_id_t id);

/* As ht_alt_hold_first_bad; the joint limit throttle_min <= throttle_max
 * names HT_SPEED_P_THROTTLE_MAX. */
ht_speed_param_id_t ht_speed_hold_first_bad(const ht_speed_hold_params_t *p);

#ifdef __cplusplus
}
#endif

#endif /* HELICAL_HOLD_PARAMS_H */
