/*
 * dcm.h - the attitude estimator: a fixed-point direction cosine matrix with
 * PI drift correction (W. Premerlani, P. Bizard, "Direction Cosine Matrix
 * IMU: Theory", 2009), the estimate the helical-turn law flies on.
 *
 * Frames (the library's, see docs/control-law.md):
 *   body  X out the left wing, Y forward, Z down (right-handed);
 *   earth north, east, down.
 *   R maps body coordinates to earth coordinates: row i of R is earth axis i
 *   seen in the body frame. R[2] (the bottom row) is earth-down in the body
 *   frame: level [0, 0, 1], right bank phi gives R[2][0] = -sin(phi), nose up
 *   theta gives R[2][1] = -sin(theta), inverted R[2][2] = -1. That row is the
 *   law's tilt input (ht_input_t x, y, z). Column 1 of R is the nose in earth
 *   axes: the heading is atan2(R[1][1], R[0][1]).
 *   Gyro rates: about +X = nose down, about +Y = roll right, about +Z = nose
 *   right (from FRD rates p, q, r: w_X = -q, w_Y = p, w_Z = r).
 *   Specific force (what an accelerometer reads): level, unaccelerated flight
 *   reads [0, 0, -1] g; a steady coordinated turn at bank phi reads
 *   [0, 0, -1/cos(phi)] g.
 *
 * Each IMU sample: R <- R (I + [w dt]x + [w dt]x^2 / 2) with w = gyro - bias
 * + correction (the second-order term keeps the step a rotation to O(dt^4):
 * without it the row-wise renormalization turns the step's stretch into a
 * rotation error of (w dt)^2 / 2 per sample, 1.5 degrees in one 5 rad/s
 * roll), w dt clamped to 0.5 rad per axis and sample; then renormalization
 * (the orthogonality error of rows 0 and 1 shared half and half, row 2 =
 * row 0 x row 1, each row scaled by (3 - |r|^2) / 2).
 * Drift correction: roll/pitch from the gravity reference g = w x v - f (the
 * specific force corrected by the centripetal acceleration, v along the
 * fuselage from the airspeed or, when the GPS has a fix and centripetal is
 * AUTO, R^T times its velocity), weighted down as |g| leaves 1 g (|g| = |f|
 * without compensation; with it a coordinated turn keeps its full weight);
 * yaw from the GPS course when the ground speed is above gps_min_speed,
 * scaled by the nose's horizontal length (cos pitch), else from a
 * magnetometer when given; beyond 90 degrees of yaw error the pull stays at
 * its maximum. The yaw error acts about the earth vertical. A PI loop turns
 * the error into a rate correction; its integral is the gyro-bias estimate,
 * bounded. docs/estimator.md has the formats, the precision and the figures.
 *
 * Integer only; no float, libm, malloc, recursion or global state: the
 * caller owns ht_dcm_t (read-only after init) and ht_dcm_state_t.
 */
#ifndef HELICAL_DCM_H
#define HELICAL_DCM_H

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

/* Fills p with the defaults above. */
void ht_dcm_params_default(ht_dcm_params_t *p);

/* HT_DCM_P_<ID> of each row of params.def, in its order. */
#define HT_PARAM_X_DCM_ID(id, name, field, unit, fmt, lo, hi, def, desc) HT_DCM_P_##id,
typedef enum {
    HT_DCM_P_NONE = 0,
    HT_PARAMS_DCM(HT_PARAM_X_DCM_ID) HT_DCM_P_COUNT
} ht_dcm_param_id_t;

/* "imu_rate_hz", "kp_rollpitch", ... or "". */
const char *ht_dcm_param_name(ht_dcm_param_id_t id);

/* The table's row of a parameter, or NULL (HT_DCM_P_NONE, HT_DCM_P_COUNT, ...). */
const ht_param_info_t *ht_dcm_param_info(ht_dcm_param_id_t id);

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

/* 0 = OK, 1 = NULL, 2 = a parameter out of range (*bad, may be NULL). */
int ht_dcm_init(ht_dcm_t *d, const ht_dcm_params_t *p, ht_dcm_param_id_t *bad);

/* One IMU sample, body axes, Q16. */
typedef struct {
    q16_t gyro_rad_s[3];
    q16_t accel_g[3]; /* specific force */
} ht_imu_sample_t;

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

/* Health flags (ht_dcm_state_t.flags, ht_dcm_output_t.flags). */
enum ht_dcm_flag {
    HT_DCM_F_ALIGNED = 1u << 0,         /* ht_dcm_align has run (or the first sample did) */
    HT_DCM_F_GYRO_SATURATED = 1u << 1,  /* this sample: a gyro axis at its full scale */
    HT_DCM_F_ACCEL_SATURATED = 1u << 2, /* this sample: an accelerometer axis at its full scale */
    HT_DCM_F_ACCEL_IGNORED = 1u << 3,   /* this sample: |g| outside the band (or an
                                           accelerometer axis saturated): no roll/pitch aid */
    HT_DCM_F_RENORM_FAILED = 1u << 4,   /* a row's norm left [0.5, 1.5]: R was reset from the
                                           accelerometer with the last heading (level when
                                           |f| < 0.5 g); latched until ht_dcm_reset */
    HT_DCM_F_YAW_AIDED = 1u << 5,       /* this sample: yaw corrected from GPS course / mag */
    HT_DCM_F_BIAS_LIMITED = 1u << 6,    /* a bias component sits on its bound */
    HT_DCM_F_CF_GPS = 1u << 7,          /* this sample's centripetal term used GPS velocity */
    HT_DCM_F_GPS_ACCEL = 0x100u,        /* this sample's roll/pitch reference was the GPS
                                            acceleration (not the accelerometer's w x v model) */
    HT_DCM_F_HEADING_KNOWN = 0x200u     /* the heading is the nose's: a turn has taught the
                                            wind (the course no longer carries the crab) or a
                                            magnetometer is valid */
};

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

typedef struct {
    int32_t r[3][3];          /* the matrix, Q30 (2^30 = 1.0) */
    int32_t bias[3];          /* integral of the PI loop = gyro-bias estimate, rad/s, Q30 */
    int32_t omega_corr[3];    /* last proportional correction, rad/s, Q16 */
    q16_t rate_rad_s[3];      /* last sample's gyro (clamped to its full scale) - bias, Q16 */
    q16_t accel_fwd_g;        /* filtered rate of change of the airspeed, g, Q16 */
    int16_t speed_prev_cm_s;  /* the airspeed of the previous sample ... */
    uint8_t speed_prev_valid; /* ... when it was valid */
    int32_t g_filt_q24[3];    /* the gravity reference, low-passed (vibration), g, Q24 */
    int32_t r2_filt_q30[3];   /* R[2] through the same low-pass, Q30 */
    uint8_t g_filt_valid;
    uint16_t recover_samples; /* samples left of the stronger correction after a gyro
                                 saturation (one second at the IMU rate) */
    ht_dcm_ga_t ga;           /* the GPS acceleration reference */
    uint16_t gps_age_samples; /* samples since the last gps_fresh (saturates) */
    ht_dcm_wind_t wind;       /* the wind estimate */
    uint16_t flags;
    uint32_t samples;
} ht_dcm_state_t;

/* R = identity (level, nose east), zero bias, no flags: the next sample with
 * |f| >= 0.5 g aligns roll and pitch from its accelerometer, heading north. */
void ht_dcm_reset(ht_dcm_state_t *s);

/*
 * Start-up alignment: roll and pitch from one (averaged) accelerometer
 * reading, any attitude (not level, inverted); yaw from heading_cdeg
 * (a GPS course or magnetometer heading in 0.01 deg, [0, 36000)), or 0 when
 * heading_valid is 0; heading_cdeg >= 36000 is read modulo 36000). The
 * heading is the nose's azimuth, or the right wing's minus 90 degrees when
 * the nose is within 7 degrees of vertical. Zero bias; sets ALIGNED, keeps a
 * latched RENORM_FAILED. Returns 0; 1 when |accel| is below 0.5 g (no
 * gravity reference: s is left as it was); 2 when d, s or accel_g is NULL
 * or d is not initialised (nothing changed).
 */
int ht_dcm_align(const ht_dcm_t *d, ht_dcm_state_t *s, const q16_t accel_g[3],
                 uint8_t heading_valid, uint16_t heading_cdeg);

/*
 * Alignment to a known attitude: earth-down in body axes (Q14, any length
 * above 0.5) and the nose's horizontal direction (north, east parts, Q14, any
 * length; both 0: heading north), e.g. from another attitude source when the
 * estimator starts in flight. As ht_dcm_align otherwise (zero bias). Returns
 * 0, 1 for a down vector too short, 2 for NULL or an uninitialised d.
 */
int ht_dcm_align_to(const ht_dcm_t *d, ht_dcm_state_t *s, const q14_t down_q14[3],
                    q14_t nose_north_q14, q14_t nose_east_q14);

/* One IMU sample. NULL d, s or imu, or an uninitialised d: nothing happens.
 * aid may be NULL (no aiding). Gyro and accelerometer axes are clamped to
 * their full scales (flagged). */
void ht_dcm_update(const ht_dcm_t *d, ht_dcm_state_t *s, const ht_imu_sample_t *imu,
                   const ht_dcm_aiding_t *aid);

typedef struct {
    q14_t r[3][3];            /* R rounded to Q14; r[2] is the law's tilt row */
    q16_t gyro_bias_rad_s[3]; /* bias estimate */
    int16_t roll_cdeg;        /* telemetry Euler angles: (-18000, 18000] */
    int16_t pitch_cdeg;       /* [-9000, 9000] */
    uint16_t yaw_cdeg;        /* [0, 36000) */
    q16_t gyro_rad_s[3];      /* the last sample's rates minus the bias (for the law) */
    uint16_t flags;
} ht_dcm_output_t;

/* The estimate in the caller's formats (Euler angles: roll = atan2(-R20, R22),
 * pitch = atan2(-R21, |(R20, R22)|), yaw = atan2(R11, R01), each rounded to
 * 0.01 degree). NULL s: *out is zeroed; NULL out: nothing. */
void ht_dcm_output(const ht_dcm_state_t *s, ht_dcm_output_t *out);

#ifdef __cplusplus
}
#endif

#endif /* HELICAL_DCM_H */
