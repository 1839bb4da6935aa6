/*
 * config_check.h - the joint validity of a whole flight-mode configuration:
 * the rules no single row of params.def can judge (src/guidance/
 * config_check.c; docs/parameters.md "Joint validity").
 *
 * Every row has its own range, but a set of rows can be in range one by one
 * and still lose the aircraft: the mode switch on the aileron stick, the
 * inverted switch on a channel the receiver does not have, an inverted
 * threshold that a centred channel already reaches, an arrival radius that
 * "reaches" a waypoint every step. ht_config_check is the one rule for all
 * of them. ht_modes_init calls it after the rows' own checks, so it is
 * applied identically wherever a configuration is made live: at boot
 * (fw_init), on every parameter set of the link (the modes are
 * re-initialised from the changed configuration, and a refusal restores the
 * old value), on a stored set (the Matek loader runs fw_init on it and keeps
 * the defaults when it fails) and on a mission (the modes are re-initialised
 * with the new list).
 *
 * Integer only, no state; run at configuration time, never per step.
 */
#ifndef HELICAL_CONFIG_CHECK_H
#define HELICAL_CONFIG_CHECK_H

#include <stdint.h>

#include "helical/guidance/mode_params.h"
#include "helical/guidance/nav.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The most channels a receiver gives the modes (= HT_MODES_RC_MAX, which
 * modes.c asserts; not included from modes.h, which includes this). */
#define HT_CFG_RC_MAX 16u

/* What the configuration breaks, first rule first (the order of the
 * checks). */
typedef enum {
    HT_CFG_OK = 0,
    HT_CFG_NULL,               /* NULL parameters, or count > 0 with a NULL list */
    HT_CFG_RC_CHANNELS,        /* rc_channels outside [1, HT_CFG_RC_MAX] */
    HT_CFG_STICK_ABSENT,       /* a stick's input is not a channel of the receiver */
    HT_CFG_STICKS_SHARED,      /* two sticks on one input */
    HT_CFG_MODE_ABSENT,        /* the mode switch is not a channel of the receiver */
    HT_CFG_MODE_ON_STICK,      /* the mode switch is a stick's input */
    HT_CFG_INVERTED_ABSENT,    /* the inverted switch is not a channel of the receiver */
    HT_CFG_INVERTED_ON_STICK,  /* the inverted switch is a stick's input */
    HT_CFG_INVERTED_ON_MODE,   /* the inverted switch is the mode switch's input */
    HT_CFG_INVERTED_THRESHOLD, /* not above the stick centre, or beyond full stick */
    HT_CFG_ARRIVAL_RADIUS,     /* 2 x arrival radius >= a leg of the list (*bad_waypoint:
                                  the leg's end; the closing leg when looping ends at 0) */
    HT_CFG_COUNT
} ht_cfg_status_t;

/*
 * Judge p (with its blocks' rows already in range) and the waypoint list.
 * The rules:
 *   - the receiver has rc_channels channels, 1 .. HT_CFG_RC_MAX;
 *   - the four sticks' inputs are channels of the receiver, all distinct;
 *   - the mode switch and the inverted switch are channels of the receiver,
 *     neither is a stick's input, and they differ (a mode switch also
 *     switching inverted flight would turn the aircraft over on a mode
 *     change);
 *   - the inverted threshold is strictly above the aileron stick's centre
 *     and at most its full travel (centre + travel): a channel held at the
 *     centre (an unassigned channel of a CRSF receiver sits at 1500 us) never
 *     commands inverted, and the switch can reach it;
 *   - every leg of the list (waypoint i-1 to i, and last to first when the
 *     list loops and has two or more) is longer than twice the arrival
 *     radius: once a waypoint is reached (within the radius) the next one
 *     is farther than the radius, so each waypoint is reached once, not one
 *     per step.
 * Returns the first broken rule (enum order) or HT_CFG_OK; *bad_waypoint
 * (may be NULL) is the leg's end for HT_CFG_ARRIVAL_RADIUS, else 0.
 */
ht_cfg_status_t ht_config_check(const ht_modes_params_t *p, const ht_waypoint_t *waypoints,
                                uint16_t count, uint16_t *bad_waypoint);

/* The reason as the ground station reads it, naming the rows; at most 43
 * characters, so that ht_modes_bad_name's "joint.<reason>" fits a
 * STATUSTEXT (49 characters); "" for HT_CFG_OK and outside the enum. */
const char *ht_config_reason(ht_cfg_status_t status);

#ifdef __cplusplus
}
#endif

#endif /* HELICAL_CONFIG_CHECK_H */
