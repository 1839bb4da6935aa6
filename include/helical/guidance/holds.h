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

#include "helical/guidance/hold_params.h"
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
 * The parameters (ht_alt_hold_params_t) and their ids: hold_params.h.
 */
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
 * The parameters (ht_speed_hold_params_t) and their ids: hold_params.h.
 */
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
