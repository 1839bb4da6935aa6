/*
 * test_guide.c - the turn-rate trim (include/helical/guidance/guide.h): its
 * parameters, its pass-through when off, its learning against a double
 * reference of the same equations, and a simulated aircraft whose turn falls
 * short of its command.
 */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "helical/guidance/guide.h"
#include "q14_test_rng.h"
#include "unity.h"

#define RATE_HZ 40u

void setUp(void) {}
void tearDown(void) {}

static ht_guide_t make(int enable)
{
    ht_guide_params_t p;
    ht_guide_params_default(&p);
    p.turn_trim = (uint8_t)enable;
    ht_guide_t g;
    TEST_ASSERT_EQUAL_INT(0, ht_guide_init(&g, &p, RATE_HZ, NULL));
    return g;
}

/* A heading vector of direction psi and horizontal length len, Q14. */
static void heading(double psi, double len, q14_t *n, q14_t *e)
{
    *n = (q14_t)lround(16384.0 * len * cos(psi));
    *e = (q14_t)lround(16384.0 * len * sin(psi));
}

/* --- parameters ---------------------------------------------------------- */

static void test_defaults_and_conversions(void)
{
    ht_guide_params_t p;
    ht_guide_params_default(&p);
    TEST_ASSERT_EQUAL_UINT8(1u, p.turn_trim);
    TEST_ASSERT_EQUAL_INT32(10 * 65536, p.turn_trim_tau_s);
    TEST_ASSERT_EQUAL_INT32(6554, p.turn_trim_max);            /* 0.1 * 65536 rounded */
    TEST_ASSERT_EQUAL_INT32(2294, p.turn_trim_min_rate_rad_s); /* 0.035 * 65536 */
    TEST_ASSERT_EQUAL_INT32(2 * 65536, p.turn_trim_hold_s);
    ht_guide_t g;
    TEST_ASSERT_EQUAL_INT(0, ht_guide_init(&g, &p, RATE_HZ, NULL));
    TEST_ASSERT_EQUAL_INT32(400, g.tau_ticks);   /* 10 s at 40 Hz */
    TEST_ASSERT_EQUAL_UINT16(80u, g.hold_ticks); /* 2 s at 40 Hz */
    TEST_ASSERT_EQUAL_INT16(72, g.min_rate_q11); /* 2294 / 32 = 71.7 */
    TEST_ASSERT_EQUAL_INT32(6554 * 16384, g.max_q30);
    /* the slowest and fastest step rates */
    TEST_ASSERT_EQUAL_INT(0, ht_guide_init(&g, &p, 1u, NULL));
    TEST_ASSERT_EQUAL_INT32(10, g.tau_ticks);
    TEST_ASSERT_EQUAL_INT(0, ht_guide_init(&g, &p, 1000u, NULL));
    TEST_ASSERT_EQUAL_INT32(10000, g.tau_ticks);
    TEST_ASSERT_EQUAL_UINT16(2000u, g.hold_ticks);
    /* the longest tau and hold at 1 kHz stay in their types */
    p.turn_trim_tau_s = 120 * 65536;
    p.turn_trim_hold_s = 10 * 65536;
    TEST_ASSERT_EQUAL_INT(0, ht_guide_init(&g, &p, 1000u, NULL));
    TEST_ASSERT_EQUAL_INT32(120000, g.tau_ticks);
    TEST_ASSERT_EQUAL_UINT16(10000u, g.hold_ticks);
}

/* Every row's bounds pass and one step beyond each is refused by name; a
 * bad rate and NULL have their own codes. */
static void test_every_bound_edge(void)
{
    int checked = 0;
    for (int i = 1; i < (int)HT_GUIDE_P_COUNT; ++i) {
        const ht_guide_param_id_t id = (ht_guide_param_id_t)i;
        const ht_param_info_t *info = ht_guide_param_info(id);
        TEST_ASSERT_NOT_NULL(info);
        const int64_t edges[4] = {info->min_raw, info->max_raw, (int64_t)info->min_raw - 1,
                                  (int64_t)info->max_raw + 1};
        for (int k = 0; k < 4; ++k) {
            ht_guide_params_t p;
            ht_guide_params_default(&p);
            const int64_t v = edges[k];
            switch (id) {
            case HT_GUIDE_P_TURN_TRIM:
                if (v < 0) {
                    continue; /* a uint8_t cannot hold min - 1 */
                }
                p.turn_trim = (uint8_t)v;
                break;
            case HT_GUIDE_P_TURN_TRIM_TAU:
                p.turn_trim_tau_s = (q16_t)v;
                break;
            case HT_GUIDE_P_TURN_TRIM_MAX:
                p.turn_trim_max = (q16_t)v;
                break;
            case HT_GUIDE_P_TURN_TRIM_MIN_RATE:
                p.turn_trim_min_rate_rad_s = (q16_t)v;
                break;
            default:
                p.turn_trim_hold_s = (q16_t)v;
                break;
            }
            ht_guide_t g;
            ht_guide_param_id_t bad = HT_GUIDE_P_COUNT;
            const int rc = ht_guide_init(&g, &p, RATE_HZ, &bad);
            char msg[80];
            (void)snprintf(msg, sizeof msg, "%s = %lld", info->name, (long long)v);
            TEST_ASSERT_EQUAL_INT_MESSAGE((k < 2) ? 0 : 2, rc, msg);
            if (k >= 2) {
                TEST_ASSERT_EQUAL_STRING_MESSAGE(info->name, ht_guide_param_name(bad), msg);
                TEST_ASSERT_EQUAL_UINT8(0u, g.ready);
            }
            checked++;
        }
    }
    TEST_ASSERT_EQUAL_INT(4 * HT_PARAM_GUIDE_COUNT - 1, checked);
    ht_guide_params_t p;
    ht_guide_params_default(&p);
    ht_guide_t g;
    TEST_ASSERT_EQUAL_INT(3, ht_guide_init(&g, &p, 0u, NULL));
    TEST_ASSERT_EQUAL_INT(3, ht_guide_init(&g, &p, 1001u, NULL));
    TEST_ASSERT_EQUAL_INT(1, ht_guide_init(NULL, &p, RATE_HZ, NULL));
    TEST_ASSERT_EQUAL_INT(1, ht_guide_init(&g, NULL, RATE_HZ, NULL));
    TEST_ASSERT_EQUAL_STRING("", ht_guide_param_name(HT_GUIDE_P_NONE));
    TEST_ASSERT_EQUAL_STRING("", ht_guide_param_name(HT_GUIDE_P_COUNT));
    TEST_ASSERT_NULL(ht_guide_param_info(HT_GUIDE_P_COUNT));
}

/* --- off: the seed's law ------------------------------------------------- */

/* Off (and an unusable g, and NULL state) give every int16 command back
 * unchanged whatever the heading does, and leave the state alone. */
static void test_off_passes_every_command_through(void)
{
    const ht_guide_t off = make(0);
    ht_guide_t unusable;
    (void)memset(&unusable, 0, sizeof unusable);
    const ht_guide_t on = make(1);
    ht_guide_state_t s;
    ht_guide_reset(&s);
    uint64_t rng = 7u;
    for (int32_t c = INT16_MIN; c <= INT16_MAX; ++c) {
        const q14_t n = (q14_t)(int32_t)(q14t_next(&rng) & 0x7FFFu);
        const q14_t e = (q14_t)(int32_t)(q14t_next(&rng) & 0x7FFFu);
        TEST_ASSERT_EQUAL_INT16(c, ht_guide_turn_rate(&off, &s, (q11_t)c, n, e, 0u));
        TEST_ASSERT_EQUAL_INT16(c, ht_guide_turn_rate(&unusable, &s, (q11_t)c, n, e, 0u));
        TEST_ASSERT_EQUAL_INT16(c, ht_guide_turn_rate(NULL, &s, (q11_t)c, n, e, 0u));
        TEST_ASSERT_EQUAL_INT16(c, ht_guide_turn_rate(&on, NULL, (q11_t)c, n, e, 0u));
    }
    TEST_ASSERT_EQUAL_INT32(0, s.k_q30);
    TEST_ASSERT_EQUAL_UINT8(0u, s.have_prev);
}

/* --- learning against a double reference ---------------------------------- */

/* A simulated aircraft: its heading turns at (1 - shortfall) times the rate
 * it is given. Flies n steps of cmd; returns the last step's output. */
typedef struct {
    double psi;       /* rad */
    double len;       /* the heading vector's horizontal length */
    double shortfall; /* fraction of the given rate the aircraft misses */
} plant_t;

static q11_t fly(const ht_guide_t *g, ht_guide_state_t *s, plant_t *a, q11_t cmd, int steps)
{
    q11_t used = cmd;
    for (int i = 0; i < steps; ++i) {
        q14_t n;
        q14_t e;
        heading(a->psi, a->len, &n, &e);
        used = ht_guide_turn_rate(g, s, cmd, n, e, 0u);
        a->psi += (1.0 - a->shortfall) * ((double)used / 2048.0) / (double)RATE_HZ;
    }
    return used;
}

/* An aircraft 5 % short of every command: the trim settles at 1/0.95 - 1 =
 * 5.26 % and the turn flown is the command within 0.2 %. */
static void test_trim_converges_on_a_short_turn(void)
{
    const ht_guide_t g = make(1);
    ht_guide_state_t s;
    ht_guide_reset(&s);
    plant_t a = {0.3, 0.95, 0.05};
    const q11_t cmd = 358; /* 10 deg/s */
    /* the entry: nothing learnt before the command has been steady 2 s */
    (void)fly(&g, &s, &a, cmd, 80);
    TEST_ASSERT_EQUAL_INT32(0, s.k_q30);
    (void)fly(&g, &s, &a, cmd, 4000); /* 100 s = 10 tau */
    const double k = (double)s.k_q30 / 1073741824.0;
    TEST_ASSERT_DOUBLE_WITHIN(0.002, 1.0 / 0.95 - 1.0, k);
    /* the flown rate over the next 20 s against the command */
    const double psi0 = a.psi;
    (void)fly(&g, &s, &a, cmd, 800);
    const double flown = (a.psi - psi0) / 20.0;
    TEST_ASSERT_DOUBLE_WITHIN(0.002 * (358.0 / 2048.0), 358.0 / 2048.0, flown);
    /* the same in a left turn, an aircraft that over-turns by 4 % */
    ht_guide_reset(&s);
    plant_t b = {-2.0, 0.8, -0.04};
    (void)fly(&g, &s, &b, (q11_t)-536, 4500); /* -15 deg/s */
    TEST_ASSERT_DOUBLE_WITHIN(0.002, 1.0 / 1.04 - 1.0, (double)s.k_q30 / 1073741824.0);
}

/* k against the same update in double over a random sequence of measured
 * rates (the heading turned by a random rate each step). */
static void test_update_matches_double_reference(void)
{
    const ht_guide_t g = make(1);
    ht_guide_state_t s;
    ht_guide_reset(&s);
    uint64_t rng = 2026u;
    const q11_t cmd = -400;
    double psi = 1.0;
    double k_ref = 0.0;
    double worst = 0.0;
    double moved = 0.0;
    for (int i = 0; i < 4000; ++i) {
        q14_t n0;
        q14_t e0;
        heading(psi, 1.0, &n0, &e0);
        const double r = (double)cmd / 2048.0 *
                         (0.6 + 0.8 * ((double)(q14t_next(&rng) >> 11) / 9007199254740992.0));
        const double psi1 = psi + r / (double)RATE_HZ;
        q14_t n1;
        q14_t e1;
        heading(psi1, 1.0, &n1, &e1);
        const int learn = (i > 0) && ((uint32_t)s.steady + 1u >= g.hold_ticks);
        (void)ht_guide_turn_rate(&g, &s, cmd, n1, e1, 0u);
        if (learn) {
            /* the measured rate the vectors show, taken in Q13 as guide.c
             * takes them (any int16 input must fit its products) */
            const double a0 = (double)(n0 / 2);
            const double b0 = (double)(e0 / 2);
            const double a1 = (double)(n1 / 2);
            const double b1 = (double)(e1 / 2);
            const double cross = a0 * b1 - b0 * a1;
            const double dot = a0 * a1 + b0 * b1;
            const double meas = cross / dot * RATE_HZ;
            const double c = (double)cmd / 2048.0;
            double ratio = (c - meas) / c;
            ratio = fmax(-0.5, fmin(0.5, ratio));
            k_ref = fmax(-0.1, fmin(0.1, k_ref + ratio / (double)g.tau_ticks));
            const double d = fabs((double)s.k_q30 / 1073741824.0 - k_ref);
            worst = fmax(worst, d);
            moved = fmax(moved, fabs(k_ref));
        }
        psi = psi1;
    }
    /* each step rounds the tangent (Q20: the rate by up to 1.9e-5 rad/s,
     * 1e-4 of the command, 5e-7 of k) and the ratio and its step (Q30) to
     * nearest, unbiased: a random walk of 4000 such steps, about 3e-5; a
     * bias of half an LSB a step (a truncation) would be 2e-3 */
    char msg[64];
    (void)snprintf(msg, sizeof msg, "worst |k - k_ref| = %.3g", worst);
    TEST_ASSERT_TRUE_MESSAGE(worst < 5e-5, msg);
    TEST_ASSERT_TRUE(moved > 0.005); /* it learnt something */
}

/* --- bounds, resets and holds ---------------------------------------------- */

/* Half the commanded rate flown: k stops at turn_trim_max and the output is
 * cmd * 1.1, rounded. */
static void test_trim_is_bounded(void)
{
    const ht_guide_t g = make(1);
    ht_guide_state_t s;
    ht_guide_reset(&s);
    plant_t a = {0.0, 1.0, 0.5};
    const q11_t used = fly(&g, &s, &a, 500, 3000);
    TEST_ASSERT_EQUAL_INT32(g.max_q30, s.k_q30);
    TEST_ASSERT_EQUAL_INT16(550, used);
    /* the largest commands saturate, never wrap */
    s.k_q30 = g.max_q30;
    s.last_cmd = INT16_MAX;
    q14_t n;
    q14_t e;
    heading(0.0, 1.0, &n, &e);
    TEST_ASSERT_EQUAL_INT16(INT16_MAX, ht_guide_turn_rate(&g, &s, INT16_MAX, n, e, 1u));
    s.k_q30 = g.max_q30;
    s.last_cmd = INT16_MIN;
    TEST_ASSERT_EQUAL_INT16(INT16_MIN, ht_guide_turn_rate(&g, &s, INT16_MIN, n, e, 1u));
    s.k_q30 = -g.max_q30;
    TEST_ASSERT_EQUAL_INT16(-29491, ht_guide_turn_rate(&g, &s, INT16_MIN, n, e, 1u));
}

/* A glitch (the heading stands still: measured 0) moves k by at most half a
 * step of 1/tau. */
static void test_glitch_is_clamped(void)
{
    const ht_guide_t g = make(1);
    ht_guide_state_t s;
    ht_guide_reset(&s);
    q14_t n;
    q14_t e;
    heading(0.5, 1.0, &n, &e);
    for (int i = 0; i < 81; ++i) {
        (void)ht_guide_turn_rate(&g, &s, 300, n, e, 1u); /* steady, held */
    }
    TEST_ASSERT_EQUAL_INT32(0, s.k_q30);
    (void)ht_guide_turn_rate(&g, &s, 300, n, e, 0u);
    TEST_ASSERT_EQUAL_INT32(1342177, s.k_q30); /* 0.5 / 400 in Q30, rounded */
}

/* A reversal, a command below the minimum, and a slewing command: each
 * does what the header says. */
static void test_resets_and_holds(void)
{
    const ht_guide_t g = make(1);
    ht_guide_state_t s;
    ht_guide_reset(&s);
    plant_t a = {0.0, 1.0, 0.1};
    (void)fly(&g, &s, &a, 358, 600);
    const int32_t k = s.k_q30;
    TEST_ASSERT_TRUE(k > 0);
    /* slewing (a new value every step): k is kept and applied, not learnt */
    for (int i = 1; i <= 20; ++i) {
        (void)fly(&g, &s, &a, (q11_t)(358 + i), 1);
        TEST_ASSERT_EQUAL_INT32(k, s.k_q30);
    }
    /* the caller's hold */
    q14_t n;
    q14_t e;
    heading(a.psi, 1.0, &n, &e);
    for (int i = 0; i < 200; ++i) {
        (void)ht_guide_turn_rate(&g, &s, 400, n, e, 1u);
    }
    TEST_ASSERT_EQUAL_INT32(k, s.k_q30);
    /* a reversal forgets it */
    (void)ht_guide_turn_rate(&g, &s, -400, n, e, 0u);
    TEST_ASSERT_EQUAL_INT32(0, s.k_q30);
    TEST_ASSERT_EQUAL_UINT16(0u, s.steady);
    /* below the minimum rate: unchanged and forgotten */
    s.k_q30 = k;
    TEST_ASSERT_EQUAL_INT16(71, ht_guide_turn_rate(&g, &s, 71, n, e, 0u));
    TEST_ASSERT_EQUAL_INT32(0, s.k_q30);
    TEST_ASSERT_EQUAL_INT16(0, ht_guide_turn_rate(&g, &s, 0, n, e, 0u));
}

/* A nose within 72 degrees of the vertical (|h| < 0.3) or a turn of more
 * than 0.1 rad in a step measures nothing: k does not move. */
static void test_no_heading_no_learning(void)
{
    const ht_guide_t g = make(1);
    ht_guide_state_t s;
    ht_guide_reset(&s);
    plant_t a = {0.0, 0.29, 0.3};
    (void)fly(&g, &s, &a, 358, 1000);
    TEST_ASSERT_EQUAL_INT32(0, s.k_q30);
    plant_t b = {0.0, 1.0, -30.0}; /* 31 x the command: 0.136 rad per step */
    ht_guide_reset(&s);
    (void)fly(&g, &s, &b, 358, 1000);
    TEST_ASSERT_EQUAL_INT32(0, s.k_q30);
    /* the vertical nose itself: a zero vector */
    ht_guide_reset(&s);
    for (int i = 0; i < 200; ++i) {
        TEST_ASSERT_EQUAL_INT16(358, ht_guide_turn_rate(&g, &s, 358, 0, 0, 0u));
    }
    TEST_ASSERT_EQUAL_INT32(0, s.k_q30);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_defaults_and_conversions);
    RUN_TEST(test_every_bound_edge);
    RUN_TEST(test_off_passes_every_command_through);
    RUN_TEST(test_trim_converges_on_a_short_turn);
    RUN_TEST(test_update_matches_double_reference);
    RUN_TEST(test_trim_is_bounded);
    RUN_TEST(test_glitch_is_clamped);
    RUN_TEST(test_resets_and_holds);
    RUN_TEST(test_no_heading_no_learning);
    return UNITY_END();
}
