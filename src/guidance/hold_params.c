/*
 * hold_params.c - the holds' parameters from the table (params.def
 * HT_PARAMS_ALT, HT_PARAMS_SPEED): defaults, names, rows and the range
 * checks that name the first bad field. See include/helical/guidance/hold_params.h.
 */
#include <stddef.h>

#include "helical/guidance/hold_params.h"
#include "helical/params/param_rows.h"

#define HOLD_RATE_MAX_HZ 1000u

// cppcheck-suppress misra-c2012-10.8 ; D-10.8-FROM-REAL: the table's bounds, folded constants
static const ht_param_info_t alt_rows[HT_PARAM_ALT_COUNT] = {HT_PARAMS_ALT(HT_PARAM_X_INFO)};
// cppcheck-suppress misra-c2012-10.8 ; D-10.8-FROM-REAL: the table's bounds, folded constants
static const ht_param_info_t speed_rows[HT_PARAM_SPEED_COUNT] = {HT_PARAMS_SPEED(HT_PARAM_X_INFO)};

static int rate_ok(uint16_t rate_hz)
{
    return (rate_hz >= 1u) && (rate_hz <= HOLD_RATE_MAX_HZ);
}

/* --- altitude hold ------------------------------------------------------- */

void ht_alt_hold_params_default(ht_alt_hold_params_t *p, uint16_t rate_hz)
{
    if (p == NULL) {
        return;
    }
    // cppcheck-suppress misra-c2012-10.8 ; D-10.8-FROM-REAL: the table's defaults, folded constants
    HT_PARAMS_ALT(HT_PARAM_X_SET_DEFAULT)
    p->rate_hz = rate_hz;
}

const ht_param_info_t *ht_alt_hold_param_info(ht_alt_param_id_t id)
{
    return ht_param_row(alt_rows, HT_PARAM_ALT_COUNT, (int)id);
}

const char *ht_alt_hold_param_name(ht_alt_param_id_t id)
{
    return (id == HT_ALT_P_RATE_HZ) ? "rate_hz" : ht_param_row_name(ht_alt_hold_param_info(id));
}

ht_alt_param_id_t ht_alt_hold_first_bad(const ht_alt_hold_params_t *p)
{
    int row = 0;
    int bad = 0;
    // cppcheck-suppress misra-c2012-10.8 ; D-10.8-FROM-REAL: the table's bounds, folded constants
    HT_PARAMS_ALT(HT_PARAM_X_FIRST_BAD)
    (void)row;
    if (bad != 0) {
        return (ht_alt_param_id_t)bad;
    }
    if (p->integral_band_cm > p->max_error_cm) {
        return HT_ALT_P_INTEGRAL_BAND;
    }
    if (p->protect_valid_cm_s > p->protect_cm_s) {
        return HT_ALT_P_PROTECT_VALID;
    }
    return rate_ok(p->rate_hz) ? HT_ALT_P_NONE : HT_ALT_P_RATE_HZ;
}

/* --- airspeed hold ------------------------------------------------------- */

void ht_speed_hold_params_default(ht_speed_hold_params_t *p, uint16_t rate_hz)
{
    if (p == NULL) {
        return;
    }
    // cppcheck-suppress misra-c2012-10.8 ; D-10.8-FROM-REAL: the table's defaults, folded constants
    HT_PARAMS_SPEED(HT_PARAM_X_SET_DEFAULT)
    p->rate_hz = rate_hz;
}

const ht_param_info_t *ht_speed_hold_param_info(ht_speed_param_id_t id)
{
    return ht_param_row(speed_rows, HT_PARAM_SPEED_COUNT, (int)id);
}

const char *ht_speed_hold_param_name(ht_speed_param_id_t id)
{
    return (id == HT_SPEED_P_RATE_HZ) ? "rate_hz" : ht_param_row_name(ht_speed_hold_param_info(id));
}

ht_speed_param_id_t ht_speed_hold_first_bad(const ht_speed_hold_params_t *p)
{
    int row = 0;
    int bad = 0;
    // cppcheck-suppress misra-c2012-10.8 ; D-10.8-FROM-REAL: the table's bounds, folded constants
    HT_PARAMS_SPEED(HT_PARAM_X_FIRST_BAD)
    (void)row;
    if (bad != 0) {
        return (ht_speed_param_id_t)bad;
    }
    if (p->throttle_max < p->throttle_min) {
        return HT_SPEED_P_THROTTLE_MAX;
    }
    return rate_ok(p->rate_hz) ? HT_SPEED_P_NONE : HT_SPEED_P_RATE_HZ;
}
