/*
 * guide.h - the guidance between the modes and the law, beyond the seed: the
 * turn-rate trim (docs/control-law.md "Extensions beyond the seed").
 *
 * Why: the seed's law is proportional only. In a steady turn the aircraft
 * needs a steady aileron to hold its bank (a roll moment: the c172p's at 54
 * degrees of bank), which the law can only give from a standing roll error,
 * so the bank is not the target's and the turn rate is off by a steady 2-5 %
 * (4.6 % in the c172p's 15 deg/s descending turn on the true attitude). The
 * seed objects to integral feedback on the attitude loops; this is not one:
 * it is a slow correction of the turn-rate *command* from the measured turn
 * rate, bounded to a fraction of the command, learning only in a steady turn
 * (the command unchanged for turn_trim_hold), so a turn entry, a roll and a
 * reversal fly the seed's law, and a steady turn reaches its rate.
 *
 *   k      <- k + clamp((cmd - measured) / cmd, +/-0.5) / (turn_trim_tau * rate)
 *   |k|    <= turn_trim_max
 *   used    = cmd (1 + k)
 *
 * The measured rate is that of the estimate's heading (the nose's horizontal
 * direction from one step to the next), not the gyros' component about the
 * vertical: the heading is held to the GPS course, so its rate is the true
 * one on average, where the gyros' scale-factor and cross-axis errors (0.5 %
 * and 2 % on an ICM-42688-P) put 1-3 % into R . gyro in a turn, which the
 * trim would fly. k resets when the command falls below turn_trim_min_rate
 * or changes sign (the two directions' roll moments differ), and holds (does not learn) while the
 * caller says so (the law's tilt limit, a surface at its stop, manual flight, an estimator that
 * does not know its heading yet: firmware/fw_step.c).
 *
 * Formats: commands in Q11 rad/s as the law's (ht_input_t), the measured
 * rate in Q20 rad/s; k in Q30. turn_trim = 0 passes the command through unchanged: the seed's law
 * bit for bit.
 */
#ifndef HELICAL_GUIDE_H
#define HELICAL_GUIDE_H

#include <stdint.h>

#include "helical/params.h"
#include "helical/math/q14.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The parameters (params.def HT_PARAMS_GUIDE: names, units, ranges,
 * defaults). */
typedef struct {
    HT_PARAMS_GUIDE(HT_PARAM_X_FIELD)
} ht_guide_params_t;

/* HT_GUIDE_P_<ID> of each row of params.def, in its order. */
#define HT_PARAM_X_GUIDE_ID(id, name, field, unit, fmt, lo, hi, def, desc) HT_GUIDE_P_##id,
typedef enum {
    HT_GUIDE_P_NONE = 0,
    HT_PARAMS_GUIDE(HT_PARAM_X_GUIDE_ID) HT_GUIDE_P_COUNT
} ht_guide_param_id_t;

/* Fills p with the table's defaults. */
void ht_guide_params_default(ht_guide_params_t *p);

/* "turn_trim", ... or "" (HT_GUIDE_P_NONE, out of range). */
const char *ht_guide_param_name(ht_guide_param_id_t id);

/* The table's row of a parameter, or NULL. */
const ht_param_info_t *ht_guide_param_info(ht_guide_param_id_t id);

/* The parameters converted once for a step rate; read-only after init. */
typedef struct {
    ht_guide_params_t p;
    q11_t min_rate_q11;  /* turn_trim_min_rate in Q11 rad/s, at least 1 */
    int32_t tau_ticks;   /* turn_trim_tau in steps, at least 1 */
    int32_t max_q30;     /* turn_trim_max in Q30 */
    uint16_t hold_ticks; /* turn_trim_hold in steps */
    uint16_t rate_hz;    /* the step rate */
    uint8_t ready;
} ht_guide_t;

/* The caller's state (zero = no trim learnt). */
typedef struct {
    int32_t k_q30;    /* the trim, a fraction of the command */
    q11_t last_cmd;   /* the previous step's command */
    uint16_t steady;  /* steps the command has been unchanged, <= hold_ticks */
    q14_t prev_north; /* the previous step's heading vector */
    q14_t prev_east;
    uint8_t have_prev;
} ht_guide_state_t;

/* 0 = OK, 1 = NULL, 2 = a parameter out of range (*bad names it; may be
 * NULL), 3 = rate_hz outside [1, 1000]. On failure g is unusable and the
 * step passes its command through. */
int ht_guide_init(ht_guide_t *g, const ht_guide_params_t *p, uint16_t rate_hz,
                  ht_guide_param_id_t *bad);

/* Forget the trim. */
void ht_guide_reset(ht_guide_state_t *s);

/*
 * One control step: the turn-rate command the law is given. heading_north /
 * heading_east: the nose's horizontal direction in earth axes (R[0][1],
 * R[1][1], Q14; any length above 0.3); hold != 0 keeps k as it is this step
 * (still applied). NULL pointers or an unusable g give cmd.
 */
q11_t ht_guide_turn_rate(const ht_guide_t *g, ht_guide_state_t *s, q11_t cmd, q14_t heading_north,
                         q14_t heading_east, uint8_t hold);

#ifdef __cplusplus
}
#endif

#endif /* HELICAL_GUIDE_H */
