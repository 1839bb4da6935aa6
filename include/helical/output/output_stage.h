/*
 * output_stage.h - surface commands to servo pulses: per-channel centre,
 * trim, travel, reversing and end points. Portable, integer only, no state;
 * the configuration belongs to the caller.
 *
 * For each channel:  command = os_mix(cmd, function)          (mixer.h)
 *                    c       = clamp(command, -1, 1); if reversed, c = -c
 *                    pulse   = centre + trim + round(c * travel)
 *                    pulse   = clamp(pulse, min_us, max_us)  <- always last
 * so no pulse ever leaves [min_us, max_us], whatever the commands and
 * whatever the centre, trim and travel.
 *
 * Rounding of c * travel is to nearest with ties away from zero: a reversed
 * channel is the exact mirror of a normal one about centre + trim.
 *
 * The throttle is the same formula with a command in [0, 1]: centre_us is the
 * idle pulse and travel_us the change from idle to full.
 */
#ifndef HELICAL_OUTPUT_STAGE_H
#define HELICAL_OUTPUT_STAGE_H

#include <stdint.h>

#include "helical/output/mixer.h"
#include "helical/math/q14.h"

#ifdef __cplusplus
extern "C" {
#endif

#define OS_MAX_CHANNELS 8u

/* What os_channel_check accepts. Beyond these a servo is being abused. */
#define OS_PULSE_MIN_US  500u  /* lowest end point, centre or failsafe */
#define OS_PULSE_MAX_US  2500u /* highest */
#define OS_TRAVEL_MAX_US 1000u /* travel in [0, 1000] us per full command */
#define OS_TRIM_MAX_US   500   /* trim in [-500, +500] us */

typedef struct {
    uint8_t function;   /* os_function_t */
    uint8_t reversed;   /* nonzero: the command is negated before scaling */
    uint16_t centre_us; /* pulse at command 0 (throttle: idle) */
    int16_t trim_us;    /* added to the centre */
    uint16_t travel_us; /* pulse change for a full command (1.0) */
    uint16_t min_us;    /* end points: the output never leaves [min_us, max_us] */
    uint16_t max_us;
    uint16_t failsafe_us; /* pulse in failsafe, also held within the end points */
} os_channel_t;

typedef struct {
    uint8_t count; /* channels in use, [1, OS_MAX_CHANNELS] */
    os_channel_t ch[OS_MAX_CHANNELS];
} os_config_t;

/*
 * A conventional channel for a function: centre 1500, travel 500, end points
 * 1000..2000, failsafe at centre; throttle: idle 1000, travel 1000, failsafe
 * 1000 (idle). Not reversed, no trim.
 */
void os_channel_default(os_channel_t *ch, uint8_t function);

/* OS_OK, or OS_ERR_CONFIG when a field is outside the ranges above, an end
 * point pair is inverted (min_us > max_us) or the function is unknown. */
os_status_t os_channel_check(const os_channel_t *ch);

/* Every channel in use; the first bad channel goes to *bad_channel (may be
 * NULL). A count of 0 or above OS_MAX_CHANNELS is OS_ERR_CONFIG with
 * *bad_channel = count. */
os_status_t os_config_check(const os_config_t *cfg, uint8_t *bad_channel);

/*
 * One command to one pulse; defined for every int16 command (outside
 * [-1, 1] it is clamped first). A NULL channel gives 0. With a channel that
 * os_channel_check refuses the result is still clamped to the end points (an
 * inverted pair yields min_us).
 */
uint16_t os_pulse_us(const os_channel_t *ch, q14_t command);

/*
 * The whole output stage: mix, then convert each of cfg->count channels into
 * pulse_us[0 .. count-1]. Returns OS_ERR_NULL, or OS_ERR_CONFIG when
 * cfg->count is 0 or above OS_MAX_CHANNELS (nothing written); otherwise OS_OK.
 * Call os_config_check once at start-up: os_compute trusts the fields.
 */
os_status_t os_compute(const os_config_t *cfg, const os_command_t *cmd,
                       uint16_t pulse_us[OS_MAX_CHANNELS]);

/* Every channel's failsafe pulse, clamped to its end points. Same statuses. */
os_status_t os_failsafe(const os_config_t *cfg, uint16_t pulse_us[OS_MAX_CHANNELS]);

#ifdef __cplusplus
}
#endif

#endif /* HELICAL_OUTPUT_STAGE_H */
