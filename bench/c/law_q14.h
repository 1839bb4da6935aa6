/*
 * law_q14.h - the helical-turn law of docs/control-law.md written the cheap
 * embedded way (the MatrixPilot style): int16 values in Q14 (tilt, errors,
 * surfaces), Q11 rates, Q12 gains, int32 intermediates only, no 64-bit
 * product, no float. For the benchmark's "where is the floor" comparison
 * only (bench/README.md); never part of the library.
 *
 * It takes the library's own structs (ht_params_t at init, ht_input_t per
 * step) so the bench feeds it exactly what it feeds ht_step.
 */
#ifndef BENCH_LAW_Q14_H
#define BENCH_LAW_Q14_H

#include <stdint.h>

#include "helical/law/helical_turn.h"

/* The parameters in the 16-bit law's formats, converted once (law_q14_init),
 * the way ht_init converts them for the library. Axis order as the library:
 * 0 = body X (elevator gains), 1 = body Y (aileron), 2 = body Z (rudder). */
typedef struct {
    int16_t kp[3], kff[3], kd[3]; /* Q12: gains in [0, 8) (saturated there) */
    int16_t kffd[3];              /* kff + kd, Q12 (the scheduled form's rate gain) */
    int16_t v_ref_cm_s, v_min_cm_s;
    int16_t max_tilt_q12; /* Q12, (0, 8) */
    uint8_t schedule;
    /* max_tilt * g in the units of turn_rate (Q11) * airspeed (cm/s): the
     * tilt limit is |omega * S| > tilt_lim, no ratio needed to test it. */
    int32_t tilt_lim;
} law_q14_ctl_t;

typedef struct {
    int16_t aileron, elevator, rudder; /* Q14, [-1, 1] */
    int16_t tilt_x, tilt_y, tilt_z;    /* Q14 target tilt (Eq. 5, 6, inverted) */
} law_q14_output_t;

/* Convert the library's parameters (already range-checked by ht_init).
 * Returns 0, or 1 on a NULL argument. */
int32_t law_q14_init(law_q14_ctl_t *ctl, const ht_params_t *p);

/* One control step: integer only, int32 intermediates, one division
 * (v_ref / S); a second one only on the tilt-limit and |pitch| > 8 branches. */
void law_step_q14(const law_q14_ctl_t *ctl, const ht_input_t *in, law_q14_output_t *out);

#endif /* BENCH_LAW_Q14_H */
