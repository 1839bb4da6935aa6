/*
 * board.h - what the portable firmware needs from a board.
 *
 * One implementation per board lives in boards/<name>/ and is chosen at link
 * time: every board defines exactly these functions, the firmware's main
 * loop (firmware/fw_main.c) calls only these, and no portable file ever
 * includes a board's own header. A board keeps its driver state in its own
 * file (static instances of caller-owned driver structs); the library in src/
 * holds no state at all.
 *
 * Units: pulse widths in microseconds (uint16_t *_us), rates in hertz.
 * Channels are numbered from 0.
 *
 * Porting to a new board: implement every function below in
 * boards/<name>/board_<name>.c, add a CMakeLists.txt that links it with
 * firmware/ (ht_firmware) and the helical library, and see boards/README.md.
 */
#ifndef HELICAL_BOARD_H
#define HELICAL_BOARD_H

#include <stddef.h>
#include <stdint.h>

#include "helical/estimator/dcm.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Most servo outputs and RC inputs any board offers (8 + 8). */
#define BOARD_MAX_SERVOS    8u
#define BOARD_MAX_RC_INPUTS 8u

/* The control tick rate: the helical-turn step runs once per tick. */
#define BOARD_CONTROL_HZ_DEFAULT 40u
#define BOARD_CONTROL_HZ_MIN     1u
#define BOARD_CONTROL_HZ_MAX     400u

/* The servo frame rate: analogue servos want 50 Hz, digital ones up to 400. */
#define BOARD_SERVO_HZ_DEFAULT 50u
#define BOARD_SERVO_HZ_MIN     50u
#define BOARD_SERVO_HZ_MAX     400u

typedef enum {
    BOARD_OK = 0,
    BOARD_ERR_NULL = 1,   /* a NULL pointer */
    BOARD_ERR_RANGE = 2,  /* a rate or channel out of range: nothing changed */
    BOARD_ERR_HW = 3,     /* the hardware did not come up (clock, timer) */
    BOARD_ERR_NO_DATA = 4 /* no fresh sensor or RC data this tick */
} board_status_t;

typedef struct {
    uint16_t control_hz;     /* [BOARD_CONTROL_HZ_MIN, BOARD_CONTROL_HZ_MAX] */
    uint16_t servo_frame_hz; /* [BOARD_SERVO_HZ_MIN, BOARD_SERVO_HZ_MAX] */
    uint16_t servo_start_us; /* pulse every servo channel emits from init until the
                                first commit; 0 = no pulses at all (the default: an
                                ESC then sees no signal rather than a wrong throttle) */
} board_config_t;

#define BOARD_CONFIG_DEFAULT                                                                       \
    {                                                                                              \
        BOARD_CONTROL_HZ_DEFAULT, BOARD_SERVO_HZ_DEFAULT, 0u                                       \
    }

/* The check every board_init starts with, kept here so that every board
 * refuses exactly the same configurations: BOARD_ERR_NULL, BOARD_ERR_RANGE
 * (a rate outside its documented range) or BOARD_OK. */
static inline board_status_t board_config_check(const board_config_t *cfg)
{
    if (cfg == NULL) {
        return BOARD_ERR_NULL;
    }
    if (cfg->control_hz < BOARD_CONTROL_HZ_MIN || cfg->control_hz > BOARD_CONTROL_HZ_MAX ||
        cfg->servo_frame_hz < BOARD_SERVO_HZ_MIN || cfg->servo_frame_hz > BOARD_SERVO_HZ_MAX) {
        return BOARD_ERR_RANGE;
    }
    return BOARD_OK;
}

/*
 * The sensor seam: raw measurements, in the estimator's formats (dcm.h),
 * library body axes (X out the left wing, Y forward, Z down). The board's
 * drivers scale their counts into these; the firmware step
 * (firmware/fw_step.h) does everything else, the attitude included.
 */
typedef struct {
    uint8_t fresh;           /* a new solution since the previous read */
    uint8_t fix;             /* 0 none, 2 2-D, 3 3-D: only 3 is used */
    int32_t lat_e7, lon_e7;  /* degrees * 1e7 */
    int32_t alt_cm;          /* above mean sea level */
    int32_t vel_ned_cm_s[3]; /* north, east, down */
} board_gps_t;

typedef struct {
    uint8_t imu_fresh;   /* a new IMU sample */
    ht_imu_sample_t imu; /* gyro Q16 rad/s, specific force Q16 g (level: 0, 0, -1) */
    board_gps_t gps;
    uint8_t airspeed_fresh; /* a live pitot reading */
    int16_t airspeed_cm_s;  /* INDICATED airspeed (sea-level density), as the pitot's driver
                               gives it: the step makes it true with the baro (air_data.h) */
    uint8_t baro_fresh;
    int32_t baro_alt_cm;     /* pressure altitude, mean sea level */
    uint8_t baro_temp_valid; /* the baro measured the static temperature (else the ISA's) */
    int16_t baro_temp_cdeg;  /* 0.01 degC */
} board_sensors_t;

/* Why the firmware entered failsafe (passed to board_failsafe). */
typedef enum {
    BOARD_FS_NONE = 0,
    BOARD_FS_RC_LOST = 1, /* no valid RC frame for the configured time */
    BOARD_FS_SENSORS = 2, /* no IMU sample for the firmware's timeout */
    BOARD_FS_CONFIG = 3   /* the output-stage or law configuration was refused:
                             the loop writes no pulses at all; the board should
                             silence its servo outputs */
} board_failsafe_t;

/*
 * Bring up clocks, the control tick timer and the servo outputs. Servo
 * outputs start at cfg->servo_start_us on every channel. A bad config returns
 * BOARD_ERR_RANGE and touches no hardware.
 */
board_status_t board_init(const board_config_t *cfg);

/* How many servo outputs and RC inputs this board has (<= BOARD_MAX_*). */
uint8_t board_servo_count(void);
uint8_t board_rc_count(void);

/*
 * Wait for the next control tick. Returns the number of ticks that elapsed
 * since the previous call beyond the one waited for (0 = on time), so the
 * caller can detect overruns.
 */
uint16_t board_wait_tick(void);

/*
 * The pilot's RC pulses, in microseconds, for channels [0, count). A channel
 * with no valid pulse reads 0. Returns BOARD_OK when a fresh, complete frame
 * was received since the previous call, BOARD_ERR_NO_DATA when not (the
 * pulses then hold the last frame, or 0 if none ever came), BOARD_ERR_NULL
 * or BOARD_ERR_RANGE on bad arguments.
 */
board_status_t board_rc_read_us(uint16_t pulse_us[], uint8_t count);

/*
 * Stage one servo pulse. Nothing reaches the pins until board_servo_commit():
 * then all staged channels change together, at the start of the same servo
 * frame. The board clamps to its own hardware limits (a pulse never exceeds
 * the frame); the output stage has already applied the airframe limits.
 */
board_status_t board_servo_write_us(uint8_t channel, uint16_t pulse_us);
void board_servo_commit(void);

/* Fill the sensor seam for this tick (the fresh flags say what is new);
 * BOARD_ERR_NO_DATA when nothing at all is fresh. */
board_status_t board_sensors_read(board_sensors_t *out);

/*
 * Failsafe hook: called by the firmware loop once when it enters failsafe
 * (reason != BOARD_FS_NONE) and once when it leaves (BOARD_FS_NONE). The
 * loop itself already outputs the configured failsafe pulses; the board may
 * add what only it can do (LED, buzzer, log, cut an ignition).
 */
void board_failsafe(board_failsafe_t reason);

#ifdef __cplusplus
}
#endif

#endif /* HELICAL_BOARD_H */
