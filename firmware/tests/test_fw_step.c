/*
 * test_fw_step.c - the one firmware step: configuration refusals, the
 * control-rate gate, the IMU-loss failsafe, the estimator feeding the law,
 * the guided path against the holds/guard/law/output stage called by hand,
 * and the pilot path's RC-loss policy (the modes' one).
 */
#include "helical/estimator/air_data.h"
#include "unity.h"

#include "fw_step.h"

#include <math.h>
#include <string.h>

static fw_config_t cfg;
static fw_t fw;
static fw_inputs_t in;
static fw_output_t out;

void setUp(void)
{
    fw_config_default(&cfg);
    memset(&in, 0, sizeof in);
    memset(&out, 0, sizeof out);
    in.sensors.imu_fresh = 1u;
    in.sensors.imu.accel_g[2] = -Q16_ONE; /* level, at rest */
    in.sensors.airspeed_fresh = 1u;
    /* the pitot's indicated 19.90 m/s is 20.00 m/s true at 100 m of
     * pressure altitude (air_data.h): the law flies 20 m/s */
    in.sensors.airspeed_cm_s = 1990;
    in.sensors.baro_fresh = 1u;
    in.sensors.baro_alt_cm = 10000;
}

void tearDown(void) {}

static int run_until_control(void)
{
    for (unsigned k = 1u; k <= 1000u; ++k) {
        if (fw_step(&fw, &in, &out) != 0) {
            return (int)k;
        }
    }
    return 0;
}

static void test_refusals_name_the_block(void)
{
    TEST_ASSERT_EQUAL_INT(0, fw_init(&fw, NULL));
    TEST_ASSERT_EQUAL_UINT8(FW_BAD_NULL, fw.bad);
    cfg.law.kp_aileron = 65 * Q16_ONE;
    TEST_ASSERT_EQUAL_INT(0, fw_init(&fw, &cfg));
    TEST_ASSERT_EQUAL_UINT8(FW_BAD_LAW, fw.bad);
    TEST_ASSERT_EQUAL_INT32(HT_P_KP_AILERON, fw.bad_sub);
    fw_config_default(&cfg);
    cfg.dcm.imu_rate_hz = 20u;
    TEST_ASSERT_EQUAL_INT(0, fw_init(&fw, &cfg));
    TEST_ASSERT_EQUAL_UINT8(FW_BAD_DCM, fw.bad);
    fw_config_default(&cfg);
    cfg.control_divider = 4u; /* 40 Hz * 4 != 200 Hz */
    TEST_ASSERT_EQUAL_INT(0, fw_init(&fw, &cfg));
    TEST_ASSERT_EQUAL_UINT8(FW_BAD_DIVIDER, fw.bad);
    fw_config_default(&cfg);
    cfg.out.ch[0].min_us = 2500u;
    TEST_ASSERT_EQUAL_INT(0, fw_init(&fw, &cfg));
    TEST_ASSERT_EQUAL_UINT8(FW_BAD_OUTPUT, fw.bad);
    /* a refused configuration never produces a pulse */
    TEST_ASSERT_EQUAL_INT(0, fw_step(&fw, &in, &out));
    TEST_ASSERT_EQUAL_UINT8(0u, out.pulse_count);
    TEST_ASSERT_EQUAL_INT(0, fw_step(NULL, &in, &out));
    TEST_ASSERT_EQUAL_INT(0, fw_step(&fw, NULL, &out));
}

static void test_control_runs_every_divider_samples(void)
{
    TEST_ASSERT_EQUAL_INT(1, fw_init(&fw, &cfg));
    TEST_ASSERT_EQUAL_INT(5, run_until_control()); /* 200 Hz / 40 Hz */
    TEST_ASSERT_EQUAL_INT(5, run_until_control());
    TEST_ASSERT_EQUAL_UINT32(10u, fw.samples);
    TEST_ASSERT_EQUAL_UINT32(2u, fw.control_steps);
    TEST_ASSERT_EQUAL_UINT8(5u, out.pulse_count);
}

static void test_level_imu_gives_a_level_estimate_to_the_law(void)
{
    TEST_ASSERT_EQUAL_INT(1, fw_init(&fw, &cfg));
    for (int k = 0; k < 200; ++k) { /* one second */
        (void)run_until_control();
    }
    TEST_ASSERT_INT_WITHIN(2, 0, out.nav.down_q14[0]);
    TEST_ASSERT_INT_WITHIN(2, 0, out.nav.down_q14[1]);
    TEST_ASSERT_INT_WITHIN(2, Q14_ONE, out.nav.down_q14[2]);
    TEST_ASSERT_EQUAL_INT16(out.nav.down_q14[2], out.law_in.z);
    TEST_ASSERT_EQUAL_INT16(2000, out.law_in.airspeed_cm_s);
    TEST_ASSERT_EQUAL_INT32(10000, out.nav.altitude_cm);
    TEST_ASSERT_TRUE((out.est.flags & HT_DCM_F_ALIGNED) != 0u);
}

static void test_imu_loss_gives_the_failsafe_pulses(void)
{
    TEST_ASSERT_EQUAL_INT(1, fw_init(&fw, &cfg));
    (void)run_until_control();
    TEST_ASSERT_EQUAL_UINT8(0u, out.failsafe);
    in.sensors.imu_fresh = 0u;
    int k = 0;
    while (out.failsafe == 0u && k < 100) {
        (void)run_until_control();
        ++k;
    }
    TEST_ASSERT_EQUAL_UINT8(1u, out.failsafe);
    /* within the timeout (40 samples = 8 control steps) and not before */
    TEST_ASSERT_EQUAL_INT(8, k);
    uint16_t fs[OS_MAX_CHANNELS];
    TEST_ASSERT_EQUAL_INT(OS_OK, os_failsafe(&cfg.out, fs));
    TEST_ASSERT_EQUAL_UINT16_ARRAY(fs, out.pulse_us, cfg.out.count);
    /* an external solution keeps flying without an IMU (the SIL's truth) */
    fw_nav_t nav;
    memset(&nav, 0, sizeof nav);
    nav.down_q14[2] = Q14_ONE;
    nav.airspeed_cm_s = 2000;
    in.external = &nav;
    (void)run_until_control();
    TEST_ASSERT_EQUAL_UINT8(0u, out.failsafe);
}

/* The guided path is the holds, the guard, the law and the output stage in
 * that order: the same calls by hand give the same pulses. */
static void test_guided_path_is_the_library_chain(void)
{
    TEST_ASSERT_EQUAL_INT(1, fw_init(&fw, &cfg));
    fw_nav_t nav;
    memset(&nav, 0, sizeof nav);
    nav.down_q14[0] = -5000; /* banked right */
    nav.down_q14[2] = 15600;
    nav.gyro_q11_rad_s[1] = 300;
    nav.airspeed_cm_s = 2500;
    nav.altitude_cm = 9000;
    nav.climb_cm_s = -50;
    fw_guided_t g;
    memset(&g, 0, sizeof g);
    g.turn_rate_rad_s = Q11_FROM_REAL(0.3);
    g.altitude_hold = 1u;
    g.altitude_cm = 10000;
    g.speed_hold = 1u;
    g.airspeed_cm_s = 2200;
    in.external = &nav;
    in.guided = &g;
    (void)run_until_control();

    ht_alt_hold_state_t alt;
    ht_alt_hold_reset(&alt);
    ht_speed_hold_state_t spd;
    ht_speed_hold_reset(&spd);
    ht_upset_guard_state_t ug;
    ht_upset_guard_reset(&ug);
    q16_t pitch = ht_alt_hold_step_v(&cfg.modes.alt, &alt, 10000, 9000, -50, 0u, 2500);
    pitch = ht_upset_guard_step(&cfg.guard, &ug, -5000, 0, 15600, 0u, pitch);
    const q14_t thr = ht_speed_hold_step(&cfg.modes.speed, &spd, 2200, 2500, pitch);
    ht_controller_t ctl;
    TEST_ASSERT_EQUAL_INT(HT_OK, ht_init(&ctl, &cfg.law, NULL));
    const ht_input_t li = {-5000, 0, 15600, Q11_FROM_REAL(0.3), pitch, 2500, {0, 300, 0}, 0u, 0, 0};
    /* ht_step writes the fields, not the padding: zero it as the firmware's
     * own output is, so that the whole-struct comparison below compares
     * what the law wrote (uninitialised padding made it depend on the stack) */
    ht_output_t lo;
    memset(&lo, 0, sizeof lo);
    ht_step(&ctl, &li, &lo);
    const os_command_t cmd = {lo.aileron, lo.elevator, lo.rudder, thr};
    uint16_t pulses[OS_MAX_CHANNELS];
    TEST_ASSERT_EQUAL_INT(OS_OK, os_compute(&cfg.out, &cmd, pulses));
    TEST_ASSERT_EQUAL_UINT16_ARRAY(pulses, out.pulse_us, cfg.out.count);
    TEST_ASSERT_EQUAL_INT32(pitch, out.pitch_cmd);
    TEST_ASSERT_EQUAL_INT16(thr, out.throttle);
    TEST_ASSERT_EQUAL_MEMORY(&lo, &out.law, sizeof lo);
}

/* The law's option inputs (docs/control-law.md "Extensions beyond the
 * seed"). roll_in off: a guided step reaches the law as a step, with no
 * turn acceleration. roll_in on: it is slewed, and the law is given that
 * slope as its turn acceleration, 0 once the slew is done. The slew is the
 * modes' turn_slew (180 deg/s^2 = 3.1416 rad/s^2: 0.07854 rad/s per 40 Hz
 * step) when roll_in_rate_max allows it (8 rad/s at 20 m/s: 0.0981 rad/s per
 * step), else the one of roll_in_rate_max (test below). */
static void ramp_guided_turn(fw_guided_t *g, double per_step, int steps)
{
    const double target = 0.3;
    g->turn_rate_rad_s = Q11_FROM_REAL(0.3);
    int k = 0;
    for (; k < 40 && (k == 0 || out.law_in.turn_rate_rad_s < g->turn_rate_rad_s); ++k) {
        (void)run_until_control();
        const double expect = fmin(target, (k + 1) * per_step);
        TEST_ASSERT_INT_WITHIN(2, (int)lround(expect * 2048.0), out.law_in.turn_rate_rad_s);
        if (expect < target) {
            /* the slope in Q11, within the Q16 step's rounding */
            TEST_ASSERT_INT_WITHIN(64, (int)lround(per_step * 40.0 * 2048.0),
                                   out.law_in.turn_accel_rad_s2);
        }
    }
    TEST_ASSERT_EQUAL_INT(steps, k);
    (void)run_until_control();
    TEST_ASSERT_EQUAL_INT16(Q11_FROM_REAL(0.3), out.law_in.turn_rate_rad_s);
    TEST_ASSERT_EQUAL_INT16(0, out.law_in.turn_accel_rad_s2);
}

static void test_roll_in_slews_a_guided_step(void)
{
    fw_guided_t g;
    memset(&g, 0, sizeof g);
    g.throttle = Q14_ONE / 2;
    in.guided = &g;
    TEST_ASSERT_EQUAL_INT(1, fw_init(&fw, &cfg));
    (void)run_until_control();
    g.turn_rate_rad_s = Q11_FROM_REAL(0.3);
    (void)run_until_control();
    TEST_ASSERT_EQUAL_INT16(Q11_FROM_REAL(0.3), out.law_in.turn_rate_rad_s);
    TEST_ASSERT_EQUAL_INT16(0, out.law_in.turn_accel_rad_s2);

    cfg.law.roll_in = 1u;
    cfg.law.roll_in_rate_max_rad_s = Q16_FROM_REAL(8.0);
    g.turn_rate_rad_s = 0;
    TEST_ASSERT_EQUAL_INT(1, fw_init(&fw, &cfg));
    (void)run_until_control();
    TEST_ASSERT_EQUAL_INT16(0, out.law_in.turn_accel_rad_s2); /* the first step: no history */
    ramp_guided_turn(&g, 3.14159265 / 40.0, 4);               /* 0.3 / 0.0785: four steps */
}

/* With roll_in_rate_max = 1 rad/s at 20 m/s the guided slew is the bank
 * rate's: g / S * 1 rad/s = 0.4905 rad/s^2, 0.01226 rad/s per 40 Hz step
 * (Q16 floor of 65536 * 981 / 2000 / 40 = 803 LSB), so 0.3 rad/s takes 25
 * steps; with no airspeed it is floored at v_min (5 m/s): 4x the slew. */
static void test_roll_in_slew_follows_the_bank_rate_bound(void)
{
    fw_guided_t g;
    memset(&g, 0, sizeof g);
    g.throttle = Q14_ONE / 2;
    in.guided = &g;
    cfg.law.roll_in = 1u;
    cfg.law.roll_in_rate_max_rad_s = Q16_FROM_REAL(1.0);
    TEST_ASSERT_EQUAL_INT(1, fw_init(&fw, &cfg));
    (void)run_until_control();
    ramp_guided_turn(&g, 803.0 / 65536.0, 25);

    in.sensors.airspeed_cm_s = 0; /* floored at v_min = 5 m/s: 3213 LSB per step */
    g.turn_rate_rad_s = 0;
    TEST_ASSERT_EQUAL_INT(1, fw_init(&fw, &cfg));
    (void)run_until_control();
    ramp_guided_turn(&g, 3213.0 / 65536.0, 7);
    in.sensors.airspeed_cm_s = 1990; /* 20 m/s true at 100 m */
}

/* The lateral specific force reaches the law low-passed at the IMU rate
 * (200 Hz: 2^4 samples, 80 ms): a step of 0.2 g is 1/16 of the way after
 * one sample and settled within 1 LSB after a second. */
static void test_lateral_force_is_filtered_into_the_law(void)
{
    TEST_ASSERT_EQUAL_INT(1, fw_init(&fw, &cfg));
    TEST_ASSERT_EQUAL_UINT8(4u, fw.accel_lat_shift);
    in.sensors.imu.accel_g[0] = Q16_FROM_REAL(0.2);
    (void)fw_step(&fw, &in, &out);
    TEST_ASSERT_INT_WITHIN(1, Q16_FROM_REAL(0.2), fw.accel_lat_q20); /* Q20 / 16 */
    for (int k = 0; k < 200; ++k) {
        (void)run_until_control();
    }
    TEST_ASSERT_INT_WITHIN(1, Q14_FROM_REAL(0.2), out.law_in.accel_lat_g);
    TEST_ASSERT_INT_WITHIN(1, Q14_FROM_REAL(0.2), out.modes.law_in.accel_lat_g);
    /* anything a driver gives is held: 32 g, then 2 g in the law's Q14 */
    in.sensors.imu.accel_g[0] = INT32_MAX;
    for (int k = 0; k < 200; ++k) {
        (void)run_until_control();
    }
    TEST_ASSERT_EQUAL_INT16(INT16_MAX, out.law_in.accel_lat_g);
    TEST_ASSERT_INT_WITHIN(16, 32 * 16 * Q16_ONE, fw.accel_lat_q20);
}

/* The pilot path: no RC ever -> manual, neutral, throttle 0; a good RC
 * then lost -> the modes' failsafe (RTH) after rc_loss_ticks. */
static void test_pilot_path_rc_loss_policy(void)
{
    TEST_ASSERT_EQUAL_INT(1, fw_init(&fw, &cfg));
    (void)run_until_control();
    TEST_ASSERT_EQUAL_UINT8(HT_MODE_MANUAL, out.modes.mode);
    TEST_ASSERT_EQUAL_UINT8(0u, out.modes.failsafe);
    in.rc_count = 8u;
    const uint16_t rc[8] = {1500u, 1500u, 1100u, 1500u, 1500u, 1000u, 1500u, 1500u};
    memcpy(in.rc_us, rc, sizeof rc);
    in.rc_fresh = 1u;
    (void)run_until_control();
    TEST_ASSERT_EQUAL_UINT8(HT_MODE_FBW, out.modes.mode);
    in.rc_fresh = 0u;
    unsigned k = 0u;
    while (out.modes.failsafe == 0u && k < 100u) {
        (void)run_until_control();
        ++k;
    }
    TEST_ASSERT_EQUAL_UINT32(cfg.modes.rc_loss_ticks, k);
    TEST_ASSERT_EQUAL_UINT8(HT_MODE_RTH, out.modes.mode);
}

/* Any int32 from a GPS driver or the link: a velocity or a position at the
 * type's ends, a baro altitude jumping from one end to the other. Bounded
 * answers, no overflow (the sanitized build traps one). */
static void test_extreme_gps_and_baro_values(void)
{
    TEST_ASSERT_EQUAL_INT(1, fw_init(&fw, &cfg));
    in.sensors.gps.fresh = 1u;
    in.sensors.gps.fix = 3u;
    const int32_t ends[4] = {INT32_MIN, INT32_MAX, -1, 0};
    for (int k = 0; k < 4; ++k) {
        for (int i = 0; i < 3; ++i) {
            in.sensors.gps.vel_ned_cm_s[i] = ends[(k + i) % 4];
        }
        in.sensors.gps.lat_e7 = ends[k];
        in.sensors.gps.lon_e7 = ends[(k + 1) % 4];
        in.sensors.baro_alt_cm = ends[(k + 2) % 4];
        (void)run_until_control();
        TEST_ASSERT_EQUAL_UINT8(5u, out.pulse_count);
        TEST_ASSERT_TRUE(out.nav.airspeed_cm_s >= 0);
    }
}

/* The board gives the pitot's INDICATED airspeed; the step makes it true
 * once, with the latest baro reading (issue 33, item 13): at 3 000 m of
 * pressure altitude 20.00 m/s indicated is 23.21 m/s true (ISA), for the law
 * and the estimate alike; with the baro's temperature ISA + 20 K, 24.01 m/s
 * (sqrt(275.65 / 255.65) more); before any baro reading, sea level. */
static void test_pitot_made_true_with_the_baro(void)
{
    in.sensors.airspeed_cm_s = 2000;
    in.sensors.baro_fresh = 0u;
    TEST_ASSERT_EQUAL_INT(1, fw_init(&fw, &cfg));
    (void)run_until_control();
    TEST_ASSERT_EQUAL_INT16(2000, out.law_in.airspeed_cm_s); /* no baro yet */
    in.sensors.baro_fresh = 1u;
    in.sensors.baro_alt_cm = 300000;
    (void)run_until_control();
    TEST_ASSERT_INT16_WITHIN(1, 2321, out.law_in.airspeed_cm_s);
    TEST_ASSERT_EQUAL_INT16(out.law_in.airspeed_cm_s, out.nav.airspeed_cm_s);
    TEST_ASSERT_EQUAL_INT16(ht_true_airspeed_cm_s(2000, 300000, 0, 0u), out.nav.airspeed_cm_s);
    in.sensors.baro_temp_valid = 1u;
    in.sensors.baro_temp_cdeg = 250; /* ISA at 3 000 m is -4.5 degC: ISA + 7 K */
    (void)run_until_control();
    TEST_ASSERT_EQUAL_INT16(ht_true_airspeed_cm_s(2000, 300000, 250, 1u), out.nav.airspeed_cm_s);
    TEST_ASSERT_INT16_WITHIN(1, 2351, out.nav.airspeed_cm_s); /* 23.21 sqrt(275.65/268.65) */
    /* a stale baro keeps the last reading's density */
    in.sensors.baro_fresh = 0u;
    in.sensors.airspeed_cm_s = 1000;
    (void)run_until_control();
    TEST_ASSERT_EQUAL_INT16(ht_true_airspeed_cm_s(1000, 300000, 250, 1u), out.nav.airspeed_cm_s);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_pitot_made_true_with_the_baro);
    RUN_TEST(test_refusals_name_the_block);
    RUN_TEST(test_control_runs_every_divider_samples);
    RUN_TEST(test_level_imu_gives_a_level_estimate_to_the_law);
    RUN_TEST(test_imu_loss_gives_the_failsafe_pulses);
    RUN_TEST(test_guided_path_is_the_library_chain);
    RUN_TEST(test_pilot_path_rc_loss_policy);
    RUN_TEST(test_roll_in_slews_a_guided_step);
    RUN_TEST(test_roll_in_slew_follows_the_bank_rate_bound);
    RUN_TEST(test_lateral_force_is_filtered_into_the_law);
    RUN_TEST(test_extreme_gps_and_baro_values);
    return UNITY_END();
}
