/*
 * sil_board.h - the host "board" of the SIL harness.
 *
 * A board port like the STM32 one: it owns the firmware's state and calls
 * the one firmware step (firmware/fw_step.h) once per IMU sample. Only the
 * two ends are host-specific: the "sensor drivers" here convert the
 * simulator's doubles (the IMU samples, GPS, pitot and baro synthesized from
 * JSBSim by sil/helical_sil/sensors/models.py) into the seam's fixed-point formats,
 * as a driver would from raw counts, and the "servo driver" turns each pulse
 * back into the normalized deflection JSBSim takes: (pulse - centre) / travel.
 * The scenario's commands are the step's guided command (or RC pulses for
 * the flight modes); JSBSim's true state can be given as the external
 * solution (scenario [attitude] source = "truth") for comparison.
 *
 * Floating point exists only in this host file's conversions (parameters
 * from the scenario, sensors, actuators); the step itself is the firmware's.
 *
 * Python calls it through ctypes (sil/helical_sil/sim/board.py mirrors these
 * structs; keep both in step: sil_board_abi_version() guards it).
 */
#ifndef HELICAL_SIL_BOARD_H
#define HELICAL_SIL_BOARD_H

#include <stddef.h>
#include <stdint.h>

#include "link/fw_link.h"
#include "fw_step.h"

#ifdef __cplusplus
extern "C" {
#endif

#define SIL_BOARD_ABI_VERSION                                                                      \
    15 /* 8: raw sensors, the one firmware step; 9: align_to_truth;                                \
          10: dcm_gps_latency_s; 11: law[] and estimator[] from the parameter table;               \
          12: guidance[] (the turn-rate trim);                                                     \
          13: alt_hold[] and speed_hold[] from the parameter table;                                \
          14: modes[], fbw[], nav[], aoa[] from the parameter table;                               \
          15: the MAVLink ground-station link (sil_link_*) */

/* Flight modes (ABI 6): RC pulses the scripted pilot sends, waypoints the
 * configuration can carry. */
#define SIL_RC_COUNT      8
#define SIL_MAX_WAYPOINTS 64
/* IMU samples per control step the host may give (ABI 8) */
#define SIL_IMU_MAX 32

/* Everything configurable, in physical units (host doubles). */
typedef struct {
    /* ABI 11: the control law and the estimator, one value per row of the
     * parameter table (include/helical/params.def), in its order and in its
     * units (law[HT_P_V_REF - 1] in m/s, estimator[HT_DCM_P_GPS_LATENCY - 1]
     * in ms, ...). Each must be finite and within the row's bounds; a refusal
     * quotes them. estimator[HT_DCM_P_IMU_RATE - 1] is the IMU rate, a whole
     * multiple of control_rate_hz (at most SIL_IMU_MAX samples per step).
     * sil/helical_sil/config/params.py reads the same table. */
    double law[HT_PARAM_LAW_COUNT];
    double estimator[HT_PARAM_DCM_COUNT];
    /* ABI 12: the guidance between the modes and the law (guide.h), the
     * same way */
    double guidance[HT_PARAM_GUIDE_COUNT];
    /* ABI 13: the altitude and airspeed holds (holds.h), the same way; their
     * step rate is control_rate_hz */
    double alt_hold[HT_PARAM_ALT_COUNT];
    double speed_hold[HT_PARAM_SPEED_COUNT];
    /* the altitude hold's initial integrators (pitch ratio, [-4, 4]), upright
     * and inverted: harness state, not parameters */
    double alt_integral_upright, alt_integral_inverted;
    /* output stage: servo trims, as a fraction of travel, [-1, 1] (rounded to 1 us) */
    double trim_aileron, trim_elevator, trim_rudder;
    int32_t control_rate_hz;
    /* flight modes (modes.h; ABI 6). modes_enabled = 0: the scenario's
     * commands are the firmware step's guided command; 1: the RC pulses of
     * sil_command_t go through the flight modes. */
    int32_t modes_enabled;
    int32_t modes_pitch_mode; /* ht_pitch_mode_t of the controller the modes drive */
    /* ABI 14: the modes' own rows, fly-by-wire, the waypoint guidance and the
     * AoA / elevator-trim model, one value per row of their tables (nav's
     * home_alt_m above the same datum as altitude_m: here sea level) */
    double modes[HT_PARAM_MODES_COUNT];
    double fbw[HT_PARAM_FBW_COUNT];
    double nav[HT_PARAM_NAV_COUNT];
    double aoa[HT_PARAM_AOA_COUNT];
    /* waypoints: north, east (m from the start point), altitude (m, same datum
     * as altitude_m); rounded to whole metres */
    int32_t waypoint_count;
    double waypoints[SIL_MAX_WAYPOINTS][3];
    /* ABI 15: the ground-station link's MAVLink ids, [0, 255]; 0 takes the
     * default (system: the table's LNK_SYSID row; component 1, the autopilot) */
    int32_t link_sysid, link_compid;
} sil_config_t;

/* One control step's measurements (library axes: X left, Y forward, Z down).
 * The raw part is the board seam (firmware/fw_step.h): imu_count IMU samples
 * taken since the previous control step (the last one now), GPS, pitot, baro.
 * The truth part is JSBSim's own state: the control flies on it when
 * use_truth != 0 (the estimator still runs on the raw part). */
typedef struct {
    int32_t imu_count;                 /* [0, SIL_IMU_MAX] */
    double gyro_rad_s[SIL_IMU_MAX][3]; /* body rates */
    double accel_g[SIL_IMU_MAX][3];    /* specific force, g (level flight: 0, 0, -1) */
    int32_t gps_fresh, gps_fix;        /* a new solution; 3 = 3-D fix */
    double gps_lat_deg, gps_lon_deg, gps_alt_m;
    double gps_vel_ned_m_s[3];
    int32_t airspeed_fresh;
    double
        pitot_m_s; /* INDICATED airspeed, as the pitot driver gives it (the step makes it true) */
    int32_t baro_fresh;
    double baro_alt_m;
    /* truth */
    int32_t use_truth;
    double dcm_x, dcm_y, dcm_z;    /* DCM bottom row */
    double gyro_x, gyro_y, gyro_z; /* body rates, rad/s */
    double airspeed_m_s;
    double altitude_m;
    double climb_m_s; /* + = up */
    double north_m, east_m;
    double vel_north_m_s, vel_east_m_s;
    double heading_rad;
    /* ABI 9: nonzero: before this step's samples, align the estimator to the
     * truth above (a run that starts in flight: as if aligned before takeoff) */
    int32_t align_to_truth;
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

/* Actuators (after the output stage) and the firmware's telemetry. */
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
    /* ABI 8: the estimator and the solution the control flew on */
    int32_t control_ran;
    double est_x, est_y, est_z; /* the estimate's bottom row */
    double est_roll_deg, est_pitch_deg, est_yaw_deg;
    double est_bias_rad_s[3];
    int32_t est_flags;          /* HT_DCM_F_* */
    double nav_x, nav_y, nav_z; /* the bottom row the law was given */
    double nav_airspeed_m_s, nav_altitude_m, nav_climb_m_s, nav_north_m, nav_east_m;
    int32_t guard_engaged;
} sil_actuators_t;

/* The SIL's servo channels (output stage channels, conventional defaults:
 * centre 1500 us, travel 500 us, end points 1000..2000; throttle idle 1000,
 * travel 1000). */
// cppcheck-suppress misra-c2012-5.7 ; D-ANON-ENUM: an anonymous enum has no tag to repeat
enum {
    SIL_CH_AILERON = 0,
    SIL_CH_ELEVATOR = 1,
    SIL_CH_RUDDER = 2,
    SIL_CH_THROTTLE = 3,
    SIL_CH_COUNT = 4
};

/* The host board: the firmware's configuration and state (no globals). */
typedef struct {
    fw_config_t cfg;
    fw_t fw;
    ht_waypoint_t waypoints[SIL_MAX_WAYPOINTS]; /* read by the modes (must not move) */
    fw_output_t out;                            /* the last control step */
    fw_link_t link; /* ABI 15: the ground-station link (MAVLink 2), on fw and cfg */
    uint8_t modes_enabled;
    uint8_t ready;
    /* The flight log (boards/sil/sil_log.h) sets this after init: called
     * after each control step with the step's state, its last inputs, its outputs and
     * the step's clock (IMU samples so far, in us). NULL: no log. A hook
     * rather than a call, so that this file does not depend on the log's. */
    void (*after_step)(void *ctx, const fw_t *fw, const fw_inputs_t *in, const fw_output_t *out,
                       uint64_t time_us);
    void *after_step_ctx;
} sil_board_t;

int sil_board_abi_version(void);
size_t sil_board_size(void);
size_t sil_config_size(void);
size_t sil_sensors_size(void);
size_t sil_command_size(void);
size_t sil_actuators_size(void);

/* The groups of the parameter table, in sil_config_t's arrays. */
// cppcheck-suppress misra-c2012-5.7 ; D-ANON-ENUM: an anonymous enum has no tag to repeat
enum {
    SIL_GROUP_LAW = 0,
    SIL_GROUP_ESTIMATOR = 1,
    SIL_GROUP_GUIDANCE = 2,
    SIL_GROUP_ALT_HOLD = 3,
    SIL_GROUP_SPEED_HOLD = 4,
    SIL_GROUP_MODES = 5,
    SIL_GROUP_FBW = 6,
    SIL_GROUP_NAV = 7,
    SIL_GROUP_AOA = 8,
    SIL_GROUP_COUNT = 9
};

/* The parameter table's rows, for the harness's cross-check
 * (sil/tests/test_params.py): a SIL_GROUP_*, index from 0 in the table's
 * order. NULL / 0 for anything else. */
const ht_param_info_t *sil_param_info(int group, int index);
int sil_param_count(int group);

/*
 * Convert and check the configuration. Returns 0 on success; otherwise a
 * non-zero code and the name of the offending field in err (NUL-terminated;
 * for a row of the parameter table, with its value, bounds, unit and format:
 * "kp_aileron = 65 is outside [0, 64] (per unit error, Q16)").
 */
int sil_board_init(sil_board_t *b, const sil_config_t *cfg, char *err, size_t err_len);

/* One control step: doubles in (each IMU sample through fw_step, the
 * control chain on the last one), doubles out. */
void sil_board_step(sil_board_t *b, const sil_sensors_t *s, const sil_command_t *c,
                    sil_actuators_t *a);

/* --- ABI 15: the ground-station link (firmware/link/fw_link.h) -----------------
 * The host moves bytes only, as a UART driver would: the firmware's link
 * parses them and builds every frame. sil_board_step calls
 * fw_link_after_step after each control step, with the board's clock (the
 * control steps run, at control_rate_hz, in ms). */

/* Bytes from the ground station (any split). Nothing before init. */
void sil_link_rx(sil_board_t *b, const uint8_t *bytes, size_t n);
/* Up to cap bytes to send; returns how many were written to buf. */
size_t sil_link_tx(sil_board_t *b, uint8_t *buf, size_t cap);
/* The link's counters (fw_link_counters_t) by index: how many, each one's
 * name (NULL out of range) and value (0 out of range or before init). */
int sil_link_counter_count(void);
const char *sil_link_counter_name(int index);
uint32_t sil_link_counter(const sil_board_t *b, int index);

#ifdef __cplusplus
}
#endif

#endif /* HELICAL_SIL_BOARD_H */
