/*
 * config_check.c - the joint validity of a flight-mode configuration
 * (include/helical/guidance/config_check.h): the rules between rows.
 */
#include <stddef.h>

#include "helical/guidance/config_check.h"

/* Indexed by ht_cfg_status_t; each at most 43 characters, so that
 * ht_modes_bad_name's "joint." and the text fit a STATUSTEXT's 50 bytes with
 * a terminator; naming the rows by their table names. */
static const char *const reasons[HT_CFG_COUNT] = {
    "",
    "configuration missing",
    "rc_channels outside 1..16",
    "a stick input is not a receiver channel",
    "two sticks share one RC input",
    "mode_input is not a receiver channel",
    "mode_input is a stick channel",
    "inverted_input is not a receiver channel",
    "inverted_input is a stick channel",
    "inverted_input is the mode_input",
    "inverted_threshold_us not in (centre, full]",
    "arrival_radius_m not below half a leg",
};

const char *ht_config_reason(ht_cfg_status_t status)
{
    if ((unsigned)status >= (unsigned)HT_CFG_COUNT) {
        return "";
    }
    return reasons[status];
}

static int is_stick(const os_rc_map_t *rc, uint8_t input)
{
    return ((rc->aileron.input == input) || (rc->elevator.input == input) ||
            (rc->rudder.input == input) || (rc->throttle.input == input))
               ? 1
               : 0;
}

static ht_cfg_status_t check_inputs(const ht_modes_params_t *p)
{
    if ((p->rc_channels < 1u) || (p->rc_channels > HT_CFG_RC_MAX)) {
        return HT_CFG_RC_CHANNELS;
    }
    const uint8_t sticks[4] = {p->rc.aileron.input, p->rc.elevator.input, p->rc.rudder.input,
                               p->rc.throttle.input};
    for (unsigned i = 0u; i < 4u; ++i) {
        if (sticks[i] >= p->rc_channels) {
            return HT_CFG_STICK_ABSENT;
        }
    }
    for (unsigned i = 0u; i < 4u; ++i) {
        for (unsigned j = i + 1u; j < 4u; ++j) {
            if (sticks[i] == sticks[j]) {
                return HT_CFG_STICKS_SHARED;
            }
        }
    }
    if (p->mode_input >= p->rc_channels) {
        return HT_CFG_MODE_ABSENT;
    }
    if (is_stick(&p->rc, p->mode_input) != 0) {
        return HT_CFG_MODE_ON_STICK;
    }
    if (p->fbw.inverted_input >= p->rc_channels) {
        return HT_CFG_INVERTED_ABSENT;
    }
    if (is_stick(&p->rc, p->fbw.inverted_input) != 0) {
        return HT_CFG_INVERTED_ON_STICK;
    }
    if (p->fbw.inverted_input == p->mode_input) {
        return HT_CFG_INVERTED_ON_MODE;
    }
    /* the receiver's calibrated range is the aileron stick's: a centred
     * channel must stay upright, full deflection must reach inverted */
    const uint32_t centre = p->rc.aileron.centre_us;
    const uint32_t full = centre + p->rc.aileron.travel_us;
    const uint32_t thr = p->fbw.inverted_threshold_us;
    if ((thr <= centre) || (thr > full)) {
        return HT_CFG_INVERTED_THRESHOLD;
    }
    return HT_CFG_OK;
}

static int32_t abs32(int32_t v)
{
    return (v < 0) ? -v : v;
}

/* 1 when the horizontal distance from a to b is more than span_m (span_m
 * <= 10 000: twice the row's 5 000 m bound). Without 64-bit arithmetic: a
 * leg with either component beyond span_m is longer; else both components
 * are at most 10 000 m and the squares fit 32 bits. */
static int leg_longer(const ht_waypoint_t *a, const ht_waypoint_t *b, int32_t span_m)
{
    const int32_t dn = abs32(b->north_m - a->north_m); /* |coordinates| <= 10^7: no overflow */
    const int32_t de = abs32(b->east_m - a->east_m);
    if ((dn > span_m) || (de > span_m)) {
        return 1;
    }
    return (((dn * dn) + (de * de)) > (span_m * span_m)) ? 1 : 0;
}

static ht_cfg_status_t check_legs(const ht_modes_params_t *p, const ht_waypoint_t *w,
                                  uint16_t count, uint16_t *bad_waypoint)
{
    const int32_t span_m = 2 * (int32_t)p->nav.arrival_radius_m;
    for (uint16_t i = 1u; i < count; ++i) {
        if (leg_longer(&w[i - 1u], &w[i], span_m) == 0) {
            *bad_waypoint = i;
            return HT_CFG_ARRIVAL_RADIUS;
        }
    }
    if ((p->nav.loop != 0u) && (count >= 2u) && (leg_longer(&w[count - 1u], &w[0], span_m) == 0)) {
        *bad_waypoint = 0u;
        return HT_CFG_ARRIVAL_RADIUS;
    }
    return HT_CFG_OK;
}

ht_cfg_status_t ht_config_check(const ht_modes_params_t *p, const ht_waypoint_t *waypoints,
                                uint16_t count, uint16_t *bad_waypoint)
{
    uint16_t bad_wp = 0u;
    ht_cfg_status_t s = HT_CFG_OK;
    if ((p == NULL) || ((count > 0u) && (waypoints == NULL))) {
        s = HT_CFG_NULL;
    } else {
        s = check_inputs(p);
        if (s == HT_CFG_OK) {
            s = check_legs(p, waypoints, count, &bad_wp);
        }
    }
    if (bad_waypoint != NULL) {
        *bad_waypoint = bad_wp;
    }
    return s;
}
