/* Unit tests of waypoint navigation and the two guidance laws
 * (include/helical/guidance/nav.h): the sin-of-error primitive, the heading-error and
 * L1 laws against double-precision references on seeded random geometry,
 * arrival and the list edges, far-away positions, zero speed, parameter
 * checks, and closed-loop kinematic runs (a point mass that turns at the
 * commanded rate, integrated in double) on a straight track, a square
 * circuit and the home loiter. */
#include "unity.h"

#include "helical/guidance/nav.h"
#include "ht_test_support.h"

#include <math.h>
#include <stddef.h>
#include <stdio.h>

#define PI   3.14159265358979323846
#define Q28  268435456.0
#define Q16  65536.0
#define WMAX (60.0 * PI / 180.0)

static ht_nav_params_t prm;

void setUp(void)
{
    const ht_nav_params_t d = HT_NAV_PARAMS_DEFAULT;
    prm = d;
}

void tearDown(void) {}

static ht_nav_input_t mk_in(double n_m, double e_m, double vn, double ve)
{
    ht_nav_input_t in = {(int32_t)lround(n_m * 100.0),
                         (int32_t)lround(e_m * 100.0),
                         (int32_t)lround(vn * 100.0),
                         (int32_t)lround(ve * 100.0),
                         0,
                         0};
    return in;
}

/* --- the primitive ------------------------------------------------------- */

static void test_sin_error_sweep_and_edges(void)
{
    uint64_t seed = 42u;
    double worst = 0.0;
    for (int i = 0; i < 100000; i++) {
        double a = ts_uniform(&seed, -PI, PI), d = ts_uniform(&seed, -PI, PI);
        double la = ts_uniform(&seed, 1.0, 1e9), ld = ts_uniform(&seed, 1.0, 1e9);
        int32_t an = (int32_t)lround(la * cos(a)), ae = (int32_t)lround(la * sin(a));
        int32_t dn = (int32_t)lround(ld * cos(d)), de = (int32_t)lround(ld * sin(d));
        double ea = atan2(ae, an), ed = atan2(de, dn);
        double err = remainder(ed - ea, 2.0 * PI);
        uint8_t b;
        int32_t s = ht_nav_sin_error_q28(an, ae, dn, de, &b);
        if (fabs(fabs(err) - PI / 2.0) < 1e-6 || fabs(fabs(err) - PI) < 1e-6) {
            continue; /* on a boundary: either side is right */
        }
        double want = (cos(err) <= 0.0) ? ((sin(err) >= 0.0) ? 1.0 : -1.0) : sin(err);
        double e = fabs(s / Q28 - want);
        worst = fmax(worst, e);
        TEST_ASSERT_TRUE(e < 2e-7); /* ~50 LSB of Q28 from the two unit vectors */
        TEST_ASSERT_EQUAL_UINT8(cos(err) <= 0.0, b);
    }
    printf("sin(error): worst %.2e over 1e5 random pairs\n", worst);
    uint8_t b;
    /* exactly 180 deg: +1 (a right turn), flagged */
    TEST_ASSERT_EQUAL_INT32((int32_t)HT_Q28_ONE, ht_nav_sin_error_q28(100, 0, -100, 0, &b));
    TEST_ASSERT_EQUAL_UINT8(1u, b);
    TEST_ASSERT_EQUAL_INT32((int32_t)HT_Q28_ONE, ht_nav_sin_error_q28(0, 7, 0, -7, &b));
    /* exactly 90 deg right and left */
    TEST_ASSERT_EQUAL_INT32((int32_t)HT_Q28_ONE, ht_nav_sin_error_q28(1, 0, 0, 1, &b));
    TEST_ASSERT_EQUAL_INT32(-(int32_t)HT_Q28_ONE, ht_nav_sin_error_q28(1, 0, 0, -1, &b));
    /* same direction: 0, not flagged */
    TEST_ASSERT_EQUAL_INT32(0, ht_nav_sin_error_q28(5, 5, 1000, 1000, &b));
    TEST_ASSERT_EQUAL_UINT8(0u, b);
    /* zero vectors: 0 */
    TEST_ASSERT_EQUAL_INT32(0, ht_nav_sin_error_q28(0, 0, 1, 0, &b));
    TEST_ASSERT_EQUAL_INT32(0, ht_nav_sin_error_q28(1, 0, 0, 0, NULL));
    /* int32 extremes */
    TEST_ASSERT_EQUAL_INT32((int32_t)HT_Q28_ONE,
                            ht_nav_sin_error_q28(INT32_MAX, 0, INT32_MIN, 0, &b));
    /* facing south, south-east is to the left (counter-clockwise) */
    TEST_ASSERT_INT32_WITHIN(64, (int32_t)lround(-Q28 * sqrt(0.5)),
                             ht_nav_sin_error_q28(INT32_MIN, 0, INT32_MIN, INT32_MAX, &b));
}

/* --- references ---------------------------------------------------------- */

static double clampd(double v, double lim)
{
    return fmax(-lim, fmin(lim, v));
}

/* sin of the angle from u to v with the beyond-90 rule, and its cosine. */
static double ref_sin(double un, double ue, double vn, double ve, double *cosv)
{
    double lu = hypot(un, ue), lv = hypot(vn, ve);
    double s = (un * ve - ue * vn) / (lu * lv), c = (un * vn + ue * ve) / (lu * lv);
    *cosv = c;
    return (c <= 0.0) ? ((s >= 0.0) ? 1.0 : -1.0) : s;
}

static void test_heading_law_against_reference(void)
{
    ht_nav_t nav;
    uint64_t seed = 7u;
    double worst = 0.0;
    for (int i = 0; i < 20000; i++) {
        ht_waypoint_t wp = {(int32_t)ts_uniform(&seed, -5000, 5000),
                            (int32_t)ts_uniform(&seed, -5000, 5000), 100};
        TEST_ASSERT_EQUAL_INT(0, ht_nav_init(&nav, &prm, &wp, 1u, NULL, NULL));
        ht_nav_state_t s;
        ht_nav_reset(&s, 0, 0);
        double pn = ts_uniform(&seed, -5000, 5000), pe = ts_uniform(&seed, -5000, 5000);
        double psi = ts_uniform(&seed, -PI, PI), v = ts_uniform(&seed, 3, 60);
        ht_nav_input_t in = mk_in(pn, pe, v * cos(psi), v * sin(psi));
        ht_nav_output_t o;
        ht_nav_waypoint_step(&nav, &s, &in, &o);
        if (o.arrived) {
            continue;
        }
        double c;
        double sn = ref_sin(in.vel_north_cm_s, in.vel_east_cm_s, wp.north_m * 100.0 - in.north_cm,
                            wp.east_m * 100.0 - in.east_cm, &c);
        if (fabs(c) < 1e-6) {
            continue;
        }
        double want = nav.turn_rate_max_rad_s / Q16 * sn;
        double e = fabs(o.turn_rate_rad_s / Q16 - want) * Q16;
        worst = fmax(worst, e);
        TEST_ASSERT_TRUE(e <= 1.0);
        TEST_ASSERT_INT32_WITHIN(2,
                                 (int32_t)lround(hypot(wp.north_m * 100.0 - in.north_cm,
                                                       wp.east_m * 100.0 - in.east_cm)),
                                 o.distance_cm);
    }
    /* turn_rate_max itself: 60 deg/s to 1 LSB */
    TEST_ASSERT_INT32_WITHIN(1, (int32_t)lround(WMAX * Q16), nav.turn_rate_max_rad_s);
    printf("heading law: worst %.3f LSB of Q16 rad/s over 2e4 random cases\n", worst);
}

typedef struct {
    double turn, xt, cos_eta;
} ref_l1_t;

/* dn, de: the direction of motion; speed: the ground speed. */
static ref_l1_t ref_l1(double an, double ae, double bn, double be, double pn, double pe, double dn,
                       double de, double speed, double l1, double vfloor, double wmax)
{
    ref_l1_t r;
    double len = hypot(bn - an, be - ae);
    double tn = (bn - an) / len, te = (be - ae) / len;
    double rn = pn - an, re = pe - ae;
    r.xt = tn * re - te * rn;
    double h = (fabs(r.xt) < l1) ? sqrt(l1 * l1 - r.xt * r.xt) : 0.0;
    double qn = h * tn + r.xt * te, qe = h * te - r.xt * tn;
    double s = ref_sin(dn, de, qn, qe, &r.cos_eta);
    double v = fmax(speed, vfloor);
    r.turn = clampd(2.0 * v * s / l1, wmax);
    return r;
}

static void test_l1_law_against_reference(void)
{
    prm.law = (uint8_t)HT_GUIDE_L1;
    prm.arrival_radius_m = 1u;
    ht_nav_t nav;
    uint64_t seed = 11u;
    double worst = 0.0, worst_rel = 0.0;
    int n = 0;
    for (int i = 0; i < 20000; i++) {
        prm.l1_m = (uint16_t)ts_uniform(&seed, 5, 600);
        ht_waypoint_t wp = {(int32_t)ts_uniform(&seed, -5000, 5000),
                            (int32_t)ts_uniform(&seed, -5000, 5000), 100};
        TEST_ASSERT_EQUAL_INT(0, ht_nav_init(&nav, &prm, &wp, 1u, NULL, NULL));
        double an = ts_uniform(&seed, -5000, 5000), ae = ts_uniform(&seed, -5000, 5000);
        /* a point near the track: a fraction along, up to 3 L1 aside */
        double f = ts_uniform(&seed, -0.2, 0.9);
        double len = hypot(wp.north_m - an, wp.east_m - ae);
        double tn = (wp.north_m - an) / len, te = (wp.east_m - ae) / len;
        double off = ts_uniform(&seed, -3.0, 3.0) * prm.l1_m;
        double pn = an + f * len * tn - off * te, pe = ae + f * len * te + off * tn;
        double psi = ts_uniform(&seed, -PI, PI), v = ts_uniform(&seed, 0.5, 60);
        ht_nav_state_t s;
        ht_nav_reset(&s, (int32_t)lround(an * 100), (int32_t)lround(ae * 100));
        ht_nav_input_t in = mk_in(pn, pe, v * cos(psi), v * sin(psi));
        /* below course_min the nose direction is used: the same direction here */
        in.heading_north = ts_fix16(cos(psi), 14);
        in.heading_east = ts_fix16(sin(psi), 14);

        ht_nav_output_t o;
        ht_nav_waypoint_step(&nav, &s, &in, &o);
        if (o.arrived) {
            continue;
        }
        int slow = hypot(in.vel_north_cm_s, in.vel_east_cm_s) < prm.course_min_cm_s;
        ref_l1_t r = ref_l1(s.from_north_cm, s.from_east_cm, wp.north_m * 100.0, wp.east_m * 100.0,
                            in.north_cm, in.east_cm, slow ? in.heading_north : in.vel_north_cm_s,
                            slow ? in.heading_east : in.vel_east_cm_s,
                            hypot(in.vel_north_cm_s, in.vel_east_cm_s), prm.l1_m * 100.0,
                            prm.v_floor_cm_s, nav.turn_rate_max_rad_s / Q16);
        if (fabs(r.cos_eta) < 1e-4 || fabs(fabs(r.xt) - prm.l1_m * 100.0) < 5.0) {
            continue; /* a tie of the beyond-90 rule or the L1 circle */
        }
        n++;
        double vv = fmax(hypot(in.vel_north_cm_s, in.vel_east_cm_s), prm.v_floor_cm_s);
        double scale = 2.0 * vv / (prm.l1_m * 100.0);
        double e = fabs(o.turn_rate_rad_s / Q16 - r.turn);
        worst = fmax(worst, e * Q16);
        char msg[200];
        worst_rel = fmax(worst_rel, e / scale);
        snprintf(msg, sizeof msg, "case %d: turn %.6f want %.6f xt %.1f/%.1f l1 %u v %.1f cos %.5f",
                 i, o.turn_rate_rad_s / Q16, r.turn, o.cross_track_cm / 1.0, r.xt, prm.l1_m, vv,
                 r.cos_eta);
        /* near the L1 circle h = sqrt(L1^2 - xt^2) amplifies the 1/2 cm
         * rounding of xt and h by |xt| / h */
        double hh = sqrt(fmax(0.0, pow(prm.l1_m * 100.0, 2) - r.xt * r.xt));
        double cond = (fabs(r.xt) < prm.l1_m * 100.0) ? 1.0 + fabs(r.xt) / fmax(hh, 1.0) : 1.0;
        /* and V is used to 1 cm/s */
        TEST_ASSERT_TRUE_MESSAGE(
            e <= scale * (2e-4 + cond / (prm.l1_m * 100.0) + 1.0 / vv) + 3.0 / Q16, msg);
        TEST_ASSERT_TRUE_MESSAGE(fabs(o.cross_track_cm - r.xt) <= 2.0, msg);
    }
    printf("L1 law: %d cases, worst %.2f LSB of Q16 rad/s, worst relative to 2V/L1 %.2e\n", n,
           worst, worst_rel);
    TEST_ASSERT_TRUE(n > 15000);
}

static void test_l1_worked_case(void)
{
    /* Track north along east = 0, aircraft 30 m east of it flying north at
     * 15 m/s, L1 = 60 m: eta = -30 deg (the L1 point is 30 deg left),
     * turn = 2 * 15 * sin(-30) / 60 = -0.25 rad/s. */
    prm.law = (uint8_t)HT_GUIDE_L1;
    ht_waypoint_t wp = {1000, 0, 100};
    ht_nav_t nav;
    TEST_ASSERT_EQUAL_INT(0, ht_nav_init(&nav, &prm, &wp, 1u, NULL, NULL));
    ht_nav_state_t s;
    ht_nav_reset(&s, 0, 0);
    ht_nav_input_t in = mk_in(100, 30, 15, 0);
    ht_nav_output_t o;
    ht_nav_waypoint_step(&nav, &s, &in, &o);
    TEST_ASSERT_INT32_WITHIN(2, (int32_t)lround(-0.25 * Q16), o.turn_rate_rad_s);
    TEST_ASSERT_EQUAL_INT32(3000, o.cross_track_cm);
    TEST_ASSERT_EQUAL_INT32(10000, o.target_alt_cm);
    /* 100 m east (beyond L1): the L1 point is the foot: eta = -90 deg -> -1,
     * turn = 2 * 15 / 60 = 0.5 rad/s left */
    in = mk_in(100, 100, 15, 0);
    ht_nav_waypoint_step(&nav, &s, &in, &o);
    TEST_ASSERT_INT32_WITHIN(2, (int32_t)lround(-0.5 * Q16), o.turn_rate_rad_s);
    TEST_ASSERT_TRUE(o.flags & HT_NAV_F_BEYOND_90);
    /* the limit: 60 m/s gives 2 rad/s, limited to 60 deg/s */
    in = mk_in(100, 100, 60, 0);
    ht_nav_waypoint_step(&nav, &s, &in, &o);
    TEST_ASSERT_INT32_WITHIN(1, -nav.turn_rate_max_rad_s, o.turn_rate_rad_s);
    TEST_ASSERT_TRUE(o.flags & HT_NAV_F_LIMITED);
    /* zero speed: the floor (5 m/s) with the heading vector's direction */
    in = mk_in(100, 30, 0, 0);
    in.heading_north = Q14_ONE;
    ht_nav_waypoint_step(&nav, &s, &in, &o);
    TEST_ASSERT_INT32_WITHIN(2, (int32_t)lround(2.0 * 5.0 * -0.5 / 60.0 * Q16), o.turn_rate_rad_s);
}

static void test_heading_law_180_and_beyond_90(void)
{
    ht_waypoint_t wp = {-1000, 0, 50};
    ht_nav_t nav;
    TEST_ASSERT_EQUAL_INT(0, ht_nav_init(&nav, &prm, &wp, 1u, NULL, NULL));
    ht_nav_state_t s;
    ht_nav_reset(&s, 0, 0);
    ht_nav_input_t in = mk_in(0, 0, 15, 0); /* flying north, target due south */
    ht_nav_output_t o;
    ht_nav_waypoint_step(&nav, &s, &in, &o);
    TEST_ASSERT_EQUAL_INT32(nav.turn_rate_max_rad_s, o.turn_rate_rad_s); /* right, full */
    TEST_ASSERT_TRUE(o.flags & HT_NAV_F_BEYOND_90);
    in = mk_in(0, 0, 15, -0.01); /* a hair left of north: the target is clockwise-left */
    ht_nav_waypoint_step(&nav, &s, &in, &o);
    TEST_ASSERT_EQUAL_INT32(-nav.turn_rate_max_rad_s, o.turn_rate_rad_s);
    in = mk_in(0, 0, 0, 15); /* flying east, target south: 90 deg right: full right */
    ht_nav_waypoint_step(&nav, &s, &in, &o);
    TEST_ASSERT_EQUAL_INT32(nav.turn_rate_max_rad_s, o.turn_rate_rad_s);
    in = mk_in(0, 0, -15, 15); /* 45 deg right: sin 45 */
    ht_nav_waypoint_step(&nav, &s, &in, &o);
    TEST_ASSERT_INT32_WITHIN(1, (int32_t)lround(WMAX * sqrt(0.5) * Q16), o.turn_rate_rad_s);
}

static void test_no_direction_and_low_speed_heading(void)
{
    ht_waypoint_t wp = {0, 1000, 50};
    ht_nav_t nav;
    TEST_ASSERT_EQUAL_INT(0, ht_nav_init(&nav, &prm, &wp, 1u, NULL, NULL));
    ht_nav_state_t s;
    ht_nav_reset(&s, 0, 0);
    ht_nav_output_t o;
    ht_nav_input_t in = mk_in(0, 0, 0, 0); /* V = 0, no heading */
    ht_nav_waypoint_step(&nav, &s, &in, &o);
    TEST_ASSERT_EQUAL_INT32(0, o.turn_rate_rad_s);
    TEST_ASSERT_TRUE(o.flags & HT_NAV_F_NO_DIRECTION);
    in = mk_in(0, 0, 1.0, 0); /* 1 m/s (below course_min 2 m/s), nose east: on course */
    in.heading_east = 100;
    ht_nav_waypoint_step(&nav, &s, &in, &o);
    TEST_ASSERT_EQUAL_INT32(0, o.turn_rate_rad_s);
    TEST_ASSERT_FALSE(o.flags & HT_NAV_F_NO_DIRECTION);
    in = mk_in(0, 0, 1.0, 0); /* 1 m/s north, no heading: the slow velocity, 90 deg right */
    ht_nav_waypoint_step(&nav, &s, &in, &o);
    TEST_ASSERT_EQUAL_INT32(nav.turn_rate_max_rad_s, o.turn_rate_rad_s);
    in = mk_in(0, 0, 3.0, 0); /* 3 m/s north: the velocity rules, 90 deg right */
    in.heading_east = 100;
    ht_nav_waypoint_step(&nav, &s, &in, &o);
    TEST_ASSERT_EQUAL_INT32(nav.turn_rate_max_rad_s, o.turn_rate_rad_s);
}

static void test_far_positions_saturate_without_wrapping(void)
{
    const int32_t far[] = {INT32_MIN, -2000000000, 2000000000, INT32_MAX};
    for (int law = 0; law < 2; law++) {
        prm.law = (uint8_t)law;
        ht_waypoint_t wp[2] = {{HT_NAV_COORD_MAX_M, -HT_NAV_COORD_MAX_M, 100}, {0, 0, 100}};
        ht_nav_t nav;
        TEST_ASSERT_EQUAL_INT(0, ht_nav_init(&nav, &prm, wp, 2u, NULL, NULL));
        for (unsigned i = 0; i < 4u; i++) {
            for (unsigned j = 0; j < 4u; j++) {
                ht_nav_state_t s;
                ht_nav_reset(&s, far[i], far[j]); /* the leg starts here */
                s.index = 1u;                     /* target: the origin */
                ht_nav_input_t in = {far[i], far[j], 1500, 0, 0, 0};
                ht_nav_output_t o;
                ht_nav_waypoint_step(&nav, &s, &in, &o);
                TEST_ASSERT_TRUE(o.distance_cm > 2000000000); /* saturated, not wrapped */
                TEST_ASSERT_FALSE(o.arrived);
                /* the direction is right: the target is south when far north */
                double want_dir = atan2(-(double)far[j], -(double)far[i]);
                double sn = sin(want_dir); /* error from north = bearing */
                double expect = (cos(want_dir) <= 0.0) ? ((sn >= 0) ? 1.0 : -1.0) : sn;
                if (law == 0) {
                    TEST_ASSERT_INT32_WITHIN(2, (int32_t)lround(expect * nav.turn_rate_max_rad_s),
                                             o.turn_rate_rad_s);
                }
                TEST_ASSERT_TRUE(o.turn_rate_rad_s <= nav.turn_rate_max_rad_s &&
                                 o.turn_rate_rad_s >= -nav.turn_rate_max_rad_s);
            }
        }
        /* the waypoint at +-10,000 km is accepted and its cm value exact */
        ht_nav_state_t s;
        ht_nav_reset(&s, 0, 0);
        ht_nav_input_t in = {HT_NAV_COORD_MAX_M * 100, -HT_NAV_COORD_MAX_M * 100, 0, 100, 0, 0};
        ht_nav_output_t o;
        ht_nav_waypoint_step(&nav, &s, &in, &o);
        TEST_ASSERT_EQUAL_UINT8(1u, o.arrived);
        TEST_ASSERT_EQUAL_UINT16(1u, o.index);
    }
}

/* --- arrival and the list ------------------------------------------------ */

static void test_arrival_radius_passing_and_wrap(void)
{
    ht_waypoint_t wp[3] = {{100, 0, 50}, {100, 100, 60}, {0, 100, 70}};
    ht_nav_t nav;
    TEST_ASSERT_EQUAL_INT(0, ht_nav_init(&nav, &prm, wp, 3u, NULL, NULL));
    ht_nav_state_t s;
    ht_nav_reset(&s, 0, 0);
    ht_nav_output_t o;
    ht_nav_input_t in = mk_in(79.9, 0, 15, 0); /* 20.1 m short */
    ht_nav_waypoint_step(&nav, &s, &in, &o);
    TEST_ASSERT_EQUAL_UINT8(0u, o.arrived);
    TEST_ASSERT_EQUAL_INT32(5000, o.target_alt_cm);
    in = mk_in(80.0, 0, 15, 0); /* exactly 20 m: reached */
    ht_nav_waypoint_step(&nav, &s, &in, &o);
    TEST_ASSERT_EQUAL_UINT8(1u, o.arrived);
    TEST_ASSERT_EQUAL_UINT16(1u, o.index);
    TEST_ASSERT_EQUAL_INT32(6000, o.target_alt_cm);  /* the next one's */
    TEST_ASSERT_EQUAL_INT32(10000, s.from_north_cm); /* the leg starts at the reached one */
    /* passing the perpendicular 50 m aside of waypoint 1 counts */
    in = mk_in(150, 100.01, 0, 15);
    ht_nav_waypoint_step(&nav, &s, &in, &o);
    TEST_ASSERT_EQUAL_UINT8(1u, o.arrived);
    TEST_ASSERT_TRUE(o.flags & HT_NAV_F_PASSED);
    TEST_ASSERT_EQUAL_UINT16(2u, o.index);
    in = mk_in(10, 100, -15, 0);
    ht_nav_waypoint_step(&nav, &s, &in, &o);
    TEST_ASSERT_EQUAL_UINT16(0u, o.index); /* looped */
    TEST_ASSERT_EQUAL_UINT32(3u, s.reached);
}

static void test_coincident_waypoints_and_no_loop(void)
{
    ht_waypoint_t wp[3] = {{100, 0, 50}, {100, 0, 50}, {100, 0, 80}};
    prm.loop = 0u;
    ht_nav_t nav;
    TEST_ASSERT_EQUAL_INT(0, ht_nav_init(&nav, &prm, wp, 3u, NULL, NULL));
    ht_nav_state_t s;
    ht_nav_reset(&s, 0, 0);
    ht_nav_output_t o;
    ht_nav_input_t in = mk_in(99, 0, 15, 0);
    for (int k = 1; k <= 3; k++) { /* one waypoint per step */
        ht_nav_waypoint_step(&nav, &s, &in, &o);
        TEST_ASSERT_EQUAL_UINT8(1u, o.arrived);
        TEST_ASSERT_EQUAL_UINT32((uint32_t)k, s.reached);
    }
    TEST_ASSERT_EQUAL_UINT8(1u, s.done);
    ht_nav_waypoint_step(&nav, &s, &in, &o); /* finished: loiter about the last one */
    TEST_ASSERT_TRUE(o.flags & HT_NAV_F_LOITER);
    TEST_ASSERT_EQUAL_INT32(8000, o.target_alt_cm);
    /* the leg of length 0 from a coincident start: go-to-point */
    ht_nav_reset(&s, 10000, 0);
    in = mk_in(0, 50, 15, 0);
    ht_nav_waypoint_step(&nav, &s, &in, &o);
    TEST_ASSERT_TRUE(o.flags & HT_NAV_F_ZERO_LEG);
    TEST_ASSERT_TRUE(o.turn_rate_rad_s < 0); /* target north-west of a north-flyer */
}

static void test_empty_list_loiters_home(void)
{
    ht_nav_t nav;
    TEST_ASSERT_EQUAL_INT(0, ht_nav_init(&nav, &prm, NULL, 0u, NULL, NULL));
    ht_nav_state_t s;
    ht_nav_reset(&s, 0, 0);
    ht_nav_input_t in = mk_in(60, 0, 0, 15); /* on the circle, flying clockwise */
    ht_nav_output_t o;
    ht_nav_waypoint_step(&nav, &s, &in, &o);
    TEST_ASSERT_TRUE(o.flags & HT_NAV_F_NO_WAYPOINTS);
    TEST_ASSERT_TRUE(o.flags & HT_NAV_F_LOITER);
    TEST_ASSERT_EQUAL_INT32(10000, o.target_alt_cm);
    TEST_ASSERT_INT32_WITHIN(2, (int32_t)lround(15.0 / 60.0 * Q16), o.turn_rate_rad_s); /* V/R */
    /* null arguments: zero output */
    ht_nav_waypoint_step(NULL, &s, &in, &o);
    TEST_ASSERT_EQUAL_INT32(0, o.turn_rate_rad_s);
    ht_nav_home_step(&nav, NULL, &in, &o);
    TEST_ASSERT_EQUAL_INT32(0, o.target_alt_cm);
}

static void test_init_names_each_bad_field(void)
{
    ht_waypoint_t wp[2] = {{0, 0, 0}, {0, 0, 0}};
    for (int f = 1; f < (int)HT_NAV_P_COUNT; f++) {
        ht_nav_params_t b = prm;
        uint16_t count = 2u;
        const ht_waypoint_t *list = wp;
        wp[1].north_m = 0;
        switch ((ht_nav_param_id_t)f) {
        case HT_NAV_P_LAW:
            b.law = 2u;
            break;
        case HT_NAV_P_TURN_RATE_MAX:
            b.turn_rate_max_deg_s = 361;
            break;
        case HT_NAV_P_L1:
            b.l1_m = 601u;
            break;
        case HT_NAV_P_ARRIVAL_RADIUS:
            b.arrival_radius_m = 0u;
            break;
        case HT_NAV_P_LOITER_RADIUS:
            b.loiter_radius_m = 4u;
            break;
        case HT_NAV_P_HOME_ALT:
            b.home_alt_m = HT_NAV_ALT_MAX_M + 1;
            break;
        case HT_NAV_P_V_FLOOR:
            b.v_floor_cm_s = 99;
            break;
        case HT_NAV_P_COURSE_MIN:
            b.course_min_cm_s = -1;
            break;
        case HT_NAV_P_LOOP:
            b.loop = 2u;
            break;
        case HT_NAV_P_WAYPOINT_COUNT:
            list = NULL;
            break;
        default:
            wp[1].north_m = HT_NAV_COORD_MAX_M + 1;
            break;
        }
        ht_nav_t nav;
        ht_nav_param_id_t bad = HT_NAV_P_NONE;
        uint16_t bw = 99u;
        TEST_ASSERT_EQUAL_INT(2, ht_nav_init(&nav, &b, list, count, &bad, &bw));
        TEST_ASSERT_EQUAL_INT(f, (int)bad);
        TEST_ASSERT_TRUE(ht_nav_param_name(bad)[0] != 0);
        TEST_ASSERT_EQUAL_UINT8(0u, nav.ready);
        if (f == (int)HT_NAV_P_WAYPOINT) {
            TEST_ASSERT_EQUAL_UINT16(1u, bw);
        }
    }
    ht_nav_t nav;
    ht_nav_param_id_t bad;
    TEST_ASSERT_EQUAL_INT(2, ht_nav_init(&nav, &prm, wp, HT_NAV_MAX_WAYPOINTS + 1u, &bad, NULL));
    TEST_ASSERT_EQUAL_STRING("count", ht_nav_param_name(bad));
    TEST_ASSERT_EQUAL_INT(1, ht_nav_init(NULL, &prm, wp, 1u, &bad, NULL));
    TEST_ASSERT_EQUAL_STRING("", ht_nav_param_name(HT_NAV_P_COUNT));
}

/* --- closed loop: a point mass that turns at the commanded rate ---------- */

typedef struct {
    double n, e, psi, v; /* m, rad (0 = north, + = clockwise), m/s */
} plane_t;

static ht_nav_output_t fly_step(const ht_nav_t *nav, ht_nav_state_t *s, plane_t *p, int home)
{
    const double dt = 1.0 / 40.0;
    ht_nav_input_t in = mk_in(p->n, p->e, p->v * cos(p->psi), p->v * sin(p->psi));
    ht_nav_output_t o;
    if (home) {
        ht_nav_home_step(nav, s, &in, &o);
    } else {
        ht_nav_waypoint_step(nav, s, &in, &o);
    }
    double w = o.turn_rate_rad_s / Q16;
    /* exact circular arc over dt at rate w */
    p->n += p->v * cos(p->psi + 0.5 * w * dt) * dt;
    p->e += p->v * sin(p->psi + 0.5 * w * dt) * dt;
    p->psi += w * dt;
    return o;
}

static void test_closed_loop_straight_track_converges(void)
{
    for (int law = 0; law < 2; law++) {
        prm.law = (uint8_t)law;
        ht_waypoint_t wp = {3000, 0, 100};
        ht_nav_t nav;
        TEST_ASSERT_EQUAL_INT(0, ht_nav_init(&nav, &prm, &wp, 1u, NULL, NULL));
        ht_nav_state_t s;
        ht_nav_reset(&s, 0, 0);
        /* 100 m east of the track 0 -> 3 km north, flying east (away) at 15 m/s */
        plane_t p = {0.0, 100.0, PI / 2.0, 15.0};
        double xt_last_km = 0.0, prev_xt = 1e9, xt_at_arrival = 0.0, max_sin_late = 0.0;
        double overshoot = 0.0; /* the largest excursion to the west (the far side) */
        int monotone = 1, arrived = 0;
        for (int k = 0; k < 40 * 400 && !arrived; k++) {
            double xt = p.e; /* the track is the north axis */
            ht_nav_output_t o = fly_step(&nav, &s, &p, 0);
            arrived = o.arrived;
            overshoot = fmax(overshoot, -xt);
            if (k > 40 * 30 && law == 0) {
                monotone &= fabs(xt) <= prev_xt + 1e-6;
                prev_xt = fabs(xt);
                max_sin_late = fmax(max_sin_late, fabs(o.sin_error_q28 / Q28));
            }
            if (p.n > 2000.0) {
                xt_last_km = fmax(xt_last_km, fabs(xt));
            }
            xt_at_arrival = fabs(xt);
        }
        printf("straight track (3 km, start 100 m off, flying away), %s law: |xt| max over the "
               "last km %.3f m, at arrival %.3f m, late |sin error| max %.4f, overshoot %.2f m\n",
               law ? "L1" : "heading", xt_last_km, xt_at_arrival, max_sin_late, overshoot);
        TEST_ASSERT_TRUE(arrived);
        TEST_ASSERT_TRUE(monotone); /* heading law: no oscillation after the turn */
        if (law) {
            TEST_ASSERT_TRUE(xt_last_km < 0.05); /* on the track */
            TEST_ASSERT_TRUE(overshoot < 10.0);  /* L1 is second order: a small overshoot */
        } else {
            /* the heading law flies the line to the point: the cross-track
             * shrinks with the range, and the heading error goes to zero */
            TEST_ASSERT_TRUE(xt_at_arrival < 1.0);
            TEST_ASSERT_TRUE(max_sin_late < 0.1);
        }
    }
}

typedef struct {
    double rms_straight, max_straight, end_of_leg_max;
    int reached_all;
    double worst_min_dist;
} circuit_t;

static circuit_t fly_square(uint8_t law, double v, uint16_t l1_m)
{
    prm.law = law;
    prm.l1_m = l1_m;
    const double side = 400.0;
    ht_waypoint_t wp[4] = {{200, -200, 100}, {200, 200, 100}, {-200, 200, 100}, {-200, -200, 100}};
    ht_nav_t nav;
    TEST_ASSERT_EQUAL_INT(0, ht_nav_init(&nav, &prm, wp, 4u, NULL, NULL));
    ht_nav_state_t s;
    ht_nav_reset(&s, -25000, -30000);
    plane_t p = {-250.0, -300.0, 0.0, v};
    double min_dist[4] = {1e9, 1e9, 1e9, 1e9};
    double sum2 = 0.0, mx = 0.0, end_mx = 0.0;
    long n = 0;
    int laps_done = 0;
    int prev_index = 0;
    for (int k = 0; k < 40 * 1000 && laps_done < 4; k++) {
        uint16_t target = s.index;
        double before_n = p.n, before_e = p.e;
        ht_nav_output_t o = fly_step(&nav, &s, &p, 0);
        double dn = before_n - wp[target].north_m, de = before_e - wp[target].east_m;
        min_dist[target] = fmin(min_dist[target], hypot(dn, de));
        if (o.arrived && target == 3u) {
            laps_done++;
        }
        /* straight-leg cross-track, from lap 2: the second half of each leg
         * up to the arrival circle */
        if (laps_done >= 1 && !o.arrived && o.index == prev_index) {
            const ht_waypoint_t *b = &wp[o.index];
            const ht_waypoint_t *a = &wp[(o.index + 3u) % 4u];
            double tn = (b->north_m - a->north_m) / side, te = (b->east_m - a->east_m) / side;
            double rn = before_n - a->north_m, re = before_e - a->east_m;
            double along = rn * tn + re * te, xt = tn * re - te * rn;
            if (along >= side / 2.0 && along <= side - prm.arrival_radius_m) {
                sum2 += xt * xt;
                mx = fmax(mx, fabs(xt));
                n++;
                if (along >= side - prm.arrival_radius_m - 1.0) {
                    end_mx = fmax(end_mx, fabs(xt));
                }
            }
        }
        prev_index = o.index;
    }
    circuit_t c;
    c.rms_straight = sqrt(sum2 / (double)(n > 0 ? n : 1));
    c.max_straight = mx;
    c.end_of_leg_max = end_mx;
    c.reached_all = laps_done >= 4;
    c.worst_min_dist = 0.0;
    for (int i = 0; i < 4; i++) {
        c.worst_min_dist = fmax(c.worst_min_dist, min_dist[i]);
    }
    return c;
}

static void test_closed_loop_square_circuit_both_laws(void)
{
    const double speeds[] = {15.0, 25.0};
    for (int vi = 0; vi < 2; vi++) {
        circuit_t h = fly_square((uint8_t)HT_GUIDE_HEADING, speeds[vi], 60u);
        circuit_t l = fly_square((uint8_t)HT_GUIDE_L1, speeds[vi], 60u);
        printf("square 400 m, V = %.0f m/s, arrival 20 m (second half of each leg, laps 2-4):\n"
               "  heading law: cross-track RMS %.2f m, max %.2f m, at leg end %.2f m, "
               "closest approach worst %.2f m, 4 laps %s\n"
               "  L1 law (60 m): cross-track RMS %.2f m, max %.2f m, at leg end %.2f m, "
               "closest approach worst %.2f m, 4 laps %s\n",
               speeds[vi], h.rms_straight, h.max_straight, h.end_of_leg_max, h.worst_min_dist,
               h.reached_all ? "yes" : "NO", l.rms_straight, l.max_straight, l.end_of_leg_max,
               l.worst_min_dist, l.reached_all ? "yes" : "NO");
        TEST_ASSERT_TRUE(h.reached_all);
        TEST_ASSERT_TRUE(l.reached_all);
        /* every waypoint reached inside the arrival radius, not just passed */
        TEST_ASSERT_TRUE(h.worst_min_dist <= 20.0);
        TEST_ASSERT_TRUE(l.worst_min_dist <= 20.0);
        /* L1 sits on the straight legs; the heading law converges to the
         * line only as it closes on the waypoint */
        TEST_ASSERT_TRUE(l.rms_straight < 1.0);
        TEST_ASSERT_TRUE(l.end_of_leg_max < 0.5);
        TEST_ASSERT_TRUE(h.end_of_leg_max < 20.0);
    }
}

static void test_closed_loop_return_home_and_loiter(void)
{
    for (int law = 0; law < 2; law++) {
        prm.law = (uint8_t)law;
        ht_nav_t nav;
        TEST_ASSERT_EQUAL_INT(0, ht_nav_init(&nav, &prm, NULL, 0u, NULL, NULL));
        ht_nav_state_t s;
        ht_nav_reset(&s, 0, 0);
        plane_t p = {800.0, -600.0, 0.3, 15.0};
        ht_nav_start_leg(&s, 80000, -60000);
        double rmin = 1e9, rmax = 0.0;
        ht_nav_output_t o = {0};
        for (int k = 0; k < 40 * 400; k++) {
            o = fly_step(&nav, &s, &p, 1);
            if (k > 40 * 250) {
                double r = hypot(p.n, p.e);
                rmin = fmin(rmin, r);
                rmax = fmax(rmax, r);
            }
        }
        printf("RTH + loiter (R = 60 m, V = 15 m/s, %s law): radius %.2f .. %.2f m, "
               "turn %.4f rad/s (V/R = 0.25)\n",
               law ? "L1" : "heading", rmin, rmax, o.turn_rate_rad_s / Q16);
        TEST_ASSERT_EQUAL_UINT8(1u, s.home_loiter);
        TEST_ASSERT_TRUE(rmin > 57.0 && rmax < 63.0);
        TEST_ASSERT_EQUAL_INT32(10000, o.target_alt_cm);
    }
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_sin_error_sweep_and_edges);
    RUN_TEST(test_heading_law_against_reference);
    RUN_TEST(test_l1_law_against_reference);
    RUN_TEST(test_l1_worked_case);
    RUN_TEST(test_heading_law_180_and_beyond_90);
    RUN_TEST(test_no_direction_and_low_speed_heading);
    RUN_TEST(test_far_positions_saturate_without_wrapping);
    RUN_TEST(test_arrival_radius_passing_and_wrap);
    RUN_TEST(test_coincident_waypoints_and_no_loop);
    RUN_TEST(test_empty_list_loiters_home);
    RUN_TEST(test_init_names_each_bad_field);
    RUN_TEST(test_closed_loop_straight_track_converges);
    RUN_TEST(test_closed_loop_square_circuit_both_laws);
    RUN_TEST(test_closed_loop_return_home_and_loiter);
    return UNITY_END();
}
