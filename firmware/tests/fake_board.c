/*
 * fake_board.c - see fake_board.h. Test code: global state is the point.
 */
#include "fake_board.h"

#include <string.h>

fake_board_t fake_board;

void fake_board_reset(void)
{
    memset(&fake_board, 0, sizeof fake_board);
    fake_board.servo_count = BOARD_MAX_SERVOS;
    fake_board.rc_count = BOARD_MAX_RC_INPUTS;
    fake_board.rc_status = BOARD_OK;
    for (unsigned i = 0; i < BOARD_MAX_RC_INPUTS; ++i) {
        fake_board.rc_us[i] = 1500u;
    }
    fake_board.rc_us[2] = 1000u;
    fake_board.sensor_status = BOARD_OK;
    fake_board.sensors.imu_fresh = 1u;
    fake_board.sensors.imu.accel_g[2] = -65536; /* level, at rest */
    fake_board.sensors.airspeed_fresh = 1u;
    fake_board.sensors.airspeed_cm_s = 1500;
    fake_board.last_failsafe = BOARD_FS_NONE;
}

board_status_t board_init(const board_config_t *cfg)
{
    return cfg == NULL ? BOARD_ERR_NULL : BOARD_OK;
}

uint8_t board_servo_count(void)
{
    return fake_board.servo_count;
}

uint8_t board_rc_count(void)
{
    return fake_board.rc_count;
}

uint16_t board_wait_tick(void)
{
    return 0u;
}

board_status_t board_rc_read_us(uint16_t pulse_us[], uint8_t count)
{
    if (pulse_us == NULL) {
        return BOARD_ERR_NULL;
    }
    if (count > fake_board.rc_count) {
        return BOARD_ERR_RANGE;
    }
    for (uint8_t i = 0; i < count; ++i) {
        pulse_us[i] = fake_board.rc_us[i];
    }
    return fake_board.rc_status;
}

board_status_t board_servo_write_us(uint8_t channel, uint16_t pulse_us)
{
    if (channel >= fake_board.servo_count) {
        return BOARD_ERR_RANGE;
    }
    fake_board.staged_us[channel] = pulse_us;
    fake_board.writes++;
    fake_board.writes_since_commit++;
    return BOARD_OK;
}

void board_servo_commit(void)
{
    memcpy(fake_board.committed_us, fake_board.staged_us, sizeof fake_board.committed_us);
    fake_board.commits++;
    fake_board.writes_since_commit = 0u;
}

board_status_t board_sensors_read(board_sensors_t *out)
{
    if (out == NULL) {
        return BOARD_ERR_NULL;
    }
    if (fake_board.sensor_status == BOARD_OK) {
        *out = fake_board.sensors;
    }
    return fake_board.sensor_status;
}

void board_failsafe(board_failsafe_t reason)
{
    fake_board.failsafe_calls++;
    fake_board.last_failsafe = reason;
}
