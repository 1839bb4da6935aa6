/*
 * imu_decimate.c - the IMU's boxcar decimation (see imu_decimate.h).
 */
#include "imu_decimate.h"

#include <stddef.h>

void imu_decimate_reset(imu_decimate_t *d)
{
    if (d == NULL) {
        return;
    }
    for (unsigned i = 0u; i < 3u; ++i) {
        d->gyro_sum[i] = 0;
        d->accel_sum[i] = 0;
    }
    d->n = 0u;
}

void imu_decimate_add(imu_decimate_t *d, const ht_imu_sample_t *s)
{
    if (d == NULL || s == NULL) {
        return;
    }
    if (d->n >= IMU_DECIMATE_MAX) {
        if (d->dropped != UINT16_MAX) {
            d->dropped = (uint16_t)(d->dropped + 1u);
        }
        return;
    }
    for (unsigned i = 0u; i < 3u; ++i) {
        d->gyro_sum[i] += s->gyro_rad_s[i];
        d->accel_sum[i] += s->accel_g[i];
    }
    d->n = (uint16_t)(d->n + 1u);
}

/* a / n rounded to nearest, halves away from zero; n > 0. */
static int32_t mean_round(int32_t a, int32_t n)
{
    if (a >= 0) {
        return (a + n / 2) / n;
    }
    return -((-a + n / 2) / n);
}

uint16_t imu_decimate_take(imu_decimate_t *d, ht_imu_sample_t *out)
{
    if (d == NULL || out == NULL || d->n == 0u) {
        return 0u;
    }
    const int32_t n = (int32_t)d->n;
    for (unsigned i = 0u; i < 3u; ++i) {
        out->gyro_rad_s[i] = mean_round(d->gyro_sum[i], n);
        out->accel_g[i] = mean_round(d->accel_sum[i], n);
    }
    const uint16_t taken = d->n;
    imu_decimate_reset(d);
    return taken;
}
