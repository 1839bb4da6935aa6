/*
 * fw_main.c - main() of the flight image: bring the board up, then the one
 * firmware step (fw_step.h) on every board tick, at the IMU rate. The one
 * static instance of the firmware state lives here (firmware, not library).
 */
#include "helical/board.h"

#include "fw_board_config.h"
#include "fw_step.h"

/* Pulses to the servos: staged, then committed together. */
static void write_pulses(const fw_output_t *o)
{
    for (uint8_t i = 0u; i < o->pulse_count; ++i) {
        (void)board_servo_write_us(i, o->pulse_us[i]);
    }
    board_servo_commit();
}

/* The board hears every change of failsafe reason (LED, buzzer, log). */
static void report_failsafe(uint8_t *reported, board_failsafe_t reason)
{
    if (*reported != (uint8_t)reason) {
        *reported = (uint8_t)reason;
        board_failsafe(reason);
    }
}

static board_failsafe_t failsafe_reason(const fw_t *fw, const fw_output_t *o)
{
    if (o->pulse_count == 0u || fw->ready == 0u) {
        return BOARD_FS_CONFIG;
    }
    if (o->failsafe != 0u) {
        return BOARD_FS_SENSORS;
    }
    return (o->modes.failsafe != 0u) ? BOARD_FS_RC_LOST : BOARD_FS_NONE;
}

/* The default: the defaults fly (a board with a parameter store overrides it). */
__attribute__((weak)) void fw_board_config(fw_config_t *cfg)
{
    (void)cfg;
}

/* The defaults: no ground-station link (a board with a telemetry UART
 * overrides them, fw_board_config.h). */
__attribute__((weak)) int fw_board_link_init(fw_link_t *link)
{
    (void)link;
    return 0;
}
__attribute__((weak)) void fw_board_link_poll(fw_link_t *link)
{
    (void)link;
}
__attribute__((weak)) uint32_t fw_board_time_ms(void)
{
    return 0u;
}

// cppcheck-suppress misra-c2012-8.6 ; FP: one main per image, hil_main.c is another program
int main(void)
{
    /* static: the firmware state is not on the stack (same storage as at file scope) */
    static fw_config_t config;
    static fw_t fw;
    static fw_inputs_t in;
    static fw_output_t out;
    static fw_link_t link;
    fw_config_default(&config);
    /* the joint check (config_check.h) judges every input against the
     * receiver this board has; before the board's own configuration, which
     * may load a stored set and check it */
    const uint8_t rc_channels = board_rc_count();
    config.modes.rc_channels = (rc_channels > FW_RC_MAX) ? (uint8_t)FW_RC_MAX : rc_channels;
    fw_board_config(&config);
    board_config_t board = BOARD_CONFIG_DEFAULT;
    board.control_hz = config.dcm.imu_rate_hz; /* one board tick per IMU sample */
    if (board_init(&board) != BOARD_OK) {
        board_failsafe(BOARD_FS_CONFIG);
        for (;;) {
            /* no control without a board: stay here, outputs silenced */
        }
    }
    (void)fw_init(&fw, &config); /* a refused config: no pulses, reported below */
    const uint8_t link_on =
        ((fw_link_init(&link, &fw, &config, 0u, (uint8_t)FW_LINK_COMPID_AUTOPILOT) == 0) &&
         (fw_board_link_init(&link) != 0))
            ? 1u
            : 0u;
    uint8_t reported = (uint8_t)BOARD_FS_NONE;
    const uint8_t rc_n = board_rc_count();
    in.rc_count = (rc_n > FW_RC_MAX) ? (uint8_t)FW_RC_MAX : rc_n;
    for (;;) {
        (void)board_wait_tick();
        if (board_sensors_read(&in.sensors) != BOARD_OK) {
            in.sensors.imu_fresh = 0u;
        }
        /* a frame that arrives between control steps stays fresh until the
         * next one reads it */
        if (board_rc_read_us(in.rc_us, in.rc_count) == BOARD_OK) {
            in.rc_fresh = 1u;
        }
        if (link_on != 0u) {
            fw_board_link_poll(&link); /* the ground station's bytes in, ours out */
        }
        if (fw_step(&fw, &in, &out) != 0) {
            in.rc_fresh = 0u;
            if (out.pulse_count > 0u) {
                write_pulses(&out);
            }
            report_failsafe(&reported, failsafe_reason(&fw, &out));
            if (link_on != 0u) {
                fw_link_after_step(&link, &out, fw_board_time_ms());
            }
        } else if (fw.ready == 0u) {
            report_failsafe(&reported, BOARD_FS_CONFIG);
        } else {
            /* between control steps: the estimator ran, the pulses hold */
        }
    }
}
