/*
 * fw_step.h - THE firmware step: raw sensors -> attitude estimate -> modes or
 * guided command -> holds -> upset guard -> helical-turn law -> mixer ->
 * output stage -> servo pulses.
 *
 * Every host calls this one function, once per IMU sample:
 *   - the flight image (firmware/fw_main.c) with the board's sensors and
 *     receiver (include/helical/board.h);
 *   - the SIL host board (boards/sil) with sensors synthesized from JSBSim;
 *   - the HIL firmware (firmware/hil/hil_fw.c) with the samples of the link.
 * No host keeps a copy of any part of it (a ctest inspects the hosts' objects
 * for calls into the law, the modes, the holds or the output stage).
 *
 * Timing: the estimator runs on every call (the IMU rate, dcm.imu_rate_hz);
 * the control chain runs on every control_divider-th call (the control rate,
 * modes.rate_hz = imu_rate_hz / control_divider), and only then are new pulses
 * produced (fw_output_t.control_ran).
 *
 * Where the commands come from:
 *   - guided (fw_inputs_t.guided != NULL): a turn rate, a pitch ratio or an
 *     altitude target, a throttle or an airspeed target, inverted flight and
 *     the pitch method, from a simulator's scenario or a companion computer;
 *   - else the pilot: the RC frame through the flight modes of modes.h
 *     (manual, fly-by-wire, waypoint, return-to-home), with the one RC-loss
 *     policy of modes.h (RTH after rc_loss_ticks bad ticks).
 * Both go through the same holds (modes.alt, modes.speed and their states),
 * the same upset guard, the same law and the same output stage.
 *
 * Where the attitude comes from: the estimator (dcm.h) on the IMU samples,
 * aided by GPS and airspeed; the GPS gives position and velocity, the baro
 * the altitude. A host that has a better solution (the SIL's "truth" source,
 * for comparison) passes fw_inputs_t.external: the control chain then flies
 * on it, and the estimator still runs so that both can be compared.
 *
 * Failsafe: no IMU sample for imu_timeout_samples calls (and no external
 * solution) -> every channel at its failsafe pulse (os_failsafe). A refused
 * configuration -> no pulses at all (fw_output_t.pulse_count = 0).
 *
 * Integer only; all state is the caller's fw_t; no allocation, no globals.
 */
#ifndef HT_FW_STEP_H
#define HT_FW_STEP_H

#include <stdint.h>

#include "helical/board.h"
#include "helical/estimator/dcm.h"
#include "helical/guidance/guide.h"
#include "helical/math/geo.h"
#include "helical/law/helical_turn.h"
#include "helical/guidance/holds.h"
#include "helical/guidance/modes.h"
#include "helical/output/output_stage.h"
#include "helical/law/upset_guard.h"

#ifdef __cplusplus
extern "C" {
#endif

#define FW_RC_MAX 16u /* = HT_MODES_RC_MAX */

/* Everything the step is configured with, in the library's formats. */
typedef struct {
    ht_dcm_params_t dcm;
    ht_params_t law;         /* pitch_mode is ignored: one controller per pitch method */
    ht_modes_params_t modes; /* also the holds (modes.alt, modes.speed) and the control rate */
    ht_guide_params_t guide; /* between the modes and the law: the turn-rate trim */
    ht_upset_guard_params_t guard;
    os_config_t out;
    const ht_waypoint_t *waypoints; /* the caller's; must outlive the fw_t */
    uint16_t waypoint_count;
    uint16_t control_divider;     /* IMU samples per control step, [1, 100]; with
                                     modes.rate_hz * control_divider == dcm.imu_rate_hz */
    uint16_t imu_timeout_samples; /* samples without IMU before the failsafe, [1, 10000] */
    uint8_t modes_pitch_mode;     /* ht_pitch_mode_t the flight modes fly with */
    int32_t alt_integral_q20[2];  /* initial altitude-hold integrators, upright / inverted */
} fw_config_t;

/* The defaults: dcm, law, modes, guard and a 5-channel conventional
 * aeroplane (0 aileron, 1 elevator, 2 throttle, 3 rudder, 4 second aileron
 * reversed), IMU 200 Hz, control 40 Hz. */
void fw_config_default(fw_config_t *cfg);

/* Which block init refused (fw_t.bad). */
typedef enum {
    FW_BAD_NONE = 0,
    FW_BAD_NULL,
    FW_BAD_DCM,   /* sub = ht_dcm_param_id_t */
    FW_BAD_LAW,   /* sub = ht_param_id_t */
    FW_BAD_MODES, /* sub = ht_modes_param_id_t (modes_bad has the detail) */
    FW_BAD_GUARD,
    FW_BAD_OUTPUT,  /* sub = the first bad channel */
    FW_BAD_DIVIDER, /* control_divider or the rates do not agree */
    FW_BAD_TIMEOUT,
    FW_BAD_GUIDE /* sub = ht_guide_param_id_t */
} fw_bad_block_t;

/* A complete navigation solution (the estimator's, or an external one). */
typedef struct {
    q14_t down_q14[3];       /* DCM bottom row: the law's tilt input */
    q11_t gyro_q11_rad_s[3]; /* body rates, bias removed */
    int16_t airspeed_cm_s;
    int32_t altitude_cm;                   /* same datum as the waypoints (mean sea level) */
    int32_t climb_cm_s;                    /* + = up */
    int32_t north_cm, east_cm;             /* from home (the first 3-D fix) */
    int32_t vel_north_cm_s, vel_east_cm_s; /* ground velocity */
    q14_t heading_north, heading_east;     /* the nose's horizontal direction */
} fw_nav_t;

/* The scenario / companion command (see above). */
typedef struct {
    q11_t turn_rate_rad_s; /* about the earth vertical, + = right */
    q16_t pitch_ratio;     /* used when altitude_hold == 0 */
    int32_t altitude_cm;   /* used when altitude_hold != 0 */
    int16_t airspeed_cm_s; /* used when speed_hold != 0 */
    q14_t throttle;        /* used when speed_hold == 0, [0, 1] */
    uint8_t altitude_hold, speed_hold, inverted, pitch_mode;
} fw_guided_t;

/* One call's inputs: the board seam (raw measurements) plus the commands. */
typedef struct {
    board_sensors_t sensors;
    uint8_t rc_fresh; /* a new complete RC frame since the previous control step */
    uint8_t rc_count;
    uint16_t rc_us[FW_RC_MAX];
    const fw_guided_t *guided; /* NULL: the pilot and the flight modes */
    const fw_nav_t *external;  /* NULL: fly on the estimate */
} fw_inputs_t;

typedef struct {
    uint8_t control_ran; /* this call ran the control chain: pulses are new */
    uint8_t pulse_count; /* channels in pulse_us (0: configuration refused) */
    uint8_t failsafe;    /* 1: IMU lost, failsafe pulses */
    uint8_t guard_engaged;
    uint8_t pitot_suspect; /* the pitot reads below half the GPS speed: GPS speed flown */
    uint8_t servo_clamped; /* a surface channel sits on an end point */
    uint16_t pulse_us[OS_MAX_CHANNELS];
    q14_t throttle;
    q16_t pitch_cmd; /* the pitch ratio given to the law */
    fw_nav_t nav;    /* the solution the control flew on */
    ht_input_t law_in;
    ht_output_t law;
    ht_modes_output_t modes; /* modes path only (else zero) */
    ht_dcm_output_t est;     /* the estimator at this control step */
} fw_output_t;

/* The state, owned by the caller (boards keep one static instance). */
typedef struct {
    const fw_config_t *cfg;
    ht_dcm_t dcm;
    ht_dcm_state_t dcm_state;
    ht_controller_t law[2]; /* index = ht_pitch_mode_t */
    ht_modes_t modes;
    ht_modes_state_t modes_state; /* its alt / speed states are the guided path's too */
    ht_guide_t guide;
    ht_guide_state_t guide_state;
    uint8_t law_flags; /* the previous control step's ht_output_t flags */
    /* The law's option inputs (docs/control-law.md "Extensions beyond the
     * seed"): the lateral specific force low-passed at the IMU rate (Q20 g,
     * time constant 2^accel_lat_shift samples, 64..100 ms); with roll_in on,
     * the guided turn command slewed at the modes' turn_slew (Q16 rad/s),
     * and the previous control step's turn command (Q16 rad/s) from which
     * the turn acceleration is taken. */
    int32_t accel_lat_q20;
    uint8_t accel_lat_shift;
    uint8_t turn_primed; /* turn_prev_q16 (and guided_turn_q16) hold a command */
    q16_t guided_turn_q16;
    q16_t turn_prev_q16;
    ht_upset_guard_state_t guard_state;
    ht_geo_origin_t home;
    fw_nav_t nav; /* the estimate path's solution between control steps */
    int32_t baro_prev_cm;
    int32_t baro_climb_cm_s; /* filtered baro rate (no GPS fix) */
    uint16_t divider_count;
    uint16_t imu_age;
    uint8_t aligned, have_home, have_baro, airspeed_live, pitot_suspect;
    int16_t pitot_cm_s;      /* the last pitot reading, made true (air_data.h) */
    int32_t pressure_alt_cm; /* the last baro reading (0 before one): the pitot's density */
    int16_t air_temp_cdeg;
    uint8_t air_temp_valid;
    uint8_t ready;
    uint8_t bad;     /* fw_bad_block_t */
    int32_t bad_sub; /* the block's own field id */
    ht_modes_bad_t modes_bad;
    uint32_t samples, control_steps;
    /* A ground station's mode (fw_link.h): 0 none, else 1 + ht_mode_t. The
     * step gives the modes the pulse that selects it in place of the mode
     * switch's, so the RC-loss failsafe still wins; moving the switch
     * (away from gcs_switch, its mode when the command came; UINT8_MAX: not
     * read yet) gives the mode back to the pilot and clears gcs_mode. */
    uint8_t gcs_mode;
    uint8_t gcs_switch;
} fw_t;

/* Check the whole configuration and initialise. 1 = ready; 0 = refused
 * (fw->bad names the block, fw->bad_sub its field): every later fw_step
 * then outputs no pulses. */
int fw_init(fw_t *fw, const fw_config_t *cfg);

/* Align the estimator to a known solution (its down row and nose direction),
 * e.g. a simulator starting in flight: the next sample then does not align
 * from its accelerometer. 0 = done; else ht_dcm_align_to's code (nothing
 * changed). */
int fw_align(fw_t *fw, const fw_nav_t *nav);

/* One IMU period. Returns out->control_ran. NULL arguments: 0, nothing done. */
int fw_step(fw_t *fw, const fw_inputs_t *in, fw_output_t *out);

#ifdef __cplusplus
}
#endif

#endif /* HT_FW_STEP_H */
