/*
 * sil_imu_model.h - the SIL's IMU error model in C: the per-sample part of
 * sil/helical_sil/sensors/models.py (ImuModel.sample, _TriadErrors.apply),
 * moved next to the board because it ran once per sim frame in Python and
 * was the harness's largest cost.
 *
 * A faithful port, operation for operation (the same sums in the same order,
 * libm's sin and sqrt, no FMA: C11 without extensions), so its samples equal
 * the Python model's bit for bit (sil/tests/test_imu_model_c.py checks it on
 * seeded random states). The Python side keeps everything drawn once (the
 * error matrix, bias, phases: models.ImuModel's own constructor) and the
 * random numbers (each triad's numpy stream, handed over a block at a time),
 * so the streams and their order are the Python model's.
 *
 * Host only (float, libm): it is the simulated sensor, not the firmware's
 * per-step path, which stays integer (firmware/fw_step.c).
 */
#ifndef HELICAL_SIL_IMU_MODEL_H
#define HELICAL_SIL_IMU_MODEL_H

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* The errors of one 3-axis sensor (models._TriadErrors). */
typedef struct {
    double matrix[3][3];  /* the sensor reads matrix @ true value */
    double bias[3];       /* constant bias */
    double walk_state[3]; /* the bias random walk now */
    double sigma;         /* white noise per sample */
    double walk;          /* random-walk density, per sqrt(s) */
    double full_scale;    /* clip at +- this */
} sil_imu_triad_t;

/* One IMU (models.ImuModel): gyro rad/s, accelerometer g, library axes. */
typedef struct {
    sil_imu_triad_t gyro, accel;
    double phase_gyro[3], phase_accel[3]; /* vibration phases, rad */
    double rate_hz;                       /* sample rate */
    double vibration_hz;                  /* vibration frequency */
    double vibration_gyro;                /* amplitude, rad/s */
    double vibration_accel;               /* amplitude, g */
    double t_last_s;                      /* time of the previous sample */
    int32_t have_last;                    /* 0 before the first sample */
} sil_imu_model_t;

/* Per sim frame the caller gives these JSBSim values, in this order. */
// cppcheck-suppress misra-c2012-5.7 ; D-ANON-ENUM: an anonymous enum has no tag to repeat
enum {
    SIL_IMU_IN_P, /* velocities/p-rad_sec (FRD) */
    SIL_IMU_IN_Q,
    SIL_IMU_IN_R,
    SIL_IMU_IN_FBX, /* forces/fbx-total-lbs */
    SIL_IMU_IN_FBY,
    SIL_IMU_IN_FBZ,
    SIL_IMU_IN_MASS, /* inertia/mass-slugs */
    SIL_IMU_IN_COUNT
};

/* sil_imu_model_run's answers: 0, or why sample `*at` was refused (the
 * model's state is then that of the samples before it). */
// cppcheck-suppress misra-c2012-5.7 ; D-ANON-ENUM: an anonymous enum has no tag to repeat
enum {
    SIL_IMU_OK = 0,
    SIL_IMU_BAD_TIME = 1,   /* t not finite, or not one period after the last */
    SIL_IMU_NOT_FINITE = 2, /* a rate or force is NaN or infinite */
    SIL_IMU_FEW_NORMALS = 3 /* fewer than 6 normals per sample were given */
};

/* Samples n frames taken at t_base_s + (j + 1) * dt_s, j = 0 .. n - 1 (the
 * harness's own sum: the frames after a control step at t_base_s). in: n rows of SIL_IMU_IN_COUNT
 * values. normals_gyro, normals_accel: 6 standard normals per sample each (3 walk, 3 noise), in
 * stream order; n_normals: how many each holds. Out: gyro_rad_s, accel_g
 * (n rows of 3), saturated (n rows: bit 0 gyro, bit 1 accel; may be NULL).
 * Returns SIL_IMU_OK or an error above, *at the sample it concerns. */
int sil_imu_model_run(sil_imu_model_t *m, const double *in, int32_t n, double t_base_s, double dt_s,
                      const double *normals_gyro, const double *normals_accel, int32_t n_normals,
                      double *gyro_rad_s, double *accel_g, int32_t *saturated, int32_t *at);

/* sizeof(sil_imu_model_t): the binding checks its mirror against it. */
uint32_t sil_imu_model_size(void);

#ifdef __cplusplus
}
#endif

#endif
