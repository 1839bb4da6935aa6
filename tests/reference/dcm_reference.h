/*
 * dcm_reference.h - the attitude estimator of include/helical/estimator/dcm.h written
 * again in double precision, straight from its equations (test code only),
 * and the rotation helpers the estimator tests share: Euler angles to R in
 * the library's axes, exact rotations, angles between attitudes.
 */
#ifndef DCM_REFERENCE_H
#define DCM_REFERENCE_H

#include <stdint.h>

#include "helical/estimator/dcm.h"

#define DCMR_PI 3.14159265358979323846

typedef struct {
    double dt, kp_rp, ki_rp, kp_yaw, ki_yaw, bias_max, gyro_limit, accel_limit, band;
    double gps_min_speed_cm_s;
    int centripetal; /* ht_dcm_cf_t */
    int imu_rate;    /* samples per second (the GPS timing counts samples) */
    int lat_samples; /* gps_latency_ms in samples, rounded */
    double wind_tau; /* s (HT_DCM_WIND_TAU_S) */
} dcmr_params_t;

/* The GPS acceleration reference (dcm_gps_accel.h), in double. */
#define DCMR_GA_W 5
typedef struct {
    double open[3], closed[3]; /* sums of R f dt (g*s) */
    double closed_t, open_t;   /* their durations, s */
    int open_aligned, boundary_done, closed_ok, count, since_fix, period;
    double dv[DCMR_GA_W][3], t[DCMR_GA_W]; /* per interval, oldest first */
    double vel[DCMR_GA_W + 1][3];          /* cm/s */
    double err[2];                         /* earth north, east */
    double h[2];                           /* the GPS specific force's lean */
    int err_valid;
} dcmr_ga_t;

typedef struct {
    double r[3][3];
    double bias[3];
    double rate[3];
    int aligned;
    double g_filt[3];  /* the vibration low-pass of the gravity reference */
    double r2_filt[3]; /* R[2] through the same low-pass */
    int g_filt_valid;
    double accel_fwd;  /* filtered rate of change of the airspeed, g */
    double speed_prev; /* the previous sample's airspeed, cm/s (when valid) */
    int speed_prev_valid;
    int gps_age; /* samples since the last gps_fresh */
    dcmr_ga_t ga;
    /* the wind regression y = W + A x (dcm_wind.h), complex as [re, im] */
    double mx[2], my[2], sxx, sxy[2], a[2], w[2];
    int wind_primed, wind_solved;
} dcmr_state_t;

/* One sample of the GPS acceleration reference (r: the matrix before this
 * sample's propagation, acc clamped, acc_sat: clamped this sample). */
void dcmr_ga_sample(const dcmr_params_t *p, dcmr_ga_t *g, double r[3][3], const double acc[3],
                    int acc_sat, const ht_dcm_aiding_t *a);

/* The body-axes tilt error of the last window; 0 when none. */
int dcmr_ga_error(const dcmr_ga_t *g, double r[3][3], int heading_trusted, double e[3]);

/* The same parameters in real units (from the integer ones). */
void dcmr_params_from(const ht_dcm_params_t *p, dcmr_params_t *out);

/* R = I, zero bias. */
void dcmr_reset(dcmr_state_t *s);

/* R from a specific force and a heading (rad); 1 when |f| < 0.5 g. */
int dcmr_align(dcmr_state_t *s, const double f_g[3], double heading_rad);

/* One sample: gyro in rad/s, accel in g, the aiding as the library gets it. */
void dcmr_update(const dcmr_params_t *p, dcmr_state_t *s, const double gyro[3], const double acc[3],
                 const ht_dcm_aiding_t *aid);

/* --- rotation helpers --------------------------------------------------- */

/* R (body -> earth, library body axes X left, Y forward, Z down) of roll,
 * pitch, yaw in rad (the aerospace 3-2-1 sequence). */
void dcmr_from_euler(double roll, double pitch, double yaw, double r[3][3]);

/* The exact rotation of R by a constant body rate w for time t:
 * R(t) = R0 exp([w t]x). */
void dcmr_rotate_body(double r0[3][3], const double w[3], double t, double out[3][3]);

/* The angle (rad) of the rotation between two attitudes, robust near 0. */
double dcmr_angle_between(double a[3][3], double b[3][3]);

/* max |R R^T - I| over the nine elements. */
double dcmr_ortho_err(double r[3][3]);

/* The library state's matrix (Q30) in double. */
void dcmr_from_state(const ht_dcm_state_t *s, double r[3][3]);

/* A double matrix into the library state (Q30, rounded). */
void dcmr_to_state(double r[3][3], ht_dcm_state_t *s);

/* Euler angles of R in rad: roll (-pi, pi], pitch [-pi/2, pi/2], yaw [0, 2 pi). */
void dcmr_euler(double r[3][3], double *roll, double *pitch, double *yaw);

#endif /* DCM_REFERENCE_H */
