/*
 * board.h - what the portable firmware needs from a board.
 *
 * One implementation per board lives in boards/<name>/ and is chosen at link
 * time: every board defines exactly these functions, the portable firmware
 * loop (boards/common/fw_loop.c) calls only these, and no portable file ever
 * includes a board's own header. A board keeps its driver state in its own
 * file (static instances of caller-owned driver structs); the library in src/
 * holds no state at all.
 *
 * Units: pulse widths in microseconds (uint16_t *_us), rates in hertz.
 * Channels are numbered from 0.
 *
 * Porting to a new board: implement every function below in
 * boards/<name>/board_<name>.c, add a CMakeLists.txt that links it with
 * boards/common/fw_loop.c and the helical library, and see boards/README.md.
 */
#ifndef HELICAL_BOARD_H
#define HELICAL_BOARD_H

#include <stddef.h>
#include <stdint.h>

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
 * The sensor seam. A board with an IMU and a DCM fills this from them; the
 * STM32 image has no IMU driver yet and gives a level, wings-level attitude,
 * and a simulator link can fill it from a UART. Formats as ht_input_t.
 */
typedef struct {
    int16_t down_q14[3];       /* DCM bottom row (earth-down in body axes), Q14 */
    int16_t gyro_q11_rad_s[3]; /* body rates about X, Y, Z, Q11 rad/s */
    int16_t airspeed_cm_s;
} board_sensors_t;

/* Why the firmware entered failsafe (passed to board_failsafe). */
typedef enum {
    BOARD_FS_NONE = 0,
    BOARD_FS_RC_LOST = 1, /* no valid RC frame for the configured time */
    BOARD_FS_SENSORS = 2, /* the sensor seam returned no data */
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

/* Fill the sensor seam for this tick; BOARD_ERR_NO_DATA when nothing fresh. */
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
