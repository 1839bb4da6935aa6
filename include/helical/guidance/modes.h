/*
 * modes.h - flight modes: manual, fly-by-wire, waypoint and return-to-home,
 * selected by an RC channel, with an RC-loss failsafe and bumpless
 * transitions. This is the one call per control step that the boards and
 * the SIL make before the helical-turn step:
 *
 *   ht_modes_step(&m, &st, &in, &o);         // mode, targets, holds, AoA model
 *   ht_step(&ctl, &o.law_in, &law);          // the helical-turn law (core)
 *   ht_modes_surfaces(&o, &law, &cmd);       // + trim, manual blend -> os_command_t
 *   os_compute(&out_cfg, &cmd, pulses);      // mixer and servo output stage
 * (ht_modes_fly() does the middle three in one call.)
 *
 * Mode switch (no hysteresis; every position is far from a threshold):
 *   pulse <  thr[0]           manual
 *   thr[0] <= pulse < thr[1]  fly-by-wire
 *   thr[1] <= pulse < thr[2]  waypoint
 *   thr[2] <= pulse           return-to-home
 * Defaults 1250 / 1750 / 2100 us: a 3-position switch (1000 / 1500 / 2000 us)
 * gives manual / fly-by-wire / waypoint with 250 us of margin; RTH needs an
 * extended end point or a mix (>= 2100 us) and is normally entered by the
 * failsafe.
 *
 * RC loss. A tick's RC frame is good when the caller says it is fresh (a new
 * complete frame since the previous tick, board_rc_read_us() == BOARD_OK) and
 * every input this module reads (mode, the four sticks, the inverted switch)
 * is within [OS_RC_VALID_MIN_US, OS_RC_VALID_MAX_US]. After rc_loss_ticks bad
 * ticks in a row the RC is lost: failsafe, mode RTH, sticks ignored, upright.
 * It ends after rc_recover_ticks good ticks in a row; the switch then selects
 * the mode again. Until the loss is declared a bad tick reuses the last good
 * frame. Before the first good frame ever the failsafe is not armed: mode
 * manual, neutral surfaces, throttle 0 (a board on the bench with the
 * transmitter off must not start its motor).
 * Why return home (and circle there) rather than circle in place: most losses
 * are range losses, and flying back towards home is what brings the aircraft
 * back into range; circling where the link was lost keeps it at the edge.
 *
 * Bumpless transfer. The law has no integrator to initialise, so "bumpless"
 * means two things:
 *  1. the law's targets (turn rate, pitch ratio) are slew-limited every step
 *     (turn_slew_deg_s2, pitch_slew_per_s) from the value that matches the
 *     current state: while the surfaces are purely manual the commanded turn
 *     rate is the one that matches the current bank (ratio -X/Z at the
 *     current airspeed) and the pitch ratio the current pitch (-Y/sqrt(X^2 +
 *     Z^2), minus the AoA offset), so the law's error is zero when it takes
 *     over; between automatic modes the targets simply keep slewing;
 *  2. the surfaces are blended between manual and the law over blend_ticks
 *     (law weight = count / blend_ticks, counted up in automatic modes and
 *     down in manual), as is the throttle between stick and speed hold.
 * A change of the inverted flag is a commanded half roll, not a bump, and is
 * not slewed.
 *
 * Per-mode sources:
 *                turn rate              pitch ratio          inverted  throttle
 *   manual       (state match)          (state match)        Z < 0     stick
 *   fly-by-wire  aileron stick          elevator stick       switch    stick
 *   waypoint     nav + aileron stick    alt hold(waypoint)   switch    speed hold
 *   RTH          nav home (+ stick)     alt hold(home_alt)   switch/0  speed hold
 * (RTH in failsafe: no stick, upright.) The waypoint-mode sum is limited to
 * the nav turn_rate_max. The AoA model adds its pitch offset to the law's
 * pitch ratio and its trim to the law's elevator in every mode; both act
 * through the blend weight, so they have no effect in settled manual.
 *
 * All state is the caller's; integer only; no allocation.
 */
#ifndef HELICAL_MODES_H
#define HELICAL_MODES_H

#include <stdint.h>

#include "helical/guidance/aoa_trim.h"
#include "helical/guidance/fbw.h"
#include "helical/law/helical_turn.h"
#include "helical/guidance/holds.h"
#include "helical/output/mixer.h"
#include "helical/guidance/nav.h"
#include "helical/guidance/mode_params.h"
#include "helical/math/q14.h"

#ifdef __cplusplus
extern "C" {
#endif

#define HT_MODES_RC_MAX 16u

typedef enum {
    HT_MODE_MANUAL = 0,
    HT_MODE_FBW = 1,
    HT_MODE_WAYPOINT = 2,
    HT_MODE_RTH = 3,
    HT_MODE_COUNT
} ht_mode_t;

/* The parameters (ht_modes_params_t) and their ids (ht_modes_param_id_t):
 * mode_params.h. */

/* Fills p with the defaults documented in docs/flight-modes.md (RC inputs
 * 0 aileron, 1 elevator, 2 throttle, 3 rudder, 4 mode, 5 inverted). */
void ht_modes_params_default(ht_modes_params_t *p);

/* Which field init refused: field, and for the sub-modules their field. */
typedef struct {
    ht_modes_param_id_t field;
    int sub;           /* ht_fbw/nav/aoa/alt/speed_param_id_t when field is FBW / NAV / AOA /
                          ALT_HOLD / SPEED_HOLD */
    uint16_t waypoint; /* the bad waypoint's index for HT_NAV_P_WAYPOINT */
} ht_modes_bad_t;

/* "mode_threshold_us", "fbw.deadband_us", "nav.l1_m", ... into buf (always
 * terminated; at most size - 1 characters). */
void ht_modes_bad_name(const ht_modes_bad_t *bad, char *buf, unsigned size);

typedef struct {
    os_rc_map_t rc;
    uint8_t mode_input;
    uint16_t mode_threshold_us[3];
    uint16_t rc_loss_ticks, rc_recover_ticks, blend_ticks;
    q16_t turn_slew_rad_s_per_tick;
    q16_t pitch_slew_per_tick;
    q16_t max_tilt;     /* from the controller: limit of the state-matched ratio */
    int16_t v_min_cm_s; /* from the controller: airspeed floor of the state match */
    int16_t cruise_cm_s;
    ht_fbw_t fbw;
    ht_nav_t nav;
    ht_aoa_t aoa;
    ht_alt_hold_params_t alt;
    ht_speed_hold_params_t speed;
    uint8_t ready;
} ht_modes_t;

/*
 * Check every parameter and convert. ctl is the initialised helical-turn
 * controller the caller will step (its v_min and max_tilt are the state
 * match's). The waypoint list is the caller's and must outlive m.
 * 0 = OK, 1 = NULL, 2 = a parameter out of range (see *bad, may be NULL).
 */
int ht_modes_init(ht_modes_t *m, const ht_modes_params_t *p, const ht_controller_t *ctl,
                  const ht_waypoint_t *waypoints, uint16_t count, ht_modes_bad_t *bad);

typedef struct {
    uint8_t mode; /* ht_mode_t in effect */
    uint8_t rc_lost;
    uint8_t have_rc; /* a good frame was seen once */
    uint8_t law_inverted;
    uint16_t bad_ticks, good_ticks;
    uint16_t blend_count, throttle_blend_count;
    uint8_t rc_count;
    uint16_t rc_us[HT_MODES_RC_MAX]; /* the last good frame */
    q16_t turn_cmd_rad_s;            /* slewed turn-rate target */
    q16_t pitch_cmd;                 /* slewed pitch-ratio target (before the AoA offset) */
    ht_nav_state_t nav;
    ht_alt_hold_state_t alt;
    ht_speed_hold_state_t speed;
} ht_modes_state_t;

/* Manual, no RC yet, first waypoint, the leg starting at (north, east). */
void ht_modes_reset(ht_modes_state_t *st, int32_t north_cm, int32_t east_cm);

/* One control step's inputs. */
typedef struct {
    uint16_t rc_us[HT_MODES_RC_MAX]; /* RC pulses; 0 = no pulse */
    uint8_t rc_count;                /* pulses given, <= HT_MODES_RC_MAX */
    uint8_t rc_fresh;                /* a new complete frame since the previous tick */
    q14_t x, y, z;                   /* DCM bottom row */
    q11_t gyro_rad_s[3];             /* body rates about X, Y, Z */
    int16_t airspeed_cm_s;
    int32_t north_cm, east_cm;             /* position, local frame, home = origin */
    int32_t alt_cm;                        /* altitude, same datum as the waypoints */
    int32_t climb_cm_s;                    /* vertical speed, + = up */
    int32_t vel_north_cm_s, vel_east_cm_s; /* ground velocity */
    q14_t heading_north, heading_east;     /* nose direction (DCM first row's north
                                              and east parts), used at low ground speed */
} ht_modes_input_t;

typedef struct {
    uint8_t mode;          /* ht_mode_t in effect */
    uint8_t selected_mode; /* what the switch says (last good frame) */
    uint8_t failsafe;      /* 1: RC lost */
    uint8_t rc_good;       /* this tick's frame was good */
    uint8_t mode_changed;  /* the mode in effect changed this step */
    ht_input_t law_in;     /* the complete input of ht_step */
    q14_t throttle;        /* [0, 1] */
    q14_t elevator_trim;   /* AoA model trim, added to the law's elevator */
    q14_t blend;           /* weight of the law's surfaces, [0, 1] */
    os_command_t manual;   /* the pilot's sticks (last good frame; neutral before any) */
    q16_t turn_target_rad_s, pitch_target; /* before the slew */
    ht_nav_output_t nav;                   /* waypoint / RTH only, else zero */
    ht_aoa_output_t aoa;
} ht_modes_output_t;

/* One step. NULL or an uninitialised m: *out zeroed, state untouched. */
void ht_modes_step(const ht_modes_t *m, ht_modes_state_t *st, const ht_modes_input_t *in,
                   ht_modes_output_t *out);

/*
 * The surfaces: law (+ trim on the elevator, clamped to [-1, 1]) blended with
 * the manual sticks: cmd = manual + blend * (law - manual); throttle =
 * out->throttle. NULL law reads as all-zero surfaces.
 */
void ht_modes_surfaces(const ht_modes_output_t *o, const ht_output_t *law, os_command_t *cmd);

/* ht_modes_step, ht_step and ht_modes_surfaces in one call (law may be NULL). */
void ht_modes_fly(const ht_modes_t *m, ht_modes_state_t *st, const ht_controller_t *ctl,
                  const ht_modes_input_t *in, ht_modes_output_t *out, ht_output_t *law,
                  os_command_t *cmd);

/* The mode a switch pulse selects (thresholds as above; any pulse). */
ht_mode_t ht_modes_from_pulse(const ht_modes_t *m, uint16_t pulse_us);

#ifdef __cplusplus
}
#endif

#endif /* HELICAL_MODES_H */
