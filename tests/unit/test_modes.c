/* Unit tests of the flight modes (include/helical/guidance/modes.h): the mode switch
 * for every pulse, the RC-loss failsafe and its recovery, the per-mode
 * sources, bumpless transfer (a bound on the per-step surface change across
 * every mode change, checked on fixed cases and a seeded random sweep), the
 * AoA trim path, edges and the parameter checks. */
#include "unity.h"

#include "helical/guidance/modes.h"
#include "ht_test_support.h"

#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define PI  3.14159265358979323846
#define Q16 65536.0

static ht_modes_params_t prm;
static ht_controller_t ctl;
static ht_modes_t m;
static ht_modes_state_t st;
static const ht_waypoint_t square[4] = {
    {200, -200, 100}, {200, 200, 100}, {-200, 200, 100}, {-200, -200, 100}};

enum { RC_AIL = 0, RC_ELE = 1, RC_THR = 2, RC_RUD = 3, RC_MODE = 4, RC_INV = 5 };

static const uint16_t mode_us[4] = {1000u, 1500u, 2000u, 2150u};

void setUp(void)
{
    ht_params_t cp = HT_PARAMS_DEFAULT;
    TEST_ASSERT_EQUAL_INT(HT_OK, ht_init(&ctl, &cp, NULL));
    ht_modes_params_default(&prm);
    ht_modes_bad_t bad;
    TEST_ASSERT_EQUAL_INT(0, ht_modes_init(&m, &prm, &ctl, square, 4u, &bad));
    ht_modes_reset(&st, 0, 0);
}

void tearDown(void) {}

/* An input: bank and pitch in degrees, sticks and switch as pulses. */
static ht_modes_input_t mk_in(double bank_deg, double pitch_deg, double v_m_s, uint16_t mode,
                              uint16_t ail, uint16_t ele, uint16_t inv)
{
    ht_modes_input_t in;
    memset(&in, 0, sizeof in);
    double ph = bank_deg * PI / 180.0, th = pitch_deg * PI / 180.0;
    in.x = ts_fix16(-sin(ph) * cos(th), 14);
    in.y = ts_fix16(-sin(th), 14);
    in.z = ts_fix16(cos(ph) * cos(th), 14);
    in.airspeed_cm_s = (int16_t)lround(v_m_s * 100.0);
    in.rc_count = 8u;
    for (unsigned i = 0; i < 8u; i++) {
        in.rc_us[i] = 1500u;
    }
    in.rc_us[RC_AIL] = ail;
    in.rc_us[RC_ELE] = ele;
    in.rc_us[RC_THR] = 1400u;
    in.rc_us[RC_MODE] = mode;
    in.rc_us[RC_INV] = inv;
    in.rc_fresh = 1u;
    in.north_cm = -10000;
    in.east_cm = 5000;
    in.alt_cm = 9000;
    in.vel_north_cm_s = (int32_t)lround(v_m_s * 100.0);
    return in;
}

static os_command_t fly(const ht_modes_input_t *in, ht_modes_output_t *o)
{
    os_command_t c;
    ht_modes_output_t oo;
    ht_modes_fly(&m, &st, &ctl, in, o ? o : &oo, NULL, &c);
    return c;
}

/* --- mode switch --------------------------------------------------------- */

static void test_mode_from_every_pulse(void)
{
    for (uint32_t p = 0; p <= 2600u; p++) {
        ht_mode_t want = (p < 1250u)   ? HT_MODE_MANUAL
                         : (p < 1750u) ? HT_MODE_FBW
                         : (p < 2100u) ? HT_MODE_WAYPOINT
                                       : HT_MODE_RTH;
        TEST_ASSERT_EQUAL_INT(want, ht_modes_from_pulse(&m, (uint16_t)p));
    }
    /* through the step, with every valid pulse 800..2200 */
    for (uint16_t p = 800u; p <= 2200u; p++) {
        ht_modes_input_t in = mk_in(0, 0, 15, p, 1500u, 1500u, 1000u);
        ht_modes_output_t o;
        (void)fly(&in, &o);
        TEST_ASSERT_EQUAL_INT(ht_modes_from_pulse(&m, p), o.selected_mode);
        TEST_ASSERT_EQUAL_INT(o.selected_mode, o.mode);
        TEST_ASSERT_EQUAL_UINT8(0u, o.failsafe);
    }
    /* the nominal switch positions are >= 100 us from every threshold */
    for (unsigned i = 0; i < 4u; i++) {
        for (unsigned t = 0; t < 3u; t++) {
            int d = (int)mode_us[i] - (int)prm.mode_threshold_us[t];
            TEST_ASSERT_TRUE(d >= 50 || d <= -100);
        }
    }
    TEST_ASSERT_EQUAL_INT(HT_MODE_MANUAL, ht_modes_from_pulse(NULL, 2000u));
}

/* --- failsafe ------------------------------------------------------------ */

static void test_no_rc_ever_is_manual_neutral_throttle_zero(void)
{
    ht_modes_input_t in = mk_in(10, 0, 15, 2000u, 1800u, 1500u, 1000u);
    in.rc_fresh = 0u;
    for (int k = 0; k < 200; k++) {
        ht_modes_output_t o;
        os_command_t c = fly(&in, &o);
        TEST_ASSERT_EQUAL_INT(HT_MODE_MANUAL, o.mode);
        TEST_ASSERT_EQUAL_UINT8(0u, o.failsafe);
        TEST_ASSERT_EQUAL_INT16(0, c.throttle);
        TEST_ASSERT_EQUAL_INT16(0, c.aileron);
    }
}

static void test_loss_after_n_stale_ticks_then_rth_and_recovery(void)
{
    ht_modes_input_t in = mk_in(0, 0, 15, 1500u, 1500u, 1500u, 2000u);
    ht_modes_output_t o;
    (void)fly(&in, &o);
    TEST_ASSERT_EQUAL_INT(HT_MODE_FBW, o.mode);
    TEST_ASSERT_EQUAL_UINT8(1u, o.law_in.inverted); /* the switch */
    in.rc_fresh = 0u;
    for (unsigned k = 1; k < prm.rc_loss_ticks; k++) {
        (void)fly(&in, &o);
        TEST_ASSERT_EQUAL_INT(HT_MODE_FBW, o.mode); /* the last good frame holds */
        TEST_ASSERT_EQUAL_UINT8(0u, o.rc_good);
    }
    (void)fly(&in, &o);
    TEST_ASSERT_EQUAL_UINT8(1u, o.failsafe);
    TEST_ASSERT_EQUAL_INT(HT_MODE_RTH, o.mode);
    TEST_ASSERT_EQUAL_UINT8(0u, o.law_in.inverted); /* failsafe flies upright */
    TEST_ASSERT_EQUAL_INT32(prm.nav.home_alt_m * 100, o.nav.target_alt_cm);
    /* recovery: rc_recover_ticks good frames in a row */
    in.rc_fresh = 1u;
    for (unsigned k = 1; k < prm.rc_recover_ticks; k++) {
        (void)fly(&in, &o);
        TEST_ASSERT_EQUAL_INT(HT_MODE_RTH, o.mode);
    }
    in.rc_fresh = 0u; /* one bad frame restarts the count */
    (void)fly(&in, &o);
    in.rc_fresh = 1u;
    for (unsigned k = 1; k < prm.rc_recover_ticks; k++) {
        (void)fly(&in, &o);
        TEST_ASSERT_EQUAL_INT(HT_MODE_RTH, o.mode);
    }
    (void)fly(&in, &o);
    TEST_ASSERT_EQUAL_UINT8(0u, o.failsafe);
    TEST_ASSERT_EQUAL_INT(HT_MODE_FBW, o.mode);
}

static void test_pulses_outside_window_count_as_loss(void)
{
    const uint16_t bad[] = {0u, 799u, 2201u, 65535u};
    const unsigned inputs[] = {RC_AIL, RC_ELE, RC_THR, RC_RUD, RC_MODE, RC_INV};
    for (unsigned b = 0; b < 4u; b++) {
        for (unsigned i = 0; i < 6u; i++) {
            ht_modes_reset(&st, 0, 0);
            ht_modes_input_t in = mk_in(0, 0, 15, 2000u, 1500u, 1500u, 1000u);
            ht_modes_output_t o;
            (void)fly(&in, &o);
            in.rc_us[inputs[i]] = bad[b];
            for (unsigned k = 0; k < prm.rc_loss_ticks; k++) {
                (void)fly(&in, &o);
                TEST_ASSERT_EQUAL_UINT8(0u, o.rc_good);
            }
            TEST_ASSERT_EQUAL_UINT8(1u, o.failsafe);
            TEST_ASSERT_EQUAL_INT(HT_MODE_RTH, o.mode);
        }
    }
    /* an unused input may be anything */
    ht_modes_reset(&st, 0, 0);
    ht_modes_input_t in = mk_in(0, 0, 15, 2000u, 1500u, 1500u, 1000u);
    in.rc_us[7] = 0u;
    ht_modes_output_t o;
    (void)fly(&in, &o);
    TEST_ASSERT_EQUAL_UINT8(1u, o.rc_good);
    /* fewer pulses than the inputs used: bad */
    in.rc_count = 5u;
    (void)fly(&in, &o);
    TEST_ASSERT_EQUAL_UINT8(0u, o.rc_good);
}

/* --- sources per mode ---------------------------------------------------- */

static void test_fbw_and_waypoint_sources(void)
{
    /* FBW: full right stick = 60 deg/s target, half up-elevator = 0.25 */
    ht_modes_input_t in = mk_in(0, 0, 15, 1500u, 2000u, 1750u, 1000u);
    ht_modes_output_t o;
    (void)fly(&in, &o);
    TEST_ASSERT_INT32_WITHIN(2, (int32_t)lround(PI / 3.0 * Q16), o.turn_target_rad_s);
    /* 250 us of 500 with an 8 us deadband: (250 - 8) / (500 - 8) of 0.5 */
    TEST_ASSERT_INT32_WITHIN(4, (int32_t)lround(0.5 * 242.0 / 492.0 * Q16), o.pitch_target);
    /* the command slews towards it: 4.5 deg/s per tick at 180 deg/s^2, 40 Hz */
    int32_t step = m.turn_slew_rad_s_per_tick;
    TEST_ASSERT_INT32_WITHIN(2, (int32_t)lround(4.5 * PI / 180.0 * Q16), step);
    /* waypoint: the pilot's stick adds to navigation, limited to the nav max */
    in = mk_in(0, 0, 15, 2000u, 1500u, 1500u, 1000u);
    (void)fly(&in, &o);
    TEST_ASSERT_EQUAL_INT(HT_MODE_WAYPOINT, o.mode);
    int32_t nav_only = o.nav.turn_rate_rad_s;
    TEST_ASSERT_EQUAL_INT32(nav_only, o.turn_target_rad_s);
    in.rc_us[RC_AIL] = 1300u; /* some left stick */
    (void)fly(&in, &o);
    ht_fbw_output_t f;
    ht_fbw_step(&m.fbw, &m.rc, in.rc_us, in.rc_count, &f);
    int32_t want = q_clamp32(o.nav.turn_rate_rad_s + f.turn_rate_rad_s, -m.nav.turn_rate_max_rad_s,
                             m.nav.turn_rate_max_rad_s);
    TEST_ASSERT_EQUAL_INT32(want, o.turn_target_rad_s);
    TEST_ASSERT_TRUE(f.turn_rate_rad_s < 0);
    /* the altitude target is the waypoint's, through the altitude hold */
    TEST_ASSERT_EQUAL_INT32(10000, o.nav.target_alt_cm);
    TEST_ASSERT_TRUE(o.pitch_target > 0); /* 10 m low: climb */
}

static void test_throttle_sources_and_blend(void)
{
    ht_modes_input_t in = mk_in(0, 0, 15, 1000u, 1500u, 1500u, 1000u);
    ht_modes_output_t o;
    os_command_t c = fly(&in, &o);
    TEST_ASSERT_INT16_WITHIN(1, Q14_FROM_REAL(0.4), c.throttle); /* stick 1400 us */
    in.rc_us[RC_MODE] = 2000u;                                   /* waypoint */
    q14_t prev = c.throttle;
    for (unsigned k = 0; k < prm.blend_ticks + 5u; k++) {
        c = fly(&in, &o);
        TEST_ASSERT_TRUE(abs(c.throttle - prev) <= Q14_ONE / (int)prm.blend_ticks + 2);
        prev = c.throttle;
    }
    /* speed hold at the target, level, no integral yet: the trim 0.5 plus
     * kff * pitch; the airspeed equals the cruise target */
    q14_t sh = ht_speed_hold_step(&m.speed, &st.speed, m.cruise_cm_s, 1500, o.law_in.pitch_ratio);
    TEST_ASSERT_INT16_WITHIN(2, sh, c.throttle);
}

/* --- bumpless transfer --------------------------------------------------- */

/* The largest per-step change of any surface while stepping n times. */
static double max_step_change(ht_modes_input_t *in, int n, os_command_t *last)
{
    double worst = 0.0;
    for (int k = 0; k < n; k++) {
        os_command_t c = fly(in, NULL);
        double d = fmax(fabs((double)(c.aileron - last->aileron)),
                        fmax(fabs((double)(c.elevator - last->elevator)),
                             fabs((double)(c.rudder - last->rudder))));
        worst = fmax(worst, d / 16384.0);
        *last = c;
    }
    return worst;
}

/* The per-step bound for the default parameters and kp = 1, kff = kd = 0:
 * the blend moves the surfaces by at most 2 / blend_ticks (manual and law
 * are both in [-1, 1]); a slew step of the turn rate moves the roll target
 * by at most dw * S / g (S = airspeed), the pitch target by dp; the
 * elevator/rudder projection and the AoA trim add at most the same again. */
static double bound_for(double v)
{
    double dw = 4.5 * PI / 180.0, dp = 1.0 / 40.0;
    return 2.0 / prm.blend_ticks + dw * fmax(v, 5.0) / 9.80665 + 2.0 * dp + 0.01;
}

static void test_bumpless_manual_to_fbw_with_full_stick_in_bank(void)
{
    /* 30 deg right bank, aileron stick full right and elevator full down in
     * manual; switch to FBW: the same sticks now ask for a 60 deg/s right
     * turn and a pitch ratio of -0.5. */
    ht_modes_input_t in = mk_in(30, 5, 15, 1000u, 2000u, 1000u, 1000u);
    os_command_t last = fly(&in, NULL);
    (void)max_step_change(&in, 5, &last);
    TEST_ASSERT_INT16_WITHIN(1, Q14_ONE, last.aileron); /* manual: full right */
    TEST_ASSERT_INT16_WITHIN(1, -Q14_ONE, last.elevator);
    in.rc_us[RC_MODE] = 1500u;
    double worst = max_step_change(&in, 100, &last);
    /* without the blend and the slew: the law's output on the new targets */
    ht_input_t raw = {in.x, in.y, in.z, Q11_FROM_REAL(PI / 3.0), -Q16_ONE / 2, 1500, {0, 0, 0},
                      0u,   0,    0};
    ht_output_t lo;
    ht_step(&ctl, &raw, &lo);
    double jump = fmax(fabs(lo.aileron / 16384.0 - 1.0), fabs(lo.elevator / 16384.0 + 1.0));
    printf("manual->FBW in a 30 deg bank: worst surface step %.4f (bound %.4f); a direct "
           "switch would jump %.3f\n",
           worst, bound_for(15.0), jump);
    TEST_ASSERT_TRUE(worst <= bound_for(15.0));
    TEST_ASSERT_TRUE(jump > 3.0 * worst);
    /* and back to manual */
    in.rc_us[RC_MODE] = 1000u;
    worst = max_step_change(&in, 100, &last);
    printf("FBW->manual: worst surface step %.4f\n", worst);
    TEST_ASSERT_TRUE(worst <= bound_for(15.0));
    TEST_ASSERT_INT16_WITHIN(1, Q14_ONE, last.aileron);
}

static void test_bumpless_state_match_gives_zero_error_at_takeover(void)
{
    /* In manual, the law's input matches the current attitude: its roll and
     * pitch errors are ~0, so the law would hold the attitude. */
    const double banks[] = {-70, -30, 0, 20, 45, 150, 180, -120};
    for (unsigned i = 0; i < 8u; i++) {
        ht_modes_reset(&st, 0, 0);
        ht_modes_input_t in = mk_in(banks[i], 10, 20, 1000u, 1500u, 1500u, 1000u);
        ht_modes_output_t o;
        ht_output_t lo;
        os_command_t c;
        ht_modes_fly(&m, &st, &ctl, &in, &o, &lo, &c);
        TEST_ASSERT_EQUAL_INT(in.z < 0, o.law_in.inverted);
        char msg[80];
        snprintf(msg, sizeof msg, "bank %.0f: roll error %d pitch error %d", banks[i],
                 lo.roll_error, lo.pitch_error);
        TEST_ASSERT_TRUE_MESSAGE(abs(lo.roll_error) <= 40, msg); /* 0.25% */
        TEST_ASSERT_TRUE_MESSAGE(abs(lo.pitch_error) <= 40, msg);
    }
}

static void random_mode_changes(int aoa_on)
{
    if (aoa_on) { /* a model with sizeable coefficients: 2+3w deg, trim 0.05+0.05w */
        prm.aoa.enabled = 1u;
        prm.aoa.aoa_normal_deg = Q16_FROM_REAL(2.0);
        prm.aoa.aoa_normal_slope_deg = Q16_FROM_REAL(3.0);
        prm.aoa.aoa_inverted_deg = Q16_FROM_REAL(-3.0);
        prm.aoa.aoa_inverted_slope_deg = Q16_FROM_REAL(-4.0);
        prm.aoa.trim_normal = Q14_FROM_REAL(0.05);
        prm.aoa.trim_normal_slope = Q14_FROM_REAL(0.05);
        prm.aoa.trim_inverted = Q14_FROM_REAL(-0.2);
        prm.aoa.trim_inverted_slope = Q14_FROM_REAL(-0.05);
        TEST_ASSERT_EQUAL_INT(0, ht_modes_init(&m, &prm, &ctl, square, 4u, NULL));
    }
    uint64_t seed = 0xb0b + (uint64_t)aoa_on;
    double worst = 0.0, worst_ratio = 0.0;
    for (int trial = 0; trial < 2000; trial++) {
        ht_modes_reset(&st, 0, 0);
        double bank = ts_uniform(&seed, -75, 75), pitch = ts_uniform(&seed, -20, 20);
        int inverted = ts_rng_next(&seed) & 1u;
        if (inverted) {
            bank += 180.0;
        }
        double v = ts_uniform(&seed, 0.0, 40.0);
        unsigned from = (unsigned)(ts_rng_next(&seed) % 4u);
        unsigned to = (unsigned)(ts_rng_next(&seed) % 4u);
        uint16_t ail = (uint16_t)ts_uniform(&seed, 1000, 2000);
        uint16_t ele = (uint16_t)ts_uniform(&seed, 1000, 2000);
        ht_modes_input_t in =
            mk_in(bank, pitch, v, mode_us[from], ail, ele, inverted ? 2000u : 1000u);
        in.north_cm = (int32_t)ts_uniform(&seed, -100000, 100000);
        in.east_cm = (int32_t)ts_uniform(&seed, -100000, 100000);
        in.alt_cm = (int32_t)ts_uniform(&seed, 0, 30000);
        os_command_t last = fly(&in, NULL);
        (void)max_step_change(&in, 60, &last); /* settled in the first mode */
        in.rc_us[RC_MODE] = mode_us[to]; /* the sticks stay: in manual they are the surfaces */
        double w = max_step_change(&in, 80, &last);
        worst = fmax(worst, w);
        worst_ratio = fmax(worst_ratio, w / bound_for(v));
        char msg[120];
        snprintf(msg, sizeof msg, "trial %d %u->%u bank %.1f v %.1f: step %.4f bound %.4f", trial,
                 from, to, bank, v, w, bound_for(v));
        TEST_ASSERT_TRUE_MESSAGE(w <= bound_for(v), msg);
    }
    printf("bumpless (AoA model %s): 2000 random mode changes, worst surface step %.4f, "
           "worst step / bound %.3f\n",
           aoa_on ? "on" : "off", worst, worst_ratio);
}

static void test_bumpless_random_mode_changes(void)
{
    random_mode_changes(0);
}

static void test_bumpless_random_mode_changes_with_aoa_model(void)
{
    random_mode_changes(1);
}

static void test_failsafe_entry_is_bumpless(void)
{
    ht_modes_input_t in = mk_in(20, 3, 15, 1500u, 1800u, 1600u, 1000u);
    os_command_t last = fly(&in, NULL);
    (void)max_step_change(&in, 60, &last);
    in.rc_fresh = 0u;
    double w = max_step_change(&in, 200, &last);
    TEST_ASSERT_EQUAL_UINT8(1u, st.rc_lost);
    TEST_ASSERT_TRUE(w <= bound_for(15.0));
}

/* --- closed loop through the whole step ---------------------------------- */

/* A point mass that turns at the commanded (slewed) turn rate and climbs at
 * V sin(atan(pitch ratio)): waypoint mode flies the square, then the RC
 * dies and the failsafe brings it home and circles. */
static void test_closed_loop_circuit_then_rc_loss(void)
{
    for (int law = 0; law < 2; law++) {
        prm.nav.law = (uint8_t)law;
        TEST_ASSERT_EQUAL_INT(0, ht_modes_init(&m, &prm, &ctl, square, 4u, NULL));
        ht_modes_reset(&st, -30000, -30000);
        double n = -300.0, e = -300.0, psi = 0.0, h = 80.0, v = 15.0, dt = 1.0 / 40.0;
        double alt_err2 = 0.0;
        long alt_n = 0;
        uint32_t reached_at_loss = 0u;
        double rmin = 1e9, rmax = 0.0;
        ht_modes_output_t o;
        for (int k = 0; k < 40 * 700; k++) {
            double t = k * dt;
            ht_modes_input_t in = mk_in(0, 0, v, 2000u, 1500u, 1500u, 1000u);
            in.north_cm = (int32_t)lround(n * 100.0);
            in.east_cm = (int32_t)lround(e * 100.0);
            in.alt_cm = (int32_t)lround(h * 100.0);
            in.vel_north_cm_s = (int32_t)lround(v * cos(psi) * 100.0);
            in.vel_east_cm_s = (int32_t)lround(v * sin(psi) * 100.0);
            in.rc_fresh = (uint8_t)(t < 400.0); /* the link dies at 400 s */
            (void)fly(&in, &o);
            if (t >= 400.0 && reached_at_loss == 0u) {
                reached_at_loss = st.nav.reached;
            }
            double w = o.law_in.turn_rate_rad_s / 2048.0;
            double p = o.law_in.pitch_ratio / Q16;
            n += v * cos(psi + 0.5 * w * dt) * dt;
            e += v * sin(psi + 0.5 * w * dt) * dt;
            psi += w * dt;
            h += v * p / sqrt(1.0 + p * p) * dt;
            if (t > 100.0 && t < 400.0) {
                alt_err2 += (h - 100.0) * (h - 100.0);
                alt_n++;
            }
            if (t > 600.0) {
                double r = hypot(n, e);
                rmin = fmin(rmin, r);
                rmax = fmax(rmax, r);
            }
        }
        printf("modes closed loop (%s law): %u waypoints reached in 400 s, altitude RMS %.2f m "
               "(100..400 s); after RC loss: mode %u, loiter radius %.1f..%.1f m, alt %.1f m\n",
               law ? "L1" : "heading", reached_at_loss, sqrt(alt_err2 / (double)alt_n), o.mode,
               rmin, rmax, h);
        TEST_ASSERT_TRUE(reached_at_loss >= 12u); /* 1600 m laps at 15 m/s: > 3 laps */
        TEST_ASSERT_EQUAL_INT(HT_MODE_RTH, o.mode);
        TEST_ASSERT_EQUAL_UINT8(1u, o.failsafe);
        TEST_ASSERT_TRUE(rmin > 55.0 && rmax < 65.0);
        TEST_ASSERT_TRUE(fabs(h - 100.0) < 2.0);
        TEST_ASSERT_TRUE(sqrt(alt_err2 / (double)alt_n) < 2.0);
    }
}

/* --- AoA trim and edges -------------------------------------------------- */

static void test_aoa_trim_reaches_the_elevator_through_the_blend(void)
{
    prm.aoa.enabled = 1u;
    prm.aoa.trim_normal = Q14_FROM_REAL(0.1);
    prm.aoa.aoa_normal_deg = Q16_FROM_REAL(3.0);
    TEST_ASSERT_EQUAL_INT(0, ht_modes_init(&m, &prm, &ctl, square, 4u, NULL));
    ht_modes_input_t in = mk_in(0, 0, 15, 1500u, 1500u, 1500u, 1000u);
    ht_modes_output_t o;
    ht_output_t lo;
    os_command_t c;
    for (unsigned k = 0; k < prm.blend_ticks; k++) {
        ht_modes_fly(&m, &st, &ctl, &in, &o, &lo, &c);
    }
    TEST_ASSERT_EQUAL_INT16(Q14_ONE, o.blend);
    TEST_ASSERT_EQUAL_INT16(Q14_FROM_REAL(0.1), o.elevator_trim);
    TEST_ASSERT_INT16_WITHIN(1, (q14_t)(lo.elevator + Q14_FROM_REAL(0.1)), c.elevator);
    /* the offset: 3 deg * Z = 3 deg added to the stick's pitch ratio (0 here),
     * after the pitch slew has had time */
    for (unsigned k = 0; k < 80u; k++) {
        ht_modes_fly(&m, &st, &ctl, &in, &o, &lo, &c);
    }
    TEST_ASSERT_INT32_WITHIN(2, (int32_t)lround(3.0 * PI / 180.0 * Q16), o.law_in.pitch_ratio);
    /* settled manual: the surfaces are the sticks exactly, trim or not */
    in.rc_us[RC_MODE] = 1000u;
    in.rc_us[RC_ELE] = 1700u;
    for (unsigned k = 0; k <= prm.blend_ticks; k++) {
        ht_modes_fly(&m, &st, &ctl, &in, &o, &lo, &c);
    }
    TEST_ASSERT_EQUAL_INT16(0, o.blend);
    TEST_ASSERT_EQUAL_INT16(o.manual.elevator, c.elevator);
    TEST_ASSERT_INT16_WITHIN(1, Q14_FROM_REAL(0.4), c.elevator);
}

static void test_extreme_inputs_are_defined(void)
{
    const q14_t vals[] = {INT16_MIN, -Q14_ONE, 0, Q14_ONE, INT16_MAX};
    const int16_t speeds[] = {INT16_MIN, -1, 0, 1500, INT16_MAX};
    const int32_t pos[] = {INT32_MIN, 0, INT32_MAX};
    for (unsigned mo = 0; mo < 4u; mo++) {
        for (unsigned i = 0; i < 5u; i++) {
            for (unsigned j = 0; j < 5u; j++) {
                for (unsigned k = 0; k < 5u; k++) {
                    ht_modes_input_t in = mk_in(0, 0, 15, mode_us[mo], 1500u, 1500u, 1000u);
                    in.x = vals[i];
                    in.y = vals[k];
                    in.z = vals[j];
                    in.airspeed_cm_s = speeds[k];
                    in.north_cm = pos[i % 3u];
                    in.east_cm = pos[j % 3u];
                    in.alt_cm = pos[k % 3u];
                    in.climb_cm_s = pos[(i + j) % 3u];
                    in.vel_north_cm_s = pos[(j + k) % 3u];
                    ht_modes_output_t o;
                    os_command_t c = fly(&in, &o);
                    TEST_ASSERT_TRUE(c.aileron >= -Q14_ONE && c.aileron <= Q14_ONE);
                    TEST_ASSERT_TRUE(c.elevator >= -Q14_ONE && c.elevator <= Q14_ONE);
                    TEST_ASSERT_TRUE(c.rudder >= -Q14_ONE && c.rudder <= Q14_ONE);
                    TEST_ASSERT_TRUE(c.throttle >= 0 && c.throttle <= Q14_ONE);
                    TEST_ASSERT_TRUE(o.turn_target_rad_s <= 8 * Q16_ONE &&
                                     o.turn_target_rad_s >= -8 * Q16_ONE);
                }
            }
        }
    }
    ht_modes_output_t o;
    ht_modes_step(NULL, &st, NULL, &o);
    TEST_ASSERT_EQUAL_INT32(0, o.law_in.turn_rate_rad_s);
    ht_modes_step(&m, &st, NULL, NULL); /* no crash */
    os_command_t c;
    ht_modes_surfaces(NULL, NULL, &c);
    TEST_ASSERT_EQUAL_INT16(0, c.throttle);
}

static void test_init_names_each_bad_field(void)
{
    char name[64];
    for (int f = 1; f < (int)HT_MODES_P_COUNT; f++) {
        ht_modes_params_t b;
        ht_modes_params_default(&b);
        const ht_controller_t *cp = &ctl;
        const char *want = NULL;
        switch ((ht_modes_param_id_t)f) {
        case HT_MODES_P_RC_AILERON:
            b.rc.aileron.travel_us = 0u;
            want = "rc.aileron";
            break;
        case HT_MODES_P_RC_ELEVATOR:
            b.rc.elevator.input = 16u;
            want = "rc.elevator";
            break;
        case HT_MODES_P_RC_RUDDER:
            b.rc.rudder.centre_us = 100u;
            want = "rc.rudder";
            break;
        case HT_MODES_P_RC_THROTTLE:
            b.rc.throttle.travel_us = 5000u;
            want = "rc.throttle";
            break;
        case HT_MODES_P_MODE_INPUT:
            b.mode_input = 16u;
            want = "mode_input";
            break;
        case HT_MODES_P_MODE_THRESHOLD:
            b.mode_threshold_us[1] = b.mode_threshold_us[2];
            want = "mode_threshold_us";
            break;
        case HT_MODES_P_RC_LOSS_TICKS:
            b.rc_loss_ticks = 0u;
            want = "rc_loss_ticks";
            break;
        case HT_MODES_P_RC_RECOVER_TICKS:
            b.rc_recover_ticks = 10001u;
            want = "rc_recover_ticks";
            break;
        case HT_MODES_P_BLEND_TICKS:
            b.blend_ticks = 0u;
            want = "blend_ticks";
            break;
        case HT_MODES_P_TURN_SLEW:
            b.turn_slew_deg_s2 = 0;
            want = "turn_slew_deg_s2";
            break;
        case HT_MODES_P_PITCH_SLEW:
            b.pitch_slew_per_s = 0;
            want = "pitch_slew_per_s";
            break;
        case HT_MODES_P_CRUISE:
            b.cruise_cm_s = 99;
            want = "cruise_m_s";
            break;
        case HT_MODES_P_RATE_HZ:
            b.rate_hz = 0u;
            want = "rate_hz";
            break;
        case HT_MODES_P_CONTROLLER:
            cp = NULL;
            want = "controller";
            break;
        case HT_MODES_P_FBW:
            b.fbw.deadband_us = 91u;
            want = "fbw.deadband_us";
            break;
        case HT_MODES_P_NAV:
            b.nav.l1_m = 4u;
            want = "nav.l1_m";
            break;
        case HT_MODES_P_AOA:
            b.aoa.load_max = 0;
            want = "aoa.load_max";
            break;
        case HT_MODES_P_JOINT:
            b.mode_input = 0u; /* a legal row, the aileron stick's input */
            want = "joint.mode_input is a stick channel";
            break;
        case HT_MODES_P_ALT_HOLD:
            b.alt.rate_hz = 50u; /* legal alone, not the modes' rate */
            want = "alt.rate_hz";
            break;
        default:
            b.speed.throttle_max = -1;
            want = "speed.throttle_max";
            break;
        }
        ht_modes_t mm;
        ht_modes_bad_t bad;
        TEST_ASSERT_EQUAL_INT(2, ht_modes_init(&mm, &b, cp, square, 4u, &bad));
        TEST_ASSERT_EQUAL_INT(f, (int)bad.field);
        ht_modes_bad_name(&bad, name, sizeof name);
        TEST_ASSERT_EQUAL_STRING(want, name);
        TEST_ASSERT_EQUAL_UINT8(0u, mm.ready);
    }
    /* a bad waypoint names its index */
    ht_waypoint_t wp[2] = {{0, 0, 0}, {0, 0, HT_NAV_ALT_MAX_M + 1}};
    ht_modes_bad_t bad;
    TEST_ASSERT_EQUAL_INT(2, ht_modes_init(&m, &prm, &ctl, wp, 2u, &bad));
    ht_modes_bad_name(&bad, name, sizeof name);
    TEST_ASSERT_EQUAL_STRING("nav.waypoints", name);
    TEST_ASSERT_EQUAL_UINT16(1u, bad.waypoint);
    /* a short buffer is truncated and terminated */
    char tiny[4];
    ht_modes_bad_name(&bad, tiny, sizeof tiny);
    TEST_ASSERT_EQUAL_STRING("nav", tiny);
    TEST_ASSERT_EQUAL_INT(1, ht_modes_init(NULL, &prm, &ctl, square, 4u, &bad));
    /* an empty waypoint list is accepted (waypoint mode then circles home) */
    TEST_ASSERT_EQUAL_INT(0, ht_modes_init(&m, &prm, &ctl, NULL, 0u, &bad));
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_mode_from_every_pulse);
    RUN_TEST(test_no_rc_ever_is_manual_neutral_throttle_zero);
    RUN_TEST(test_loss_after_n_stale_ticks_then_rth_and_recovery);
    RUN_TEST(test_pulses_outside_window_count_as_loss);
    RUN_TEST(test_fbw_and_waypoint_sources);
    RUN_TEST(test_throttle_sources_and_blend);
    RUN_TEST(test_bumpless_manual_to_fbw_with_full_stick_in_bank);
    RUN_TEST(test_bumpless_state_match_gives_zero_error_at_takeover);
    RUN_TEST(test_bumpless_random_mode_changes);
    RUN_TEST(test_bumpless_random_mode_changes_with_aoa_model);
    RUN_TEST(test_failsafe_entry_is_bumpless);
    RUN_TEST(test_aoa_trim_reaches_the_elevator_through_the_blend);
    RUN_TEST(test_extreme_inputs_are_defined);
    RUN_TEST(test_init_names_each_bad_field);
    RUN_TEST(test_closed_loop_circuit_then_rc_loss);
    return UNITY_END();
}
