/*
 * dcm_types.h - the attitude estimator's parameters, its converted
 * constants (ht_dcm_t), the aiding measurements and the states of its GPS
 * acceleration reference and wind estimate: what the estimator's step
 * (src/estimator/dcm.c) and its parts (src/estimator/dcm_gps_accel.c,
 * dcm_wind.c) share. The estimator's API is dcm.h (which includes this).
 */
#ifndef HELICAL_DCM_TYPES_H
#define HELICAL_DCM_TYPES_H

#include <stdint.h>

#include "helical/params.h"
#include "helical/math/q14.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Where the centripetal compensation takes the velocity from. */
typedef enum {
    HT_DCM_CF_OFF = 0,      /* no compensation (for comparison only) */
    HT_DCM_CF_AIRSPEED = 1, /* v = [0, airspeed, 0] in body axes */
    HT_DCM_CF_AUTO = 2      /* the GPS velocity when it has a fix, else the airspeed */
} ht_dcm_cf_t;

/* Parameters, physical units as integers (no float on the board). The
 * fields, their order, units, ranges and defaults are those of the parameter
 * table, include/helical/params.def:
 *   uint16_t imu_rate_hz;       one ht_dcm_update per sample, [50, 1000]; default 200
 *   q16_t kp_rollpitch;         1/s, [0, 16]; default 0.2 (MatrixPilot-like)
 *   q16_t ki_rollpitch;         1/s^2, [0, 4]; default 0.01
 *   q16_t kp_yaw;               1/s, [0, 16]; default 0.5
 *   q16_t ki_yaw;               1/s^2, [0, 4]; default 0.02
 *   q16_t gyro_bias_max_rad_s;  bound of each bias component, [0, 1]; default 0.1
 *   q16_t gyro_limit_rad_s;     the gyro's full scale: |w| >= this flags saturation,
 *                               [1, 64]; default 34.9 (2000 deg/s)
 *   q16_t accel_limit_g;        the accelerometer's full scale, [1, 32]; default 16
 *   q16_t accel_band_g;         the gravity reference's weight falls linearly from 1
 *                               at |f| = 1 g to 0 at |f| = 1 +/- band, (0, 4]; default 0.5
 *   int16_t gps_min_speed_cm_s; course used for yaw above this, [0, 10000]; default 300
 *   uint8_t centripetal;        ht_dcm_cf_t; default HT_DCM_CF_AUTO
 *   uint16_t gps_latency_ms;    a GPS velocity is delivered this long after its epoch
 *                               (gps_fresh), [0, 500]; default 100. It must be below the
 *                               GPS period for the GPS acceleration reference (see below)
 */
typedef struct {
    HT_PARAMS_DCM(HT_PARAM_X_FIELD)
} ht_dcm_params_t;

/* The parameters converted once; read-only after ht_dcm_init. Internal
 * formats are the implementation's (see dcm.c). */
typedef struct {
    ht_dcm_params_t p;
    int32_t dt_q30;               /* 1 / imu_rate_hz in s, Q30 */
    int32_t kp_rp_dt_q32;         /* kp_rollpitch * dt, Q32 */
    int32_t kp_yaw_dt_q32;        /* kp_yaw * dt, Q32 */
    int32_t ki_rp_dt_q34;         /* ki_rollpitch * dt, Q34 */
    int32_t ki_yaw_dt_q34;        /* ki_yaw * dt, Q34 */
    int32_t bias_max_q30;         /* gyro_bias_max in rad/s, Q30 */
    int32_t inv_band_q30;         /* 1 / accel_band: mantissa (q_recip_q30) ... */
    uint8_t inv_band_shift;       /* ... and the shift that gives the weight in Q16 */
    int32_t g_dt_q24;             /* 980.665 cm/s^2 * dt: cm/s of one sample at 1 g, Q24 */
    uint16_t gps_latency_samples; /* gps_latency_ms in IMU samples, rounded */
    int32_t wind_alpha_q30;       /* dt / HT_DCM_WIND_TAU_S: the wind's low pass per sample */
    uint8_t ready;
} ht_dcm_t;

/* The slower aiding measurements, given with every sample (flags say what
 * is new or valid). */
typedef struct {
    uint8_t gps_fix;              /* nonzero: the velocity below is a valid 3D fix (the last
                                     solution, held between GPS updates: used every sample) */
    uint8_t gps_fresh;            /* nonzero: a new GPS solution arrived with this sample
                                     (set on exactly one sample per solution: the GPS
                                     acceleration reference counts samples between them) */
    int32_t vel_ned_cm_s[3];      /* GPS ground velocity, north, east, down; clamped to
                                     +/-655.35 m/s for the centripetal term */
    uint8_t airspeed_valid;       /* nonzero: airspeed_cm_s is a live reading */
    int16_t airspeed_cm_s;        /* <= 0 is read as no airspeed */
    uint8_t mag_valid;            /* nonzero: mag is a fresh magnetometer reading */
    int16_t mag[3];               /* body axes, any scale (only the direction is used) */
    int16_t mag_declination_cdeg; /* east-positive, added to the magnetic heading
                                     (read modulo 360 degrees) */
} ht_dcm_aiding_t;

/* The wind estimate's time constant, s (src/estimator/dcm_wind.h): the regression's
 * memory, about half a turn at 10 deg/s. */
#define HT_DCM_WIND_TAU_S 20u

/* GPS intervals in the GPS acceleration reference's window (1 s at 5 Hz). */
#define HT_DCM_GA_WINDOW 5u

/*
 * The GPS acceleration reference (src/estimator/dcm_gps_accel.c): the accelerometer's
 * specific force rotated into earth axes and summed over the GPS intervals,
 * each interval shifted back by the GPS latency, against the GPS velocity
 * change over the same intervals minus gravity. Internal state.
 */
typedef struct {
    int32_t open_q16[3];                        /* sum of R f since the last boundary, g, Q16 */
    uint16_t open_n;                            /* its samples */
    uint8_t open_aligned;                       /* it began at a boundary aligned to an epoch */
    uint8_t boundary_done;                      /* a boundary since the last solution */
    int32_t closed_q12[3];                      /* the interval closed at the last boundary as a
                                                  velocity change, cm/s, Q12 */
    uint16_t closed_n;                          /* its samples */
    uint8_t closed_ok;                          /* aligned, no saturated sample */
    uint8_t count;                              /* consecutive intervals in the window, <= W */
    uint16_t since_fix;                         /* samples since the last GPS solution */
    uint16_t period;                            /* samples between the last two (0: unknown) */
    int32_t dv_q12[HT_DCM_GA_WINDOW][3];        /* the IMU's velocity change per interval,
                                                  oldest first, cm/s, Q12 */
    uint16_t n[HT_DCM_GA_WINDOW];               /* samples per interval */
    int32_t vel_cm_s[HT_DCM_GA_WINDOW + 1u][3]; /* GPS velocities at the interval ends */
    int32_t err_q30[2];                         /* the last window's tilt error, earth north and
                                                   east components (sines), Q30 */
    int32_t h_q28[2];                           /* the GPS specific force's direction, its
                                                   horizontal part (sin of its lean), Q28 */
    uint8_t err_valid;
} ht_dcm_ga_t;

/*
 * The wind estimate (src/estimator/dcm_wind.h): the GPS velocity y regressed on the
 * air velocity x over the last HT_DCM_WIND_TAU_S, y = W + A x, in complex
 * numbers (north + i east); A is a rotation (the heading error) times a
 * scale (the airspeed's error). Internal state.
 */
typedef struct {
    int32_t mx_q8[2]; /* low-passed x, cm/s, Q8 */
    int32_t my_q8[2]; /* low-passed y, cm/s, Q8 */
    int32_t sxx;      /* low-passed |x|^2, (cm/s)^2 */
    int32_t sxy[2];   /* low-passed y conj(x), real and imaginary, (cm/s)^2 */
    int32_t a_q28[2]; /* A, real and imaginary, Q28, from the last turn */
    int32_t w_q8[2];  /* W = my - A mx from the last turn, north and east, cm/s, Q8 */
    uint8_t primed;   /* the low passes hold a sample */
    uint8_t solved;   /* A and W came from a turn at least once since the reset */
} ht_dcm_wind_t;

#ifdef __cplusplus
}
#endif

#endif /* HELICAL_DCM_TYPES_H */
