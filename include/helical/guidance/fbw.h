/*
 * fbw.h - fly-by-wire: the pilot's sticks to the inputs of the helical-turn
 * law.
 *
 *   aileron stick  -> turn rate  = stick * turn_rate_max  (+ = right turn)
 *   elevator stick -> pitch ratio = stick * pitch_max     (+ = climb)
 *   inverted switch (pulse >= inverted_threshold_us) -> inverted = 1
 *
 * A stick is read with the pass-through calibration of mixer.h (os_rc_cal_t:
 * input index, trimmed centre, travel to full stick, reversing) plus a
 * deadband about the centre:
 *   s = pulse - centre (negated when reversed)
 *   |s| <= deadband: 0, else sign(s) * (|s| - deadband) / (travel - deadband),
 *   rounded to Q14 (ties away from zero), clamped to [-1, 1]
 * so the command is continuous at the deadband edge and full at full travel.
 * A pulse outside [OS_RC_VALID_MIN_US, OS_RC_VALID_MAX_US] (no signal) reads
 * as centre (0), and the inverted switch as upright; an input index beyond
 * the pulses given likewise.
 *
 * Both outputs are earth-frame quantities, so the same stick means the same
 * turn and the same climb upright and inverted (the core keeps the sign of
 * its pitch target when inverted): the pilot does not have to reverse the
 * elevator when upside down.
 */
#ifndef HELICAL_FBW_H
#define HELICAL_FBW_H

#include <stdint.h>

#include "helical/output/mixer.h"
#include "helical/params.h"
#include "helical/guidance/mode_params.h"
#include "helical/math/q14.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The parameters (ht_fbw_params_t) and their ids: mode_params.h. */

typedef struct {
    uint16_t deadband_us;
    q16_t turn_rate_max_rad_s;
    q16_t pitch_max;
    uint8_t inverted_input;
    uint16_t inverted_threshold_us;
    uint8_t ready;
} ht_fbw_t;

/* 0 = OK, 1 = NULL, 2 = a parameter out of range (*bad_field). */
int ht_fbw_init(ht_fbw_t *f, const ht_fbw_params_t *p, ht_fbw_param_id_t *bad_field);

/*
 * One stick to [-1, 1] (Q14) as described above; any pulse, any calibration:
 * a travel <= deadband or a NULL cal gives 0.
 */
q14_t ht_fbw_stick_q14(const os_rc_cal_t *cal, uint16_t deadband_us, uint16_t pulse_us);

typedef struct {
    q16_t turn_rate_rad_s; /* + = right turn */
    q16_t pitch_ratio;     /* + = climb */
    uint8_t inverted;
    q14_t aileron_stick, elevator_stick; /* the sticks after the deadband */
} ht_fbw_output_t;

/* The sticks of map->aileron and map->elevator and the inverted switch from
 * rc_us[0 .. rc_count-1]. NULL or an uninitialised f: all zero. */
void ht_fbw_step(const ht_fbw_t *f, const os_rc_map_t *map, const uint16_t rc_us[],
                 uint8_t rc_count, ht_fbw_output_t *out);

#ifdef __cplusplus
}
#endif

#endif /* HELICAL_FBW_H */
