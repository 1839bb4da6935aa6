/*
 * sil_imu_model.c - the SIL's IMU error model (see sil_imu_model.h). Each
 * expression follows sil/helical_sil/sensors/models.py in its order of
 * operations: the samples are the Python model's to the bit.
 */
#include "sil_imu_model.h"

#include <math.h>
#include <stddef.h>

/* truth.py: standard gravity, metres per foot; models.py: the timing tolerance */
#define SIL_G0_M_S2 9.80665
#define SIL_FT_M    0.3048
#define SIL_T_EPS_S 1e-6
#define SIL_PI      3.141592653589793 /* Python's math.pi */

/* _TriadErrors.apply: w = 3 walk normals then 3 noise normals. Returns 1
 * when an axis sits at its full scale. */
static int triad_apply(sil_imu_triad_t *e, const double in[3], double dt_s, const double w[6],
                       double out[3])
{
    const double k = e->walk * sqrt(dt_s);
    int saturated = 0;
    for (int i = 0; i < 3; i++) {
        e->walk_state[i] += k * w[i];
        const double *r = e->matrix[i];
        double v = r[0] * in[0] + r[1] * in[1] + r[2] * in[2] + e->bias[i] + e->walk_state[i] +
                   e->sigma * w[3 + i];
        if (fabs(v) >= e->full_scale) {
            saturated = 1;
            v = copysign(e->full_scale, v);
        }
        out[i] = v;
    }
    return saturated;
}

int sil_imu_model_run(sil_imu_model_t *m, const double *in, int32_t n, double t_base_s, double dt_s,
                      const double *normals_gyro, const double *normals_accel, int32_t n_normals,
                      double *gyro_rad_s, double *accel_g, int32_t *saturated, int32_t *at)
{
    const double period = 1.0 / m->rate_hz;
    for (int32_t j = 0; j < n; j++) {
        *at = j;
        if (6 * (j + 1) > n_normals) {
            return SIL_IMU_FEW_NORMALS;
        }
        const double t = t_base_s + ((double)j + 1.0) * dt_s;
        if (!isfinite(t)) {
            return SIL_IMU_BAD_TIME;
        }
        double dt = 0.0;
        if (m->have_last != 0) {
            dt = t - m->t_last_s;
            if (fabs(dt - period) > SIL_T_EPS_S) {
                return SIL_IMU_BAD_TIME;
            }
        }
        const double *s = &in[(int64_t)j * SIL_IMU_IN_COUNT];
        /* truth.ideal_gyro_rad_s: (-q, p, r); ideal_accel_g: FRD force per
         * mass in m/s^2, to library axes (-y, x, z), in g */
        const double m_slug = s[SIL_IMU_IN_MASS];
        const double fx = s[SIL_IMU_IN_FBX] / m_slug * SIL_FT_M;
        const double fy = s[SIL_IMU_IN_FBY] / m_slug * SIL_FT_M;
        const double fz = s[SIL_IMU_IN_FBZ] / m_slug * SIL_FT_M;
        const double tg[3] = {-s[SIL_IMU_IN_Q], s[SIL_IMU_IN_P], s[SIL_IMU_IN_R]};
        const double ta[3] = {-fy / SIL_G0_M_S2, fx / SIL_G0_M_S2, fz / SIL_G0_M_S2};
        for (int i = 0; i < 3; i++) {
            if (!isfinite(tg[i]) || !isfinite(ta[i])) {
                return SIL_IMU_NOT_FINITE;
            }
        }
        m->t_last_s = t;
        m->have_last = 1;
        const double wt = 2.0 * SIL_PI * m->vibration_hz * t;
        double vg[3], va[3];
        for (int i = 0; i < 3; i++) {
            vg[i] = tg[i] + m->vibration_gyro * sin(wt + m->phase_gyro[i]);
            va[i] = ta[i] + m->vibration_accel * sin(wt + m->phase_accel[i]);
        }
        const int64_t at6 = (int64_t)j * 6; /* the sample's 6 normals, its 3 outputs */
        const int64_t at3 = (int64_t)j * 3;
        const int gs = triad_apply(&m->gyro, vg, dt, &normals_gyro[at6], &gyro_rad_s[at3]);
        const int as = triad_apply(&m->accel, va, dt, &normals_accel[at6], &accel_g[at3]);
        if (saturated != NULL) {
            saturated[j] = gs + (2 * as); /* bit 0 gyro, bit 1 accel: each 0 or 1 */
        }
    }
    *at = n;
    return SIL_IMU_OK;
}

uint32_t sil_imu_model_size(void)
{
    return (uint32_t)sizeof(sil_imu_model_t);
}
