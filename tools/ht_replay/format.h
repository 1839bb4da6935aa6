/*
 * format.h - ht_replay's output: one CSV row per step, fixed point converted
 * back to the units of docs/control-law.md.
 *
 * Columns, in this order:
 *   turn_rate_used  rad/s (Q11)      rate_x, rate_y, rate_z  rad/s (Q11)
 *   tilt_x, tilt_y, tilt_z, roll_dot, roll_cross, roll_error, pitch_error,
 *   pitch_body_x, pitch_body_z, aileron, elevator, rudder   unitless (Q14)
 *   tilt_ratio      unitless (Q16)   flags   the HT_F_* bits as an integer
 *
 * Every value is printed with six decimals. That shows every LSB: the steps
 * (Q14 6.1e-5, Q11 4.9e-4, Q16 1.5e-5) are all above 1e-6, so the printed
 * number times the scale, rounded, gives back the exact integer.
 */
#ifndef HT_REPLAY_FORMAT_H
#define HT_REPLAY_FORMAT_H

#include <stdio.h>

#include "helical/law/helical_turn.h"

/* The header line, with its "\n". */
void ht_format_header(FILE *out);

/* One row, with its "\n". */
void ht_format_row(FILE *out, const ht_output_t *o);

/* Fixed point to real: exact in a double. */
double ht_q14_to_real(q14_t v);
double ht_q11_to_real(q11_t v);
double ht_q16_to_real(q16_t v);

#endif /* HT_REPLAY_FORMAT_H */
