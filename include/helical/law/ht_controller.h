/*
 * ht_controller.h - the controller the law runs on (ht_init fills it,
 * helical_turn.h) and the flags of a step: what the law's step
 * (src/law/helical_turn.c) and its options (src/law/ht_options.c) share.
 */
#ifndef HELICAL_HT_CONTROLLER_H
#define HELICAL_HT_CONTROLLER_H

#include <stdint.h>

#include "helical/math/q14.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Per-axis gains in the core's order: index 0 = body X (elevator gains),
 * 1 = body Y (aileron gains), 2 = body Z (rudder gains). */
typedef struct {
    q16_t kp[3];
    q16_t kff[3];
    q16_t kd[3];
} ht_axis_gains_t;

/*
 * The controller: the parameters converted once into the core's formats.
 * Read-only after ht_init; several steps (and threads) may share one.
 */
typedef struct {
    ht_axis_gains_t gains;
    int16_t v_ref_cm_s;
    int16_t v_min_cm_s;
    uint8_t schedule;
    uint8_t pitch_mode;
    q16_t max_tilt;
    /* max_tilt * g in Q18 of (rad/s)*(cm/s), below 2^31: when the tilt limit
     * clamps, the turn rate used is max_tilt_g_q18 / S_cm_s. */
    int32_t max_tilt_g_q18;
    /* the options (src/law/ht_options.c): off when roll_in, kp_sideslip,
     * vertical_fade are 0 */
    uint8_t roll_in;
    int32_t roll_in_max_q25; /* roll_in_rate_max in Q25 rad/s, <= 2^28 */
    q16_t kp_sideslip;       /* Q16 per g */
    q16_t vertical_fade;     /* Q16 */
    uint32_t fade2_q28;      /* vertical_fade^2 in Q28 (0: off) */
    int32_t fade_inv_q30;    /* 1 / vertical_fade = fade_inv_q30 * 2^(16 - 30 - fade_inv_exp) */
    uint8_t fade_inv_exp;
    uint8_t ready; /* 1 after a successful ht_init */
} ht_controller_t;

/* Flags describing which branch of the law a step took. */
enum ht_step_flag {
    HT_F_AIRSPEED_FLOORED = 1u << 0,  /* airspeed < v_min: v_min used */
    HT_F_TILT_LIMITED = 1u << 1,      /* |ratio| clamped to max_tilt */
    HT_F_ROLL_BEYOND_90 = 1u << 2,    /* roll_dot <= 0: roll error = sign(cross) */
    HT_F_PITCH_BEYOND_90 = 1u << 3,   /* pitch error saturated to +/-1 */
    HT_F_FUSELAGE_VERTICAL = 1u << 4, /* X = Z = 0: projection direction defined as [-1, 0, 0] */
    HT_F_SURFACE_SATURATED = 1u << 5, /* at least one surface clamped to +/-1 */
    HT_F_ROLL_FADED = 1u << 6,        /* vertical_fade: sqrt(X^2 + Z^2) < vertical_fade */
    HT_F_ROLL_IN_LIMITED = 1u << 7    /* roll_in: the target bank rate clamped to its bound */
};

#ifdef __cplusplus
}
#endif

#endif /* HELICAL_HT_CONTROLLER_H */
