/*
 * The estimator's wind estimate (src/estimator/dcm_wind.h): a 10 m/s wind across a
 * 25 m/s flight. The course of the ground velocity then differs from the
 * heading by up to atan(10 / 25) = 21.8 degrees; the regression of the GPS
 * velocity on the air velocity in a turn finds the wind, and the course of
 * v_gps - W is the heading's. Exact sensors, a 5 Hz GPS 100 ms late.
 *
 * The flight: coordinated and level, bank phi(t) (rate g tan(phi) / V about
 * the vertical), heading psi(t). The gyro is the body rate that turns one
 * sample's true attitude into the next's; the specific force is the air
 * velocity's change minus gravity, in body axes.
 */
#include "dcm_test_util.h"

#include <string.h>

DT_DEFAULT_FIXTURE()

#define RATE       200
#define GPS_PERIOD 40 /* samples: 5 Hz */
#define LAT        20 /* samples: 100 ms */
#define V_AIR      25.0
#define G0         9.80665

/* the wind, m/s north and east */
static double wind_n, wind_e;

typedef struct {
    double t_in, t_out; /* the roll-in starts, the roll-out starts (s); 2 s each */
    double phi_turn;    /* the bank of the turn (rad) */
    double seconds;
    int pitot; /* 1: airspeed valid */
} profile_t;

static double bank_at(const profile_t *pr, double t)
{
    if (t < pr->t_in) {
        return 0.0;
    }
    if (t < pr->t_in + 2.0) {
        return pr->phi_turn * (t - pr->t_in) / 2.0;
    }
    if (t < pr->t_out) {
        return pr->phi_turn;
    }
    if (t < pr->t_out + 2.0) {
        return pr->phi_turn * (1.0 - (t - pr->t_out) / 2.0);
    }
    return 0.0;
}

typedef struct {
    double heading_err_deg; /* estimate - truth at the end */
    double track_minus_heading_deg;
    double wind_err_cm_s;  /* |W - truth| at the end */
    double tilt_worst_deg; /* the worst tilt error after the first 5 s */
    double tilt_end_deg;   /* the worst over the last 10 s */
} result_t;

static double wrap_deg(double a)
{
    while (a > 180.0) {
        a -= 360.0;
    }
    while (a <= -180.0) {
        a += 360.0;
    }
    return a;
}

static result_t fly(const profile_t *pr)
{
    const long n = (long)(pr->seconds * RATE);
    const double dt = 1.0 / RATE;
    double psi = 0.0;
    double r[3][3];
    dcmr_from_euler(0, 0, psi, r);
    dt_state_at(&st, r);
    /* the ground velocity of every sample, for the late GPS */
    static double vg[RATE * 120][2];
    ht_dcm_aiding_t aid;
    memset(&aid, 0, sizeof aid);
    result_t res = {0, 0, 0, 0, 0};
    for (long k = 0; k < n; k++) {
        const double t = (double)k * dt;
        const double phi = bank_at(pr, t), phi1 = bank_at(pr, t + dt);
        const double om = G0 * tan(phi) / V_AIR, om1 = G0 * tan(phi1) / V_AIR;
        const double psi1 = psi + 0.5 * (om + om1) * dt;
        double r1[3][3];
        dcmr_from_euler(phi1, 0, psi1, r1);
        /* the body rate: the rotation R^T R1 over one sample */
        double m[3][3];
        for (int i = 0; i < 3; i++) {
            for (int j = 0; j < 3; j++) {
                m[i][j] = r[0][i] * r1[0][j] + r[1][i] * r1[1][j] + r[2][i] * r1[2][j];
            }
        }
        const double w[3] = {(m[2][1] - m[1][2]) / (2 * dt), (m[0][2] - m[2][0]) / (2 * dt),
                             (m[1][0] - m[0][1]) / (2 * dt)};
        /* the air velocity turns at om: acceleration V om across the path */
        const double pm = 0.5 * (psi + psi1), omm = 0.5 * (om + om1);
        const double a_e[3] = {-V_AIR * omm * sin(pm) / G0, V_AIR * omm * cos(pm) / G0, 0.0};
        const double f_e[3] = {a_e[0], a_e[1], a_e[2] - 1.0};
        double f[3];
        for (int j = 0; j < 3; j++) {
            f[j] = r[0][j] * f_e[0] + r[1][j] * f_e[1] + r[2][j] * f_e[2];
        }
        vg[k][0] = V_AIR * cos(psi) + wind_n;
        vg[k][1] = V_AIR * sin(psi) + wind_e;
        aid.gps_fix = (k >= LAT) ? 1u : 0u;
        aid.gps_fresh = (k >= LAT && (k % GPS_PERIOD) == LAT) ? 1u : 0u;
        if (aid.gps_fresh != 0u) {
            aid.vel_ned_cm_s[0] = (int32_t)lround(vg[k - LAT][0] * 100.0);
            aid.vel_ned_cm_s[1] = (int32_t)lround(vg[k - LAT][1] * 100.0);
            aid.vel_ned_cm_s[2] = 0;
        }
        aid.airspeed_valid = (uint8_t)pr->pitot;
        aid.airspeed_cm_s = (int16_t)lround(V_AIR * 100.0);
        const ht_imu_sample_t imu = dt_imu(w, f);
        ht_dcm_update(&dcm, &st, &imu, &aid);
        memcpy(r, r1, sizeof r);
        psi = psi1;
        if (t > 5.0) {
            double e[3][3];
            dcmr_from_state(&st, e);
            const double c = e[2][0] * r[2][0] + e[2][1] * r[2][1] + e[2][2] * r[2][2];
            const double tilt = acos(c > 1.0 ? 1.0 : c) / DEG;
            res.tilt_worst_deg = tilt > res.tilt_worst_deg ? tilt : res.tilt_worst_deg;
            if (t > pr->seconds - 10.0) {
                res.tilt_end_deg = tilt > res.tilt_end_deg ? tilt : res.tilt_end_deg;
            }
        }
    }
    ht_dcm_output_t out;
    ht_dcm_output(&st, &out);
    res.heading_err_deg = wrap_deg(out.yaw_cdeg / 100.0 - psi / DEG);
    const double track = atan2(vg[n - 1][1], vg[n - 1][0]) / DEG;
    res.track_minus_heading_deg = wrap_deg(track - psi / DEG);
    res.wind_err_cm_s =
        hypot(st.wind.w_q8[0] / 256.0 - wind_n * 100.0, st.wind.w_q8[1] / 256.0 - wind_e * 100.0);
    return res;
}

static void setup_flight(void)
{
    prm.gps_latency_ms = 100u;
    dt_init(&dcm, &prm);
    wind_n = 0.0;
    wind_e = 10.0;
}

/*
 * Straight, a 30-degree turn for 40 s (two circles at 13 deg/s), straight
 * again for 30 s, heading north at the start in a wind from the west. The
 * straight start aligns the heading on the track (21.8 degrees off: no
 * estimator can tell the crab there); the turn teaches the wind, and
 * afterwards the heading is the air velocity's, not the track's. Measured:
 * wind within 0.53 m/s, heading within 0.5 degree (the track 17.8 degrees
 * off it at the end), tilt 5.7 degrees at worst in the first turn (the
 * crab's heading error, before the wind is known) and 0.57 degree
 * over the last 10 s.
 */
static void test_turn_teaches_the_wind_and_straight_flight_keeps_the_heading(void)
{
    setup_flight();
    const profile_t pr = {5.0, 45.0, 30.0 * DEG, 77.0, 1};
    const result_t r = fly(&pr);
    printf("  wind after a turn: |W - truth| %.1f cm/s, heading %.3f deg (track %.1f deg off), "
           "tilt worst %.3f deg, last 10 s %.3f deg\n",
           r.wind_err_cm_s, r.heading_err_deg, r.track_minus_heading_deg, r.tilt_worst_deg,
           r.tilt_end_deg);
    TEST_ASSERT_TRUE(fabs(r.track_minus_heading_deg) > 15.0); /* the crab is there */
    TEST_ASSERT_TRUE(r.wind_err_cm_s < 100.0);
    TEST_ASSERT_TRUE(fabs(r.heading_err_deg) < 1.0);
    TEST_ASSERT_TRUE(r.tilt_worst_deg < 8.0);
    TEST_ASSERT_TRUE(r.tilt_end_deg < 1.0);
    /* the heading is known once the wind is (the turn-rate trim waits for it) */
    TEST_ASSERT_EQUAL_UINT8(1u, st.wind.solved);
    TEST_ASSERT_BITS_HIGH(HT_DCM_F_HEADING_KNOWN, st.flags);
}

/*
 * Straight flight only: a cross wind and a heading error are one unknown,
 * the estimate takes no wind (W stays exactly 0) and the heading follows
 * the track, the documented limit of any GPS-only heading.
 */
static void test_straight_flight_learns_no_wind(void)
{
    setup_flight();
    const profile_t pr = {1000.0, 1000.0, 0.0, 60.0, 1};
    const result_t r = fly(&pr);
    TEST_ASSERT_EQUAL_INT32(0, st.wind.w_q8[0]);
    TEST_ASSERT_EQUAL_INT32(0, st.wind.w_q8[1]);
    TEST_ASSERT_BITS_LOW(HT_DCM_F_HEADING_KNOWN, st.flags); /* the crab is unknown */
    printf("  straight flight: heading %.2f deg from the truth, the track %.2f deg\n",
           r.heading_err_deg, r.track_minus_heading_deg);
    TEST_ASSERT_FLOAT_WITHIN(0.5, r.track_minus_heading_deg, r.heading_err_deg);
}

/* Without a pitot the air velocity's length is the GPS speed's: no wind. */
static void test_no_pitot_no_wind(void)
{
    setup_flight();
    const profile_t pr = {5.0, 45.0, 30.0 * DEG, 60.0, 0};
    (void)fly(&pr);
    TEST_ASSERT_EQUAL_UINT8(0u, st.wind.primed);
    TEST_ASSERT_EQUAL_INT32(0, st.wind.w_q8[0]);
    TEST_ASSERT_EQUAL_INT32(0, st.wind.w_q8[1]);
}

/*
 * The edges: GPS velocities at the int32 extremes and the airspeed at its
 * maximum, every sample a solution, in a turn: nothing overflows (the
 * sanitized build checks), the wind stays within its 50 m/s bound and A
 * within [0.5, 2].
 */
static void test_extreme_inputs_stay_bounded(void)
{
    prm.gps_latency_ms = 0u;
    dt_init(&dcm, &prm);
    double r0[3][3];
    dcmr_from_euler(30 * DEG, 0, 0, r0);
    dt_state_at(&st, r0);
    const double w[3] = {0.1 * r0[2][0], 0.1 * r0[2][1], 0.1 * r0[2][2]};
    const double f[3] = {0, 0, -1.0 / cos(30 * DEG)};
    const ht_imu_sample_t imu = dt_imu(w, f);
    static const int32_t v[4] = {INT32_MAX, INT32_MIN, 0, -1};
    ht_dcm_aiding_t aid;
    memset(&aid, 0, sizeof aid);
    aid.gps_fix = 1u;
    aid.gps_fresh = 1u;
    aid.airspeed_valid = 1u;
    aid.airspeed_cm_s = INT16_MAX;
    for (long k = 0; k < 20000L; k++) {
        aid.vel_ned_cm_s[0] = v[k % 4];
        aid.vel_ned_cm_s[1] = v[(k / 4) % 4];
        aid.vel_ned_cm_s[2] = v[(k / 16) % 4];
        ht_dcm_update(&dcm, &st, &imu, &aid);
        for (int i = 0; i < 2; i++) {
            TEST_ASSERT_TRUE(st.wind.w_q8[i] <= 5000 * 256 && st.wind.w_q8[i] >= -5000 * 256);
        }
        const double a2 =
            pow(st.wind.a_q28[0] / 268435456.0, 2) + pow(st.wind.a_q28[1] / 268435456.0, 2);
        TEST_ASSERT_TRUE(st.wind.primed == 0u || (a2 >= 0.25 - 1e-6 && a2 <= 4.0 + 1e-6));
    }
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_turn_teaches_the_wind_and_straight_flight_keeps_the_heading);
    RUN_TEST(test_straight_flight_learns_no_wind);
    RUN_TEST(test_no_pitot_no_wind);
    RUN_TEST(test_extreme_inputs_stay_bounded);
    return UNITY_END();
}
