/*
 * The estimator's propagation and renormalization (the PI gains zero):
 * constant rates against the closed-form rotation, a coning motion, 10^6
 * random-rate steps for orthonormality, 10^6 zero-rate steps for drift, and
 * the fixed-point step against the double reference of the same equations.
 */
#include "dcm_test_util.h"

#include <stdlib.h>
#include <string.h>

static ht_dcm_t dcm;
static ht_dcm_state_t st;

void setUp(void)
{
    const ht_dcm_params_t p = dt_params_open_loop();
    dt_init(&dcm, &p);
}

void tearDown(void) {}

static const ht_dcm_aiding_t no_aid = {0};
/* an accelerometer reading outside the band: the gravity reference is off
 * (the gains are zero anyway; this keeps the ACCEL_IGNORED path honest) */
static const double f_off[3] = {0.0, 0.0, -3.0};

/* Rotate at w (rad/s) for n samples from r0; the worst angle to the exact
 * rotation over the run, and that of the double reference. */
static void constant_rate(const double w[3], int n, double *worst_fix, double *worst_ref)
{
    double r0[3][3];
    dcmr_from_euler(20 * DEG, -10 * DEG, 30 * DEG, r0);
    dt_state_at(&st, r0);
    dcmr_params_t rp;
    dcmr_params_from(&dcm.p, &rp);
    dcmr_state_t rs;
    dcmr_reset(&rs);
    memcpy(rs.r, r0, sizeof r0);
    rs.aligned = 1;
    const ht_imu_sample_t imu = dt_imu(w, f_off);
    const double wq[3] = {imu.gyro_rad_s[0] / 65536.0, imu.gyro_rad_s[1] / 65536.0,
                          imu.gyro_rad_s[2] / 65536.0};
    *worst_fix = 0.0;
    *worst_ref = 0.0;
    for (int k = 1; k <= n; k++) {
        ht_dcm_update(&dcm, &st, &imu, &no_aid);
        dcmr_update(&rp, &rs, wq, f_off, &no_aid);
        double ex[3][3];
        dcmr_rotate_body(r0, wq, k / 200.0, ex);
        const double ef = dt_att_err(&st, ex);
        const double er = dcmr_angle_between(rs.r, ex);
        *worst_fix = ef > *worst_fix ? ef : *worst_fix;
        *worst_ref = er > *worst_ref ? er : *worst_ref;
    }
}

/* One full turn at 1 rad/s about X, Y, Z and a mixed axis (1257 samples at
 * 200 Hz); also 5 rad/s (a fast roll) for one turn. The second-order step
 * with renormalization turns by w dt - (w dt)^3 / 6 per sample: 2.6e-5 rad
 * per turn at 1 rad/s, 6.6e-4 at 5 rad/s. */
static void test_constant_rate_full_turn_vs_closed_form(void)
{
    const double axes[4][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0.6, -0.48, 0.64}};
    for (int a = 0; a < 4; a++) {
        for (int sp = 0; sp < 2; sp++) {
            const double rate = sp == 0 ? 1.0 : 5.0;
            const double w[3] = {rate * axes[a][0], rate * axes[a][1], rate * axes[a][2]};
            const int n = (int)ceil(2.0 * DT_PI / rate * 200.0);
            double wf, wr;
            constant_rate(w, n, &wf, &wr);
            const double model = pow(rate / 200.0, 3) / 6.0 * n; /* the step's own error */
            char msg[160];
            snprintf(msg, sizeof msg,
                     "axis %d, %.0f rad/s: worst %.3e rad (double reference %.3e, model %.3e)", a,
                     rate, wf, wr, model);
            printf("  %s\n", msg);
            /* the library is the algorithm: within 1e-6 rad of its double form */
            TEST_ASSERT_TRUE_MESSAGE(fabs(wf - wr) < 1e-6, msg);
            /* and the algorithm within 1.2x its truncation model + 1e-6 */
            TEST_ASSERT_TRUE_MESSAGE(wf < 1.2 * model + 1e-6, msg);
        }
    }
}

/* Classic coning: R(t) = R0 Rot([cos Wt, sin Wt, 0], b), whose body rate is
 * W [-sin b sin Wt, sin b cos Wt, cos b - 1]. b = 2 degrees, 5 Hz, 60 s at
 * 200 Hz. The attitude error is the rate-integration algorithm's coning
 * drift (4.7e-3 rad in 60 s, the drift correction's job in flight); the
 * library must match its double form, and the error stays within 1.1x the
 * coning model. */
static void test_coning_error_bounded(void)
{
    double r0[3][3];
    dcmr_from_euler(10 * DEG, 5 * DEG, 40 * DEG, r0);
    const double b = 2.0 * DEG, big_w = 2.0 * DT_PI * 5.0, dt = 1.0 / 200.0;
    const double x_axis[3] = {1, 0, 0};
    double start[3][3]; /* the cone at t = 0: rotated by b about X */
    dcmr_rotate_body(r0, x_axis, b, start);
    dt_state_at(&st, start);
    dcmr_params_t rp;
    dcmr_params_from(&dcm.p, &rp);
    dcmr_state_t rs;
    dcmr_reset(&rs);
    memcpy(rs.r, start, sizeof start);
    rs.aligned = 1;
    double worst = 0.0, worst_ref = 0.0, worst_diff = 0.0;
    for (int k = 0; k < 200 * 60; k++) {
        /* the rate averaged over the sample interval, as an integrating
         * (or anti-alias filtered) gyro reports it */
        const double t0 = k * dt, t1 = (k + 1) * dt;
        const double w[3] = {sin(b) * (cos(big_w * t1) - cos(big_w * t0)) / dt,
                             sin(b) * (sin(big_w * t1) - sin(big_w * t0)) / dt,
                             big_w * (cos(b) - 1.0)};
        const ht_imu_sample_t imu = dt_imu(w, f_off);
        const double wq[3] = {imu.gyro_rad_s[0] / 65536.0, imu.gyro_rad_s[1] / 65536.0,
                              imu.gyro_rad_s[2] / 65536.0};
        ht_dcm_update(&dcm, &st, &imu, &no_aid);
        dcmr_update(&rp, &rs, wq, f_off, &no_aid);
        const double tt = (k + 1) * dt;
        /* exact: rotation by b about [cos Wt, sin Wt, 0] */
        const double ax[3] = {cos(big_w * tt), sin(big_w * tt), 0.0};
        double ex[3][3];
        dcmr_rotate_body(r0, ax, b, ex);
        double m[3][3];
        dcmr_from_state(&st, m);
        const double e = dcmr_angle_between(m, ex);
        const double er = dcmr_angle_between(rs.r, ex);
        const double ed = dcmr_angle_between(m, rs.r);
        worst = e > worst ? e : worst;
        worst_ref = er > worst_ref ? er : worst_ref;
        worst_diff = ed > worst_diff ? ed : worst_diff;
    }
    /* a single-sample rate algorithm drifts about the cone axis at
     * W b^2 / 2 (1 - sin(W dt) / (W dt)): 7.9e-5 rad/s here */
    const double model = big_w * b * b / 2.0 * (1.0 - sin(big_w * dt) / (big_w * dt)) * 60.0;
    char msg[240];
    snprintf(msg, sizeof msg,
             "coning 2 deg at 5 Hz, 60 s: worst attitude error %.3e rad (double reference "
             "%.3e, coning model %.3e), library vs reference %.3e",
             worst, worst_ref, model, worst_diff);
    printf("  %s\n", msg);
    TEST_ASSERT_TRUE_MESSAGE(worst_diff < 1e-5, msg);
    TEST_ASSERT_TRUE_MESSAGE(worst < 1.1 * model, msg);
}

/* 10^6 samples of random rates (uniform +/-3 rad/s per axis, new every
 * sample, seed 1): R stays orthonormal. */
static void test_orthonormal_over_a_million_random_steps(void)
{
    double r0[3][3];
    dcmr_from_euler(10 * DEG, 5 * DEG, 200 * DEG, r0);
    dt_state_at(&st, r0);
    uint64_t seed = 1u;
    double worst = 0.0;
    for (long k = 0; k < 1000000L; k++) {
        const double w[3] = {dt_uniform(&seed, -3, 3), dt_uniform(&seed, -3, 3),
                             dt_uniform(&seed, -3, 3)};
        const ht_imu_sample_t imu = dt_imu(w, f_off);
        ht_dcm_update(&dcm, &st, &imu, &no_aid);
        if ((k & 255) == 0 || k > 999000L) {
            double m[3][3];
            dcmr_from_state(&st, m);
            const double e = dcmr_ortho_err(m);
            worst = e > worst ? e : worst;
        }
    }
    char msg[120];
    snprintf(msg, sizeof msg, "10^6 random steps: worst |R R^T - I| = %.3e (%.1f LSB of Q30)",
             worst, worst * 1073741824.0);
    printf("  %s\n", msg);
    TEST_ASSERT_TRUE_MESSAGE(worst < 2e-8, msg);
    TEST_ASSERT_EQUAL_UINT16(HT_DCM_F_ALIGNED | HT_DCM_F_ACCEL_IGNORED, st.flags);
}

/* Zero rates for 10^6 samples (83 minutes at 200 Hz) from a general
 * attitude: rounding does not drift the attitude. */
static void test_zero_rate_no_drift_over_a_million_steps(void)
{
    double r0[3][3];
    dcmr_from_euler(-35 * DEG, 22 * DEG, 123 * DEG, r0);
    dt_state_at(&st, r0);
    ht_dcm_state_t start = st;
    const double z[3] = {0, 0, 0};
    const ht_imu_sample_t imu = dt_imu(z, f_off);
    int32_t worst = 0;
    for (long k = 0; k < 1000000L; k++) {
        ht_dcm_update(&dcm, &st, &imu, &no_aid);
        if ((k & 1023) == 0 || k == 999999L) {
            for (int i = 0; i < 3; i++) {
                for (int j = 0; j < 3; j++) {
                    const int32_t d = abs(st.r[i][j] - start.r[i][j]);
                    worst = d > worst ? d : worst;
                }
            }
        }
    }
    char msg[120];
    snprintf(msg, sizeof msg, "zero rate, 10^6 steps: worst element change %d LSB of Q30 (%.2e)",
             (int)worst, worst / 1073741824.0);
    printf("  %s\n", msg);
    TEST_ASSERT_TRUE_MESSAGE(worst <= 8, msg);
    TEST_ASSERT_TRUE(dt_att_err(&st, r0) < 1e-8);
}

/* A small constant rate (0.001 rad/s) for 10^5 samples: the angle turned
 * matches w t within the rounding of theta (half a Q30 LSB per sample). */
static void test_slow_rate_integrates_exactly(void)
{
    double r0[3][3];
    dcmr_from_euler(0, 0, 0, r0);
    dt_state_at(&st, r0);
    const double w[3] = {0.0, 0.0, 0.001};
    const ht_imu_sample_t imu = dt_imu(w, f_off);
    const double wq = imu.gyro_rad_s[2] / 65536.0;
    for (long k = 0; k < 100000L; k++) {
        ht_dcm_update(&dcm, &st, &imu, &no_aid);
    }
    ht_dcm_output_t out;
    ht_dcm_output(&st, &out);
    const double yaw = atan2((double)st.r[1][1], (double)st.r[0][1]);
    const double expect = wq * 500.0;
    char msg[120];
    snprintf(msg, sizeof msg, "0.001 rad/s for 500 s: yaw %.9f rad, w t %.9f rad", yaw, expect);
    printf("  %s\n", msg);
    /* theta = w dt is rounded to Q30 once per sample: 66/65536 rad/s * 5 ms
     * is 5406.7 LSB, carried as 5407, 0.3 LSB (5.5e-5 relative) too much.
     * The bound is half an LSB per sample, 4.7e-5 rad here: 9.3e-8 rad/s at
     * 200 Hz, 1/160 of one Q16 gyro LSB. */
    TEST_ASSERT_DOUBLE_WITHIN(100000.0 * 0.5 / 1073741824.0, expect, yaw);
    TEST_ASSERT_TRUE(fabs(yaw - expect) > 1e-6); /* the rounding is visible: 2.7e-5 */
    TEST_ASSERT_INT_WITHIN(1, (int)lround(expect / DEG * 100.0), out.yaw_cdeg);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_constant_rate_full_turn_vs_closed_form);
    RUN_TEST(test_coning_error_bounded);
    RUN_TEST(test_orthonormal_over_a_million_random_steps);
    RUN_TEST(test_zero_rate_no_drift_over_a_million_steps);
    RUN_TEST(test_slow_rate_integrates_exactly);
    return UNITY_END();
}
