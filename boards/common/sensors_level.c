/*
 * sensors_level.c - the sensor seam with no IMU behind it: level, upright,
 * not rotating, at 15 m/s. This is where an IMU driver plus a DCM (or the
 * simulator link over a UART) plugs in: a board links a file that fills
 * board_sensors_t from real measurements instead of this one.
 */
#include "helical/board.h"

#include <stddef.h>

board_status_t board_sensors_read(board_sensors_t *out)
{
    if (out == NULL) {
        return BOARD_ERR_NULL;
    }
    out->down_q14[0] = 0;
    out->down_q14[1] = 0;
    out->down_q14[2] = 16384; /* earth-down along body Z: level */
    out->gyro_q11_rad_s[0] = 0;
    out->gyro_q11_rad_s[1] = 0;
    out->gyro_q11_rad_s[2] = 0;
    out->airspeed_cm_s = 1500;
    return BOARD_OK;
}
