/*
 * test_config_check.c - the joint validity of a flight-mode configuration
 * (helical/guidance/config_check.h) against a reference written here from
 * the rules as docs/parameters.md states them, and through ht_modes_init:
 *   - every (mode_input, inverted_input, rc_channels) of 0..15 x 0..15 x
 *     0..17 (exhaustive), every stick layout of 4 inputs in 0..7 (4096);
 *   - every inverted threshold of its row's range 800..2200 us with the
 *     default calibration (centre 1500, travel 500) and with two others;
 *   - seeded random legs against a double reference (|leg| > 2 radius),
 *     the exact edges (a leg of 2r refused, 2r + 1 m accepted) and the
 *     closing leg of a looping list, with coordinates at +-10 000 km;
 *   - the cases of issue 33 (mode switch on the aileron, inverted switch on
 *     a stick or the mode switch, threshold 800 us, a mode input the
 *     receiver lacks) refused by ht_modes_init with the reason named;
 *   - the reasons: one per status, distinct, at most 49 characters.
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "helical/guidance/config_check.h"
#include "helical/guidance/modes.h"
#include "unity.h"

static ht_controller_t ctl;

void setUp(void) {}

void tearDown(void) {}

/* --- the reference ------------------------------------------------------- */

static int ref_is_stick(const ht_modes_params_t *p, int in)
{
    return (p->rc.aileron.input == in) || (p->rc.elevator.input == in) ||
           (p->rc.rudder.input == in) || (p->rc.throttle.input == in);
}

static ht_cfg_status_t ref_inputs(const ht_modes_params_t *p)
{
    const int n = p->rc_channels;
    if (n < 1 || n > 16) {
        return HT_CFG_RC_CHANNELS;
    }
    const int s[4] = {p->rc.aileron.input, p->rc.elevator.input, p->rc.rudder.input,
                      p->rc.throttle.input};
    for (int i = 0; i < 4; ++i) {
        if (s[i] >= n) {
            return HT_CFG_STICK_ABSENT;
        }
    }
    for (int i = 0; i < 4; ++i) {
        for (int j = 0; j < 4; ++j) {
            if (i != j && s[i] == s[j]) {
                return HT_CFG_STICKS_SHARED;
            }
        }
    }
    if (p->mode_input >= n) {
        return HT_CFG_MODE_ABSENT;
    }
    if (ref_is_stick(p, p->mode_input)) {
        return HT_CFG_MODE_ON_STICK;
    }
    if (p->fbw.inverted_input >= n) {
        return HT_CFG_INVERTED_ABSENT;
    }
    if (ref_is_stick(p, p->fbw.inverted_input)) {
        return HT_CFG_INVERTED_ON_STICK;
    }
    if (p->fbw.inverted_input == p->mode_input) {
        return HT_CFG_INVERTED_ON_MODE;
    }
    const int c = p->rc.aileron.centre_us;
    const int t = p->fbw.inverted_threshold_us;
    if (!(t > c && t <= c + p->rc.aileron.travel_us)) {
        return HT_CFG_INVERTED_THRESHOLD;
    }
    return HT_CFG_OK;
}

static int ref_leg_ok(const ht_waypoint_t *a, const ht_waypoint_t *b, int radius_m)
{
    const double dn = (double)b->north_m - (double)a->north_m;
    const double de = (double)b->east_m - (double)a->east_m;
    return hypot(dn, de) > 2.0 * radius_m;
}

/* --- the tests ----------------------------------------------------------- */

static void test_the_defaults_pass(void)
{
    ht_modes_params_t p;
    ht_modes_params_default(&p);
    uint16_t bad = 99u;
    TEST_ASSERT_EQUAL_INT(HT_CFG_OK, ht_config_check(&p, NULL, 0u, &bad));
    TEST_ASSERT_EQUAL_UINT16(0u, bad);
    TEST_ASSERT_EQUAL_INT(HT_CFG_NULL, ht_config_check(NULL, NULL, 0u, &bad));
    TEST_ASSERT_EQUAL_INT(HT_CFG_NULL, ht_config_check(&p, NULL, 2u, NULL));
}

static void test_switch_inputs_exhaustive(void)
{
    ht_modes_params_t p;
    ht_modes_params_default(&p);
    long refused = 0;
    for (int n = 0; n <= 17; ++n) {
        for (int mode = 0; mode < 16; ++mode) {
            for (int inv = 0; inv < 16; ++inv) {
                p.rc_channels = (uint8_t)n;
                p.mode_input = (uint8_t)mode;
                p.fbw.inverted_input = (uint8_t)inv;
                const ht_cfg_status_t want = ref_inputs(&p);
                char msg[64];
                (void)snprintf(msg, sizeof msg, "channels %d mode %d inverted %d", n, mode, inv);
                TEST_ASSERT_EQUAL_INT_MESSAGE(want, ht_config_check(&p, NULL, 0u, NULL), msg);
                refused += (want != HT_CFG_OK) ? 1 : 0;
            }
        }
    }
    /* accepted: 6..16 channels, both switches on distinct non-stick inputs
     * below n: sum over n of (n - 4)(n - 5) = 2 + 6 + ... + 132 = 572 */
    TEST_ASSERT_EQUAL_INT(18 * 256 - 572, refused);
}

static void test_stick_layouts_exhaustive(void)
{
    ht_modes_params_t p;
    ht_modes_params_default(&p);
    p.mode_input = 8u;
    p.fbw.inverted_input = 9u;
    int accepted = 0;
    for (int k = 0; k < 4096; ++k) {
        p.rc.aileron.input = (uint8_t)(k & 7);
        p.rc.elevator.input = (uint8_t)((k >> 3) & 7);
        p.rc.rudder.input = (uint8_t)((k >> 6) & 7);
        p.rc.throttle.input = (uint8_t)((k >> 9) & 7);
        const ht_cfg_status_t want = ref_inputs(&p);
        TEST_ASSERT_EQUAL_INT(want, ht_config_check(&p, NULL, 0u, NULL));
        accepted += (want == HT_CFG_OK) ? 1 : 0;
    }
    TEST_ASSERT_EQUAL_INT(8 * 7 * 6 * 5, accepted); /* the distinct layouts */
    p.rc_channels = 6u; /* sticks on 0..3 fit, the switches on 8 and 9 do not */
    p.rc.aileron.input = 0u;
    p.rc.elevator.input = 1u;
    p.rc.rudder.input = 3u;
    p.rc.throttle.input = 2u;
    TEST_ASSERT_EQUAL_INT(HT_CFG_MODE_ABSENT, ht_config_check(&p, NULL, 0u, NULL));
    p.rc.throttle.input = 6u;
    TEST_ASSERT_EQUAL_INT(HT_CFG_STICK_ABSENT, ht_config_check(&p, NULL, 0u, NULL));
}

static void test_inverted_threshold_every_pulse(void)
{
    static const uint16_t centres[3] = {1500u, 1520u, 1100u};
    static const uint16_t travels[3] = {500u, 400u, 1000u};
    for (int c = 0; c < 3; ++c) {
        ht_modes_params_t p;
        ht_modes_params_default(&p);
        p.rc.aileron.centre_us = centres[c];
        p.rc.aileron.travel_us = travels[c];
        int accepted = 0;
        for (int t = 800; t <= 2200; ++t) {
            p.fbw.inverted_threshold_us = (uint16_t)t;
            const ht_cfg_status_t want = ref_inputs(&p);
            TEST_ASSERT_EQUAL_INT(want, ht_config_check(&p, NULL, 0u, NULL));
            accepted += (want == HT_CFG_OK) ? 1 : 0;
        }
        /* (centre, centre + travel] clipped to the row's 2200 */
        const int hi = (centres[c] + travels[c] > 2200) ? 2200 : centres[c] + travels[c];
        TEST_ASSERT_EQUAL_INT(hi - centres[c], accepted);
    }
}

static void test_legs_against_a_double_reference(void)
{
    ht_modes_params_t p;
    ht_modes_params_default(&p);
    srand(33u);
    ht_waypoint_t w[8];
    int refused = 0;
    for (int trial = 0; trial < 20000; ++trial) {
        p.nav.arrival_radius_m = (uint16_t)(1 + rand() % 5000);
        p.nav.loop = (uint8_t)(rand() & 1);
        const uint16_t count = (uint16_t)(rand() % 8 + 1);
        /* spans near the radius (the interesting edge) and anywhere */
        const int32_t span = ((trial & 1) != 0) ? 4 * (int32_t)p.nav.arrival_radius_m : 10000000;
        for (uint16_t i = 0; i < count; ++i) {
            w[i].north_m = (int32_t)(rand() % (2 * span + 1)) - span;
            w[i].east_m = (int32_t)(rand() % (2 * span + 1)) - span;
            w[i].alt_m = 100;
        }
        ht_cfg_status_t want = HT_CFG_OK;
        uint16_t want_wp = 0u;
        for (uint16_t i = 1u; i < count && want == HT_CFG_OK; ++i) {
            if (!ref_leg_ok(&w[i - 1u], &w[i], p.nav.arrival_radius_m)) {
                want = HT_CFG_ARRIVAL_RADIUS;
                want_wp = i;
            }
        }
        if (want == HT_CFG_OK && p.nav.loop && count >= 2u &&
            !ref_leg_ok(&w[count - 1u], &w[0], p.nav.arrival_radius_m)) {
            want = HT_CFG_ARRIVAL_RADIUS;
        }
        uint16_t got_wp = 99u;
        TEST_ASSERT_EQUAL_INT(want, ht_config_check(&p, w, count, &got_wp));
        TEST_ASSERT_EQUAL_UINT16(want_wp, got_wp);
        refused += (want != HT_CFG_OK) ? 1 : 0;
    }
    TEST_ASSERT_TRUE(refused > 1000 && refused < 19000); /* both answers exercised */
    printf("legs: %d of 20000 random lists refused\n", refused);
}

static void test_leg_edges_and_extremes(void)
{
    ht_modes_params_t p;
    ht_modes_params_default(&p); /* arrival 20 m, looping */
    ht_waypoint_t w[3] = {{0, 0, 100}, {40, 0, 100}, {0, 0, 100}};
    uint16_t bad = 0u;
    TEST_ASSERT_EQUAL_INT(HT_CFG_ARRIVAL_RADIUS, ht_config_check(&p, w, 2u, &bad));
    TEST_ASSERT_EQUAL_UINT16(1u, bad); /* a leg of exactly 2r */
    w[1].north_m = 41;
    TEST_ASSERT_EQUAL_INT(HT_CFG_OK, ht_config_check(&p, w, 2u, &bad));
    w[1].north_m = 24; /* a diagonal of 40.8 m: 24^2 + 33^2 = 1665 > 1600 */
    w[1].east_m = 33;
    TEST_ASSERT_EQUAL_INT(HT_CFG_OK, ht_config_check(&p, w, 2u, &bad));
    w[1].east_m = 32; /* 40 m exactly: 24^2 + 32^2 = 1600 */
    TEST_ASSERT_EQUAL_INT(HT_CFG_ARRIVAL_RADIUS, ht_config_check(&p, w, 2u, &bad));
    /* a repeated waypoint (a leg of 0) and the closing leg when looping */
    w[1].north_m = 1000;
    w[1].east_m = 0;
    w[2] = w[0];
    w[2].north_m = 10;
    TEST_ASSERT_EQUAL_INT(HT_CFG_ARRIVAL_RADIUS, ht_config_check(&p, w, 3u, &bad));
    TEST_ASSERT_EQUAL_UINT16(0u, bad); /* the closing leg, last -> first */
    p.nav.loop = 0u;
    TEST_ASSERT_EQUAL_INT(HT_CFG_OK, ht_config_check(&p, w, 3u, &bad));
    /* one waypoint has no leg; opposite corners of the guidance's range */
    TEST_ASSERT_EQUAL_INT(HT_CFG_OK, ht_config_check(&p, w, 1u, &bad));
    p.nav.arrival_radius_m = 5000u;
    ht_waypoint_t far[2] = {{-10000000, -10000000, 0}, {10000000, 10000000, 0}};
    TEST_ASSERT_EQUAL_INT(HT_CFG_OK, ht_config_check(&p, far, 2u, &bad));
    far[1].north_m = -10000000 + 6000;
    far[1].east_m = -10000000 + 8000; /* 10 000 m: exactly 2 x 5000 */
    TEST_ASSERT_EQUAL_INT(HT_CFG_ARRIVAL_RADIUS, ht_config_check(&p, far, 2u, &bad));
}

/* The configurations issue 33 found accepted, refused by ht_modes_init
 * (which boot, the link's parameter set and the stored set all go
 * through) with the reason as ht_modes_bad_name gives it. */
static void test_issue_33_cases_refused_by_modes_init(void)
{
    static const struct {
        int what; /* 0 mode_input, 1 inverted_input, 2 threshold, 3 channels then mode */
        int value;
        const char *name;
    } cases[] = {
        {0, 0, "joint.mode_input is a stick channel"},
        {0, 3, "joint.mode_input is a stick channel"},
        {1, 0, "joint.inverted_input is a stick channel"},
        {1, 2, "joint.inverted_input is a stick channel"},
        {1, 4, "joint.inverted_input is the mode_input"},
        {2, 800, "joint.inverted_threshold_us not in (centre, full]"},
        {2, 1500, "joint.inverted_threshold_us not in (centre, full]"},
        {2, 2001, "joint.inverted_threshold_us not in (centre, full]"},
        {3, 15, "joint.mode_input is not a receiver channel"},
        {4, 15, "joint.inverted_input is not a receiver channel"},
    };
    for (unsigned i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
        ht_modes_params_t p;
        ht_modes_params_default(&p);
        switch (cases[i].what) {
        case 0:
            p.mode_input = (uint8_t)cases[i].value;
            break;
        case 1:
            p.fbw.inverted_input = (uint8_t)cases[i].value;
            break;
        case 2:
            p.fbw.inverted_threshold_us = (uint16_t)cases[i].value;
            break;
        case 3:
            p.rc_channels = 8u; /* the SIL's receiver */
            p.mode_input = (uint8_t)cases[i].value;
            break;
        default:
            p.rc_channels = 8u;
            p.fbw.inverted_input = (uint8_t)cases[i].value;
            break;
        }
        ht_modes_t m;
        ht_modes_bad_t bad;
        TEST_ASSERT_EQUAL_INT_MESSAGE(2, ht_modes_init(&m, &p, &ctl, NULL, 0u, &bad),
                                      cases[i].name);
        TEST_ASSERT_EQUAL_INT(HT_MODES_P_JOINT, bad.field);
        char name[64];
        ht_modes_bad_name(&bad, name, (unsigned)sizeof name);
        TEST_ASSERT_EQUAL_STRING(cases[i].name, name);
        TEST_ASSERT_EQUAL_UINT8(0u, m.ready);
    }
    /* NAV_ARRIVAL_RADS beyond half the spacing: refused with the list */
    ht_modes_params_t p;
    ht_modes_params_default(&p);
    p.nav.arrival_radius_m = 150u;
    const ht_waypoint_t sq[4] = {{0, 0, 100}, {300, 0, 100}, {300, 300, 100}, {0, 300, 100}};
    ht_modes_t m;
    ht_modes_bad_t bad;
    TEST_ASSERT_EQUAL_INT(2, ht_modes_init(&m, &p, &ctl, sq, 4u, &bad));
    TEST_ASSERT_EQUAL_INT(HT_CFG_ARRIVAL_RADIUS, bad.sub);
    TEST_ASSERT_EQUAL_UINT16(1u, bad.waypoint);
    p.nav.arrival_radius_m = 149u;
    TEST_ASSERT_EQUAL_INT(0, ht_modes_init(&m, &p, &ctl, sq, 4u, &bad));
}

static void test_reasons(void)
{
    for (int s = 1; s < (int)HT_CFG_COUNT; ++s) {
        const char *r = ht_config_reason((ht_cfg_status_t)s);
        TEST_ASSERT_TRUE(strlen(r) > 0u && strlen(r) <= 43u);
        for (int t = 1; t < s; ++t) {
            TEST_ASSERT_NOT_EQUAL(0, strcmp(r, ht_config_reason((ht_cfg_status_t)t)));
        }
    }
    TEST_ASSERT_EQUAL_STRING("", ht_config_reason(HT_CFG_OK));
    TEST_ASSERT_EQUAL_STRING("", ht_config_reason(HT_CFG_COUNT));
    TEST_ASSERT_EQUAL_STRING("", ht_config_reason((ht_cfg_status_t)200));
}

int main(void)
{
    const ht_params_t lp = HT_PARAMS_DEFAULT;
    if (ht_init(&ctl, &lp, NULL) != HT_OK) {
        return 1;
    }
    UNITY_BEGIN();
    RUN_TEST(test_the_defaults_pass);
    RUN_TEST(test_switch_inputs_exhaustive);
    RUN_TEST(test_stick_layouts_exhaustive);
    RUN_TEST(test_inverted_threshold_every_pulse);
    RUN_TEST(test_legs_against_a_double_reference);
    RUN_TEST(test_leg_edges_and_extremes);
    RUN_TEST(test_issue_33_cases_refused_by_modes_init);
    RUN_TEST(test_reasons);
    return UNITY_END();
}
