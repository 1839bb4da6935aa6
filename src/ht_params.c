/*
 * ht_params.c - parameter checking and the one-time conversion of the
 * physical-unit parameters into the controller's formats (ht_init).
 */
#include <stddef.h>

#include "helical/helical_turn.h"

/* The ranges are public (helical_turn.h). Why they are what they are:
 * gains above 64 per unit error (or per rad/s) would saturate the surfaces on
 * sensor noise alone; a floor below 1 m/s makes v_ref / S meaningless (and
 * unbounded); |ratio| <= 8 is 82.9 degrees of bank, beyond which the law's
 * target is nearly a knife edge, and max_tilt * g stays well inside its
 * format. */
/* 980.665 (g in cm/s^2) in Q20: max_tilt (Q16) * g -> Q18 of (rad/s)*(cm/s). */
#define HT_G_CM_S2_Q20 1028301783L

static const char *const param_names[HT_P_COUNT] = {
    "",           "kp_aileron", "kp_elevator", "kp_rudder", "kff_aileron", "kff_elevator",
    "kff_rudder", "kd_aileron", "kd_elevator", "kd_rudder", "v_ref",       "v_min",
    "schedule",   "max_tilt",   "pitch_mode"};

const char *ht_param_name(ht_param_id_t id)
{
    if ((int)id <= 0 || (int)id >= (int)HT_P_COUNT) {
        return "";
    }
    return param_names[id];
}

static int gain_ok(q16_t g)
{
    return g >= 0 && g <= HT_GAIN_MAX_Q16;
}

/* The rate gain of one axis, kff * v_ref / v_min + kd * s_p,max, at most
 * HT_RATE_GAIN_MAX, exactly and without a division or a 64-bit product:
 * kff * v_ref + kd * v_p <= 512 * 2^16 * v_min with the gains in Q16 and
 * v_p = v_ref scheduled, v_min not. The left side reaches 2^38, so each gain
 * is split at bit 11: sum = hi * 2^11 + lo with hi, lo below 2^27. */
static int rate_gain_ok(q16_t kff, q16_t kd, const ht_params_t *p)
{
    const uint32_t v_ref = (uint32_t)p->v_ref_cm_s; /* <= 2^15 (checked before) */
    const uint32_t v_p = (p->schedule != 0u) ? v_ref : (uint32_t)p->v_min_cm_s;
    const uint32_t kf = (uint32_t)kff, kdu = (uint32_t)kd; /* <= 2^22 */
    const uint32_t lo = ((kf & 2047u) * v_ref) + ((kdu & 2047u) * v_p);
    const uint32_t hi = ((kf >> 11) * v_ref) + ((kdu >> 11) * v_p) + (lo >> 11);
    const uint32_t lim =
        (uint32_t)p->v_min_cm_s * (uint32_t)HT_RATE_GAIN_MAX * 32u; /* 2^25 v / 2^11 */
    return (hi < lim) || (hi == lim && (lo & 2047u) == 0u);
}

/* The nine gains in ht_params_t's (and ht_param_id_t's) order: kp, kff, kd,
 * each aileron, elevator, rudder. */
#define N_GAINS 9

/* The first parameter out of range, or HT_P_NONE. */
static ht_param_id_t first_bad_param(const ht_params_t *p, const q16_t gains[N_GAINS])
{
    for (int i = 0; i < N_GAINS; i++) {
        if (!gain_ok(gains[i])) {
            const int id = (int)HT_P_KP_AILERON + i;
            return (ht_param_id_t)id;
        }
    }
    if (p->v_min_cm_s < HT_V_MIN_LOWEST_CM_S || p->v_min_cm_s > HT_V_REF_MAX_CM_S) {
        return HT_P_V_MIN;
    }
    if (p->v_ref_cm_s < p->v_min_cm_s || p->v_ref_cm_s > HT_V_REF_MAX_CM_S ||
        p->v_ref_cm_s > HT_SCALE_MAX * p->v_min_cm_s) {
        return HT_P_V_REF;
    }
    if (p->schedule > 1u) {
        return HT_P_SCHEDULE;
    }
    /* A rate gain too large for the law to be exact: the axis' kff names it
     * when kff alone exceeds the limit, else its kd. */
    for (int i = 0; i < 3; i++) {
        if (!rate_gain_ok(gains[3 + i], gains[6 + i], p)) {
            const int kd_named = rate_gain_ok(gains[3 + i], 0, p);
            const int id = (int)HT_P_KFF_AILERON + i + (3 * kd_named);
            return (ht_param_id_t)id;
        }
    }
    if (p->max_tilt <= 0 || p->max_tilt > HT_MAX_TILT_LIMIT_Q16) {
        return HT_P_MAX_TILT;
    }
    if (p->pitch_mode != (uint8_t)HT_PITCH_EARTH_FRAME &&
        p->pitch_mode != (uint8_t)HT_PITCH_TILT_CROSS) {
        return HT_P_PITCH_MODE;
    }
    return HT_P_NONE;
}

ht_status_t ht_init(ht_controller_t *ctl, const ht_params_t *params, ht_param_id_t *bad_field)
{
    if (bad_field != NULL) {
        *bad_field = HT_P_NONE;
    }
    if (ctl == NULL || params == NULL) {
        return HT_ERR_NULL;
    }
    const ht_controller_t zero = {0};
    *ctl = zero; /* unusable (ready = 0) until every check has passed */
    /* One copy of the gains, indexed by the checks (a second copy, or a
     * controller built on the stack and copied, costs flash that the budget
     * of README "Boards and firmware" counts). */
    const q16_t gains[N_GAINS] = {params->kp_aileron,  params->kp_elevator,  params->kp_rudder,
                                  params->kff_aileron, params->kff_elevator, params->kff_rudder,
                                  params->kd_aileron,  params->kd_elevator,  params->kd_rudder};
    const ht_param_id_t bad = first_bad_param(params, gains);
    if (bad != HT_P_NONE) {
        if (bad_field != NULL) {
            *bad_field = bad;
        }
        return HT_ERR_PARAM;
    }
    /* Body axis order X, Y, Z = elevator, aileron, rudder gains (nine plain
     * copies are smaller than a loop with the index permutation). */
    ctl->gains.kp[0] = params->kp_elevator;
    ctl->gains.kp[1] = params->kp_aileron;
    ctl->gains.kp[2] = params->kp_rudder;
    ctl->gains.kff[0] = params->kff_elevator;
    ctl->gains.kff[1] = params->kff_aileron;
    ctl->gains.kff[2] = params->kff_rudder;
    ctl->gains.kd[0] = params->kd_elevator;
    ctl->gains.kd[1] = params->kd_aileron;
    ctl->gains.kd[2] = params->kd_rudder;
    ctl->v_ref_cm_s = (int16_t)params->v_ref_cm_s;
    ctl->v_min_cm_s = (int16_t)params->v_min_cm_s;
    ctl->schedule = params->schedule;
    ctl->pitch_mode = params->pitch_mode;
    ctl->max_tilt = params->max_tilt;
    ctl->max_tilt_g_q18 = q_mul32(params->max_tilt, HT_G_CM_S2_Q20, 18); /* <= 2.06e9 */
    ctl->ready = 1u;
    return HT_OK;
}
