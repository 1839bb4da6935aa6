/*
 * dcm_params.c - the estimator's parameters: defaults, range checks that name
 * the field, and the one-time conversion into the per-sample formats
 * (ht_dcm_init). See include/helical/estimator/dcm.h and docs/estimator.md.
 */
#include <stddef.h>

#include "helical/estimator/dcm.h"
#include "helical/params/param_rows.h"

// cppcheck-suppress misra-c2012-10.8 ; D-10.8-FROM-REAL: the table's bounds, folded constants
static const ht_param_info_t dcm_param_info[HT_PARAM_DCM_COUNT] = {HT_PARAMS_DCM(HT_PARAM_X_INFO)};

const char *ht_dcm_param_name(ht_dcm_param_id_t id)
{
    return ht_param_row_name(ht_dcm_param_info(id));
}

const ht_param_info_t *ht_dcm_param_info(ht_dcm_param_id_t id)
{
    return ht_param_row(dcm_param_info, HT_PARAM_DCM_COUNT, (int)id);
}

/* One row's default (params.def), folded to an integer constant. */
#define SET_DEFAULT(id, name, field, unit, fmt, lo, hi, def, desc)                                 \
    p->field = HT_PARAM_RAW_##fmt(def);

void ht_dcm_params_default(ht_dcm_params_t *p)
{
    if (p == NULL) {
        return;
    }
    // cppcheck-suppress misra-c2012-10.8 ; D-10.8-FROM-REAL: the table's defaults, folded constants
    HT_PARAMS_DCM(SET_DEFAULT)
}

static int in_range(int32_t v, int32_t lo, int32_t hi)
{
    return (v >= lo) && (v <= hi);
}

/* One row's range check (params.def). */
#define RANGE_CHECK(id, name, field, unit, fmt, lo, hi, def, desc)                                 \
    if (!in_range(p->field, HT_PARAM_RAW_##fmt(lo), HT_PARAM_RAW_##fmt(hi))) {                     \
        return HT_DCM_P_##id;                                                                      \
    }

/* The first parameter out of its range (table order), or HT_DCM_P_NONE. */
static ht_dcm_param_id_t first_bad(const ht_dcm_params_t *p)
{
    // cppcheck-suppress misra-c2012-10.8 ; D-10.8-FROM-REAL: the table's bounds, folded constants
    HT_PARAMS_DCM(RANGE_CHECK)
    return HT_DCM_P_NONE;
}

int ht_dcm_init(ht_dcm_t *d, const ht_dcm_params_t *p, ht_dcm_param_id_t *bad)
{
    if (bad != NULL) {
        *bad = HT_DCM_P_NONE;
    }
    if (d == NULL || p == NULL) {
        return 1;
    }
    const ht_dcm_t zero = {0};
    *d = zero; /* unusable until every check has passed */
    const ht_dcm_param_id_t b = first_bad(p);
    if (b != HT_DCM_P_NONE) {
        if (bad != NULL) {
            *bad = b;
        }
        return 2;
    }
    ht_dcm_t c = zero;
    c.p = *p;
    /* dt = 1 / rate, Q30, rounded: 2^30 / rate within half an LSB */
    const uint32_t rate = p->imu_rate_hz;
    const uint32_t dt_u = ((uint32_t)1u << 30) / rate;
    const uint32_t rem = ((uint32_t)1u << 30) - (dt_u * rate);
    const uint32_t dt_r = dt_u + (((2u * rem) >= rate) ? 1u : 0u);
    c.dt_q30 = (int32_t)dt_r;
    /* gain * dt: Q16 * Q30 = Q46; kp*dt <= 16 * 0.02 = 0.32 fits Q32, ki*dt <=
     * 4 * 0.02 = 0.08 fits Q34. Both keep >= 20 significant bits at the
     * defaults, so the integrator sees increments far below a Q30 LSB. */
    c.kp_rp_dt_q32 = q_mul32(p->kp_rollpitch, c.dt_q30, 14u);
    c.kp_yaw_dt_q32 = q_mul32(p->kp_yaw, c.dt_q30, 14u);
    c.ki_rp_dt_q34 = q_mul32(p->ki_rollpitch, c.dt_q30, 12u);
    c.ki_yaw_dt_q34 = q_mul32(p->ki_yaw, c.dt_q30, 12u);
    c.bias_max_q30 = p->gyro_bias_max_rad_s * 16384; /* <= 2^30 */
    /* 1 / band as a mantissa and exponent: the weight is (band - |dev|) / band */
    unsigned e = 0u;
    c.inv_band_q30 = q_recip_q30(p->accel_band_g, &e);
    const unsigned shift = 14u + e; /* Q16 * Q30 * 2^-(30+e) * 2^16; e <= 18 */
    c.inv_band_shift = (uint8_t)shift;
    /* 980.665 cm/s^2 * dt in Q24: 980.665 * 2^14 = 16067215.4 (rounded to
     * 16067215, 2.5e-8 relative), divided by the rate in two steps so that
     * the remainder keeps its 10 more bits; at most 321 344 308 at 50 Hz */
    const uint32_t g_q14 = 16067215u;
    const uint32_t g_hi = g_q14 / rate;
    const uint32_t g_lo = (((g_q14 % rate) << 10) + (rate / 2u)) / rate;
    const uint32_t g_dt = (g_hi << 10) + g_lo;
    c.g_dt_q24 = (int32_t)g_dt;
    /* the latency in samples, rounded: <= 500 */
    c.gps_latency_samples = (uint16_t)((((uint32_t)p->gps_latency_ms * rate) + 500u) / 1000u);
    /* dt / tau, rounded: 2^30 / (rate * tau) >= 1073 at 1 kHz */
    const uint32_t wind_alpha = (dt_r + (HT_DCM_WIND_TAU_S / 2u)) / HT_DCM_WIND_TAU_S;
    c.wind_alpha_q30 = (int32_t)wind_alpha;
    c.ready = 1u;
    *d = c;
    return 0;
}
