/*
 * The estimator's drift correction: gyro-bias estimation with GPS course
 * aiding, the centripetal compensation in a steady 45-degree turn (and its
 * absence), GPS and magnetometer yaw convergence, the accelerometer's weight
 * across its band, and the closed loop against the double reference.
 */
#include "dcm_test_util.h"

#include <string.h>

DT_DEFAULT_FIXTURE()

/* Level flight north at 25 m/s with a gyro bias (rad/s), GPS course aiding,
 * airspeed valid; 60 s at 200 Hz from the true attitude. Gains kp 1, ki 0.1
 * (both loops): the defaults' slow pole is ki/kp = 0.01/s (a 100 s time
 * constant, docs/estimator.md), too slow to settle in one minute. */
static void fly_level_with_bias(const double bias[3], double est[3])
{
    prm.kp_rollpitch = Q16_ONE;
    prm.ki_rollpitch = dt_q16(0.1);
    prm.kp_yaw = Q16_ONE;
    prm.ki_yaw = dt_q16(0.1);
    dt_init(&dcm, &prm);
    double r0[3][3];
    dcmr_from_euler(0, 0, 0, r0);
    dt_state_at(&st, r0);
    const double f[3] = {0, 0, -1};
    const ht_imu_sample_t imu = dt_imu(bias, f);
    ht_dcm_aiding_t aid = {0};
    aid.gps_fix = 1u;
    aid.gps_fresh = 1u;
    aid.vel_ned_cm_s[0] = 2500;
    aid.airspeed_valid = 1u;
    aid.airspeed_cm_s = 2500;
    for (int k = 0; k < 200 * 60; k++) {
        ht_dcm_update(&dcm, &st, &imu, &aid);
        TEST_ASSERT_EQUAL_UINT16(HT_DCM_F_ALIGNED | HT_DCM_F_YAW_AIDED | HT_DCM_F_CF_GPS,
                                 st.flags & ~(uint16_t)0); /* never limited, never ignored */
    }
    ht_dcm_output_t out;
    ht_dcm_output(&st, &out);
    for (int i = 0; i < 3; i++) {
        est[i] = out.gyro_bias_rad_s[i] / 65536.0;
    }
    /* and the attitude is back at the truth */
    TEST_ASSERT_TRUE(dt_att_err(&st, r0) < 0.05 * DEG);
}

static void test_bias_each_axis_and_together_within_005_deg_s(void)
{
    const double one = 1.0 * DEG;
    const double cases[4][3] = {{one, 0, 0}, {0, one, 0}, {0, 0, one}, {one, -one, one}};
    for (int c = 0; c < 4; c++) {
        double est[3];
        setUp();
        fly_level_with_bias(cases[c], est);
        const double bq[3] = {dt_q16(cases[c][0]) / 65536.0, dt_q16(cases[c][1]) / 65536.0,
                              dt_q16(cases[c][2]) / 65536.0};
        printf("  bias case %d: estimate [%.4f %.4f %.4f] deg/s, true [%.4f %.4f %.4f]\n", c,
               est[0] / DEG, est[1] / DEG, est[2] / DEG, bq[0] / DEG, bq[1] / DEG, bq[2] / DEG);
        for (int i = 0; i < 3; i++) {
            TEST_ASSERT_DOUBLE_WITHIN(0.05 * DEG, bq[i], est[i]);
        }
    }
}

/* A steady coordinated turn: bank 45 deg, 25 m/s, turn rate g tan(phi) / V
 * about the earth vertical, specific force [0, 0, -1/cos(phi)], GPS course
 * along the track. Returns the worst bank error over 60 s (deg). */
static double turn_bank_error(uint8_t cf, double *final_err)
{
    prm.centripetal = cf;
    dt_init(&dcm, &prm);
    const double phi = 45.0 * DEG, v = 25.0, om = 9.80665 * tan(phi) / v;
    double r[3][3];
    dcmr_from_euler(phi, 0, 0, r);
    dt_state_at(&st, r);
    const double w[3] = {om * r[2][0], om * r[2][1], om * r[2][2]};
    const double f[3] = {0, 0, -1.0 / cos(phi)};
    const ht_imu_sample_t imu = dt_imu(w, f);
    double worst = 0.0;
    double err = 0.0;
    for (int k = 0; k < 200 * 60; k++) {
        const double psi = om * k / 200.0;
        ht_dcm_aiding_t aid = {0};
        aid.gps_fix = 1u;
        aid.gps_fresh = 1u;
        aid.vel_ned_cm_s[0] = (int32_t)lround(v * 100.0 * cos(psi));
        aid.vel_ned_cm_s[1] = (int32_t)lround(v * 100.0 * sin(psi));
        aid.airspeed_valid = 1u;
        aid.airspeed_cm_s = (int16_t)lround(v * 100.0);
        ht_dcm_update(&dcm, &st, &imu, &aid);
        ht_dcm_output_t out;
        ht_dcm_output(&st, &out);
        err = fabs(out.roll_cdeg / 100.0 - 45.0);
        worst = err > worst ? err : worst;
        if (cf == (uint8_t)HT_DCM_CF_OFF && (k + 1) % 1000 == 0) {
            printf("    no compensation, t = %2d s: bank %.2f deg, bias [%.3f %.3f %.3f] deg/s\n",
                   (k + 1) / 200, out.roll_cdeg / 100.0, out.gyro_bias_rad_s[0] / 65536.0 / DEG,
                   out.gyro_bias_rad_s[1] / 65536.0 / DEG, out.gyro_bias_rad_s[2] / 65536.0 / DEG);
        }
    }
    *final_err = err;
    return worst;
}

static void test_centripetal_compensation_in_a_45_deg_turn(void)
{
    double fin_gps, fin_air, fin_off;
    const double gps = turn_bank_error((uint8_t)HT_DCM_CF_AUTO, &fin_gps);
    TEST_ASSERT_TRUE((st.flags & HT_DCM_F_CF_GPS) != 0u);
    TEST_ASSERT_TRUE((st.flags & HT_DCM_F_ACCEL_IGNORED) == 0u);
    const double bias_gps = fabs(st.bias[1] / 1073741824.0) / DEG;
    setUp();
    const double air = turn_bank_error((uint8_t)HT_DCM_CF_AIRSPEED, &fin_air);
    TEST_ASSERT_TRUE((st.flags & HT_DCM_F_CF_GPS) == 0u);
    setUp();
    const double off = turn_bank_error((uint8_t)HT_DCM_CF_OFF, &fin_off);
    const double bias_off = fabs(st.bias[1] / 1073741824.0) / DEG;
    printf("  false roll-axis bias after 60 s: %.4f deg/s compensated, %.3f without\n", bias_gps,
           bias_off);
    /* the uncompensated loop also teaches the integrator a false bias */
    TEST_ASSERT_TRUE(bias_gps < 0.01);
    TEST_ASSERT_TRUE(bias_off > 0.5);
    printf("  45 deg turn, 60 s: worst bank error GPS velocity %.3f deg (final %.3f), "
           "airspeed %.3f (final %.3f), no compensation %.3f (final %.3f)\n",
           gps, fin_gps, air, fin_air, off, fin_off);
    TEST_ASSERT_TRUE(gps < 1.5);
    TEST_ASSERT_TRUE(air < 1.5);
    /* without it the estimate leans toward level, measurably */
    TEST_ASSERT_TRUE(off > 3.0);
    TEST_ASSERT_TRUE(off > 4.0 * gps);
}

/* Level, heading north, the estimate starting 90 degrees off (east): the
 * GPS course pulls it back (default gains). */
static void test_gps_yaw_converges_from_90_degrees(void)
{
    const q16_t down[3] = {0, 0, -Q16_ONE};
    TEST_ASSERT_EQUAL_INT(0, ht_dcm_align(&dcm, &st, down, 1u, 9000u));
    const double z[3] = {0, 0, 0}, f[3] = {0, 0, -1};
    const ht_imu_sample_t imu = dt_imu(z, f);
    ht_dcm_aiding_t aid = {0};
    aid.gps_fix = 1u;
    aid.gps_fresh = 1u;
    aid.vel_ned_cm_s[0] = 2000;
    ht_dcm_output_t out;
    int t10 = -1;
    int e30 = 0;
    for (int k = 0; k < 200 * 60; k++) {
        ht_dcm_update(&dcm, &st, &imu, &aid);
        TEST_ASSERT_TRUE((st.flags & HT_DCM_F_YAW_AIDED) != 0u);
        ht_dcm_output(&st, &out);
        const int e = out.yaw_cdeg > 18000 ? 36000 - out.yaw_cdeg : out.yaw_cdeg;
        if (t10 < 0 && e < 1000) {
            t10 = k;
        }
        if (k == 200 * 30) {
            e30 = e;
        }
    }
    const int e = out.yaw_cdeg > 18000 ? 36000 - out.yaw_cdeg : out.yaw_cdeg;
    printf("  GPS yaw from 90 deg: within 10 deg after %.2f s, error after 30 s %.2f deg, "
           "after 60 s %.2f deg\n",
           t10 / 200.0, e30 / 100.0, e / 100.0);
    /* kp_yaw 0.5: the pull is 0.5 rad/s at 90 degrees, then exponential
     * with 2 s; the integral winds up during the transient (ki * 3 rad s =
     * 0.016 rad/s, 1.8 degrees of yaw offset) and leaves with the loop's
     * slow pole, ki / kp = 0.01/s: about 1 degree remains after 60 s */
    TEST_ASSERT_TRUE(t10 > 0 && t10 < 200 * 6);
    TEST_ASSERT_TRUE(e < 150);
    TEST_ASSERT_TRUE(e < e30);
    /* below the minimum ground speed the course is not used */
    aid.vel_ned_cm_s[0] = prm.gps_min_speed_cm_s;
    ht_dcm_update(&dcm, &st, &imu, &aid);
    TEST_ASSERT_TRUE((st.flags & HT_DCM_F_YAW_AIDED) == 0u);
    aid.vel_ned_cm_s[0] = prm.gps_min_speed_cm_s + 2;
    ht_dcm_update(&dcm, &st, &imu, &aid);
    TEST_ASSERT_TRUE((st.flags & HT_DCM_F_YAW_AIDED) != 0u);
    /* a 180-degree error still turns (the pull is full beyond 90 degrees) */
    TEST_ASSERT_EQUAL_INT(0, ht_dcm_align(&dcm, &st, down, 1u, 18000u));
    for (int k = 0; k < 200 * 20; k++) {
        ht_dcm_update(&dcm, &st, &imu, &aid);
    }
    ht_dcm_output(&st, &out);
    const int e2 = out.yaw_cdeg > 18000 ? 36000 - out.yaw_cdeg : out.yaw_cdeg;
    TEST_ASSERT_TRUE(e2 < 500);
}

/* Magnetometer yaw: field inclination 60 deg down, declination +8 deg;
 * the aircraft rolled 20 deg and pitched 10 deg, true heading 250 deg;
 * the estimate starts at heading 200 deg; no GPS. */
static void test_magnetometer_yaw_converges_with_declination(void)
{
    const double roll = 20 * DEG, pitch = 10 * DEG, psi = 250 * DEG;
    double r[3][3];
    dcmr_from_euler(roll, pitch, psi, r);
    const double inc = 60 * DEG, dec = 8 * DEG;
    const double me[3] = {cos(inc) * cos(dec), cos(inc) * sin(dec), sin(inc)};
    ht_dcm_aiding_t aid = {0};
    aid.mag_valid = 1u;
    aid.mag_declination_cdeg = 800;
    for (int j = 0; j < 3; j++) {
        double mb = 0.0; /* R^T m */
        for (int i = 0; i < 3; i++) {
            mb += r[i][j] * me[i];
        }
        aid.mag[j] = (int16_t)lround(mb * 4000.0);
    }
    double f[3];
    dt_gravity_body(r, f);
    const q16_t fq[3] = {dt_q16(f[0]), dt_q16(f[1]), dt_q16(f[2])};
    TEST_ASSERT_EQUAL_INT(0, ht_dcm_align(&dcm, &st, fq, 1u, 20000u));
    const double z[3] = {0, 0, 0};
    const ht_imu_sample_t imu = dt_imu(z, f);
    for (int k = 0; k < 200 * 60; k++) {
        ht_dcm_update(&dcm, &st, &imu, &aid);
        TEST_ASSERT_TRUE((st.flags & HT_DCM_F_YAW_AIDED) != 0u);
    }
    ht_dcm_output_t out;
    ht_dcm_output(&st, &out);
    printf("  magnetometer: yaw %.2f deg (true 250), roll %.2f, pitch %.2f, attitude error %.3f "
           "deg\n",
           out.yaw_cdeg / 100.0, out.roll_cdeg / 100.0, out.pitch_cdeg / 100.0,
           dt_att_err(&st, r) / DEG);
    /* 50 degrees to pull in with the default gains: the integral's windup
     * decays at 0.01/s, as with the GPS course above */
    TEST_ASSERT_INT_WITHIN(100, 25000, out.yaw_cdeg);
    TEST_ASSERT_TRUE(dt_att_err(&st, r) < 1.0 * DEG);
    TEST_ASSERT_INT_WITHIN(5, 2000, out.roll_cdeg);
    TEST_ASSERT_INT_WITHIN(5, 1000, out.pitch_cdeg);
    /* GPS course has priority over the magnetometer when both are valid */
    aid.gps_fix = 1u;
    aid.gps_fresh = 1u;
    aid.vel_ned_cm_s[0] = 2000;
    ht_dcm_update(&dcm, &st, &imu, &aid);
    TEST_ASSERT_TRUE(st.omega_corr[0] != 0 || st.omega_corr[1] != 0 || st.omega_corr[2] != 0);
}

/* The proportional correction for a fixed 10-degree roll error, as |f|
 * moves through the band (0.5 g): weight 1 at 1 g, 1/2 at 0.75 and 1.25 g,
 * 0 (flag ACCEL_IGNORED) at 0.5 and 1.5 g and beyond. */
static double corr_at(double g)
{
    double r[3][3];
    dcmr_from_euler(10 * DEG, 0, 0, r);
    dt_state_at(&st, r);
    const double z[3] = {0, 0, 0}, f[3] = {0, 0, -g};
    const ht_imu_sample_t imu = dt_imu(z, f);
    const ht_dcm_aiding_t aid = {0};
    ht_dcm_update(&dcm, &st, &imu, &aid);
    return st.omega_corr[1] / 65536.0; /* about Y: roll */
}

static void test_accel_weight_across_the_band(void)
{
    const double full = corr_at(1.0);
    TEST_ASSERT_TRUE((st.flags & HT_DCM_F_ACCEL_IGNORED) == 0u);
    /* kp (0.4) / 2 (the w x v model's half gain) * sin(10 deg), rolling left
     * (-Y) toward level */
    TEST_ASSERT_DOUBLE_WITHIN(1e-4, -(prm.kp_rollpitch / 65536.0) / 2 * sin(10 * DEG), full);
    TEST_ASSERT_DOUBLE_WITHIN(2e-4, 0.5 * full, corr_at(0.75));
    TEST_ASSERT_DOUBLE_WITHIN(2e-4, 0.5 * full, corr_at(1.25));
    TEST_ASSERT_DOUBLE_WITHIN(2e-4, 0.1 * full, corr_at(1.45));
    TEST_ASSERT_TRUE((st.flags & HT_DCM_F_ACCEL_IGNORED) == 0u);
    const double outside[4] = {1.5, 0.5, 2.5, 0.0};
    for (int i = 0; i < 4; i++) {
        TEST_ASSERT_EQUAL_DOUBLE(0.0, corr_at(outside[i]));
        TEST_ASSERT_TRUE((st.flags & HT_DCM_F_ACCEL_IGNORED) != 0u);
    }
}

/* The closed loop (default gains, aiding on) against the double reference
 * of the same equations: 10^5 samples of a random manoeuvring flight (bank
 * to +/-60, pitch to +/-30 degrees, noisy accelerometer, GPS velocity along
 * the nose plus a 3 m/s crosswind, airspeed), seed 7. The attitudes stay
 * within 2e-5 rad (0.001 deg) of each other: the two differ only by the
 * integer code's roundings, which the loop carries; with the integral gain
 * 0.002 the worst was 9.5e-6 rad, with the default 0.01 1.3e-5, and with the
 * course against the air velocity and the learning gate 1.9e-5. (Near a
 * vertical nose the GPS course cannot tell the heading and the two drift
 * apart faster: the flight stays where the course means something.) */
static void test_closed_loop_tracks_double_reference(void)
{
    prm.gps_latency_ms = 100; /* the default: the course is carried forward */
    dt_init(&dcm, &prm);
    double r0[3][3];
    dcmr_from_euler(15 * DEG, -5 * DEG, 60 * DEG, r0);
    dt_state_at(&st, r0);
    dcmr_params_t rp;
    dcmr_params_from(&prm, &rp);
    dcmr_state_t rs;
    dcmr_reset(&rs);
    memcpy(rs.r, r0, sizeof r0);
    rs.aligned = 1;
    uint64_t seed = 7u;
    double w[3] = {0, 0, 0};
    double worst = 0.0, worst_bias = 0.0, worst_wind = 0.0;
    double tr = 0.0, tp = 0.0, tyr = 0.0;
    for (long k = 0; k < 100000L; k++) {
        /* a new target bank (+/-60 deg), pitch (+/-30 deg) and yaw rate
         * every 2 s, flown with rates proportional to the error */
        if (k % 400 == 0) {
            tr = dt_uniform(&seed, -60, 60) * DEG;
            tp = dt_uniform(&seed, -30, 30) * DEG;
            tyr = dt_uniform(&seed, -0.3, 0.3);
        }
        double ro, pi, ya;
        dcmr_euler(rs.r, &ro, &pi, &ya);
        w[0] = -(tp - pi);
        w[1] = tr - ro;
        w[2] = tyr;
        double f[3];
        dt_gravity_body(rs.r, f);
        for (int i = 0; i < 3; i++) {
            f[i] += dt_uniform(&seed, -0.2, 0.2);
        }
        const ht_imu_sample_t imu = dt_imu(w, f);
        /* a 5 Hz GPS: a new velocity (the nose's, plus a 1 m/s crosswind)
         * every 40 samples, held between; the GPS acceleration reference
         * runs on it (the velocity is not consistent with the specific
         * force: this compares the two implementations, not accuracy) */
        static ht_dcm_aiding_t aid;
        aid.gps_fix = 1u;
        aid.gps_fresh = (k % 40 == 0) ? 1u : 0u;
        if (aid.gps_fresh != 0u) {
            aid.vel_ned_cm_s[0] = (int32_t)lround(2000.0 * rs.r[0][1]);
            aid.vel_ned_cm_s[1] = (int32_t)lround(2000.0 * rs.r[1][1] + 100.0);
            aid.vel_ned_cm_s[2] = (int32_t)lround(2000.0 * rs.r[2][1]);
        }
        aid.airspeed_valid = 1u;
        aid.airspeed_cm_s = 2000;
        const double wq[3] = {imu.gyro_rad_s[0] / 65536.0, imu.gyro_rad_s[1] / 65536.0,
                              imu.gyro_rad_s[2] / 65536.0};
        const double fq[3] = {imu.accel_g[0] / 65536.0, imu.accel_g[1] / 65536.0,
                              imu.accel_g[2] / 65536.0};
        ht_dcm_update(&dcm, &st, &imu, &aid);
        dcmr_update(&rp, &rs, wq, fq, &aid);
        const double e = dt_att_err(&st, rs.r);
        worst = e > worst ? e : worst;
        for (int i = 0; i < 3; i++) {
            const double be = fabs(st.bias[i] / 1073741824.0 - rs.bias[i]);
            worst_bias = be > worst_bias ? be : worst_bias;
        }
        for (int i = 0; i < 2; i++) {
            const double we = fabs(st.wind.w_q8[i] / 256.0 - rs.w[i]);
            worst_wind = we > worst_wind ? we : worst_wind;
        }
    }
    printf("  closed loop vs double reference, 10^5 samples: attitude %.3e rad, bias %.3e "
           "rad/s, wind %.3f cm/s (reference's %.1f %.1f)\n",
           worst, worst_bias, worst_wind, rs.w[0], rs.w[1]);
    TEST_ASSERT_TRUE(rs.wind_solved != 0); /* the wind fit ran */
    /* Measured 3.8e-5 rad, 1.7e-6 rad/s and 0.08 cm/s (the fit finds the
     * 1 m/s wind within 1 cm/s). Without the wind fit the two agree within
     * 2.2e-6 rad: the fit's W is a difference of large moments (this
     * flight's headings hardly ever fill a turn), and its rounding, 0.1 cm/s
     * of W, turns the course by up to 5e-5 rad at 20 m/s, which the yaw
     * loop follows. */
    TEST_ASSERT_TRUE(worst_wind < 0.5);
    TEST_ASSERT_TRUE(worst < 1e-4);
    TEST_ASSERT_TRUE(worst_bias < 5e-6);
}

/* Speeding up in level flight: the specific force leans forward by the
 * acceleration (0.1 g reads as 5.7 degrees of nose-up), the airspeed rises
 * with it. The compensation's rate-of-change term keeps the pitch; without
 * compensation the estimate pitches up toward atan(0.1). 20 s at 200 Hz. */
static double accelerating_pitch_error(uint8_t cf)
{
    prm.centripetal = cf;
    dt_init(&dcm, &prm);
    double r[3][3];
    dcmr_from_euler(0, 0, 0, r);
    dt_state_at(&st, r);
    const double w[3] = {0, 0, 0};
    const double f[3] = {0, 0.1, -1.0}; /* 0.1 g forward */
    const ht_imu_sample_t imu = dt_imu(w, f);
    double v = 1500.0; /* cm/s */
    ht_dcm_output_t out;
    for (int k = 0; k < 200 * 20; k++) {
        ht_dcm_aiding_t aid = {0};
        aid.airspeed_valid = 1u;
        aid.airspeed_cm_s = (int16_t)lround(v);
        ht_dcm_update(&dcm, &st, &imu, &aid);
        v += 0.1 * 980.665 / 200.0;
    }
    ht_dcm_output(&st, &out);
    return fabs(out.pitch_cdeg / 100.0);
}

static void test_forward_acceleration_is_compensated(void)
{
    const double with = accelerating_pitch_error((uint8_t)HT_DCM_CF_AIRSPEED);
    setUp();
    const double without = accelerating_pitch_error((uint8_t)HT_DCM_CF_OFF);
    printf("  0.1 g forward for 20 s: pitch error %.3f deg compensated, %.2f without\n", with,
           without);
    TEST_ASSERT_TRUE(with < 0.3);
    TEST_ASSERT_TRUE(without > 2.0);
}

/* A steady level turn at 60 deg of bank with the nose 5 deg up: the air
 * velocity is horizontal and without sideslip, so in body axes it has an
 * angle of attack of 10 deg. Its w x v is what the accelerometer sees; the
 * compensation recovers that angle from the zero climb rate (along the
 * fuselage alone it would be 0.2 g off). 60 s. */
static void test_turn_angle_of_attack_from_the_climb_rate(void)
{
    prm.centripetal = (uint8_t)HT_DCM_CF_AIRSPEED;
    dt_init(&dcm, &prm);
    const double phi = 60.0 * DEG, theta = 5.0 * DEG, v = 60.0;
    double r[3][3];
    dcmr_from_euler(phi, theta, 0, r);
    dt_state_at(&st, r);
    /* coordinated: the air velocity in the plane of symmetry, V [0, cos a, sin a],
     * and horizontal: v . R[2] = 0, so tan a = -R[2][1] / R[2][2] (10 deg here) */
    const double alpha = atan2(-r[2][1], r[2][2]);
    double vb[3] = {0, v * cos(alpha), v * sin(alpha)};
    const double om = 9.80665 * tan(phi) / v;
    const double w[3] = {om * r[2][0], om * r[2][1], om * r[2][2]};
    double f[3];
    f[0] = (w[1] * vb[2] - w[2] * vb[1]) / 9.80665 - r[2][0];
    f[1] = (w[2] * vb[0] - w[0] * vb[2]) / 9.80665 - r[2][1];
    f[2] = (w[0] * vb[1] - w[1] * vb[0]) / 9.80665 - r[2][2];
    const ht_imu_sample_t imu = dt_imu(w, f);
    ht_dcm_output_t out;
    double worst = 0.0;
    for (int k = 0; k < 200 * 60; k++) {
        ht_dcm_aiding_t aid = {0};
        aid.airspeed_valid = 1u;
        aid.airspeed_cm_s = (int16_t)lround(v * 100.0);
        ht_dcm_update(&dcm, &st, &imu, &aid);
        ht_dcm_output(&st, &out);
        const double e = fabs(out.roll_cdeg / 100.0 - 60.0) + fabs(out.pitch_cdeg / 100.0 - 5.0);
        worst = e > worst ? e : worst;
    }
    printf("  60 deg turn, nose 5 deg up (alpha %.1f deg): worst roll + pitch error %.3f deg\n",
           atan2(vb[2], vb[1]) / DEG, worst);
    TEST_ASSERT_TRUE(worst < 0.3);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_bias_each_axis_and_together_within_005_deg_s);
    RUN_TEST(test_centripetal_compensation_in_a_45_deg_turn);
    RUN_TEST(test_gps_yaw_converges_from_90_degrees);
    RUN_TEST(test_magnetometer_yaw_converges_with_declination);
    RUN_TEST(test_accel_weight_across_the_band);
    RUN_TEST(test_closed_loop_tracks_double_reference);
    RUN_TEST(test_forward_acceleration_is_compensated);
    RUN_TEST(test_turn_angle_of_attack_from_the_climb_rate);
    return UNITY_END();
}
