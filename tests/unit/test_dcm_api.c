/*
 * The estimator's contract at its edges: every parameter at its min and max
 * and one step beyond (the refusal names the field), NULL and uninitialised
 * inputs, sensor saturation flags, renormalization failure and recovery,
 * alignment at any attitude, and the integer trigonometry against libm.
 */
#include "dcm_test_util.h"

#include <stdlib.h>
#include <string.h>

#include "../../src/estimator/dcm_trig.h"

DT_DEFAULT_FIXTURE()

/* --- parameters -------------------------------------------------------- */

static void expect_param(ht_dcm_params_t p, ht_dcm_param_id_t id, int ok)
{
    ht_dcm_t d;
    ht_dcm_param_id_t bad = HT_DCM_P_COUNT;
    const int r = ht_dcm_init(&d, &p, &bad);
    if (ok) {
        TEST_ASSERT_EQUAL_INT_MESSAGE(0, r, ht_dcm_param_name(id));
        TEST_ASSERT_EQUAL_INT(HT_DCM_P_NONE, bad);
        TEST_ASSERT_EQUAL_UINT8(1u, d.ready);
    } else {
        TEST_ASSERT_EQUAL_INT_MESSAGE(2, r, ht_dcm_param_name(id));
        TEST_ASSERT_EQUAL_INT_MESSAGE(id, bad, ht_dcm_param_name(id));
        TEST_ASSERT_EQUAL_UINT8(0u, d.ready);
    }
}

#define EDGE(field, id, lo, hi)                                                                    \
    do {                                                                                           \
        ht_dcm_params_t p = prm;                                                                   \
        p.field = (lo);                                                                            \
        expect_param(p, id, 1);                                                                    \
        p.field = (hi);                                                                            \
        expect_param(p, id, 1);                                                                    \
        p.field = (lo)-1;                                                                          \
        expect_param(p, id, 0);                                                                    \
        p.field = (hi) + 1;                                                                        \
        expect_param(p, id, 0);                                                                    \
    } while (0)

static void test_parameter_edges_each_field(void)
{
    EDGE(imu_rate_hz, HT_DCM_P_IMU_RATE, 50u, 1000u);
    EDGE(kp_rollpitch, HT_DCM_P_KP_ROLLPITCH, 0, 2 * Q16_ONE);
    EDGE(ki_rollpitch, HT_DCM_P_KI_ROLLPITCH, 0, 4 * Q16_ONE);
    EDGE(kp_yaw, HT_DCM_P_KP_YAW, 0, 16 * Q16_ONE);
    EDGE(ki_yaw, HT_DCM_P_KI_YAW, 0, 4 * Q16_ONE);
    EDGE(gyro_bias_max_rad_s, HT_DCM_P_BIAS_MAX, 0, Q16_ONE);
    EDGE(gyro_limit_rad_s, HT_DCM_P_GYRO_LIMIT, Q16_ONE, 64 * Q16_ONE);
    EDGE(accel_limit_g, HT_DCM_P_ACCEL_LIMIT, Q16_ONE, 32 * Q16_ONE);
    EDGE(accel_band_g, HT_DCM_P_ACCEL_BAND, 1, 4 * Q16_ONE);
    EDGE(gps_min_speed_cm_s, HT_DCM_P_GPS_MIN_SPEED, 0, 10000);
    {
        ht_dcm_params_t p = prm;
        p.gps_latency_ms = 0u;
        expect_param(p, HT_DCM_P_GPS_LATENCY, 1);
        p.gps_latency_ms = 500u;
        expect_param(p, HT_DCM_P_GPS_LATENCY, 1);
        p.gps_latency_ms = 501u;
        expect_param(p, HT_DCM_P_GPS_LATENCY, 0);
        p.gps_latency_ms = UINT16_MAX;
        expect_param(p, HT_DCM_P_GPS_LATENCY, 0);
    }
    {
        ht_dcm_params_t p = prm;
        p.centripetal = (uint8_t)HT_DCM_CF_OFF;
        expect_param(p, HT_DCM_P_CENTRIPETAL, 1);
        p.centripetal = (uint8_t)HT_DCM_CF_AUTO;
        expect_param(p, HT_DCM_P_CENTRIPETAL, 1);
        p.centripetal = 3u;
        expect_param(p, HT_DCM_P_CENTRIPETAL, 0);
    }
    TEST_ASSERT_EQUAL_STRING("imu_rate_hz", ht_dcm_param_name(HT_DCM_P_IMU_RATE));
    TEST_ASSERT_EQUAL_STRING("accel_band", ht_dcm_param_name(HT_DCM_P_ACCEL_BAND));
    TEST_ASSERT_EQUAL_STRING("centripetal", ht_dcm_param_name(HT_DCM_P_CENTRIPETAL));
    TEST_ASSERT_EQUAL_STRING("gps_latency", ht_dcm_param_name(HT_DCM_P_GPS_LATENCY));
    TEST_ASSERT_EQUAL_STRING("", ht_dcm_param_name(HT_DCM_P_NONE));
    TEST_ASSERT_EQUAL_STRING("", ht_dcm_param_name(HT_DCM_P_COUNT));
    for (int i = 1; i < (int)HT_DCM_P_COUNT; i++) {
        TEST_ASSERT_TRUE(strlen(ht_dcm_param_name((ht_dcm_param_id_t)i)) > 0u);
    }
}

static void test_defaults_and_derived_values(void)
{
    TEST_ASSERT_EQUAL_UINT16(200u, prm.imu_rate_hz);
    TEST_ASSERT_EQUAL_INT32(26214, prm.kp_rollpitch);
    TEST_ASSERT_EQUAL_INT32(2621, prm.ki_rollpitch);
    TEST_ASSERT_EQUAL_INT32(32768, prm.kp_yaw);
    TEST_ASSERT_EQUAL_INT32(1311, prm.ki_yaw);
    TEST_ASSERT_EQUAL_INT32(6554, prm.gyro_bias_max_rad_s);
    TEST_ASSERT_EQUAL_INT32(2287206, prm.gyro_limit_rad_s);
    TEST_ASSERT_EQUAL_INT32(16 * Q16_ONE, prm.accel_limit_g);
    TEST_ASSERT_EQUAL_INT32(Q16_ONE / 2, prm.accel_band_g);
    TEST_ASSERT_EQUAL_INT16(300, prm.gps_min_speed_cm_s);
    TEST_ASSERT_EQUAL_UINT8(HT_DCM_CF_AUTO, prm.centripetal);
    /* dt: 2^30 / rate rounded, at each end */
    TEST_ASSERT_EQUAL_INT32(5368709, dcm.dt_q30); /* 5368709.12 */
    {
        /* the GPS latency (the fixture sets 0: its velocities have none) in
         * samples, rounded; 980.665 cm/s^2 * dt in Q24 within 2e-8 */
        ht_dcm_params_t q;
        ht_dcm_params_default(&q);
        TEST_ASSERT_EQUAL_UINT16(100u, q.gps_latency_ms);
        ht_dcm_t dq;
        dt_init(&dq, &q);
        TEST_ASSERT_EQUAL_UINT16(20u, dq.gps_latency_samples);
        TEST_ASSERT_INT32_WITHIN(2, 82264143, dq.g_dt_q24); /* 82264142.64 */
        /* the wind's weight per sample, dt / 20 s in Q30: 5368709 / 20 */
        TEST_ASSERT_EQUAL_INT32(268435, dq.wind_alpha_q30); /* 268435.45 */
        q.imu_rate_hz = 333u;
        dt_init(&dq, &q);
        TEST_ASSERT_EQUAL_UINT16(33u, dq.gps_latency_samples); /* 33.3 */
        TEST_ASSERT_INT32_WITHIN(2, 49407893, dq.g_dt_q24);    /* 49407893.48 */
        q.imu_rate_hz = 50u;
        q.gps_latency_ms = 500u;
        dt_init(&dq, &q);
        TEST_ASSERT_EQUAL_UINT16(25u, dq.gps_latency_samples);
        TEST_ASSERT_INT32_WITHIN(8, 329056571, dq.g_dt_q24); /* 329056570.57 */
        TEST_ASSERT_EQUAL_INT32(1073742, dq.wind_alpha_q30); /* 21474836 / 20 = 1073741.8 */
    }
    ht_dcm_params_t p = prm;
    p.imu_rate_hz = 1000u;
    dt_init(&dcm, &p);
    TEST_ASSERT_EQUAL_INT32(1073742, dcm.dt_q30); /* 1073741.824 */
    p.imu_rate_hz = 50u;
    p.kp_rollpitch = 2 * Q16_ONE;
    p.ki_rollpitch = 4 * Q16_ONE;
    dt_init(&dcm, &p);
    TEST_ASSERT_EQUAL_INT32(21474836, dcm.dt_q30);
    /* the largest gain products fit: 0.04 in Q32, 0.08 in Q34 */
    TEST_ASSERT_DOUBLE_WITHIN(1e-8, 0.04, dcm.kp_rp_dt_q32 / 4294967296.0);
    TEST_ASSERT_DOUBLE_WITHIN(1e-8, 0.08, dcm.ki_rp_dt_q34 / 17179869184.0);
    ht_dcm_params_default(NULL); /* no crash */
}

/* --- NULL and uninitialised ---------------------------------------------- */

static void test_null_and_uninitialised_inputs(void)
{
    ht_dcm_param_id_t bad = HT_DCM_P_COUNT;
    TEST_ASSERT_EQUAL_INT(1, ht_dcm_init(NULL, &prm, &bad));
    TEST_ASSERT_EQUAL_INT(HT_DCM_P_NONE, bad);
    ht_dcm_t d;
    TEST_ASSERT_EQUAL_INT(1, ht_dcm_init(&d, NULL, NULL));
    /* a refused init leaves d unusable: update does nothing */
    ht_dcm_params_t p = prm;
    p.imu_rate_hz = 0u;
    TEST_ASSERT_EQUAL_INT(2, ht_dcm_init(&d, &p, NULL));
    const double w[3] = {1, 1, 1}, f[3] = {0, 0, -1};
    const ht_imu_sample_t imu = dt_imu(w, f);
    const ht_dcm_aiding_t aid = {0};
    ht_dcm_state_t before = st;
    ht_dcm_update(&d, &st, &imu, &aid);
    TEST_ASSERT_EQUAL_MEMORY(&before, &st, sizeof st);
    ht_dcm_update(NULL, &st, &imu, &aid);
    ht_dcm_update(&dcm, &st, NULL, &aid);
    ht_dcm_update(&dcm, NULL, &imu, &aid);
    TEST_ASSERT_EQUAL_MEMORY(&before, &st, sizeof st);
    TEST_ASSERT_EQUAL_INT(2, ht_dcm_align(&d, &st, imu.accel_g, 0u, 0u));
    TEST_ASSERT_EQUAL_INT(2, ht_dcm_align(NULL, &st, imu.accel_g, 0u, 0u));
    TEST_ASSERT_EQUAL_INT(2, ht_dcm_align(&dcm, NULL, imu.accel_g, 0u, 0u));
    TEST_ASSERT_EQUAL_INT(2, ht_dcm_align(&dcm, &st, NULL, 0u, 0u));
    TEST_ASSERT_EQUAL_MEMORY(&before, &st, sizeof st);
    /* NULL aiding is no aiding */
    ht_dcm_update(&dcm, &st, &imu, NULL);
    TEST_ASSERT_EQUAL_UINT32(1u, st.samples);
    TEST_ASSERT_EQUAL_UINT16(HT_DCM_F_ALIGNED, st.flags);
    ht_dcm_reset(NULL);
    ht_dcm_output(&st, NULL);
    ht_dcm_output_t out;
    memset(&out, 0x5A, sizeof out);
    ht_dcm_output(NULL, &out);
    TEST_ASSERT_EQUAL_INT16(0, out.r[2][2]);
    TEST_ASSERT_EQUAL_UINT16(0u, out.flags);
}

/* The first sample aligns roll and pitch from its accelerometer reading. */
static void test_first_sample_aligns(void)
{
    double r[3][3];
    dcmr_from_euler(-30 * DEG, 12 * DEG, 0, r);
    double f[3];
    dt_gravity_body(r, f);
    const double w[3] = {0, 0, 0};
    const ht_imu_sample_t imu = dt_imu(w, f);
    /* below 0.5 g it cannot: not aligned yet, and no reference used */
    const double weak[3] = {0, 0, -0.3};
    const ht_imu_sample_t imu_weak = dt_imu(w, weak);
    ht_dcm_update(&dcm, &st, &imu_weak, NULL);
    TEST_ASSERT_EQUAL_UINT16(HT_DCM_F_ACCEL_IGNORED, st.flags);
    ht_dcm_update(&dcm, &st, &imu, NULL);
    TEST_ASSERT_TRUE((st.flags & HT_DCM_F_ALIGNED) != 0u);
    ht_dcm_output_t out;
    ht_dcm_output(&st, &out);
    TEST_ASSERT_INT_WITHIN(1, -3000, out.roll_cdeg);
    TEST_ASSERT_INT_WITHIN(1, 1200, out.pitch_cdeg);
    TEST_ASSERT_INT_WITHIN(1, 0, out.yaw_cdeg > 18000 ? out.yaw_cdeg - 36000 : out.yaw_cdeg);
}

/* --- saturation -------------------------------------------------------- */

static void test_saturation_flags_at_the_full_scales(void)
{
    ht_imu_sample_t imu = {{0, 0, 0}, {0, 0, -Q16_ONE}};
    const q16_t gl = prm.gyro_limit_rad_s, al = prm.accel_limit_g;
    for (int axis = 0; axis < 3; axis++) {
        for (int sign = -1; sign <= 1; sign += 2) {
            setUp();
            imu.gyro_rad_s[axis] = sign * (gl - 1);
            ht_dcm_update(&dcm, &st, &imu, NULL);
            TEST_ASSERT_EQUAL_UINT16(0u, st.flags & HT_DCM_F_GYRO_SATURATED);
            imu.gyro_rad_s[axis] = sign * gl;
            ht_dcm_update(&dcm, &st, &imu, NULL);
            TEST_ASSERT_EQUAL_UINT16(HT_DCM_F_GYRO_SATURATED, st.flags & HT_DCM_F_GYRO_SATURATED);
            /* beyond the full scale the rate is clamped: the same rotation */
            ht_dcm_state_t a = st, b = st;
            ht_dcm_update(&dcm, &a, &imu, NULL);
            imu.gyro_rad_s[axis] = (sign > 0) ? INT32_MAX : -INT32_MAX;
            ht_dcm_update(&dcm, &b, &imu, NULL);
            TEST_ASSERT_EQUAL_INT32_ARRAY(&a.r[0][0], &b.r[0][0], 9);
            /* the rate uses the bias from before the sample (st.bias) */
            TEST_ASSERT_EQUAL_INT32(sign * gl - ((st.bias[axis] + 8192) >> 14), b.rate_rad_s[axis]);
            imu.gyro_rad_s[axis] = 0;
            ht_dcm_update(&dcm, &st, &imu, NULL); /* per-sample flag: cleared */
            TEST_ASSERT_EQUAL_UINT16(0u, st.flags & HT_DCM_F_GYRO_SATURATED);
        }
    }
    for (int axis = 0; axis < 3; axis++) {
        setUp();
        ht_imu_sample_t s = {{0, 0, 0}, {0, 0, -Q16_ONE}};
        s.accel_g[axis] = (axis == 2) ? -(al - 1) : al - 1;
        ht_dcm_update(&dcm, &st, &s, NULL);
        TEST_ASSERT_EQUAL_UINT16(0u, st.flags & HT_DCM_F_ACCEL_SATURATED);
        s.accel_g[axis] = (axis == 2) ? -al : al;
        ht_dcm_update(&dcm, &st, &s, NULL);
        /* a clipped accelerometer is no gravity reference */
        TEST_ASSERT_EQUAL_UINT16(HT_DCM_F_ACCEL_SATURATED | HT_DCM_F_ACCEL_IGNORED,
                                 st.flags & (HT_DCM_F_ACCEL_SATURATED | HT_DCM_F_ACCEL_IGNORED));
        s.accel_g[axis] = INT32_MIN;
        ht_dcm_update(&dcm, &st, &s, NULL);
        TEST_ASSERT_TRUE((st.flags & HT_DCM_F_ACCEL_SATURATED) != 0u);
    }
}

/* The bias bound: a 10 deg/s bias with ki large drives the estimate onto
 * gyro_bias_max (0.1 rad/s), flagged; it never goes beyond. */
static void test_bias_limited_flag(void)
{
    prm.ki_rollpitch = 4 * Q16_ONE;
    prm.kp_rollpitch = 2 * Q16_ONE; /* the row's top */
    dt_init(&dcm, &prm);
    double r[3][3];
    dcmr_from_euler(0, 0, 0, r);
    dt_state_at(&st, r);
    const double w[3] = {0, 10 * DEG, 0}, f[3] = {0, 0, -1};
    const ht_imu_sample_t imu = dt_imu(w, f);
    int seen = 0;
    for (int k = 0; k < 200 * 20; k++) {
        ht_dcm_update(&dcm, &st, &imu, NULL);
        TEST_ASSERT_TRUE(abs(st.bias[1]) <= dcm.bias_max_q30);
        seen |= (st.flags & HT_DCM_F_BIAS_LIMITED) != 0u;
    }
    TEST_ASSERT_TRUE(seen);
    TEST_ASSERT_EQUAL_INT32(dcm.bias_max_q30, st.bias[1]);
    ht_dcm_output_t out;
    ht_dcm_output(&st, &out);
    TEST_ASSERT_EQUAL_INT32(prm.gyro_bias_max_rad_s, out.gyro_bias_rad_s[1]);
    /* the attitude is held by the proportional term: bank error
     * (10 deg/s - 0.1 rad/s) / (kp / 2) = 0.0745 rad with kp = 2 (the
     * accelerometer's w x v reference runs at half the gains) */
    TEST_ASSERT_DOUBLE_WITHIN(0.004, (10 * DEG - 0.1) / 1.0, dt_att_err(&st, r));
}

/* --- renormalization failure ------------------------------------------- */

static void test_renorm_failure_resets_from_accel_and_latches(void)
{
    double r[3][3];
    dcmr_from_euler(0, 0, 70 * DEG, r);
    dt_state_at(&st, r);
    /* corrupt: rows 0 and 1 twice their length (|r|^2 = 4 > 2.25; row 2 is
     * rebuilt from them by every renormalization) */
    for (int j = 0; j < 3; j++) {
        st.r[0][j] *= 2;
        st.r[1][j] *= 2;
    }
    double truth[3][3];
    dcmr_from_euler(25 * DEG, -10 * DEG, 70 * DEG, truth);
    double f[3];
    dt_gravity_body(truth, f);
    const double w[3] = {0, 0, 0};
    const ht_imu_sample_t imu = dt_imu(w, f);
    ht_dcm_update(&dcm, &st, &imu, NULL);
    TEST_ASSERT_TRUE((st.flags & HT_DCM_F_RENORM_FAILED) != 0u);
    /* roll and pitch from the accelerometer, the heading kept */
    ht_dcm_output_t out;
    ht_dcm_output(&st, &out);
    TEST_ASSERT_INT_WITHIN(1, 2500, out.roll_cdeg);
    TEST_ASSERT_INT_WITHIN(1, -1000, out.pitch_cdeg);
    TEST_ASSERT_INT_WITHIN(1, 7000, out.yaw_cdeg);
    double m[3][3];
    dcmr_from_state(&st, m);
    TEST_ASSERT_TRUE(dcmr_ortho_err(m) < 1e-7);
    /* latched over good samples, cleared by reset */
    for (int k = 0; k < 10; k++) {
        ht_dcm_update(&dcm, &st, &imu, NULL);
    }
    TEST_ASSERT_TRUE((st.flags & HT_DCM_F_RENORM_FAILED) != 0u);
    ht_dcm_reset(&st);
    TEST_ASSERT_EQUAL_UINT16(0u, st.flags);
    /* a zero matrix, and one of saturated garbage, with no usable gravity
     * (free fall): level at the last heading (north when none) */
    for (int c = 0; c < 2; c++) {
        setUp();
        for (int i = 0; i < 3; i++) {
            for (int j = 0; j < 3; j++) {
                st.r[i][j] = (c == 0) ? 0 : ((i + j) % 2 ? INT32_MIN : INT32_MAX);
            }
        }
        st.flags = HT_DCM_F_ALIGNED;
        const double ff[3] = {0, 0, 0};
        const ht_imu_sample_t fall = dt_imu(w, ff);
        ht_dcm_update(&dcm, &st, &fall, NULL);
        TEST_ASSERT_TRUE((st.flags & HT_DCM_F_RENORM_FAILED) != 0u);
        dcmr_from_state(&st, m);
        TEST_ASSERT_TRUE(dcmr_ortho_err(m) < 1e-7);
        TEST_ASSERT_DOUBLE_WITHIN(1e-8, 1.0, m[2][2]);
    }
}

/* --- alignment --------------------------------------------------------- */

static void test_align_any_attitude(void)
{
    /* roll, pitch, heading (deg) */
    const double cases[][3] = {{0, 0, 0},    {0, 0, 123.45},    {30, -20, 250}, {-60, 45, 10},
                               {180, 0, 90}, {170, -30, 300},   {0, 80, 45},    {0, -80, 200},
                               {90, 0, 0},   {-90, 10, 359.99}, {0, 90, 0},     {0, -90, 0}};
    for (unsigned c = 0; c < sizeof cases / sizeof cases[0]; c++) {
        double r[3][3];
        dcmr_from_euler(cases[c][0] * DEG, cases[c][1] * DEG, cases[c][2] * DEG, r);
        double f[3];
        dt_gravity_body(r, f);
        const q16_t fq[3] = {dt_q16(f[0] * 0.9), dt_q16(f[1] * 0.9), dt_q16(f[2] * 0.9)};
        ht_dcm_reset(&st);
        st.bias[0] = 12345;
        const uint16_t hd = (uint16_t)lround(cases[c][2] * 100.0);
        TEST_ASSERT_EQUAL_INT(0, ht_dcm_align(&dcm, &st, fq, 1u, hd));
        TEST_ASSERT_EQUAL_INT32(0, st.bias[0]);
        TEST_ASSERT_EQUAL_UINT16(HT_DCM_F_ALIGNED, st.flags);
        double m[3][3];
        dcmr_from_state(&st, m);
        char msg[96];
        snprintf(msg, sizeof msg, "case roll %.0f pitch %.0f heading %.2f: error %.3e", cases[c][0],
                 cases[c][1], cases[c][2], dcmr_angle_between(m, r));
        TEST_ASSERT_TRUE_MESSAGE(dcmr_ortho_err(m) < 1e-7, msg);
        /* the double alignment of the same (Q16) reading: 2e-7 rad */
        dcmr_state_t rs;
        dcmr_reset(&rs);
        const double fd[3] = {fq[0] / 65536.0, fq[1] / 65536.0, fq[2] / 65536.0};
        TEST_ASSERT_EQUAL_INT(0, dcmr_align(&rs, fd, hd / 100.0 * DEG));
        TEST_ASSERT_TRUE_MESSAGE(dcmr_angle_between(m, rs.r) < 2e-7, msg);
        /* and the true attitude within the Q16 reading's resolution */
        if (fabs(cases[c][1]) < 90.0) {
            TEST_ASSERT_TRUE_MESSAGE(dcmr_angle_between(m, r) < 2e-5, msg);
        } else {
            /* at pitch +/-90 the heading and roll are one angle: the bottom
             * row and the right wing's azimuth are what is defined */
            for (int j = 0; j < 3; j++) {
                TEST_ASSERT_DOUBLE_WITHIN(1e-7, r[2][j], m[2][j]);
            }
            TEST_ASSERT_DOUBLE_WITHIN(1e-6, atan2(-r[1][0], -r[0][0]), atan2(-m[1][0], -m[0][0]));
        }
    }
    /* heading not valid: north; heading 36000 and beyond: modulo */
    const q16_t down[3] = {0, 0, -Q16_ONE};
    ht_dcm_output_t out;
    TEST_ASSERT_EQUAL_INT(0, ht_dcm_align(&dcm, &st, down, 0u, 9000u));
    ht_dcm_output(&st, &out);
    TEST_ASSERT_EQUAL_UINT16(0u, out.yaw_cdeg);
    TEST_ASSERT_EQUAL_INT(0, ht_dcm_align(&dcm, &st, down, 1u, 45000u));
    ht_dcm_output(&st, &out);
    TEST_ASSERT_EQUAL_UINT16(9000u, out.yaw_cdeg);
    /* |a| below 0.5 g is refused and leaves R as it was */
    const ht_dcm_state_t before = st;
    const q16_t weak[3] = {0, 0, -(Q16_ONE / 2 - 2)};
    TEST_ASSERT_EQUAL_INT(1, ht_dcm_align(&dcm, &st, weak, 1u, 0u));
    TEST_ASSERT_EQUAL_MEMORY(&before, &st, sizeof st);
    const q16_t zero[3] = {0, 0, 0};
    TEST_ASSERT_EQUAL_INT(1, ht_dcm_align(&dcm, &st, zero, 1u, 0u));
    const q16_t half[3] = {0, 0, -(Q16_ONE / 2 + 2)};
    TEST_ASSERT_EQUAL_INT(0, ht_dcm_align(&dcm, &st, half, 1u, 0u));
    /* the largest readings: no overflow */
    const q16_t huge[3] = {INT32_MIN, INT32_MAX, INT32_MIN};
    TEST_ASSERT_EQUAL_INT(0, ht_dcm_align(&dcm, &st, huge, 1u, 0u));
    double m[3][3];
    dcmr_from_state(&st, m);
    TEST_ASSERT_TRUE(dcmr_ortho_err(m) < 1e-7);
}

/* --- trigonometry and the output --------------------------------------- */

static void test_cordic_against_libm(void)
{
    uint64_t seed = 3u;
    double worst_atan = 0.0, worst_sc = 0.0, worst_mag = 0.0;
    for (long k = 0; k < 200000L; k++) {
        /* every magnitude: a random mantissa shifted by a random amount */
        const int sh = (int)(dt_rng(&seed) % 31u);
        int32_t x = (int32_t)(dt_rng(&seed) >> 33) >> sh;
        int32_t y = (int32_t)(dt_rng(&seed) >> 33) >> (int)(dt_rng(&seed) % 31u);
        x = (dt_rng(&seed) & 1u) ? x : -x;
        y = (dt_rng(&seed) & 1u) ? y : -y;
        if (k < 8) { /* the extremes */
            const int32_t ex[8][2] = {{INT32_MIN, 0},
                                      {0, INT32_MIN},
                                      {INT32_MAX, INT32_MIN},
                                      {INT32_MIN, INT32_MIN},
                                      {1, 0},
                                      {0, -1},
                                      {-1, 0},
                                      {INT32_MAX, INT32_MAX}};
            x = ex[k][0];
            y = ex[k][1];
        }
        int32_t mk;
        const int32_t a = ht_dcm_atan2_bam(y, x, &mk);
        const double ref = atan2((double)y, (double)x);
        double e = a * (DT_PI / 2147483648.0) - ref;
        e = fabs(remainder(e, 2.0 * DT_PI));
        worst_atan = e > worst_atan ? e : worst_atan;
        const double mag = hypot((double)x, (double)y) * 1.6467602581210654;
        if (mag < 2147483000.0 && mag > 1e6) {
            const double me = fabs(mk - mag) / mag;
            worst_mag = me > worst_mag ? me : worst_mag;
        }
        const int32_t ang = (int32_t)(uint32_t)(dt_rng(&seed) >> 32);
        int32_t c, s;
        ht_dcm_sincos_q30(ang, &c, &s);
        const double ar = ang * (DT_PI / 2147483648.0);
        const double ec = fmax(fabs(c / 1073741824.0 - cos(ar)), fabs(s / 1073741824.0 - sin(ar)));
        worst_sc = ec > worst_sc ? ec : worst_sc;
    }
    printf("  CORDIC vs libm, 2e5 cases: atan2 %.2e rad, magnitude %.2e relative, sin/cos %.2e\n",
           worst_atan, worst_mag, worst_sc);
    /* 31 table entries rounded to half a binary-angle LSB (1.5e-9 rad) and
     * 31 truncating shifts: 2.6e-8 rad measured; 0.01 degree is 1.7e-4 */
    TEST_ASSERT_TRUE(worst_atan < 4e-8);
    TEST_ASSERT_TRUE(worst_mag < 1e-6);
    TEST_ASSERT_TRUE(worst_sc < 3e-8);
    TEST_ASSERT_EQUAL_INT32(0, ht_dcm_atan2_bam(0, 0, NULL));
    /* conversions at their edges */
    TEST_ASSERT_EQUAL_INT32(18000, ht_dcm_bam_to_cdeg(INT32_MIN));
    TEST_ASSERT_EQUAL_INT32(18000, ht_dcm_bam_to_cdeg(INT32_MAX));
    TEST_ASSERT_EQUAL_INT32(9000, ht_dcm_bam_to_cdeg(HT_BAM_90));
    TEST_ASSERT_EQUAL_INT32(HT_BAM_90, ht_dcm_cdeg_to_bam(9000));
    TEST_ASSERT_EQUAL_INT32(-HT_BAM_90, ht_dcm_cdeg_to_bam(-9000));
    TEST_ASSERT_EQUAL_INT32(INT32_MAX, ht_dcm_cdeg_to_bam(18000));
}

/* Euler angles of random attitudes: within 0.5 cdeg + 1e-6 of libm on the
 * state's own matrix, in their documented ranges. */
static void test_euler_output_against_libm(void)
{
    uint64_t seed = 11u;
    double worst = 0.0;
    for (long k = 0; k < 100000L; k++) {
        double r[3][3];
        const double roll = dt_uniform(&seed, -DT_PI, DT_PI);
        const double pitch = dt_uniform(&seed, -DT_PI / 2, DT_PI / 2);
        const double yaw = dt_uniform(&seed, 0, 2 * DT_PI);
        dcmr_from_euler(roll, pitch, yaw, r);
        dt_state_at(&st, r);
        ht_dcm_output_t out;
        ht_dcm_output(&st, &out);
        double m[3][3], er, ep, ey;
        dcmr_from_state(&st, m);
        dcmr_euler(m, &er, &ep, &ey);
        TEST_ASSERT_TRUE(out.roll_cdeg > -18000 && out.roll_cdeg <= 18000);
        TEST_ASSERT_TRUE(out.pitch_cdeg >= -9000 && out.pitch_cdeg <= 9000);
        TEST_ASSERT_TRUE(out.yaw_cdeg < 36000u);
        const double d[3] = {remainder(out.roll_cdeg - er / DEG * 100.0, 36000.0),
                             out.pitch_cdeg - ep / DEG * 100.0,
                             remainder(out.yaw_cdeg - ey / DEG * 100.0, 36000.0)};
        for (int i = 0; i < 3; i++) {
            /* roll and yaw are undefined at pitch +/-90 */
            if (i != 1 && fabs(ep) > 89.9 * DEG) {
                continue;
            }
            worst = fabs(d[i]) > worst ? fabs(d[i]) : worst;
        }
        for (int i = 0; i < 3; i++) {
            for (int j = 0; j < 3; j++) {
                TEST_ASSERT_INT_WITHIN(1, (int)lround(m[i][j] * 16384.0), out.r[i][j]);
            }
        }
    }
    printf("  Euler output vs libm, 1e5 attitudes: worst %.4f cdeg\n", worst);
    TEST_ASSERT_TRUE(worst <= 0.5 + 1e-4);
    /* the edges: level north, inverted, pitch +/-90 */
    double r[3][3];
    ht_dcm_output_t out;
    dcmr_from_euler(DT_PI, 0, 0, r);
    dt_state_at(&st, r);
    ht_dcm_output(&st, &out);
    TEST_ASSERT_EQUAL_INT16(18000, out.roll_cdeg);
    TEST_ASSERT_EQUAL_INT16(-Q14_ONE, out.r[2][2]);
    dcmr_from_euler(0, DT_PI / 2, 0, r);
    dt_state_at(&st, r);
    ht_dcm_output(&st, &out);
    TEST_ASSERT_EQUAL_INT16(9000, out.pitch_cdeg);
    dcmr_from_euler(0, -DT_PI / 2, 0, r);
    dt_state_at(&st, r);
    ht_dcm_output(&st, &out);
    TEST_ASSERT_EQUAL_INT16(-9000, out.pitch_cdeg);
    dcmr_from_euler(0, 0, 2 * DT_PI - 1e-9, r);
    dt_state_at(&st, r);
    ht_dcm_output(&st, &out);
    TEST_ASSERT_EQUAL_UINT16(0u, out.yaw_cdeg);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_parameter_edges_each_field);
    RUN_TEST(test_defaults_and_derived_values);
    RUN_TEST(test_null_and_uninitialised_inputs);
    RUN_TEST(test_first_sample_aligns);
    RUN_TEST(test_saturation_flags_at_the_full_scales);
    RUN_TEST(test_bias_limited_flag);
    RUN_TEST(test_renorm_failure_resets_from_accel_and_latches);
    RUN_TEST(test_align_any_attitude);
    RUN_TEST(test_cordic_against_libm);
    RUN_TEST(test_euler_output_against_libm);
    return UNITY_END();
}
