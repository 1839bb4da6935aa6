/*
 * fake_board.h - a scriptable board.h implementation for host tests of the
 * portable firmware loop: the test sets what the board reports and reads
 * back what the loop wrote.
 */
#ifndef HT_FAKE_BOARD_H
#define HT_FAKE_BOARD_H

#include <stdint.h>

#include "helical/board.h"

typedef struct {
    /* what the board reports */
    uint8_t servo_count;
    uint8_t rc_count;
    board_status_t rc_status;
    uint16_t rc_us[BOARD_MAX_RC_INPUTS];
    board_status_t sensor_status;
    board_sensors_t sensors;
    /* what the loop did */
    uint16_t staged_us[BOARD_MAX_SERVOS];
    uint16_t committed_us[BOARD_MAX_SERVOS];
    uint32_t writes, writes_since_commit, commits;
    uint32_t failsafe_calls;
    board_failsafe_t last_failsafe;
} fake_board_t;

extern fake_board_t fake_board;

/* Reset to: 8 servos, 8 RC inputs, fresh frames all at 1500 us except the
 * throttle input 2 at 1000 us, level attitude, 15 m/s, no calls recorded. */
void fake_board_reset(void);

#endif /* HT_FAKE_BOARD_H */
