/*
 * ht_reference.h - the helical-turn law in double precision, written straight
 * from docs/control-law.md. Test code only: it is what the Q14 core is
 * measured against.
 */
#ifndef HT_REFERENCE_H
#define HT_REFERENCE_H

#include "helical/law/helical_turn.h"

typedef struct {
    double x, y, z;   /* DCM bottom row */
    double turn_rate; /* rad/s */
    double pitch;     /* ratio */
    double airspeed;  /* m/s */
    double gyro[3];   /* rad/s about X, Y, Z */
    int inverted;
    double turn_accel; /* rad/s^2 (roll_in) */
    double accel_lat;  /* g, + = toward the left wing (kp_sideslip) */
} ht_ref_input_t;

typedef struct {
    double kp[3], kff[3], kd[3]; /* body axis order X (elevator), Y (aileron), Z (rudder) */
    double v_ref, v_min, max_tilt;
    int schedule;
    int pitch_mode;
    /* the options (docs/control-law.md "Extensions beyond the seed") */
    int roll_in;
    double roll_in_max;   /* rad/s */
    double kp_sideslip;   /* per g */
    double vertical_fade; /* 0 = off */
} ht_ref_params_t;

typedef struct {
    double turn_rate_used, ratio;
    double tilt[3];
    double rate[3];
    double roll_dot, roll_cross, roll_error;
    double pitch_error, pitch_body_x, pitch_body_z;
    double aileron, elevator, rudder;
    /* The rotation demand d_X, d_Y, d_Z of step 10 before the clamp of step 11
     * (aileron = clamp(d_Y), elevator = clamp(-d_X), rudder = clamp(d_Z)). */
    double demand[3];
    /* Distances to the spec's branch boundaries, for sweeps that must skip
     * inputs on a boundary (where a tie can go either way). */
    double ratio_margin; /* |ratio| - max_tilt before the clamp */
    double pitch_agree;  /* Y*Yt + a*t: <= 0 saturates the pitch error */
    double pitch_raw;    /* the pitch error before saturation */
    double a;            /* sqrt(X^2 + Z^2) */
    /* the options: the target bank rate added to the roll axis' target rate,
     * the fade factor of the roll error (1 when it does not act; roll_error
     * above is the faded one), the rudder's sideslip term */
    double roll_in_rate, roll_fade, sideslip_rudder;
} ht_ref_output_t;

/* The parameters exactly as the controller holds them (after conversion). */
void ht_ref_params_from_controller(const ht_controller_t *ctl, ht_ref_params_t *p);

/* The real value of each fixed-point input. */
void ht_ref_input_from_fixed(const ht_input_t *in, ht_ref_input_t *r);

/* One step of the law. */
void ht_ref_step(const ht_ref_params_t *p, const ht_ref_input_t *in, ht_ref_output_t *out);

#endif
