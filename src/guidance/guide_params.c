/*
 * guide_params.c - the guidance's parameters: defaults, range checks that
 * name the field, and the one-time conversion to a step rate (ht_guide_init).
 * See include/helical/guidance/guide.h.
 */
#include <stddef.h>

#include "helical/guidance/guide.h"
#include "helical/params/param_rows.h"

// cppcheck-suppress misra-c2012-10.8 ; D-10.8-FROM-REAL: the table's bounds, folded constants
static const ht_param_info_t rows[HT_PARAM_GUIDE_COUNT] = {HT_PARAMS_GUIDE(HT_PARAM_X_INFO)};

const char *ht_guide_param_name(ht_guide_param_id_t id)
{
    return ht_param_row_name(ht_guide_param_info(id));
}

const ht_param_info_t *ht_guide_param_info(ht_guide_param_id_t id)
{
    return ht_param_row(rows, HT_PARAM_GUIDE_COUNT, (int)id);
}

/* One row's default (params.def), folded to an integer constant. */
#define SET_DEFAULT(id, name, field, unit, fmt, lo, hi, def, desc)                                 \
    p->field = HT_PARAM_RAW_##fmt(def);

void ht_guide_params_default(ht_guide_params_t *p)
{
    if (p == NULL) {
        return;
    }
    // cppcheck-suppress misra-c2012-10.8 ; D-10.8-FROM-REAL: the table's defaults, folded constants
    HT_PARAMS_GUIDE(SET_DEFAULT)
}

static int in_range(int32_t v, int32_t lo, int32_t hi)
{
    return (v >= lo) && (v <= hi);
}

/* One row's range check (params.def). */
#define RANGE_CHECK(id, name, field, unit, fmt, lo, hi, def, desc)                                 \
    if (!in_range((int32_t)p->field, HT_PARAM_RAW_##fmt(lo), HT_PARAM_RAW_##fmt(hi))) {            \
        return HT_GUIDE_P_##id;                                                                    \
    }

/* The first parameter out of its range (table order), or HT_GUIDE_P_NONE. */
static ht_guide_param_id_t first_bad(const ht_guide_params_t *p)
{
    // cppcheck-suppress misra-c2012-10.8 ; D-10.8-FROM-REAL: the table's bounds, folded constants
    HT_PARAMS_GUIDE(RANGE_CHECK)
    return HT_GUIDE_P_NONE;
}

int ht_guide_init(ht_guide_t *g, const ht_guide_params_t *p, uint16_t rate_hz,
                  ht_guide_param_id_t *bad)
{
    if (bad != NULL) {
        *bad = HT_GUIDE_P_NONE;
    }
    if (g == NULL || p == NULL) {
        return 1;
    }
    const ht_guide_t zero = {0};
    *g = zero; /* unusable until every check has passed */
    const ht_guide_param_id_t b = first_bad(p);
    if (b != HT_GUIDE_P_NONE) {
        if (bad != NULL) {
            *bad = b;
        }
        return 2;
    }
    if (rate_hz < 1u || rate_hz > 1000u) {
        return 3;
    }
    ht_guide_t c = zero;
    c.p = *p;
    const uint32_t rate = rate_hz;
    /* Q16 rad/s to Q11, rounded; at least one LSB (0.028 deg/s) */
    const int32_t min_q11 = q_rshift_round(p->turn_trim_min_rate_rad_s, 5u);
    c.min_rate_q11 = (q11_t)((min_q11 < 1) ? 1 : min_q11); /* <= 4 rad/s = 8192 */
    /* tau * rate in steps: (Q16 >> 4) * rate <= 491520 * 1000 fits, then >> 12 */
    const uint32_t tau_u = (uint32_t)p->turn_trim_tau_s;
    const uint32_t tau_steps = (((tau_u >> 4) * rate) + 2048u) >> 12;
    c.tau_ticks = (tau_steps < 1u) ? 1 : (int32_t)tau_steps;
    c.max_q30 = p->turn_trim_max * 16384; /* <= 0.5 * 2^30 */
    /* hold * rate in steps: <= 655360 * 1000 fits */
    const uint32_t hold_u = (uint32_t)p->turn_trim_hold_s;
    c.hold_ticks = (uint16_t)(((hold_u * rate) + 32768u) >> 16);
    c.rate_hz = rate_hz;
    c.ready = 1u;
    *g = c;
    return 0;
}
