/*
 * nav.h - waypoint navigation: a waypoint list in local metres, arrival, two
 * guidance laws that both give the desired earth-vertical turn rate of the
 * helical-turn law, return-to-home and a loiter circle.
 *
 * Local frame: north, east (horizontal, metres or centimetres) and altitude
 * (up). The origin is home. Turn rate: + = clockwise seen from above (a right
 * turn), as ht_input_t.
 *
 * Guidance laws (no trigonometry: every angle is a pair of unit vectors, in
 * Q28, and sin/cos of the angle between two directions are their cross and
 * dot products):
 *   HT_GUIDE_HEADING  turn = turn_rate_max * sin(e), e = the angle from the
 *                     direction of motion to the direction of the target;
 *                     beyond 90 deg (cos(e) <= 0) sin(e) is replaced by
 *                     sign(sin(e)) (sign(0) = +1: a target exactly behind is a
 *                     right turn), i.e. +-turn_rate_max.
 *   HT_GUIDE_L1       a point L1 ahead on the track (the intersection of the
 *                     circle of radius L1 about the aircraft with the track
 *                     line beyond the foot of the perpendicular; when the track
 *                     is farther than L1 the point is the foot itself); eta =
 *                     the angle from the direction of motion to that point;
 *                     lateral acceleration a = 2 V^2 sin(eta) / L1, turn =
 *                     a / V = 2 V sin(eta) / L1 with the same beyond-90 rule,
 *                     then limited to +-turn_rate_max. V = ground speed,
 *                     floored at v_floor.
 * Direction of motion: the ground velocity, or the heading vector when the
 * ground speed is below course_min (GPS course is noise at low speed) and the
 * heading vector is not zero. With neither (zero velocity and zero heading),
 * the turn is 0 (flag HT_NAV_F_NO_DIRECTION).
 *
 * Waypoints and legs: the track of a leg runs from the leg start (the
 * previous waypoint, or where navigation started) to the target waypoint. A
 * waypoint is reached when the distance to it is <= arrival_radius, or when
 * the aircraft has passed the line through it perpendicular to the track
 * (along-track >= leg length, on a leg longer than 0): then the next leg
 * starts at the reached waypoint. At most one waypoint is reached per step.
 * After the last one: loop = 1 starts over at waypoint 0; loop = 0 loiters
 * around the last one at its altitude. An empty list (count 0) loiters around
 * home at home_alt. Coincident waypoints (a leg of length 0) are flown as
 * "go to the point" and reached one step after the other.
 *
 * Loiter: a clockwise circle of loiter_radius R about the centre:
 *   desired direction = R * tangent - clamp(d - R, -R, R) * outward
 *   turn = V / R + turn_rate_max * sin(error), limited to +-turn_rate_max.
 * Return to home: the selected law flies the leg from where RTH began to
 * home; within 2 R of home it loiters (latched until a new leg starts).
 *
 * Ranges and saturation: positions are int32 centimetres (+-21,474 km);
 * every difference and length saturates at the int32 limits instead of
 * wrapping, so far-away positions give a correct direction (the unit vector
 * of a saturated difference) and a saturated distance. Velocities are
 * clamped to +-1,000,000 cm/s. Waypoints are int32 metres within
 * +-HT_NAV_COORD_MAX_M, checked at init.
 *
 * Integer only, no allocation: the waypoint array belongs to the caller and
 * must outlive the ht_nav_t (it is read, never written).
 */
#ifndef HELICAL_NAV_H
#define HELICAL_NAV_H

#include <stdint.h>

#include "helical/params.h"
#include "helical/guidance/mode_params.h"
#include "helical/math/q14.h"

#ifdef __cplusplus
extern "C" {
#endif

#define HT_NAV_COORD_MAX_M   10000000L /* +-10,000 km north / east */
#define HT_NAV_ALT_MAX_M     100000L   /* +-100 km */
#define HT_NAV_MAX_WAYPOINTS 1000u
#define HT_NAV_VEL_MAX_CM_S  1000000L
#define HT_Q28_ONE           268435456L /* 2^28 */

typedef enum { HT_GUIDE_HEADING = 0, HT_GUIDE_L1 = 1 } ht_guide_law_t;

typedef struct {
    int32_t north_m, east_m, alt_m;
} ht_waypoint_t;

/* The parameters (ht_nav_params_t) and their ids: mode_params.h. */

/* The converted parameters and the list. Read-only after ht_nav_init. */
typedef struct {
    uint8_t law, loop;
    q16_t turn_rate_max_rad_s;
    int32_t l1_cm;
    int32_t inv_l1_q36; /* 2^36 / l1_cm */
    int32_t arrival_cm, loiter_cm;
    int32_t inv_loiter_q36; /* 2^36 / loiter_cm */
    int32_t home_alt_cm;
    int32_t v_floor_cm_s, course_min_cm_s;
    const ht_waypoint_t *waypoints;
    uint16_t count;
    uint8_t ready;
} ht_nav_t;

/* The caller's navigation state. */
typedef struct {
    uint16_t index;                      /* target waypoint */
    int32_t from_north_cm, from_east_cm; /* leg start */
    uint8_t done;                        /* loop = 0 and the list is finished */
    uint8_t home_loiter;                 /* RTH reached home and circles */
    uint32_t reached;                    /* waypoints reached so far (saturating) */
} ht_nav_state_t;

/* 0 = OK, 1 = NULL nav or params, 2 = a parameter out of range (*bad_field;
 * for HT_NAV_P_WAYPOINT also *bad_waypoint, either may be NULL). */
int ht_nav_init(ht_nav_t *nav, const ht_nav_params_t *p, const ht_waypoint_t *waypoints,
                uint16_t count, ht_nav_param_id_t *bad_field, uint16_t *bad_waypoint);

/* Target waypoint 0, no leg history; the leg starts at (north, east). */
void ht_nav_reset(ht_nav_state_t *s, int32_t north_cm, int32_t east_cm);

/* Start a new leg from (north, east) to the current target (keeps the index)
 * and clear the home loiter: call on entering waypoint mode or RTH. */
void ht_nav_start_leg(ht_nav_state_t *s, int32_t north_cm, int32_t east_cm);

typedef struct {
    int32_t north_cm, east_cm;             /* position */
    int32_t vel_north_cm_s, vel_east_cm_s; /* ground velocity */
    q14_t heading_north, heading_east;     /* horizontal direction of the nose (any
                                              length), used below course_min */
} ht_nav_input_t;

enum ht_nav_flag {
    HT_NAV_F_NO_DIRECTION = 1u << 0, /* no velocity and no heading: turn 0 */
    HT_NAV_F_BEYOND_90 = 1u << 1,    /* the error angle saturated */
    HT_NAV_F_NO_WAYPOINTS = 1u << 2, /* empty list: loitering at home */
    HT_NAV_F_ZERO_LEG = 1u << 3,     /* leg of length 0: flown as go-to-point */
    HT_NAV_F_LOITER = 1u << 4,       /* circling */
    HT_NAV_F_PASSED = 1u << 5,       /* reached by passing the perpendicular line */
    HT_NAV_F_LIMITED = 1u << 6       /* the turn rate was limited to turn_rate_max */
};

typedef struct {
    q16_t turn_rate_rad_s;  /* desired earth-vertical turn rate, + = right */
    int32_t target_alt_cm;  /* altitude target for the altitude hold */
    int32_t distance_cm;    /* to the target point (saturating) */
    int32_t cross_track_cm; /* + = right of the track (loiter: d - R) */
    int32_t sin_error_q28;  /* sin of the angle the law used (after the beyond-90 rule) */
    uint16_t index;         /* target waypoint after this step */
    uint8_t arrived;        /* 1 when a waypoint was reached this step */
    uint8_t flags;          /* HT_NAV_F_* */
} ht_nav_output_t;

/* One step of waypoint navigation. NULL or an uninitialised nav: all zero. */
void ht_nav_waypoint_step(const ht_nav_t *nav, ht_nav_state_t *s, const ht_nav_input_t *in,
                          ht_nav_output_t *out);

/* One step of return-to-home (then loiter around home at home_alt). */
void ht_nav_home_step(const ht_nav_t *nav, ht_nav_state_t *s, const ht_nav_input_t *in,
                      ht_nav_output_t *out);

/*
 * The guidance primitive: sin of the angle from direction a to direction d
 * (both in any common format, any length, int32), in Q28, + when d is
 * clockwise from a (seen from above, north-east axes). Beyond 90 deg
 * (cos <= 0) it is +-2^28 with sign(0) = +1, and *beyond_90 (may be NULL) is
 * set to 1. A zero vector gives 0 (and *beyond_90 = 0).
 */
int32_t ht_nav_sin_error_q28(int32_t a_north, int32_t a_east, int32_t d_north, int32_t d_east,
                             uint8_t *beyond_90);

#ifdef __cplusplus
}
#endif

#endif /* HELICAL_NAV_H */
