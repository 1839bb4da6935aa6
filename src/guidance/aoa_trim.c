/*
 * aoa_trim.c - the angle-of-attack and elevator-trim model (aoa_trim.h).
 * Integer only: no float, no libm, no allocation, no global mutable state.
 */
#include "helical/guidance/aoa_trim.h"

#include <stddef.h>

/* pi / 180 in Q30. */
#define DEG_TO_RAD_Q30 18740330L

int ht_aoa_init(ht_aoa_t *m, const ht_aoa_params_t *p, ht_aoa_param_id_t *bad_field)
{
    if (bad_field != NULL) {
        *bad_field = HT_AOA_P_NONE;
    }
    if (m == NULL || p == NULL) {
        return 1;
    }
    ht_aoa_t z = {0};
    *m = z;
    const ht_aoa_param_id_t bad = ht_aoa_first_bad(p);
    if (bad != HT_AOA_P_NONE) {
        if (bad_field != NULL) {
            *bad_field = bad;
        }
        return 2;
    }
    m->enabled = p->enabled;
    m->v_ref_cm_s = p->v_ref_cm_s;
    m->v_enable_cm_s = p->v_enable_cm_s;
    m->load_max = p->load_max;
    m->aoa0_rad[0] = q_mul32(p->aoa_normal_deg, DEG_TO_RAD_Q30, 30u);
    m->aoa1_rad[0] = q_mul32(p->aoa_normal_slope_deg, DEG_TO_RAD_Q30, 30u);
    m->aoa0_rad[1] = q_mul32(p->aoa_inverted_deg, DEG_TO_RAD_Q30, 30u);
    m->aoa1_rad[1] = q_mul32(p->aoa_inverted_slope_deg, DEG_TO_RAD_Q30, 30u);
    m->trim0[0] = p->trim_normal;
    m->trim1[0] = p->trim_normal_slope;
    m->trim0[1] = p->trim_inverted;
    m->trim1[1] = p->trim_inverted_slope;
    m->ready = 1u;
    return 0;
}

void ht_aoa_step(const ht_aoa_t *m, q14_t x, q14_t z, int16_t airspeed_cm_s, ht_aoa_output_t *out)
{
    if (out == NULL) {
        return;
    }
    ht_aoa_output_t o = {0};
    if (m == NULL || !m->ready) {
        *out = o;
        return;
    }
    /* |load| = |Z| + X^2 / |Z| in Q14, limited to load_max (<= 8, so the
     * Q14 sum stays below 2^18 and X^2 / |Z| below 2^30: no overflow). */
    unsigned inv = 0u;
    if (z < 0) {
        inv = 1u;
    }
    int32_t az = (z < 0) ? -(int32_t)z : (int32_t)z;
    int32_t lim_q14 = m->load_max / 4;
    int32_t mag_q14 = lim_q14;
    if (az != 0) {
        int32_t x2_q28 = (int32_t)x * (int32_t)x;
        int32_t q = (x2_q28 + (az / 2)) / az;
        if (q < lim_q14) {
            mag_q14 = az + q;
            if (mag_q14 > lim_q14) {
                mag_q14 = lim_q14;
            }
        }
    }
    int32_t mag_q16 = mag_q14 * 4;
    o.load = inv ? -mag_q16 : mag_q16;
    o.inverted = (uint8_t)inv;
    if (!m->enabled || airspeed_cm_s < m->v_enable_cm_s) {
        *out = o;
        return;
    }
    /* (v_ref / V)^2 with V >= v_enable >= 100 and v_ref <= 8 v_enable: r <= 8,
     * w <= 8 * 64 = 512. v_ref * 2^16 + V / 2 < 2^31. */
    int32_t v = airspeed_cm_s;
    int32_t r_q16 = (((int32_t)m->v_ref_cm_s * 65536) + (v / 2)) / v;
    int32_t r2_q16 = q_mul32(r_q16, r_q16, 16u);
    o.loading = q_mul32(mag_q16, r2_q16, 16u);
    o.aoa_rad = q_add_sat32(m->aoa0_rad[inv], q_mul32(m->aoa1_rad[inv], o.loading, 16u));
    o.pitch_offset = q_mul32(o.aoa_rad, z, 14u);
    int32_t trim = q_add_sat32(m->trim0[inv], q_mul32(m->trim1[inv], o.loading, 16u));
    o.elevator_trim = (q14_t)q_clamp32(trim, -Q14_ONE, Q14_ONE);
    o.active = 1u;
    *out = o;
}
