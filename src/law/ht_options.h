/*
 * ht_options.h - the law's options beyond the seed (internal to the library;
 * docs/control-law.md "Extensions beyond the seed"). Each is off when its
 * parameter is 0, and helical_turn.c then does not call it: the step is bit
 * for bit the seed's.
 */
#ifndef HELICAL_HT_OPTIONS_H
#define HELICAL_HT_OPTIONS_H

#include <stdint.h>

#include "helical/law/ht_controller.h"

/*
 * Roll-in: the target bank rate d/dt atan(r), r = omega * S / g, for a
 * constant S: ratio_dot / (1 + r^2) with ratio_dot = turn_accel * S / g, in
 * Q25 rad/s, clamped to +/-roll_in_max (HT_F_ROLL_IN_LIMITED). c1_q30 is
 * 1/sqrt(1 + r^2) of the tilt-limited r (Q30); s_cm_s the floored airspeed.
 * The caller passes 0 when the tilt limit acts (the target does not move).
 */
int32_t ht_opt_roll_in_q25(const ht_controller_t *ctl, q11_t turn_accel_q11, int32_t s_cm_s,
                           int32_t c1_q30, uint8_t *flags);

/*
 * Vertical fade: f = min(1, sqrt(X^2 + Z^2) / vertical_fade) in Q30 (0 for
 * X = Z = 0); Q30 one when it does not act. Sets HT_F_ROLL_FADED when f < 1.
 */
int32_t ht_opt_fade_q30(const ht_controller_t *ctl, q14_t x, q14_t z, uint8_t *flags);

/* Sideslip: kp_sideslip * accel_lat in Q20 commands (|.| <= 2^27). */
int32_t ht_opt_sideslip_q20(const ht_controller_t *ctl, q14_t accel_lat_g);

#endif /* HELICAL_HT_OPTIONS_H */
