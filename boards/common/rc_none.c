/*
 * rc_none.c - RC input for a board without a receiver driver yet (any board
 * may link it): never a
 * frame, so the firmware flies its RC failsafe (the law holding wings level).
 * A PPM/SBUS driver, or the simulator link, replaces this file.
 */
#include "helical/board.h"

#include <stddef.h>

uint8_t board_rc_count(void)
{
    return 8u;
}

board_status_t board_rc_read_us(uint16_t pulse_us[], uint8_t count)
{
    if (pulse_us == NULL) {
        return BOARD_ERR_NULL;
    }
    if (count > BOARD_MAX_RC_INPUTS) {
        return BOARD_ERR_RANGE;
    }
    for (uint8_t i = 0; i < count; ++i) {
        pulse_us[i] = 0u;
    }
    return BOARD_ERR_NO_DATA;
}
