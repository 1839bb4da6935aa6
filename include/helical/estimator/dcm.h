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

#include "helical/estimator/dcm_types.h"
#include "helical/params.h"
#include "helical/math/q14.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Fills p with the defaults (ht_dcm_params_t, dcm_types.h). */
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

/* 0 = OK, 1 = NULL, 2 = a parameter out of range (*bad, may be NULL). */
int ht_dcm_init(ht_dcm_t *d, const ht_dcm_params_t *p, ht_dcm_param_id_t *bad);

/* One IMU sample, body axes, Q16. */
typedef struct {
    q16_t gyro_rad_s[3];
    q16_t accel_g[3]; /* specific force */
} ht_imu_sample_t;

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
