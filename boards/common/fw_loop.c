/*
 * fw_loop.c - the portable control tick (see fw_loop.h). Integer only.
 */
#include "fw_loop.h"

#include <stdbool.h>
#include <stddef.h>

void fw_config_default(fw_config_t *cfg)
{
    if (cfg == NULL) {
        return;
    }
    const ht_params_t law = HT_PARAMS_DEFAULT;
    cfg->law = law;
    static const uint8_t fn[5] = {OS_FN_AILERON, OS_FN_ELEVATOR, OS_FN_THROTTLE, OS_FN_RUDDER,
                                  OS_FN_AILERON2};
    cfg->out.count = 5u;
    for (uint8_t i = 0; i < OS_MAX_CHANNELS; ++i) {
        os_channel_default(&cfg->out.ch[i], i < 5u ? fn[i] : (uint8_t)OS_FN_NONE);
    }
    cfg->out.ch[4].reversed = 1u;
    const os_rc_cal_t stick = {0u, 0u, 0u, 1500u, 500u};
    cfg->rc.aileron = stick;
    cfg->rc.elevator = stick;
    cfg->rc.elevator.input = 1u;
    cfg->rc.rudder = stick;
    cfg->rc.rudder.input = 3u;
    const os_rc_cal_t thr = {2u, 0u, 1u, 1000u, 1000u};
    cfg->rc.throttle = thr;
    cfg->mode_input = 4u;
    cfg->manual_below_us = 1300u;
    cfg->rc_timeout_ticks = 20u;    /* 0.5 s at 40 Hz */
    cfg->sensor_timeout_ticks = 4u; /* 0.1 s at 40 Hz */
    // cppcheck-suppress misra-c2012-10.8 ; D-10.8-FROM-REAL: compile-time constant
    cfg->max_turn_rate_rad_s = Q11_FROM_REAL(0.5);
    // cppcheck-suppress misra-c2012-10.8 ; D-10.8-FROM-REAL: compile-time constant
    cfg->max_pitch_ratio = Q16_FROM_REAL(0.3);
    cfg->failsafe_throttle = 0;
}

static int rc_cal_ok(const os_rc_cal_t *c)
{
    return os_rc_cal_check(c) == OS_OK && c->input < BOARD_MAX_RC_INPUTS;
}

static int config_valid(const fw_config_t *cfg)
{
    return os_config_check(&cfg->out, NULL) == OS_OK && rc_cal_ok(&cfg->rc.aileron) &&
           rc_cal_ok(&cfg->rc.elevator) && rc_cal_ok(&cfg->rc.rudder) &&
           rc_cal_ok(&cfg->rc.throttle) && cfg->mode_input < BOARD_MAX_RC_INPUTS &&
           cfg->rc_timeout_ticks >= 1u && cfg->sensor_timeout_ticks >= 1u &&
           cfg->max_turn_rate_rad_s >= 0 && cfg->max_pitch_ratio >= 0 &&
           cfg->max_pitch_ratio <= 4 * Q16_ONE && cfg->failsafe_throttle >= 0 &&
           cfg->failsafe_throttle <= Q14_ONE && cfg->out.count <= board_servo_count();
}

int fw_init(fw_state_t *fw, const fw_config_t *cfg)
{
    if (fw == NULL) {
        return 0;
    }
    const fw_state_t zero = {0};
    *fw = zero;
    fw->cfg = cfg;
    /* Start "lost" so that nothing flies before the first RC frame and the
     * first sensor reading arrive. */
    fw->mode = (uint8_t)FW_MODE_FAILSAFE;
    fw->failsafe = (uint8_t)BOARD_FS_NONE;
    if (cfg == NULL || !config_valid(cfg) || ht_init(&fw->ctl, &cfg->law, NULL) != HT_OK) {
        return 0;
    }
    fw->rc_age_ticks = cfg->rc_timeout_ticks;
    fw->pilot_mode = (uint8_t)FW_MODE_STABILISED;
    fw->sensor_age_ticks = cfg->sensor_timeout_ticks;
    fw->config_ok = 1u;
    return 1;
}

static uint16_t age(uint16_t a)
{
    return (a == UINT16_MAX) ? a : (uint16_t)(a + 1u);
}

/* Stick -> target: round(stick * full / 2^14), saturated. */
static int32_t scale_stick(q14_t stick, int32_t full)
{
    return q_mul32(stick, full, 14u);
}

static void law_command(fw_state_t *fw, const os_command_t *sticks, os_command_t *cmd)
{
    const board_sensors_t *s = &fw->sensors;
    ht_input_t *in = &fw->law_in;
    in->x = s->down_q14[0];
    in->y = s->down_q14[1];
    in->z = s->down_q14[2];
    in->turn_rate_rad_s =
        (q11_t)q_sat16(scale_stick(sticks->aileron, fw->cfg->max_turn_rate_rad_s));
    in->pitch_ratio = scale_stick(sticks->elevator, fw->cfg->max_pitch_ratio);
    in->airspeed_cm_s = s->airspeed_cm_s;
    in->gyro_rad_s[0] = s->gyro_q11_rad_s[0];
    in->gyro_rad_s[1] = s->gyro_q11_rad_s[1];
    in->gyro_rad_s[2] = s->gyro_q11_rad_s[2];
    in->inverted = 0u;
    ht_step(&fw->ctl, in, &fw->law_out);
    cmd->aileron = fw->law_out.aileron;
    cmd->elevator = fw->law_out.elevator;
    cmd->rudder = fw->law_out.rudder;
    cmd->throttle = sticks->throttle;
}

static void set_failsafe(fw_state_t *fw, board_failsafe_t reason)
{
    if (fw->failsafe != (uint8_t)reason) {
        fw->failsafe = (uint8_t)reason;
        board_failsafe(reason);
    }
}

static void write_outputs(fw_state_t *fw)
{
    for (uint8_t i = 0; i < fw->cfg->out.count; ++i) {
        (void)board_servo_write_us(i, fw->pulse_us[i]);
    }
    board_servo_commit();
}

void fw_tick(fw_state_t *fw, uint16_t late_ticks)
{
    if (fw == NULL) {
        return;
    }
    fw->ticks++;
    fw->late_ticks += late_ticks;
    if (!fw->config_ok) {
        fw->mode = (uint8_t)FW_MODE_FAILSAFE;
        set_failsafe(fw, BOARD_FS_CONFIG);
        return; /* no pulses: the board silences its outputs */
    }
    const fw_config_t *cfg = fw->cfg;

    uint16_t *rc_us = fw->rc_us;
    const uint8_t rc_n = board_rc_count();
    const uint8_t rc_count = (rc_n > BOARD_MAX_RC_INPUTS) ? (uint8_t)BOARD_MAX_RC_INPUTS : rc_n;
    os_command_t *sticks = &fw->sticks_in;
    const bool rc_fresh = board_rc_read_us(rc_us, rc_count) == BOARD_OK &&
                          os_rc_command(&cfg->rc, rc_us, rc_count, sticks) == OS_OK &&
                          cfg->mode_input < rc_count &&
                          rc_us[cfg->mode_input] >= OS_RC_VALID_MIN_US &&
                          rc_us[cfg->mode_input] <= OS_RC_VALID_MAX_US;
    // cppcheck-suppress knownConditionTrueFalse ; FP: board_rc_read_us of rc_none.c, see D-FP-RC
    fw->rc_age_ticks = rc_fresh ? 0u : age(fw->rc_age_ticks);

    if (board_sensors_read(&fw->sensors_in) == BOARD_OK) {
        fw->sensors = fw->sensors_in;
        fw->sensor_age_ticks = 0u;
    } else {
        fw->sensor_age_ticks = age(fw->sensor_age_ticks);
    }

    os_command_t *cmd = &fw->cmd;
    if (fw->sensor_age_ticks >= cfg->sensor_timeout_ticks) {
        fw->mode = (uint8_t)FW_MODE_FAILSAFE;
        set_failsafe(fw, BOARD_FS_SENSORS);
        (void)os_failsafe(&cfg->out, fw->pulse_us);
        write_outputs(fw);
        return;
    }
    if (fw->rc_age_ticks >= cfg->rc_timeout_ticks) {
        fw->mode = (uint8_t)FW_MODE_FAILSAFE;
        set_failsafe(fw, BOARD_FS_RC_LOST);
        const os_command_t level = {0, 0, 0, cfg->failsafe_throttle};
        law_command(fw, &level, cmd);
    } else {
        set_failsafe(fw, BOARD_FS_NONE);
        /* A frame missed within the timeout keeps the last sticks and mode:
         * receivers and this tick run at different rates. */
        // cppcheck-suppress knownConditionTrueFalse ; FP: board_rc_read_us of rc_none.c, see
        // D-FP-RC
        if (rc_fresh) {
            fw->sticks = *sticks;
            fw->pilot_mode = (rc_us[cfg->mode_input] < cfg->manual_below_us)
                                 ? (uint8_t)FW_MODE_MANUAL
                                 : (uint8_t)FW_MODE_STABILISED;
        }
        fw->mode = fw->pilot_mode;
        if (fw->mode == (uint8_t)FW_MODE_MANUAL) {
            *cmd = fw->sticks;
        } else {
            law_command(fw, &fw->sticks, cmd);
        }
    }
    (void)os_compute(&cfg->out, cmd, fw->pulse_us);
    write_outputs(fw);
}
