/*
 * dcm_test_util.h - what the estimator tests share (header-only): parameter
 * sets, samples from real values, a seeded RNG, and the attitude error of
 * the library's state against a double matrix.
 */
#ifndef DCM_TEST_UTIL_H
#define DCM_TEST_UTIL_H

#include <math.h>
#include <stdint.h>
#include <stdio.h>

#include "dcm_reference.h"
#include "helical/estimator/dcm.h"
#include "unity.h"

#define DT_PI DCMR_PI
#define DEG   (DCMR_PI / 180.0)

static inline q16_t dt_q16(double v)
{
    return (q16_t)llround(v * 65536.0);
}

/* The defaults with the PI gains zero: the pure propagation. */
static inline ht_dcm_params_t dt_params_open_loop(void)
{
    ht_dcm_params_t p;
    ht_dcm_params_default(&p);
    p.kp_rollpitch = 0;
    p.ki_rollpitch = 0;
    p.kp_yaw = 0;
    p.ki_yaw = 0;
    return p;
}

static inline void dt_init(ht_dcm_t *d, const ht_dcm_params_t *p)
{
    ht_dcm_param_id_t bad = HT_DCM_P_COUNT;
    TEST_ASSERT_EQUAL_INT(0, ht_dcm_init(d, p, &bad));
    TEST_ASSERT_EQUAL_INT(HT_DCM_P_NONE, bad);
}

static inline ht_imu_sample_t dt_imu(const double w[3], const double f[3])
{
    ht_imu_sample_t s;
    for (int i = 0; i < 3; i++) {
        s.gyro_rad_s[i] = dt_q16(w[i]);
        s.accel_g[i] = dt_q16(f[i]);
    }
    return s;
}

/* The state at attitude r (Q30, rounded), aligned, zero bias. */
static inline void dt_state_at(ht_dcm_state_t *s, double r[3][3])
{
    ht_dcm_reset(s);
    dcmr_to_state(r, s);
    s->flags = HT_DCM_F_ALIGNED;
}

/* The angle between the state's attitude and r, rad. */
static inline double dt_att_err(const ht_dcm_state_t *s, double r[3][3])
{
    double m[3][3];
    dcmr_from_state(s, m);
    return dcmr_angle_between(m, r);
}

/* splitmix64 */
static inline uint64_t dt_rng(uint64_t *s)
{
    uint64_t z = (*s += UINT64_C(0x9E3779B97F4A7C15));
    z = (z ^ (z >> 30)) * UINT64_C(0xBF58476D1CE4E5B9);
    z = (z ^ (z >> 27)) * UINT64_C(0x94D049BB133111EB);
    return z ^ (z >> 31);
}

static inline double dt_uniform(uint64_t *s, double lo, double hi)
{
    return lo + (hi - lo) * ((double)(dt_rng(s) >> 11) / 9007199254740992.0);
}

/* f = R^T [0, 0, -1]: the specific force of unaccelerated flight at r. */
static inline void dt_gravity_body(double r[3][3], double f[3])
{
    for (int j = 0; j < 3; j++) {
        f[j] = -r[2][j];
    }
}

/* The fixture of the drift-correction and API tests: the estimator, its
 * state and its parameters, back at the defaults before every test (Unity
 * calls setUp and tearDown around each one). */
#define DT_DEFAULT_FIXTURE()                                                                       \
    static ht_dcm_t dcm;                                                                           \
    static ht_dcm_state_t st;                                                                      \
    static ht_dcm_params_t prm;                                                                    \
    void setUp(void)                                                                               \
    {                                                                                              \
        ht_dcm_params_default(&prm);                                                               \
        /* the tests give the velocity of the sample's own instant */                              \
        prm.gps_latency_ms = 0u;                                                                   \
        dt_init(&dcm, &prm);                                                                       \
        ht_dcm_reset(&st);                                                                         \
    }                                                                                              \
    void tearDown(void) {}

#endif /* DCM_TEST_UTIL_H */
