/*
 * mode_params.h - the flight modes' parameters (params.def HT_PARAMS_MODES,
 * HT_PARAMS_FBW, HT_PARAMS_NAV, HT_PARAMS_AOA): the structs, their ids, the
 * rows, names and range checks (src/guidance/mode_params.c). The blocks
 * themselves: modes.h, fbw.h, nav.h, aoa_trim.h.
 */
#ifndef HELICAL_MODE_PARAMS_H
#define HELICAL_MODE_PARAMS_H

#include <stdint.h>

#include "helical/guidance/hold_params.h"
#include "helical/output/mixer.h"
#include "helical/params.h"
#include "helical/math/q14.h"

#ifdef __cplusplus
extern "C" {
#endif

/* --- fly-by-wire (fbw.h) ------------------------------------------------- */

/* The parameters: the rows of params.def HT_PARAMS_FBW (names, units,
 * ranges, defaults). */
typedef struct {
    HT_PARAMS_FBW(HT_PARAM_X_FIELD)
} ht_fbw_params_t;

/* The table's defaults: deadband 8 us, 60 deg/s, pitch ratio 0.5 (about
 * 27 deg), switch on input 5 at 1500 us. */
#define HT_FBW_PARAMS_DEFAULT                                                                      \
    {                                                                                              \
        HT_PARAMS_FBW(HT_PARAM_X_DEFAULT)                                                          \
    }

/* HT_FBW_P_<ID> of each row, in table order. */
#define HT_PARAM_X_FBW_ID(id, name, field, unit, fmt, lo, hi, def, desc) HT_FBW_P_##id,
typedef enum {
    HT_FBW_P_NONE = 0,
    HT_PARAMS_FBW(HT_PARAM_X_FBW_ID) HT_FBW_P_COUNT
} ht_fbw_param_id_t;

/* The table's row of a parameter, or NULL. */
const ht_param_info_t *ht_fbw_param_info(ht_fbw_param_id_t id);

/* The first row outside its bounds (table order), or HT_FBW_P_NONE. p must
 * not be NULL. */
ht_fbw_param_id_t ht_fbw_first_bad(const ht_fbw_params_t *p);

const char *ht_fbw_param_name(ht_fbw_param_id_t id);

/* --- waypoint guidance (nav.h) ------------------------------------------- */

/* The parameters: the rows of params.def HT_PARAMS_NAV (names, units,
 * ranges, defaults). */
typedef struct {
    HT_PARAMS_NAV(HT_PARAM_X_FIELD)
} ht_nav_params_t;

/* The table's defaults: heading law, 60 deg/s, L1 60 m, arrival 20 m, loiter
 * 60 m, home 100 m, floor 5 m/s, course from 2 m/s, looping. */
#define HT_NAV_PARAMS_DEFAULT                                                                      \
    {                                                                                              \
        HT_PARAMS_NAV(HT_PARAM_X_DEFAULT)                                                          \
    }

/* HT_NAV_P_<ID> of each row, in table order, then the waypoint list's. */
#define HT_PARAM_X_NAV_ID(id, name, field, unit, fmt, lo, hi, def, desc) HT_NAV_P_##id,
typedef enum {
    HT_NAV_P_NONE = 0,
    HT_PARAMS_NAV(HT_PARAM_X_NAV_ID) HT_NAV_P_WAYPOINT_COUNT, /* count > HT_NAV_MAX_WAYPOINTS,
                                                                 or count > 0 with a NULL list */
    HT_NAV_P_WAYPOINT, /* a waypoint out of range: index in *bad_waypoint */
    HT_NAV_P_COUNT
} ht_nav_param_id_t;

/* The table's row of a parameter, or NULL (also for the waypoint ids). */
const ht_param_info_t *ht_nav_param_info(ht_nav_param_id_t id);

/* The first row outside its bounds (table order), or HT_NAV_P_NONE (the
 * waypoints are ht_nav_init's). p must not be NULL. */
ht_nav_param_id_t ht_nav_first_bad(const ht_nav_params_t *p);

const char *ht_nav_param_name(ht_nav_param_id_t id);

/* --- the AoA / elevator-trim model (aoa_trim.h) -------------------------- */

/* The parameters in physical units (degrees, cm/s, surface fractions): the
 * rows of params.def HT_PARAMS_AOA. Joint limit: v_ref <= 8 * v_enable
 * (named HT_AOA_P_V_ENABLE). */
typedef struct {
    HT_PARAMS_AOA(HT_PARAM_X_FIELD)
} ht_aoa_params_t;

/* The table's defaults: off, v_ref 15 m/s, enabled from 8 m/s, load limit
 * 4, all coefficients 0. */
#define HT_AOA_PARAMS_DEFAULT                                                                      \
    {                                                                                              \
        HT_PARAMS_AOA(HT_PARAM_X_DEFAULT)                                                          \
    }

/* HT_AOA_P_<ID> of each row, in table order. */
#define HT_PARAM_X_AOA_ID(id, name, field, unit, fmt, lo, hi, def, desc) HT_AOA_P_##id,
typedef enum {
    HT_AOA_P_NONE = 0,
    HT_PARAMS_AOA(HT_PARAM_X_AOA_ID) HT_AOA_P_COUNT
} ht_aoa_param_id_t;

/* The table's row of a parameter, or NULL. */
const ht_param_info_t *ht_aoa_param_info(ht_aoa_param_id_t id);

/* The first row outside its bounds (table order), then the joint limit, or
 * HT_AOA_P_NONE. p must not be NULL. */
ht_aoa_param_id_t ht_aoa_first_bad(const ht_aoa_params_t *p);

const char *ht_aoa_param_name(ht_aoa_param_id_t id);

/* --- the modes' own rows and the blocks' (modes.h) ----------------------- */

/* The parameters: the modes' own rows of params.def (HT_PARAMS_MODES:
 * names, units, ranges, defaults), then what is not a row (the RC
 * calibrations, the switch thresholds, the control rate) and the blocks,
 * each with its own rows. */
typedef struct {
    HT_PARAMS_MODES(HT_PARAM_X_FIELD)
    os_rc_map_t rc;                /* manual sticks; aileron and elevator are also FBW's */
    uint8_t rc_channels;           /* the receiver's channels (the board's board_rc_count()),
                                      [1, 16]: every input read is one of them */
    uint16_t mode_threshold_us[3]; /* strictly increasing, within the valid RC window */
    uint16_t rate_hz;              /* control rate, [1, 1000]; also alt.rate_hz, speed.rate_hz */
    ht_fbw_params_t fbw;
    ht_nav_params_t nav;
    ht_aoa_params_t aoa;
    ht_alt_hold_params_t alt;
    ht_speed_hold_params_t speed;
} ht_modes_params_t;

/* HT_MODES_P_<ID> of each own row (table order), then what is not a row. */
#define HT_PARAM_X_MODES_ID(id, name, field, unit, fmt, lo, hi, def, desc) HT_MODES_P_##id,
typedef enum {
    HT_MODES_P_NONE = 0,
    HT_PARAMS_MODES(HT_PARAM_X_MODES_ID) HT_MODES_P_RC_AILERON,
    HT_MODES_P_RC_ELEVATOR,
    HT_MODES_P_RC_RUDDER,
    HT_MODES_P_RC_THROTTLE,
    HT_MODES_P_MODE_THRESHOLD,
    HT_MODES_P_RATE_HZ,
    HT_MODES_P_CONTROLLER, /* the ht_controller_t is NULL or not initialised */
    HT_MODES_P_FBW,        /* see bad->sub (ht_fbw_param_id_t) */
    HT_MODES_P_NAV,        /* see bad->sub (ht_nav_param_id_t), bad->waypoint */
    HT_MODES_P_AOA,        /* see bad->sub (ht_aoa_param_id_t) */
    HT_MODES_P_ALT_HOLD,   /* see bad->sub (ht_alt_param_id_t; RATE_HZ: != rate_hz) */
    HT_MODES_P_SPEED_HOLD, /* see bad->sub (ht_speed_param_id_t; RATE_HZ: != rate_hz) */
    HT_MODES_P_JOINT,      /* the rows are in range but not together: bad->sub is the
                              ht_cfg_status_t of ht_config_check (config_check.h), bad->waypoint
                              the leg's end for HT_CFG_ARRIVAL_RADIUS */
    HT_MODES_P_COUNT
} ht_modes_param_id_t;

/* The table's row of one of the modes' own parameters, or NULL. */
const ht_param_info_t *ht_modes_param_info(ht_modes_param_id_t id);

/* The first of the modes' own rows outside its bounds (table order), or
 * HT_MODES_P_NONE. p must not be NULL. */
ht_modes_param_id_t ht_modes_first_bad_row(const ht_modes_params_t *p);

#ifdef __cplusplus
}
#endif

#endif /* HELICAL_MODE_PARAMS_H */
