/*
 * sil_board.h - the host "board" of the SIL harness.
 *
 * It fills the same seam as the dsPIC and STM32 boards: the sensor seam of
 * include/helical/board.h (board_sensors_t: DCM bottom row Q14, gyros Q11,
 * airspeed cm/s) plus a baro altitude and vertical speed, then the firmware
 * control step (altitude and airspeed holds -> the helical-turn core -> the
 * library's output stage, output_stage.h, with the trim found by JSBSim
 * carried as servo trims in microseconds), and servo pulses out. Only the two
 * ends differ from a real board: the "sensor driver" here converts the
 * simulator's doubles into the seam's fixed-point formats (as an IMU/ADC
 * driver would from raw counts), and the "servo driver" turns each pulse back
 * into the normalized deflection JSBSim takes: (pulse - centre) / travel.
 *
 * Not used here: boards/common/fw_loop.c, the pilot-facing loop (RC sticks,
 * mode switch, failsafe). The SIL's commands come from a scenario instead of
 * an RC receiver, and include the altitude/airspeed holds and the inverted
 * flag that the stick loop does not have.
 *
 * The fixed-point part (sil_fw_step) is integer only and uses the library
 * exactly as a board does. Floating point exists only in this host file's
 * conversions (parameters from the scenario, sensors, actuators).
 *
 * Python calls it through ctypes (sil/helical_sil/board.py mirrors these
 * structs; keep both in step: sil_board_abi_version() guards it).
 */
#ifndef HELICAL_SIL_BOARD_H
#define HELICAL_SIL_BOARD_H

#include <stddef.h>
#include <stdint.h>

#include "helical/board.h"
#include "helical/helical_turn.h"
#include "helical/holds.h"
#include "helical/modes.h"
#include "helical/output_stage.h"
#include "helical/upset_guard.h"

#ifdef __cplusplus
extern "C" {
#endif

#define SIL_BOARD_ABI_VERSION 7

/* Flight modes (ABI 6): RC pulses the scripted pilot sends, waypoints the
 * configuration can carry. */
#define SIL_RC_COUNT      8
#define SIL_MAX_WAYPOINTS 64

/* Everything configurable, in physical units (host doubles). */
typedef struct {
    /* the control law, by control-law.md name */
    double kp_aileron, kp_elevator, kp_rudder;
    double kff_aileron, kff_elevator, kff_rudder;
    double kd_aileron, kd_elevator, kd_rudder;
    double v_ref_m_s, v_min_m_s, max_tilt;
    int32_t schedule;
    /* altitude hold (holds.h) */
    double alt_kp_pitch_per_m, alt_ki_pitch_per_m_s, alt_kd_pitch_per_m_s;
    double alt_max_pitch, alt_max_integral_pitch, alt_max_error_m, alt_integral_band_m;
    /* initial integrator values (pitch ratio), upright and inverted */
    double alt_integral_upright, alt_integral_inverted;
    /* airspeed hold */
    double spd_throttle_trim, spd_throttle_min, spd_throttle_max;
    double spd_kp_throttle_per_m_s, spd_ki_throttle_per_m, spd_kff_throttle_per_pitch;
    double spd_max_integral_throttle;
    /* output stage: servo trims, as a fraction of travel, [-1, 1] (rounded to 1 us) */
    double trim_aileron, trim_elevator, trim_rudder;
    int32_t control_rate_hz;
    /* flight modes (modes.h; ABI 6). modes_enabled = 0: the scenario's
     * commands drive the holds and the law directly (as before); 1: every
     * step runs ht_modes_step -> ht_step -> ht_modes_surfaces on the RC
     * pulses of sil_command_t, and the command's other fields are unused. */
    int32_t modes_enabled;
    int32_t modes_pitch_mode; /* ht_pitch_mode_t of the controller the modes drive */
    int32_t nav_law;          /* ht_guide_law_t */
    int32_t nav_loop;
    int32_t rc_loss_ticks, rc_recover_ticks, blend_ticks;
    double nav_turn_rate_max_deg_s, nav_l1_m, nav_arrival_radius_m, nav_loiter_radius_m;
    double nav_home_alt_m; /* above the same datum as altitude_m (here: sea level) */
    double cruise_m_s;
    double fbw_turn_rate_max_deg_s, fbw_pitch_max, fbw_deadband_us;
    double turn_slew_deg_s2, pitch_slew_per_s;
    /* the AoA / elevator-trim model (aoa_trim.h) */
    int32_t aoa_enabled;
    double aoa_v_ref_m_s, aoa_v_enable_m_s, aoa_load_max;
    double aoa_normal_deg, aoa_normal_slope_deg, aoa_inverted_deg, aoa_inverted_slope_deg;
    double aoa_trim_normal, aoa_trim_normal_slope, aoa_trim_inverted, aoa_trim_inverted_slope;
    /* waypoints: north, east (m from the start point), altitude (m, same datum
     * as altitude_m); rounded to whole metres */
    int32_t waypoint_count;
    double waypoints[SIL_MAX_WAYPOINTS][3];
    /* ABI 7: the altitude hold's airspeed protection (holds.h; protect 0 = off) */
    double alt_protect_m_s, alt_protect_valid_m_s, alt_kv_pitch_per_m_s, alt_protect_tau_s;
} sil_config_t;

/* One control step's sensor readings (library axes: X left, Y forward, Z down). */
typedef struct {
    double dcm_x, dcm_y, dcm_z;    /* DCM bottom row */
    double gyro_x, gyro_y, gyro_z; /* body rates, rad/s */
    double airspeed_m_s;
    double altitude_m;
    double climb_m_s; /* + = up */
    /* navigation (ABI 6): position from the start point, ground velocity, true heading */
    double north_m, east_m;
    double vel_north_m_s, vel_east_m_s;
    double heading_rad;
} sil_sensors_t;

/* What the pilot / mission asks this step. */
typedef struct {
    double turn_rate_rad_s; /* + = right turn */
    double pitch_ratio;     /* used when altitude_hold == 0 */
    double altitude_m;      /* used when altitude_hold != 0 */
    double airspeed_m_s;    /* used when speed_hold != 0 */
    double throttle;        /* used when speed_hold == 0, [0, 1] */
    int32_t altitude_hold;
    int32_t speed_hold;
    int32_t inverted;
    int32_t pitch_mode; /* ht_pitch_mode_t */
    /* flight modes (ABI 6): the receiver. Pulses in us (0 = no pulse), inputs
     * 0 aileron, 1 elevator, 2 throttle, 3 rudder, 4 mode switch, 5 inverted
     * switch; rc_fresh = 0 simulates a dead receiver. */
    int32_t rc_us[SIL_RC_COUNT];
    int32_t rc_fresh;
} sil_command_t;

/* Actuators (after the output stage) and the law's telemetry. */
typedef struct {
    double aileron, elevator, rudder, throttle;   /* servo commands, [-1, 1] / [0, 1] */
    double law_aileron, law_elevator, law_rudder; /* the core's surfaces before trims */
    double pitch_cmd;                             /* pitch ratio given to the core */
    double turn_rate_used_rad_s;
    double roll_error, pitch_error;
    int32_t flags; /* HT_F_* of the step, | 0x100 when a servo output clamped */
    /* flight modes (ABI 6; zero when modes are off) */
    int32_t mode, selected_mode, failsafe, rc_good, inverted_cmd;
    int32_t nav_index, nav_arrived, nav_flags, nav_reached;
    double turn_target_rad_s;                 /* the mode's turn-rate target before the slew */
    double turn_cmd_rad_s;                    /* the slewed target given to the law */
    double nav_turn_rate_rad_s;               /* the guidance law's own output */
    double cross_track_m;                     /* signed, + = right of the leg (loiter: d - R) */
    double nav_distance_m;                    /* to the target point */
    double target_altitude_m;                 /* the altitude hold's target (waypoint / RTH) */
    double leg_from_north_m, leg_from_east_m; /* where the current leg starts */
    double blend;
    double aoa_pitch_offset, aoa_trim, aoa_loading;
    int32_t aoa_active;
} sil_actuators_t;

/* The SIL's servo channels (output stage channels, conventional defaults:
 * centre 1500 us, travel 500 us, end points 1000..2000; throttle idle 1000,
 * travel 1000). */
enum {
    SIL_CH_AILERON = 0,
    SIL_CH_ELEVATOR = 1,
    SIL_CH_RUDDER = 2,
    SIL_CH_THROTTLE = 3,
    SIL_CH_COUNT = 4
};

/* The firmware's state, owned by the caller (no globals). */
typedef struct {
    ht_controller_t law[2]; /* index = ht_pitch_mode_t */
    ht_alt_hold_params_t alt;
    ht_alt_hold_state_t alt_state;
    ht_speed_hold_params_t spd;
    ht_speed_hold_state_t spd_state;
    ht_upset_guard_params_t ug; /* the library defaults, as in the HIL firmware */
    ht_upset_guard_state_t ug_state;
    os_config_t out;                            /* the output stage: trims live here, in us */
    ht_waypoint_t waypoints[SIL_MAX_WAYPOINTS]; /* read by modes.nav (must not move) */
    ht_modes_t modes;
    ht_modes_state_t modes_state;
    uint8_t modes_enabled, modes_pitch_mode;
    uint8_t ready;
} sil_board_t;

/* Fixed-point command of the firmware step. */
typedef struct {
    q11_t turn_rate_rad_s;
    q16_t pitch_ratio;
    int32_t altitude_cm;
    int16_t airspeed_cm_s;
    q14_t throttle;
    uint8_t altitude_hold, speed_hold, inverted, pitch_mode;
    uint16_t rc_us[SIL_RC_COUNT]; /* modes: what board_rc_read_us would give */
    uint8_t rc_fresh;
} sil_fw_command_t;

/* Fixed-point sensors of the firmware step: the board.h seam plus baro. */
typedef struct {
    board_sensors_t imu;
    int32_t altitude_cm;
    int32_t climb_cm_s;                    /* + = up */
    int32_t north_cm, east_cm;             /* GPS position, local frame, origin = start */
    int32_t vel_north_cm_s, vel_east_cm_s; /* GPS ground velocity */
    q14_t heading_north, heading_east;     /* nose direction (used at low ground speed) */
} sil_fw_sensors_t;

typedef struct {
    uint16_t pulse_us[SIL_CH_COUNT]; /* what board_servo_write_us would get */
    q14_t throttle;
    q16_t pitch_cmd;
    ht_output_t law;
    uint8_t servo_clamped;   /* a surface pulse sits on an end point */
    ht_modes_output_t modes; /* modes on: the step's mode output (else zero) */
} sil_fw_output_t;

int sil_board_abi_version(void);
size_t sil_board_size(void);
size_t sil_config_size(void);
size_t sil_sensors_size(void);
size_t sil_command_size(void);
size_t sil_actuators_size(void);

/*
 * Convert and check the configuration. Returns 0 on success; otherwise a
 * non-zero code and the name of the offending field in err (NUL-terminated).
 */
int sil_board_init(sil_board_t *b, const sil_config_t *cfg, char *err, size_t err_len);

/* The integer-only firmware control step (what a board's control loop runs). */
void sil_fw_step(sil_board_t *b, const sil_fw_sensors_t *s, const sil_fw_command_t *c,
                 sil_fw_output_t *o);

/* Host wrapper: doubles in, doubles out, through sil_fw_step. */
void sil_board_step(sil_board_t *b, const sil_sensors_t *s, const sil_command_t *c,
                    sil_actuators_t *a);

#ifdef __cplusplus
}
#endif

#endif /* HELICAL_SIL_BOARD_H */
