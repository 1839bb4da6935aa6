/*
 * helical_turn.h - the helical-turn attitude controller (Premerlani & Hollands,
 * "Helical Turns: Part 2, Controls"), in fixed point, exactly as
 * docs/control-law.md specifies it.
 *
 * Frames (MatrixPilot): body X out the LEFT wing, Y forward, Z down. The DCM
 * bottom row [X, Y, Z] is earth-down seen in the body frame: level [0, 0, 1],
 * right bank phi gives X = -sin(phi), nose up theta gives Y = -sin(theta),
 * inverted level Z = -1. Surfaces: aileron + rolls right, elevator + pitches
 * the nose up, rudder + yaws the nose right.
 *
 * Use:
 *   ht_params_t p = HT_PARAMS_DEFAULT;     // physical units, integers only
 *   p.kp_aileron = Q16_FROM_REAL(3.0);     // folded at compile time
 *   ht_controller_t ctl;
 *   if (ht_init(&ctl, &p) != HT_OK) { ... ht_param_name(ht_init_bad_field) }
 *   ht_input_t in = { ... };  ht_output_t out;
 *   ht_step(&ctl, &in, &out);              // integer only, no state changed
 *
 * The step is a pure function of (controller, input): the law has no
 * integral term, so nothing is carried between steps, and the controller
 * struct is read-only after init. It allocates nothing, uses no float, no
 * libm, no recursion and no global mutable state.
 */
#ifndef HELICAL_HELICAL_TURN_H
#define HELICAL_HELICAL_TURN_H

#include <stdint.h>

#include "helical/params.h"
#include "helical/law/ht_controller.h"
#include "helical/math/q14.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Which pitch error the law uses. */
typedef enum {
    /* Eq. 10-11: pitch error in the earth frame, projected onto elevator and
     * rudder. The default, and the source text's final design. */
    HT_PITCH_EARTH_FRAME = 0,
    /* Eq. A.13: the body-frame cross product of target and actual tilt (the
     * source text's first method), kept for comparison in the SIL. */
    HT_PITCH_TILT_CROSS = 1
} ht_pitch_mode_t;

/*
 * The legal parameter ranges (ht_init refuses anything outside them). Within
 * them every surface is within 2 LSB of the double-precision law
 * (docs/control-law.md, "Accuracy"); the two joint limits are where 32-bit
 * arithmetic stops being exact: the scale v_ref / v_min, and the rate gain of
 * each axis, kff * v_ref / v_min + kd * s_p,max (s_p,max = v_ref / v_min with
 * the schedule, 1 without), which multiplies every error of the target rate.
 */
#define HT_GAIN_MAX_Q16           (64 * Q16_ONE) /* every kp, kff, kd in [0, 64] */
#define HT_V_MIN_LOWEST_CM_S      100            /* v_min in [1 m/s, v_ref] */
#define HT_V_REF_MAX_CM_S         32767          /* v_ref in [v_min, 327.67 m/s] */
#define HT_SCALE_MAX              32             /* v_ref <= 32 * v_min */
#define HT_RATE_GAIN_MAX          512            /* per axis, command per rad/s */
#define HT_MAX_TILT_LIMIT_Q16     (8 * Q16_ONE)  /* max_tilt in (0, 8] */
#define HT_ROLL_IN_RATE_LIMIT_Q16 (8 * Q16_ONE)  /* roll_in_rate_max in [0, 8] rad/s */

/*
 * Parameters, in physical units as integers, so that a board can hold them in
 * flash without any float support. Gains are Q16 (Q16_FROM_REAL(3.0)).
 * Ranges are checked by ht_init(). The fields, their order, units, ranges and
 * defaults are those of the parameter table, include/helical/params.def:
 *   q16_t kp_aileron, kp_elevator, kp_rudder;     command per unit error, [0, 64]
 *   q16_t kff_aileron, kff_elevator, kff_rudder;  command per rad/s at v_ref, [0, 64]
 *   q16_t kd_aileron, kd_elevator, kd_rudder;     command per rad/s, [0, 64]
 *   int32_t v_ref_cm_s;  airspeed scaling reference, [100, 32767], at most 32 * v_min,
 *                        and per axis kff * v_ref / v_min + kd * s_p,max <= 512
 *   int32_t v_min_cm_s;  airspeed floor, [100, 32767] (1 m/s)
 *   uint8_t schedule;    1: kp, kd also scaled by v_ref / S
 *   q16_t max_tilt;      limit on |turn_rate * S / g|, (0, 8]
 *   uint8_t pitch_mode;  ht_pitch_mode_t
 * and the options beyond the seed (docs/control-law.md "Extensions beyond
 * the seed"), each off by default, the law then bit for bit the seed's:
 *   uint8_t roll_in;                1: the target bank rate joins the roll target rate
 *   q16_t roll_in_rate_max_rad_s;   its bound, [0, 8] rad/s
 *   q16_t kp_sideslip;              rudder per g of lateral specific force, [0, 64]
 *   q16_t vertical_fade;            roll authority fade below sqrt(X^2 + Z^2) = this, [0, 1]
 */
typedef struct {
    HT_PARAMS_LAW(HT_PARAM_X_FIELD)
} ht_params_t;

/* The defaults of docs/control-law.md (the table's default column). */
#define HT_PARAMS_DEFAULT                                                                          \
    {                                                                                              \
        HT_PARAMS_LAW(HT_PARAM_X_DEFAULT)                                                          \
    }

/* ht_init results. */
typedef enum {
    HT_OK = 0,
    HT_ERR_NULL = 1, /* a NULL pointer */
    HT_ERR_PARAM = 2 /* a parameter out of range: see *bad_field */
} ht_status_t;

/* Parameter identifiers, for error messages (ht_param_name): HT_P_<ID> of
 * each row of params.def, in its order. */
#define HT_PARAM_X_LAW_ID(id, name, field, unit, fmt, lo, hi, def, desc) HT_P_##id,
typedef enum { HT_P_NONE = 0, HT_PARAMS_LAW(HT_PARAM_X_LAW_ID) HT_P_COUNT } ht_param_id_t;

/* The control-law.md name of a parameter ("kp_aileron", ...), or "" . */
const char *ht_param_name(ht_param_id_t id);

/* The table's row of a parameter (name, unit, format, stored bounds and
 * default), or NULL for HT_P_NONE, HT_P_COUNT and anything else. */
const ht_param_info_t *ht_param_info(ht_param_id_t id);

/*
 * Check the parameters and fill the controller. On HT_ERR_PARAM the offending
 * parameter is written to *bad_field (if bad_field is not NULL) and the
 * controller is left unusable (ht_step on it gives zero surfaces).
 */
ht_status_t ht_init(ht_controller_t *ctl, const ht_params_t *params, ht_param_id_t *bad_field);

/* One control step's inputs. */
typedef struct {
    q14_t x, y, z;         /* DCM bottom row, used as given (not renormalized) */
    q11_t turn_rate_rad_s; /* desired rate about earth vertical, + = right turn */
    q16_t pitch_ratio;     /* desired vertical / horizontal airspeed, + = climb */
    int16_t airspeed_cm_s; /* measured airspeed; anything below v_min is floored */
    q11_t gyro_rad_s[3];   /* measured body rates about X, Y, Z */
    uint8_t inverted;      /* nonzero: fly inverted */
    /* Inputs of the options (read only when the option is on; zero them):
     * roll_in: the rate of change of the commanded turn rate, + = the turn
     * rate increasing to the right; kp_sideslip: the lateral specific force,
     * the accelerometer's body X component (+ = toward the left wing),
     * saturating at +/-2 g. */
    q11_t turn_accel_rad_s2;
    q14_t accel_lat_g;
} ht_input_t;

/* One step's outputs: every intermediate of the spec, for logging. */
typedef struct {
    q11_t turn_rate_used_rad_s;                     /* omega after the tilt limit */
    q16_t tilt_ratio;                               /* omega * S / g after the limit */
    q14_t tilt_x, tilt_y, tilt_z;                   /* target tilt (Eq. 5, 6, inverted) */
    q11_t rate_x_rad_s, rate_y_rad_s, rate_z_rad_s; /* target body rate (Eq. 3) */
    q14_t roll_dot, roll_cross, roll_error;         /* Eq. 8, 9 */
    q14_t pitch_error;                /* Eq. 10 (earth-frame mode); 0 in tilt-cross mode */
    q14_t pitch_body_x, pitch_body_z; /* Eq. 11 or Eq. A.13 */
    q14_t aileron, elevator, rudder;  /* [-1, 1] */
    uint8_t flags;                    /* HT_F_* */
    /* the options: the target bank rate added to rate_y in the roll demand
     * (0 when roll_in is off); the fade factor on the roll error (1 when it
     * does not act; the roll_error above is the faded one); the rudder's
     * sideslip term, before the rudder's clamp (0 when kp_sideslip is 0) */
    q11_t roll_in_rate_rad_s;
    q14_t roll_fade;
    q14_t sideslip_rudder;
} ht_output_t;

/*
 * One control step. Integer only; ctl and in are not modified. Every input
 * value is accepted: the results are defined for the whole int16/int32 range
 * (saturating where the header of each field says so). A NULL argument or an
 * uninitialised controller writes zero surfaces (when out is not NULL).
 */
void ht_step(const ht_controller_t *ctl, const ht_input_t *in, ht_output_t *out);

#ifdef __cplusplus
}
#endif

#endif /* HELICAL_HELICAL_TURN_H */
