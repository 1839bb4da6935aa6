/*
 * dcm_gps_accel.h - the estimator's GPS acceleration reference (internal to
 * the library; src/estimator/dcm.c calls it once per sample).
 *
 * Why: the accelerometer's gravity reference needs the aircraft's own
 * acceleration removed, and the w x v model of it goes through the gyro
 * (a bias error b tilts it by b V / g: 5 degrees per deg/s at 50 m/s), the
 * airspeed and a modelled angle of attack and sideslip. The GPS measures the
 * acceleration in earth axes directly: over an interval, the velocity change
 * minus gravity times the interval is the integral of the specific force in
 * earth axes, which is what R f summed over the same interval should be. The
 * two vectors agree in direction when R is right; their cross product is the
 * tilt error. Nothing in it depends on the gyro bias, the airspeed, the wind
 * or the angle of attack.
 *
 * Timing: a solution with epoch t arrives latency L later (gps_fresh). The
 * IMU sum of an interval is closed at a boundary L before the next solution
 * is due (the last measured period between solutions minus L), so that the
 * interval covers the same time as the two velocities. The window is
 * HT_DCM_GA_WINDOW consecutive intervals (1 s at 5 Hz: the velocity noise of
 * one difference, 0.1 m/s over 0.2 s, would be 3 degrees).
 */
#ifndef HELICAL_DCM_GPS_ACCEL_H
#define HELICAL_DCM_GPS_ACCEL_H

#include <stdint.h>

#include "helical/estimator/dcm_types.h"

/* Restart: no window, no error (an outage, a re-alignment). */
void dcm_ga_reset(ht_dcm_ga_t *g);

/*
 * One IMU sample: adds R f to the open interval, closes it at its boundary,
 * and on a new GPS solution (gps_fix and gps_fresh) extends the window and,
 * when it is full, computes the tilt error. acc_saturated: this sample's
 * accelerometer was clamped (the interval is not used). Only with
 * HT_DCM_CF_AUTO; otherwise the state is reset.
 */
void dcm_ga_sample(const ht_dcm_t *d, ht_dcm_ga_t *g, const int32_t r[3][3], const int32_t acc[3],
                   uint8_t acc_saturated, const ht_dcm_aiding_t *a);

/*
 * The roll/pitch error (Q30, body axes, as rollpitch_error in dcm.c) from the
 * last window: 1 when there is one, 0 (e zeroed) when not. heading_trusted
 * 0: the part a heading error would make in a turn is dropped (see
 * drop_heading_term in dcm_gps_accel.c).
 */
int dcm_ga_error(const ht_dcm_ga_t *g, const int32_t r[3][3], uint8_t heading_trusted,
                 int32_t e[3]);

#endif /* HELICAL_DCM_GPS_ACCEL_H */
