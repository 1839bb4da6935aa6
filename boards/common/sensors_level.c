/*
 * sensors_level.c - the sensor seam of a board that has no sensor drivers
 * yet: an IMU at rest and level (no rotation, 1 g up along body -Z), no GPS,
 * no pitot, no baro. The firmware's estimator aligns on it and holds a level
 * attitude, so the image runs its whole step on the bench.
 */
#include "helical/board.h"

#include <stddef.h>
#include <string.h>

board_status_t board_sensors_read(board_sensors_t *out)
{
    if (out == NULL) {
        return BOARD_ERR_NULL;
    }
    (void)memset(out, 0, sizeof *out);
    out->imu_fresh = 1u;
    out->imu.accel_g[2] = -65536; /* -1 g along Z: the specific force at rest */
    return BOARD_OK;
}
