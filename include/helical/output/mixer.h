/*
 * mixer.h - airframe mixes: the law's surface commands (and the throttle) to
 * one command per output function, and the pilot's RC pulses to the same
 * commands for manual pass-through. Portable, integer only, no state.
 *
 * Sign conventions (those of helical_turn.h): aileron + rolls right,
 * elevator + pitches the nose up, rudder + yaws the nose right. A mixed
 * surface (ruddervator, elevon) is + when its trailing edge goes UP. Which way
 * a servo has to turn for that is the channel's business (os_channel_t
 * reversed), not the mixer's.
 */
#ifndef HELICAL_MIXER_H
#define HELICAL_MIXER_H

#include <stdint.h>

#include "helical/math/q14.h"
#include "helical/output/os_command.h"

#ifdef __cplusplus
extern "C" {
#endif

/*
 * The command for one output function, in Q14. Surfaces come out clamped to
 * [-1, 1] (a sum such as pitch + yaw = 1.5 gives exactly 1.0: the mix
 * saturates, it does not rescale); the throttle to [0, 1]. An unknown
 * function, or cmd == NULL, gives 0.
 */
q14_t os_mix(const os_command_t *cmd, uint8_t function);

/* --- manual pass-through from the pilot's receiver ------------------------ */

/* RC pulses outside this window are "no signal" (0 from a lost channel, or a
 * glitch), never a command. */
#define OS_RC_VALID_MIN_US 800u
#define OS_RC_VALID_MAX_US 2200u

/* One RC input's calibration. */
typedef struct {
    uint8_t input;      /* index into the board's RC pulses */
    uint8_t reversed;   /* nonzero: a longer pulse means a negative command */
    uint8_t unipolar;   /* nonzero (throttle): centre_us is idle, result in [0, 1] */
    uint16_t centre_us; /* stick centre (unipolar: idle), [OS_RC_VALID_MIN_US, MAX] */
    uint16_t travel_us; /* from centre to full stick, [OS_RC_TRAVEL_MIN_US, MAX] */
} os_rc_cal_t;

#define OS_RC_TRAVEL_MIN_US 100u
#define OS_RC_TRAVEL_MAX_US 1000u

/* Which RC inputs fly the aircraft in manual mode. */
typedef struct {
    os_rc_cal_t aileron, elevator, rudder, throttle;
} os_rc_map_t;

typedef enum {
    OS_OK = 0,
    OS_ERR_NULL = 1,   /* a NULL pointer */
    OS_ERR_CONFIG = 2, /* a configuration value out of range */
    OS_ERR_RANGE = 3   /* an input (RC pulse, channel count) out of range */
} os_status_t;

/* Check one calibration: OS_OK or OS_ERR_CONFIG (OS_ERR_NULL for NULL). */
os_status_t os_rc_cal_check(const os_rc_cal_t *cal);

/*
 * One RC pulse to a Q14 command: round((pulse - centre) * 1.0 / travel),
 * rounded to nearest with ties away from zero (so reversing mirrors exactly),
 * clamped to [-1, 1] (unipolar: [0, 1]). A pulse outside
 * [OS_RC_VALID_MIN_US, OS_RC_VALID_MAX_US] returns OS_ERR_RANGE and writes 0;
 * a calibration that os_rc_cal_check refuses returns OS_ERR_CONFIG and
 * writes 0.
 */
os_status_t os_rc_to_q14(const os_rc_cal_t *cal, uint16_t pulse_us, q14_t *out);

/*
 * Manual pass-through: the four sticks to an os_command_t, which then goes
 * through the same mix and channel conversion as the law's output (so a
 * V-tail or a flying wing is flown manually with ordinary sticks). rc_us has
 * rc_count pulses. On any error (an input index >= rc_count, a pulse without
 * signal, a bad calibration) returns that status and writes a neutral command
 * (surfaces 0, throttle 0): the caller goes to failsafe.
 */
os_status_t os_rc_command(const os_rc_map_t *map, const uint16_t rc_us[], uint8_t rc_count,
                          os_command_t *out);

#ifdef __cplusplus
}
#endif

#endif /* HELICAL_MIXER_H */
