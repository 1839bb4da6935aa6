/*
 * dcm_wind.h - the estimator's wind estimate (internal to the library;
 * src/estimator/dcm.c calls it at each new GPS solution).
 *
 * Why: the GPS course is the direction of the ground velocity, the heading
 * the estimator wants is the direction of the air velocity. In a wind W they
 * differ by the crab angle (asin(W / V) across the wind: 21 degrees at
 * 10 m/s and 28 m/s), which the yaw loop would chase around every turn; the
 * bias it learns from that is a false one, and the GPS acceleration's tilt
 * reference reads a heading error in a turn partly as a tilt (5 degrees RMS
 * in the c172p's 10 m/s wind scenario without this). With an estimate of W,
 * the course is taken from v_gps - W, the air velocity's direction.
 *
 * How: a wind cannot be told from a heading error in straight flight (both
 * are a constant offset between the ground and the air velocity), nor from
 * an airspeed reading k times the truth. In a turn they differ: the heading
 * error and the airspeed's scale act on the air velocity x, which turns,
 * the wind does not. So the GPS velocity y is regressed on x,
 *
 *     y = W + A x          (complex numbers: north + i east)
 *
 * over the last HT_DCM_WIND_TAU_S (exponentially weighted means of x, y,
 * |x|^2 and y conj(x)): A = cov(y, x) / var(x), W = mean(y) - A mean(x).
 * A's angle is the heading error over that time and |A| the airspeed's
 * scale; W comes out the same whatever they are, and the course from
 * y - W = A x then shows the heading error of this sample. A and W are
 * updated only while var(x) is at least 1/8 of mean(|x|^2) (the air
 * velocity's direction spread over about 20 degrees RMS: a turn) and |A|
 * is within [0.5, 2] with its angle within 90 degrees. Otherwise W holds
 * what the last turn taught (0 before any turn: the course is then the
 * ground track), so that in straight flight the course still corrects the
 * heading, given that wind.
 *
 * x is the air velocity R v (the airspeed in the plane of symmetry) turned
 * back by the heading's turn over the GPS latency, so that x and y belong
 * to the same epoch. dcm.c learns only at a new solution that aided the
 * course, with a live pitot, the body rates within 20 deg/s and the nose
 * within 60 degrees of the horizon.
 */
#ifndef HELICAL_DCM_WIND_H
#define HELICAL_DCM_WIND_H

#include <stdint.h>

#include "helical/estimator/dcm_types.h"

/* A wind beyond 50 m/s per component is not taken (the fit is wrong). */
#define DCM_WIND_MAX_CM_S 5000

/*
 * One learning step at a new GPS solution. air_q8: the air velocity's
 * horizontal part in earth axes now (north, east; cm/s, Q8); gps_cm_s: the
 * GPS ground velocity's; turn_c, turn_s: cos and sin (Q30) of the heading's
 * turn since the GPS velocity's epoch; period: samples since the previous
 * solution (the weight of this one; at most one second counts).
 */
void dcm_wind_learn(const ht_dcm_t *d, ht_dcm_wind_t *w, const int32_t air_q8[2],
                    const int32_t gps_cm_s[2], int32_t turn_c, int32_t turn_s, uint32_t period);

/* The GPS velocity through the air, v_gps - W (north, east; cm/s, Q8). */
void dcm_wind_through_air(const ht_dcm_wind_t *w, const int32_t gps_cm_s[2], int32_t out_q8[2]);

#endif /* HELICAL_DCM_WIND_H */
