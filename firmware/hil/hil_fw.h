/*
 * hil_fw.h - the firmware side of the hardware/processor-in-the-loop link
 * (docs/hil-protocol.md): configuration frames, the raw sensor samples of
 * each control step, and the answer with the pulses read back from the timer
 * and the estimator's state.
 *
 * The control step is THE firmware step (fw_step.h), as in the flight image
 * and the SIL host board. Protocol version 3 carries what the SIL host board
 * (boards/sil) gives fw_step, already converted: per control step a STEP
 * frame (GPS, pitot, baro, the guided command, flags), a TRUTH frame when the
 * simulator's solution is flown, one IMU frame per sample but the last, and a
 * SENSORS frame with the last sample, which ends the step and is answered by
 * STATE and OUTPUT. Each sample goes through fw_step as it arrives, with the
 * same inputs sil_board_step gives it, so a PIL run and a SIL run agree bit
 * for bit in both attitude modes (firmware/tests/test_hil_fw.c checks the two
 * on the host).
 *
 * Portable: the protocol and the step use only board.h plus the link
 * functions of hil_link.h, which the HIL image's board file provides. All state is
 * in the caller's hil_fw_t.
 */
#ifndef HT_HIL_FW_H
#define HT_HIL_FW_H

#include <stddef.h>
#include <stdint.h>

#include "fw_step.h"
#include "helical/board.h"
#include "helical/protocols/hil_frame.h"
#include "hil/hil_link.h"

#define HIL_PROTOCOL_VERSION                                                                       \
    8u /* 3: raw sensor samples, CFG_EST, STATE; 4: CFG_EST gps_latency_ms;                        \
          5: CFG_LAW and CFG_EST laid out by the parameter table;                                  \
          6: CFG_EST ends with the guidance's rows;                                                \
          7: CFG_ALT and CFG_SPD laid out by the parameter table;                                  \
          8: CFG_LAW ends with the law's options (roll_in, roll_in_rate_max,                       \
             kp_sideslip, vertical_fade) */

/* Message ids (docs/hil-protocol.md): host -> firmware */
#define HIL_ID_HELLO      0x01u /* empty: answered by READY */
#define HIL_ID_CFG_LAW    0x10u
#define HIL_ID_CFG_ALT    0x11u
#define HIL_ID_CFG_SPD    0x12u
#define HIL_ID_CFG_OUT    0x13u
#define HIL_ID_START      0x14u /* empty: check the staged configuration, answered by ACK */
#define HIL_ID_CFG_EST    0x15u /* the estimator, the divider, the timeout, the guidance */
#define HIL_ID_SENSORS    0x20u /* the step's last IMU sample: answered by STATE + OUTPUT */
#define HIL_ID_STEP       0x21u /* opens a control step: slow sensors, command, flags */
#define HIL_ID_TRUTH      0x22u /* the simulator's navigation solution (flag USE_TRUTH) */
#define HIL_ID_IMU        0x23u /* one IMU sample, not the step's last: not answered */
#define HIL_ID_HOST_COUNT 0x24u
/* firmware -> host */
#define HIL_ID_READY  0x81u
#define HIL_ID_NAK    0x8Eu
#define HIL_ID_ACK    0x94u
#define HIL_ID_OUTPUT 0xA0u
#define HIL_ID_STATE  0xA1u /* sent just before each OUTPUT */

/* Payload lengths. CFG_LAW is the law's rows of the parameter table
 * (include/helical/params.def) in its order, each as wide as its format;
 * CFG_EST the estimator's rows, then u16 control_divider and u16
 * imu_timeout_samples, then the guidance's rows; CFG_ALT the altitude
 * hold's rows, then u16 rate_hz and the two i32 Q20 initial integrators
 * (upright, inverted); CFG_SPD the airspeed hold's rows, then u16 rate_hz.
 * A new row lengthens its frame by itself. */
#define HIL_LEN_CFG_LAW ((uint8_t)(0u HT_PARAMS_LAW(HT_PARAM_X_BYTES)))
#define HIL_LEN_CFG_EST                                                                            \
    ((uint8_t)(0u HT_PARAMS_DCM(HT_PARAM_X_BYTES) + 4u HT_PARAMS_GUIDE(HT_PARAM_X_BYTES)))
#define HIL_LEN_CFG_ALT ((uint8_t)(0u HT_PARAMS_ALT(HT_PARAM_X_BYTES) + 10u))
#define HIL_LEN_CFG_SPD ((uint8_t)(0u HT_PARAMS_SPEED(HT_PARAM_X_BYTES) + 2u))
#define HIL_LEN_CFG_OUT 58u
#define HIL_LEN_SENSORS 28u
#define HIL_LEN_STEP    52u
#define HIL_LEN_TRUTH   42u
#define HIL_LEN_IMU     24u
#define HIL_LEN_READY   24u
#define HIL_LEN_NAK     2u
#define HIL_LEN_ACK     4u
#define HIL_LEN_OUTPUT  40u
#define HIL_LEN_STATE   55u

#define HIL_OUT_CHANNELS 4u  /* channels reported in OUTPUT (the SIL's four) */
#define HIL_IMU_MAX      32u /* IMU samples per control step (= SIL_IMU_MAX) */

/* STEP flags */
#define HIL_SF_ALTITUDE_HOLD 0x01u
#define HIL_SF_SPEED_HOLD    0x02u
#define HIL_SF_INVERTED      0x04u
#define HIL_SF_TILT_CROSS    0x08u /* pitch method HT_PITCH_TILT_CROSS; else earth frame */
#define HIL_SF_USE_TRUTH     0x10u /* fly on the TRUTH frame's solution (the estimator runs) */
#define HIL_SF_ALIGN         0x20u /* align the estimator to the TRUTH frame first (fw_align) */
#define HIL_SF_ALL           0x3Fu

/* STEP fresh bits: which slow sensor is new (given with the step's last sample) */
#define HIL_FRESH_GPS      0x01u
#define HIL_FRESH_AIRSPEED 0x02u
#define HIL_FRESH_BARO     0x04u
#define HIL_FRESH_ALL      0x07u

/* STATE flags */
#define HIL_ST_CONTROL_RAN   0x01u /* the step ran the control chain: OUTPUT is new */
#define HIL_ST_FAILSAFE      0x02u
#define HIL_ST_GUARD_ENGAGED 0x04u

/* ACK status */
#define HIL_ACK_OK      0u
#define HIL_ACK_MISSING 1u /* a configuration block was never received: detail = its id */
#define HIL_ACK_REFUSED 2u /* a block failed its check: id = the block, detail = the field */

/* ACK detail of a refused CFG_EST beyond the ht_dcm_param_id_t values */
#define HIL_EST_BAD_DIVIDER 0x40u /* control_divider * CFG_ALT rate_hz != imu_rate_hz */
#define HIL_EST_BAD_TIMEOUT 0x41u /* imu_timeout_samples out of [1, 10000] */
/* a refused guidance row: 0x80 + its ht_guide_param_id_t */
#define HIL_EST_BAD_GUIDE 0x80u

/* NAK reasons */
#define HIL_NAK_NOT_STARTED 1u /* STEP or SENSORS before a successful START */
#define HIL_NAK_BAD_FIELD   2u /* reserved bits set, a count out of range */
#define HIL_NAK_SEQUENCE                                                                           \
    3u /* SENSORS does not close the open step: no STEP, another                                   \
          seq, missing TRUTH, or not imu_count - 1 IMU frames */

/* What a STEP frame carries, in the firmware's formats. */
typedef struct {
    uint32_t seq;
    uint8_t flags;           /* HIL_SF_* */
    uint8_t imu_count;       /* samples in this step, [0, HIL_IMU_MAX]; 0: one control period
                                of calls without a sample (as the SIL host board) */
    uint8_t fresh;           /* HIL_FRESH_* as received (parse only; the writer takes
                                the sensors' flags) */
    board_sensors_t sensors; /* gps, airspeed, baro and their fresh flags; imu ignored */
    fw_guided_t guided;      /* the flags' bits are taken from flags */
} hil_step_t;

/* What a STATE frame carries (the estimate and the solution flown). */
typedef struct {
    uint32_t seq;
    uint8_t flags; /* HIL_ST_* */
    ht_dcm_output_t est;
    fw_nav_t nav;
} hil_state_t;

typedef struct {
    /* staged by the CFG_* frames, checked and put in force at START */
    fw_config_t cfg;
    uint8_t have; /* bit per CFG block received: 1 law, 2 alt, 4 spd, 8 out, 16 est */
    /* in force after START */
    fw_t fw;
    uint8_t started;
    /* the open control step (STEP received, SENSORS not yet) */
    uint8_t step_open;
    uint8_t step_broken; /* an IMU or TRUTH frame out of order: SENSORS is refused */
    uint8_t step_truth;  /* TRUTH received for the open step */
    uint8_t step_ran;    /* a call of the open step ran the control chain */
    uint8_t step_imu;    /* IMU frames stepped in the open step */
    hil_step_t step;
    /* link */
    uint8_t rx_len[HIL_ID_HOST_COUNT]; /* the decoder's table: expected lengths */
    hil_decoder_t rx;
    uint16_t naks;
    uint32_t steps;
    /* the step's working structs (kept off the stack; also telemetry) */
    fw_inputs_t fw_in;
    fw_nav_t truth;
    fw_output_t fw_out;
    hil_state_t state;
    uint8_t frame[HIL_FRAME_MAX];
    uint8_t payload[HIL_PAYLOAD_MAX];
} hil_fw_t;

/* --- the firmware side ---------------------------------------------------- */
void hil_fw_init(hil_fw_t *h);

/* Send the READY frame (the banner, and the answer to HELLO). */
void hil_fw_send_ready(hil_fw_t *h);

/* Feed one received byte; a completed good frame is acted on (and answered). */
void hil_fw_on_byte(hil_fw_t *h, uint8_t byte);

/* Payload writers and parsers (the host test builds its frames with the
 * writers; the parsers are the firmware's). */
void hil_step_write(uint8_t *p, const hil_step_t *s);
void hil_step_parse(const uint8_t *p, hil_step_t *s);
void hil_truth_write(uint8_t *p, const fw_nav_t *n);
void hil_truth_parse(const uint8_t *p, fw_nav_t *n);
/* IMU (24 bytes) and SENSORS (seq, then the sample: 28 bytes) */
void hil_imu_write(uint8_t *p, const ht_imu_sample_t *s);
void hil_imu_parse(const uint8_t *p, ht_imu_sample_t *s);
void hil_state_write(uint8_t *p, const hil_state_t *s);
void hil_state_parse(const uint8_t *p, hil_state_t *s);
/* CFG_LAW from / into the law's parameters (the table's order and widths) */
void hil_cfg_law_write(uint8_t *p, const ht_params_t *l);
void hil_cfg_law_parse(const uint8_t *p, ht_params_t *l);
/* CFG_EST from / into a configuration (dcm, control_divider, imu_timeout_samples) */
void hil_cfg_est_write(uint8_t *p, const fw_config_t *c);
void hil_cfg_est_parse(const uint8_t *p, fw_config_t *c);
/* CFG_ALT and CFG_SPD from / into a configuration (modes.alt with
 * alt_integral_q20, modes.speed) */
void hil_cfg_alt_write(uint8_t *p, const fw_config_t *c);
void hil_cfg_alt_parse(const uint8_t *p, fw_config_t *c);
void hil_cfg_spd_write(uint8_t *p, const fw_config_t *c);
void hil_cfg_spd_parse(const uint8_t *p, fw_config_t *c);

#endif /* HT_HIL_FW_H */
