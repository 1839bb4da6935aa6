/*
 * holds.h - the outer loops around the helical-turn law: altitude hold
 * (altitude error -> desired pitch ratio) and airspeed hold (airspeed error ->
 * throttle). Integer only, like the core; the caller owns all state.
 *
 * Where they sit:
 *
 *   altitude target --[ht_alt_hold_step]--> pitch ratio --+
 *   turn rate, inverted ---------------------------------+--> ht_step --> surfaces
 *   airspeed target --[ht_speed_hold_step]--> throttle
 *
 * The helical-turn law has no integral term, so a steady surface offset (a
 * T-37 flying inverted needs about -0.25 elevator) can only come from a
 * standing error of its input. The altitude hold absorbs it: its integral
 * moves the commanded pitch ratio until the altitude error is zero.
 *
 * Inverted flight: the pitch ratio is an earth-frame quantity (vertical over
 * horizontal airspeed, + = climb) and the core keeps the sign of its target
 * pitch when inverted (control-law.md, Eq. 6), so the same altitude error asks
 * for the same pitch ratio upright and inverted. What differs between the two
 * is the standing offset the integral has to supply, so the hold keeps one
 * integrator per orientation and uses the one selected by `inverted`: a roll
 * to inverted and back does not have to unwind and rebuild the integral.
 * Pass the MEASURED orientation (DCM bottom row Z < 0), not the command: the
 * offset belongs to the attitude the aircraft is in, so during a 180 degree
 * roll the integrator changes when the aircraft passes knife edge. (In the
 * SIL this lost 8 m instead of 13 m rolling a T-37 back upright.)
 *
 * Formats: altitudes in cm (int32), vertical speed in cm/s (int32), airspeed
 * in cm/s (int16, as in ht_input_t), gains in Q16 (65536 = 1.0) per the unit
 * in their name, pitch ratio in Q16, throttle in Q14 [0, 1].
 */
#ifndef HELICAL_HOLDS_H
#define HELICAL_HOLDS_H

#include <stdint.h>

#include "helical/params.h"
#include "helical/math/q14.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Status of the parameter checks. */
typedef enum {
    HT_HOLD_OK = 0,
    HT_HOLD_ERR_NULL = 1, /* a NULL pointer */
    HT_HOLD_ERR_PARAM = 2 /* a parameter out of range */
} ht_hold_status_t;

/* --- altitude hold ------------------------------------------------------- */

/*
 * pitch = clamp(kp * e + I[inv] - kd * climb, +-max_pitch)
 *   e      = target - altitude (m), clamped to +-e_max_m (keeps I and P sane
 *            far from the target; the output saturates long before)
 *   I[inv] += ki * e / rate_hz, clamped to +-max_integral; only while
 *            |e| <= integral_band (far from the target P does the work and
 *            the integral would only wind up), and not further in the
 *            direction in which the output is saturated
 *   climb  = measured vertical speed (m/s, + = up)
 */
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

/* The caller's state: one integrator per orientation, Q20 pitch ratio. */
typedef struct {
    int32_t integral_q20[2]; /* [0] upright, [1] inverted */
    int32_t airspeed_q8;     /* the protection's filtered airspeed, cm/s in Q8 */
    uint8_t airspeed_valid;  /* airspeed_q8 holds a reading (0 after reset) */
} ht_alt_hold_state_t;

/* Check the parameters; HT_HOLD_OK when every field is in range
 * (ht_alt_hold_first_bad names the first that is not). */
ht_hold_status_t ht_alt_hold_check(const ht_alt_hold_params_t *p);

/* Zero both integrators and forget the filtered airspeed. */
void ht_alt_hold_reset(ht_alt_hold_state_t *s);

/*
 * One step: the desired pitch ratio (Q16, + = climb) for the core. Updates the
 * integrator of the orientation selected by `inverted` (nonzero = the aircraft
 * is inverted: measured, Z < 0; see above).
 * NULL pointers or unchecked out-of-range parameters give 0 and change nothing
 * (call ht_alt_hold_check once at start-up).
 */
q16_t ht_alt_hold_step(const ht_alt_hold_params_t *p, ht_alt_hold_state_t *s, int32_t target_cm,
                       int32_t altitude_cm, int32_t climb_cm_s, uint8_t inverted);

/*
 * The same step with the airspeed protection (params above): airspeed_cm_s is
 * the measured airspeed. While the ceiling limits the output the integrator
 * does not integrate upward (no wind-up against the protection). With
 * protect_cm_s = 0 it gives exactly ht_alt_hold_step's output.
 */
q16_t ht_alt_hold_step_v(const ht_alt_hold_params_t *p, ht_alt_hold_state_t *s, int32_t target_cm,
                         int32_t altitude_cm, int32_t climb_cm_s, uint8_t inverted,
                         int16_t airspeed_cm_s);

/* --- airspeed hold ------------------------------------------------------- */

/*
 * throttle = clamp(trim + kff * pitch_cmd + kp * e + I, [min, max])
 *   e  = target - airspeed (m/s)
 *   I += ki * e / rate_hz, clamped to +-max_integral and not integrated
 *        further in the direction in which the throttle is saturated
 *   pitch_cmd = the pitch ratio commanded this step (climbing needs power)
 */
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

/* The caller's state: Q20 throttle. */
typedef struct {
    int32_t integral_q20;
} ht_speed_hold_state_t;

ht_hold_status_t ht_speed_hold_check(const ht_speed_hold_params_t *p);

void ht_speed_hold_reset(ht_speed_hold_state_t *s);

/*
 * One step: the throttle in Q14, within [throttle_min, throttle_max].
 * pitch_q16 is the pitch ratio commanded to the core this step.
 * NULL pointers or out-of-range parameters give 0 and change nothing.
 */
q14_t ht_speed_hold_step(const ht_speed_hold_params_t *p, ht_speed_hold_state_t *s,
                         int16_t target_cm_s, int16_t airspeed_cm_s, q16_t pitch_q16);

#ifdef __cplusplus
}
#endif

#endif /* HELICAL_HOLDS_H */
