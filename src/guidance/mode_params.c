/*
 * mode_params.c - the flight modes' parameters from the table (params.def
 * HT_PARAMS_MODES, HT_PARAMS_FBW, HT_PARAMS_NAV, HT_PARAMS_AOA): names, rows
 * and the range checks that name the first bad field. The checks of what is
 * not a row (RC calibrations, switch thresholds, the rate, waypoints) stay
 * with their modules (modes.c, nav.c).
 */
#include <stddef.h>

#include "helical/guidance/mode_params.h"
#include "helical/params/param_rows.h"

// cppcheck-suppress misra-c2012-10.8 ; D-10.8-FROM-REAL: the table's bounds, folded constants
static const ht_param_info_t modes_rows[HT_PARAM_MODES_COUNT] = {HT_PARAMS_MODES(HT_PARAM_X_INFO)};
// cppcheck-suppress misra-c2012-10.8 ; D-10.8-FROM-REAL: the table's bounds, folded constants
static const ht_param_info_t fbw_rows[HT_PARAM_FBW_COUNT] = {HT_PARAMS_FBW(HT_PARAM_X_INFO)};
// cppcheck-suppress misra-c2012-10.8 ; D-10.8-FROM-REAL: the table's bounds, folded constants
static const ht_param_info_t nav_rows[HT_PARAM_NAV_COUNT] = {HT_PARAMS_NAV(HT_PARAM_X_INFO)};
// cppcheck-suppress misra-c2012-10.8 ; D-10.8-FROM-REAL: the table's bounds, folded constants
static const ht_param_info_t aoa_rows[HT_PARAM_AOA_COUNT] = {HT_PARAMS_AOA(HT_PARAM_X_INFO)};

/* --- the modes' own rows --------------------------------------------------- */

const ht_param_info_t *ht_modes_param_info(ht_modes_param_id_t id)
{
    return ht_param_row(modes_rows, HT_PARAM_MODES_COUNT, (int)id);
}

ht_modes_param_id_t ht_modes_first_bad_row(const ht_modes_params_t *p)
{
    int row = 0;
    int bad = 0;
    // cppcheck-suppress misra-c2012-10.8 ; D-10.8-FROM-REAL: the table's bounds, folded constants
    HT_PARAMS_MODES(HT_PARAM_X_FIRST_BAD)
    (void)row;
    return (ht_modes_param_id_t)bad;
}

/* --- fly-by-wire ----------------------------------------------------------- */

const ht_param_info_t *ht_fbw_param_info(ht_fbw_param_id_t id)
{
    return ht_param_row(fbw_rows, HT_PARAM_FBW_COUNT, (int)id);
}

const char *ht_fbw_param_name(ht_fbw_param_id_t id)
{
    return ht_param_row_name(ht_fbw_param_info(id));
}

ht_fbw_param_id_t ht_fbw_first_bad(const ht_fbw_params_t *p)
{
    int row = 0;
    int bad = 0;
    // cppcheck-suppress misra-c2012-10.8 ; D-10.8-FROM-REAL: the table's bounds, folded constants
    HT_PARAMS_FBW(HT_PARAM_X_FIRST_BAD)
    (void)row;
    return (ht_fbw_param_id_t)bad;
}

/* --- waypoint guidance ----------------------------------------------------- */

const ht_param_info_t *ht_nav_param_info(ht_nav_param_id_t id)
{
    return ht_param_row(nav_rows, HT_PARAM_NAV_COUNT, (int)id);
}

const char *ht_nav_param_name(ht_nav_param_id_t id)
{
    if (id == HT_NAV_P_WAYPOINT_COUNT) {
        return "count";
    }
    if (id == HT_NAV_P_WAYPOINT) {
        return "waypoints";
    }
    return ht_param_row_name(ht_nav_param_info(id));
}

ht_nav_param_id_t ht_nav_first_bad(const ht_nav_params_t *p)
{
    int row = 0;
    int bad = 0;
    // cppcheck-suppress misra-c2012-10.8 ; D-10.8-FROM-REAL: the table's bounds, folded constants
    HT_PARAMS_NAV(HT_PARAM_X_FIRST_BAD)
    (void)row;
    return (ht_nav_param_id_t)bad;
}

/* --- the AoA / elevator-trim model ----------------------------------------- */

const ht_param_info_t *ht_aoa_param_info(ht_aoa_param_id_t id)
{
    return ht_param_row(aoa_rows, HT_PARAM_AOA_COUNT, (int)id);
}

const char *ht_aoa_param_name(ht_aoa_param_id_t id)
{
    return ht_param_row_name(ht_aoa_param_info(id));
}

ht_aoa_param_id_t ht_aoa_first_bad(const ht_aoa_params_t *p)
{
    int row = 0;
    int bad = 0;
    // cppcheck-suppress misra-c2012-10.8 ; D-10.8-FROM-REAL: the table's bounds, folded constants
    HT_PARAMS_AOA(HT_PARAM_X_FIRST_BAD)
    (void)row;
    if (bad != 0) {
        return (ht_aoa_param_id_t)bad;
    }
    /* the loading's (v_ref / V)^2 is bounded by 64 above v_enable */
    if ((int32_t)p->v_ref_cm_s > (8 * (int32_t)p->v_enable_cm_s)) {
        return HT_AOA_P_V_ENABLE;
    }
    return HT_AOA_P_NONE;
}
