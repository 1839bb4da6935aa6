/*
 * imu_decimate.h - from the IMU's 1 kHz samples to the estimator's rate
 * (200 Hz by default): the samples that arrive within one estimator period
 * are averaged (a boxcar of N = 1000 / rate samples, nominally 5).
 *
 * Why an average: it is the FIR with N equal taps, whose response has its
 * first zero at 1000 / N Hz = the output rate, so vibration near the output
 * rate and its multiples (which would alias to DC) is removed, and it keeps
 * the rate integral exact (the mean rate times the period equals the sum of
 * the 1 ms rate samples times 1 ms), which is what the estimator integrates.
 * The chips' own low-pass filters (imu_spi.h, 98/94 Hz or 100 Hz) come first.
 *
 * Integer only: each axis sums in int32. A Q16 gyro sample is at most
 * 2285406 (2^21.2), so up to IMU_DECIMATE_MAX = 64 samples (2^27.2) never
 * overflow; samples beyond it are counted and dropped. The state is the
 * caller's.
 */
#ifndef HT_IMU_DECIMATE_H
#define HT_IMU_DECIMATE_H

#include <stdint.h>

#include "helical/estimator/dcm.h"

#define IMU_DECIMATE_MAX 64u

typedef struct {
    int32_t gyro_sum[3];
    int32_t accel_sum[3];
    uint16_t n;
    uint16_t dropped; /* samples over IMU_DECIMATE_MAX in one window (saturating) */
} imu_decimate_t;

void imu_decimate_reset(imu_decimate_t *d);

/* Add one sample to the window. */
void imu_decimate_add(imu_decimate_t *d, const ht_imu_sample_t *s);

/* The window's mean (each axis rounded to nearest, halves away from zero)
 * into out, and a new window. Returns the number of samples averaged; 0
 * (out untouched) when the window was empty. */
uint16_t imu_decimate_take(imu_decimate_t *d, ht_imu_sample_t *out);

#endif /* HT_IMU_DECIMATE_H */
