/*
 * hil_fw.h - the firmware side of the hardware/processor-in-the-loop link
 * (docs/hil-protocol.md): configuration frames, one control step per sensor
 * frame, and the answer with the pulses read back from the timer.
 *
 * The control step is THE firmware step (fw_step.h), as in the flight image
 * and the SIL host board. Protocol version 2 carries the simulator's
 * navigation solution (DCM row, rates, air data) and the scenario's command,
 * already converted: each SENSORS frame is fw_step's external solution and
 * guided command, given for control_divider calls (the control chain runs on
 * the last), so a PIL run and a SIL run with the truth attitude agree bit
 * for bit (firmware/tests/test_hil_fw.c checks the two on the host). Raw IMU
 * samples over the link are the next protocol version's (docs/hil-protocol.md).
 *
 * Portable: the protocol and the step use only board.h plus the three link
 * functions below, which the HIL image's board file provides. All state is
 * in the caller's hil_fw_t.
 */
#ifndef HT_HIL_FW_H
#define HT_HIL_FW_H

#include <stddef.h>
#include <stdint.h>

#include "fw_step.h"
#include "helical/board.h"
#include "helical/hil_frame.h"

#define HIL_PROTOCOL_VERSION 2u /* 2: CFG_ALT carries the airspeed protection */

/* Message ids (docs/hil-protocol.md): host -> firmware */
#define HIL_ID_HELLO      0x01u /* empty: answered by READY */
#define HIL_ID_CFG_LAW    0x10u
#define HIL_ID_CFG_ALT    0x11u
#define HIL_ID_CFG_SPD    0x12u
#define HIL_ID_CFG_OUT    0x13u
#define HIL_ID_START      0x14u /* empty: check the staged configuration, answered by ACK */
#define HIL_ID_SENSORS    0x20u /* one control step, answered by OUTPUT (or NAK) */
#define HIL_ID_HOST_COUNT 0x21u
/* firmware -> host */
#define HIL_ID_READY  0x81u
#define HIL_ID_NAK    0x8Eu
#define HIL_ID_ACK    0x94u
#define HIL_ID_OUTPUT 0xA0u

/* Payload lengths */
#define HIL_LEN_CFG_LAW 49u
#define HIL_LEN_CFG_ALT 52u
#define HIL_LEN_CFG_SPD 22u
#define HIL_LEN_CFG_OUT 58u
#define HIL_LEN_SENSORS 41u
#define HIL_LEN_READY   24u
#define HIL_LEN_NAK     2u
#define HIL_LEN_ACK     4u
#define HIL_LEN_OUTPUT  40u

#define HIL_OUT_CHANNELS 4u /* channels reported in OUTPUT (the SIL's four) */

/* SENSORS flags */
#define HIL_SF_ALTITUDE_HOLD 0x01u
#define HIL_SF_SPEED_HOLD    0x02u
#define HIL_SF_INVERTED      0x04u
#define HIL_SF_TILT_CROSS    0x08u /* pitch method HT_PITCH_TILT_CROSS; else earth frame */
#define HIL_SF_ALL           0x0Fu

/* ACK status */
#define HIL_ACK_OK      0u
#define HIL_ACK_MISSING 1u /* a configuration block was never received: detail = its id */
#define HIL_ACK_REFUSED 2u /* a block failed its check: id = the block, detail = the field */

/* NAK reasons */
#define HIL_NAK_NOT_STARTED 1u /* SENSORS before a successful START */
#define HIL_NAK_BAD_FIELD   2u /* reserved flag bits set */

/* The navigation solution a SENSORS frame carries (protocol version 2). */
typedef struct {
    q14_t down_q14[3];       /* DCM bottom row */
    q11_t gyro_q11_rad_s[3]; /* body rates */
    int16_t airspeed_cm_s;
} hil_attitude_t;

/* The step's fixed-point inputs: the solution and the scenario's command. */
typedef struct {
    hil_attitude_t imu;
    int32_t altitude_cm;
    int32_t climb_cm_s;
    q11_t turn_rate_rad_s;
    q16_t pitch_ratio;
    int32_t altitude_cmd_cm;
    int16_t airspeed_cmd_cm_s;
    q14_t throttle;
    uint8_t flags; /* HIL_SF_* */
} hil_step_in_t;

typedef struct {
    uint16_t pulse_us[HIL_OUT_CHANNELS]; /* from the output stage */
    q14_t throttle;
    q16_t pitch_cmd;
    ht_output_t law;
    uint8_t servo_clamped;
} hil_step_out_t;

typedef struct {
    /* staged by the CFG_* frames, checked and put in force at START */
    fw_config_t cfg;
    uint8_t have; /* bit per CFG block received: 1 law, 2 alt, 4 spd, 8 out */
    /* in force after START */
    fw_t fw;
    uint8_t started;
    /* link */
    uint8_t rx_len[HIL_ID_HOST_COUNT]; /* the decoder's table: expected lengths */
    hil_decoder_t rx;
    uint16_t naks;
    uint32_t steps;
    /* the step's working structs (kept off the stack; also telemetry) */
    hil_step_in_t in;
    hil_step_out_t res;
    fw_inputs_t fw_in;
    fw_nav_t nav;
    fw_guided_t guided;
    fw_output_t fw_out;
    uint8_t frame[HIL_FRAME_MAX];
    uint8_t payload[HIL_PAYLOAD_MAX];
} hil_fw_t;

/* --- provided by the HIL image's board file ------------------------------ */
/* Bring the link up (after board_init); 0 if it did not come up. */
int hil_link_init(void);
/* One received byte, if any (never waits): 1 and *byte, or 0. */
int hil_link_poll(uint8_t *byte);
/* Send bytes on the link (blocking, bounded). */
void hil_link_send(const uint8_t *data, size_t n);
/* The pulse a servo output is producing, read back from the hardware (us). */
uint16_t hil_servo_readback_us(uint8_t channel);
/* The link's receive error count (overrun, framing, noise, parity). */
uint16_t hil_link_errors(void);

/* --- the firmware side ---------------------------------------------------- */
void hil_fw_init(hil_fw_t *h);

/* Send the READY frame (the banner, and the answer to HELLO). */
void hil_fw_send_ready(hil_fw_t *h);

/* Feed one received byte; a completed good frame is acted on (and answered). */
void hil_fw_on_byte(hil_fw_t *h, uint8_t byte);

/* The control step alone (no link): exposed for the host test. */
void hil_fw_step(hil_fw_t *h, const hil_step_in_t *in, hil_step_out_t *o);

/* Payload parsers and writers, shared with the host test. */
void hil_sensors_parse(const uint8_t *p, uint32_t *seq, hil_step_in_t *in);
void hil_sensors_write(uint8_t *p, uint32_t seq, const hil_step_in_t *in);

#endif /* HT_HIL_FW_H */
