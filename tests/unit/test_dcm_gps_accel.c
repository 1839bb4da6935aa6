/*
 * The GPS acceleration reference (src/estimator/dcm_gps_accel.c): the accelerometer in
 * earth axes against the GPS velocity's change over the same, latency-shifted
 * intervals. Exact sensors, a 5 Hz GPS whose velocity is that of its epoch,
 * delivered gps_latency_ms later, held between solutions.
 */
#include "dcm_test_util.h"

#include <string.h>

DT_DEFAULT_FIXTURE()

#define RATE       200
#define GPS_PERIOD 40 /* samples: 5 Hz */

/*
 * A steady coordinated level turn (bank phi, speed v: rate g tan(phi) / v about
 * the vertical, specific force [0, 0, -1/cos(phi)]) for the given seconds,
 * with a constant gyro bias; the GPS delivers the epoch velocity lat_true
 * samples late. Returns the worst bank error over the last 10 s (deg); the
 * bias estimate's error at the end (deg/s, largest axis) in *bias_err; the
 * samples flagged GPS_ACCEL in *n_ga.
 */
static double fly_turn(double phi, double v, double pitot_scale, const double bias[3], int lat_true,
                       int seconds, double *bias_err, long *n_ga)
{
    const double om = 9.80665 * tan(phi) / v;
    double r0[3][3];
    dcmr_from_euler(phi, 0, 0, r0);
    dt_state_at(&st, r0);
    const double w[3] = {om * r0[2][0] + bias[0], om * r0[2][1] + bias[1], om * r0[2][2] + bias[2]};
    const double f[3] = {0, 0, -1.0 / cos(phi)};
    const ht_imu_sample_t imu = dt_imu(w, f);
    ht_dcm_aiding_t aid;
    memset(&aid, 0, sizeof aid);
    aid.airspeed_valid = 1u;
    aid.airspeed_cm_s = (int16_t)lround(v * 100.0 * pitot_scale);
    double worst = 0.0;
    *n_ga = 0;
    for (long k = 0; k < (long)RATE * seconds; k++) {
        aid.gps_fix = 1u;
        aid.gps_fresh = ((k % GPS_PERIOD) == lat_true) ? 1u : 0u;
        if (aid.gps_fresh != 0u) {
            /* the velocity of the epoch lat_true samples ago (the sample's
             * time is k / RATE: the matrix after it has turned k + 1 times) */
            const double psi = om * (double)(k + 1 - lat_true) / RATE;
            aid.vel_ned_cm_s[0] = (int32_t)lround(v * 100.0 * cos(psi));
            aid.vel_ned_cm_s[1] = (int32_t)lround(v * 100.0 * sin(psi));
            aid.vel_ned_cm_s[2] = 0;
        }
        ht_dcm_update(&dcm, &st, &imu, &aid);
        *n_ga += (st.flags & HT_DCM_F_GPS_ACCEL) != 0u;
        if (k >= (long)RATE * (seconds - 10)) {
            ht_dcm_output_t out;
            ht_dcm_output(&st, &out);
            const double e = fabs(out.roll_cdeg / 100.0 - phi / DEG);
            worst = e > worst ? e : worst;
        }
    }
    double be = 0.0;
    for (int i = 0; i < 3; i++) {
        const double d = fabs(st.bias[i] / 1073741824.0 - dt_q16(bias[i]) / 65536.0) / DEG;
        be = d > be ? d : be;
    }
    *bias_err = be;
    return worst;
}

/*
 * A pitot reading 30 % low (a partly blocked tube, a wrong calibration) in a
 * 45-degree turn at 25 m/s for 60 s: the w x v model takes 30 % of the
 * centripetal acceleration for gravity and settles on a wrong bank (and
 * teaches the integral a false bias); the GPS window does not use the
 * airspeed. Measured: window 0.37 deg of bank and 0.12 deg/s of bias left
 * from its first 1.5 s on the model (it needs five GPS intervals);
 * airspeed-only 14.8 deg and 3.7 deg/s.
 */
static void test_window_does_not_use_the_airspeed(void)
{
    const double b[3] = {0, 0, 0};
    prm.gps_latency_ms = 100u;
    dt_init(&dcm, &prm);
    double be_ga;
    long n_ga;
    const double e_ga = fly_turn(45 * DEG, 25.0, 0.7, b, 20, 60, &be_ga, &n_ga);
    TEST_ASSERT_TRUE(n_ga > 60L * RATE * 9 / 10); /* the window after 1.5 s */
    setUp();
    prm.centripetal = (uint8_t)HT_DCM_CF_AIRSPEED; /* the w x v model alone */
    dt_init(&dcm, &prm);
    double be_air;
    long n_air;
    const double e_air = fly_turn(45 * DEG, 25.0, 0.7, b, 20, 60, &be_air, &n_air);
    printf("  45 deg turn, pitot 30 %% low, 60 s: GPS window bank %.3f deg, bias %.4f deg/s; "
           "airspeed w x v bank %.3f deg, bias %.4f deg/s\n",
           e_ga, be_ga, e_air, be_air);
    TEST_ASSERT_EQUAL_INT32(0, n_air);
    TEST_ASSERT_TRUE(e_ga < 0.5);
    TEST_ASSERT_TRUE(be_ga < 0.2);
    TEST_ASSERT_TRUE(e_air > 10.0 * e_ga);
}

/*
 * A 1 deg/s bias on every axis in a 30-degree turn at 50 m/s, 90 s: the
 * window learns it (measured within 0.064 deg/s, the bank within 0.45 deg;
 * the w x v model with an exact airspeed does as well here, 0.054: the
 * window's gain is where the model is wrong, above).
 */
static void test_window_learns_a_gyro_bias_in_a_turn(void)
{
    const double b[3] = {1.0 * DEG, -1.0 * DEG, 1.0 * DEG};
    prm.gps_latency_ms = 100u;
    dt_init(&dcm, &prm);
    double be;
    long n;
    const double e = fly_turn(30 * DEG, 50.0, 1.0, b, 20, 90, &be, &n);
    printf("  30 deg turn, 1 deg/s bias per axis, 90 s: bank %.3f deg, bias %.4f deg/s\n", e, be);
    TEST_ASSERT_TRUE(n > 90L * RATE * 9 / 10);
    TEST_ASSERT_TRUE(e < 0.6);
    TEST_ASSERT_TRUE(be < 0.08);
}

/* A missed solution breaks the chain of intervals (the window is dropped
 * until five consecutive intervals line up again), and losing the fix resets
 * it; the sample counting restarts from the next solutions. */
static void test_a_missed_solution_restarts_the_window(void)
{
    prm.gps_latency_ms = 100u;
    dt_init(&dcm, &prm);
    double r0[3][3];
    dcmr_from_euler(0, 0, 0, r0);
    dt_state_at(&st, r0);
    const double w[3] = {0, 0, 0};
    const double f[3] = {0, 0, -1};
    const ht_imu_sample_t imu = dt_imu(w, f);
    ht_dcm_aiding_t aid;
    memset(&aid, 0, sizeof aid);
    aid.gps_fix = 1u;
    aid.vel_ned_cm_s[0] = 2500;
    long first = -1;
    long back = -1;
    for (long k = 0; k < 4000; k++) {
        const int skip = (k >= 2000 && k < 2040); /* one solution lost */
        aid.gps_fresh = ((k % GPS_PERIOD) == 20 && !skip) ? 1u : 0u;
        ht_dcm_update(&dcm, &st, &imu, &aid);
        const int ga = (st.flags & HT_DCM_F_GPS_ACCEL) != 0u;
        if (ga && first < 0) {
            first = k;
        }
        if (k == 2040) {
            /* 2 samples after the missed one was due (2020) the chain broke */
            TEST_ASSERT_FALSE(ga);
        }
        if (k > 2040 && ga && back < 0) {
            back = k;
        }
    }
    printf("  window from sample %ld; after a missed solution back at %ld\n", first, back);
    /* solutions at 20, 60, ...: the period is known at 60, the first aligned
     * interval closes at 100 and the window is full at the 8th solution */
    TEST_ASSERT_EQUAL_INT32(300, first);
    /* the next solution (2060) restarts; full again 7 solutions later */
    TEST_ASSERT_EQUAL_INT32(2060 + 7 * GPS_PERIOD, back);
    aid.gps_fix = 0u;
    ht_dcm_update(&dcm, &st, &imu, &aid);
    TEST_ASSERT_EQUAL_UINT8(0u, st.ga.count);
    TEST_ASSERT_EQUAL_UINT16(0u, st.ga.period);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_window_does_not_use_the_airspeed);
    RUN_TEST(test_window_learns_a_gyro_bias_in_a_turn);
    RUN_TEST(test_a_missed_solution_restarts_the_window);
    return UNITY_END();
}
