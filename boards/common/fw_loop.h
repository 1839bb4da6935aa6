/*
 * fw_loop.h - the portable firmware: one control tick per call, for any
 * board that implements include/helical/board.h.
 *
 * Why here and not in src/: src/ is the library (no state, no board calls);
 * this file owns the flight-mode state machine and calls the board, so it is
 * firmware. It is still portable: it includes board.h only, never a board's
 * own header, and keeps every piece of state in the caller's fw_state_t
 * (the board's main.c holds the one static instance).
 *
 * Each tick:
 *   1. RC: a fresh frame resets rc_age; after rc_timeout_ticks without one,
 *      RC is lost.
 *   2. Sensors (board_sensors_read, the seam where an IMU/DCM or a simulator
 *      link plugs in): the last good reading is kept; after
 *      sensor_timeout_ticks without one, sensors are lost.
 *   3. Mode: configuration refused -> failsafe CONFIG (no pulses written);
 *      sensors lost -> failsafe SENSORS (each channel's failsafe_us);
 *      RC lost -> failsafe RC_LOST (the law flies wings level at zero pitch
 *      ratio, throttle failsafe_throttle); else the mode switch picks MANUAL
 *      (sticks through the mixer) or STABILISED (sticks -> turn rate and
 *      pitch ratio -> ht_step -> mixer).
 *   4. The output stage turns commands into pulses; all channels are staged
 *      and committed together. board_failsafe() hears every change of reason.
 */
#ifndef HT_FW_LOOP_H
#define HT_FW_LOOP_H

#include <stdint.h>

#include "helical/board.h"
#include "helical/helical_turn.h"
#include "helical/output_stage.h"

typedef enum { FW_MODE_FAILSAFE = 0, FW_MODE_MANUAL = 1, FW_MODE_STABILISED = 2 } fw_mode_t;

typedef struct {
    ht_params_t law;
    os_config_t out;
    os_rc_map_t rc;
    uint8_t mode_input;            /* RC input of the mode switch */
    uint16_t manual_below_us;      /* mode switch pulse below this = MANUAL */
    uint16_t rc_timeout_ticks;     /* ticks without RC before failsafe, >= 1 */
    uint16_t sensor_timeout_ticks; /* ticks without sensors before failsafe, >= 1 */
    q11_t max_turn_rate_rad_s;     /* full aileron stick in STABILISED, >= 0 */
    q16_t max_pitch_ratio;         /* full elevator stick in STABILISED, [0, 4] */
    q14_t failsafe_throttle;       /* throttle while the law flies the RC failsafe */
} fw_config_t;

/*
 * The loop's state. The per-tick working structs (RC pulses, the law's input
 * and output) live here rather than on the stack: the control tick's stack
 * budget is 256 bytes and ht_step needs most of it; they double as telemetry.
 */
typedef struct {
    ht_controller_t ctl;
    const fw_config_t *cfg;
    board_sensors_t sensors;             /* last good reading */
    board_sensors_t sensors_in;          /* this tick's reading (valid only if fresh) */
    os_command_t sticks;                 /* last good RC sticks */
    os_command_t sticks_in;              /* this tick's sticks (valid only if fresh) */
    os_command_t cmd;                    /* this tick's commands to the output stage */
    uint16_t rc_us[BOARD_MAX_RC_INPUTS]; /* this tick's RC pulses */
    ht_input_t law_in;                   /* the last step's input and output */
    ht_output_t law_out;
    uint16_t pulse_us[OS_MAX_CHANNELS]; /* last pulses staged (telemetry) */
    uint32_t ticks;
    uint32_t late_ticks; /* sum of the ticks the loop was late by */
    uint16_t rc_age_ticks;
    uint16_t sensor_age_ticks;
    uint8_t config_ok;
    uint8_t mode;       /* fw_mode_t in force */
    uint8_t pilot_mode; /* MANUAL or STABILISED: the mode switch's last valid position */
    uint8_t failsafe;   /* board_failsafe_t in force */
} fw_state_t;

/* A conventional aeroplane: servos 0 aileron, 1 elevator, 2 throttle,
 * 3 rudder, 4 second aileron (reversed); RC inputs 0..3 the same sticks
 * (throttle input 2), mode switch on input 4, 0.5 s RC timeout at 40 Hz. */
void fw_config_default(fw_config_t *cfg);

/* Check everything and initialise the law. Returns 1 when the configuration
 * was accepted; 0 leaves the loop in failsafe CONFIG for good. */
int fw_init(fw_state_t *fw, const fw_config_t *cfg);

/* One control tick; late_ticks is what board_wait_tick() returned. */
void fw_tick(fw_state_t *fw, uint16_t late_ticks);

#endif /* HT_FW_LOOP_H */
