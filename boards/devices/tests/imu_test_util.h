/*
 * imu_test_util.h - the host tests' independent model of the board
 * alignment and of the scaling (float: test code only).
 *
 * Alignment, derived from the physical description in imu_spi.h rather than
 * from the driver's table: in library body axes (X left wing, Y forward, Z
 * down) a chip mounted YAW0 has its +X toward the right wing (-1, 0, 0), +Y
 * forward (0, 1, 0), +Z up (0, 0, -1). YAWn turns the chip by n degrees
 * clockwise seen from above: a rotation by +n about body Z (down), which
 * takes forward to the right wing at 90. FLIP then turns it upside down
 * about the fuselage: diag(-1, 1, -1). A chip axis c reads c . v of a body
 * vector v.
 */
#ifndef HT_IMU_TEST_UTIL_H
#define HT_IMU_TEST_UTIL_H

#include <math.h>
#include <stdint.h>

#define TEST_PI 3.14159265358979323846

/* The chip's reading of a body-axes vector for an alignment (0..7). */
static inline void chip_from_body(unsigned align, const double body[3], double chip[3])
{
    const double base[3][3] = {{-1.0, 0.0, 0.0}, {0.0, 1.0, 0.0}, {0.0, 0.0, -1.0}};
    const double yaw = (double)(align % 4u) * (TEST_PI / 2.0);
    const double c = cos(yaw);
    const double s = sin(yaw);
    const int flip = align >= 4u;
    for (int k = 0; k < 3; ++k) {
        /* Rz(yaw) applied to the chip axis k (body coordinates) */
        double ax[3] = {c * base[k][0] - s * base[k][1], s * base[k][0] + c * base[k][1],
                        base[k][2]};
        if (flip) {
            ax[0] = -ax[0];
            ax[2] = -ax[2];
        }
        chip[k] = ax[0] * body[0] + ax[1] * body[1] + ax[2] * body[2];
    }
}

/* The exact Q16 rad/s of a gyro count at 16.4 LSB per deg/s, rounded. */
static inline double gyro_q16_exact(int16_t counts)
{
    return (double)counts * 65536.0 * TEST_PI / (180.0 * 16.4);
}

#endif /* HT_IMU_TEST_UTIL_H */
