/*
 * ht_params.c - parameter checking and the one-time conversion of the
 * physical-unit parameters into the controller's formats (ht_init).
 */
#include <stddef.h>

#include "helical/law/helical_turn.h"
#include "helical/params/param_rows.h"

/* The per-field ranges are the table's (include/helical/params.def); the
 * joint limits are checked here. Why they are what they are:
 * gains above 64 per unit error (or per rad/s) would saturate the surfaces on
 * sensor noise alone; a floor below 1 m/s makes v_ref / S meaningless (and
 * unbounded); |ratio| <= 8 is 82.9 degrees of bank, beyond which the law's
 * target is nearly a knife edge, and max_tilt * g stays well inside its
 * format. */
/* 980.665 (g in cm/s^2) in Q20: max_tilt (Q16) * g -> Q18 of (rad/s)*(cm/s). */
#define HT_G_CM_S2_Q20 1028301783L

// cppcheck-suppress misra-c2012-10.8 ; D-10.8-FROM-REAL: the table's bounds, folded constants
static const ht_param_info_t param_info[HT_PARAM_LAW_COUNT] = {HT_PARAMS_LAW(HT_PARAM_X_INFO)};

const char *ht_param_name(ht_param_id_t id)
{
    return ht_param_row_name(ht_param_info(id));
}

const ht_param_info_t *ht_param_info(ht_param_id_t id)
{
    return ht_param_row(param_info, HT_PARAM_LAW_COUNT, (int)id);
}

static int in_range(int32_t v, int32_t lo, int32_t hi)
{
    return (v >= lo) && (v <= hi);
}

/* One row's range check (params.def): the bounds fold to integer constants. */
#define RANGE_CHECK(id, name, field, unit, fmt, lo, hi, def, desc)                                 \
    if (!in_range(p->field, HT_PARAM_RAW_##fmt(lo), HT_PARAM_RAW_##fmt(hi))) {                     \
        return HT_P_##id;                                                                          \
    }

/* The first field outside its own range (table order), or HT_P_NONE. */
static ht_param_id_t first_bad_field(const ht_params_t *p)
{
    // cppcheck-suppress misra-c2012-10.8 ; D-10.8-FROM-REAL: the table's bounds, folded constants
    HT_PARAMS_LAW(RANGE_CHECK)
    return HT_P_NONE;
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

/* The first parameter out of range, or HT_P_NONE: each field in its own
 * range first (params.def), then the joint limits the table cannot state. */
static ht_param_id_t first_bad_param(const ht_params_t *p)
{
    const ht_param_id_t bad = first_bad_field(p);
    if (bad != HT_P_NONE) {
        return bad;
    }
    if (p->v_ref_cm_s < p->v_min_cm_s || p->v_ref_cm_s > HT_SCALE_MAX * p->v_min_cm_s) {
        return HT_P_V_REF;
    }
    /* A rate gain too large for the law to be exact: the axis' kff names it
     * when kff alone exceeds the limit, else its kd. */
    const q16_t kff[3] = {p->kff_aileron, p->kff_elevator, p->kff_rudder};
    const q16_t kd[3] = {p->kd_aileron, p->kd_elevator, p->kd_rudder};
    static const ht_param_id_t kff_id[3] = {HT_P_KFF_AILERON, HT_P_KFF_ELEVATOR, HT_P_KFF_RUDDER};
    static const ht_param_id_t kd_id[3] = {HT_P_KD_AILERON, HT_P_KD_ELEVATOR, HT_P_KD_RUDDER};
    for (int i = 0; i < 3; i++) {
        if (!rate_gain_ok(kff[i], kd[i], p)) {
            return (rate_gain_ok(kff[i], 0, p) != 0) ? kd_id[i] : kff_id[i];
        }
    }
    return HT_P_NONE;
}

/* The options' constants (src/law/ht_options.c); each option is off at 0. */
static void options_init(ht_controller_t *ctl, const ht_params_t *params)
{
    ctl->roll_in = params->roll_in;
    ctl->roll_in_max_q25 = params->roll_in_rate_max_rad_s * 512; /* <= 2^28 */
    ctl->kp_sideslip = params->kp_sideslip;
    const q16_t fade = params->vertical_fade; /* [0, 2^16] */
    ctl->vertical_fade = fade;
    if (fade != 0) {
        /* ceil(fade^2 / 16): X^2 + Z^2 (Q28) >= it exactly when
         * sqrt(X^2 + Z^2) >= fade; 1.0 itself (2^32 / 16) apart */
        const uint32_t f = (uint32_t)fade;
        ctl->fade2_q28 = (f >= 65536u) ? 0x10000000u : (((f * f) + 15u) >> 4);
        unsigned e = 0u;
        ctl->fade_inv_q30 = q_recip_q30(fade, &e); /* 1/fade_q16 = inv * 2^-(30 + e), e <= 16 */
        ctl->fade_inv_exp = (uint8_t)e;
    }
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
    const ht_param_id_t bad = first_bad_param(params);
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
    options_init(ctl, params);
    ctl->ready = 1u;
    return HT_OK;
}
