/*
 * Property sweep: the Q14 core against the double reference of the same law,
 * 10^5 random steps per gain set and regime with fixed seeds, over unit and
 * slightly non-normalized tilt rows, airspeeds 0..60 m/s, normal and inverted:
 * the wide regime with turn rates to +/-10 rad/s (the tilt limit is hit),
 * pitch ratios to +/-50, gyro rates to +/-6 rad/s; the cruise regime (below)
 * with the unlimited law. Only inputs within a hair of a branch boundary of
 * the spec are skipped (counted and printed): there a tie may go either way.
 */
#include <math.h>
#include <stdio.h>

#include "ht_reference.h"
#include "ht_test_support.h"
#include "unity.h"

#define STEPS_PER_SET 100000L
/* Distance (real units) under which a branch decision is a tie. The core's
 * branch quantities are exact to a few Q16 LSB (1.5e-5 each). */
#define BRANCH_EPS 1e-4

/* The project's targets are 4 LSB (Q14) for tilt, roll and pitch quantities
 * and 8 LSB for the surfaces; the core does much better, and these limits hold
 * it to what it does (half an LSB is the final rounding alone), so that a
 * regression shows. Rates in Q11 LSB. */
#define LIMIT_ANGLES_LSB   1.0
#define LIMIT_RATES_LSB    0.51
#define LIMIT_SURFACES_LSB 2.0

void setUp(void) {}
void tearDown(void) {}

/* Two input regimes: WIDE (the ranges above: most steps tilt-limited) and
 * CRUISE (turn rates to +/-1 rad/s, pitch ratios to +/-1, gyros to +/-2
 * rad/s: the unlimited law at every airspeed, where the ratio's own
 * precision reaches the surfaces through the largest scheduled gains). */
typedef enum { REGIME_WIDE, REGIME_CRUISE } regime_t;

static void random_input(uint64_t *rng, ht_input_t *in, regime_t regime)
{
    double v[3], n = 0.0;
    for (int i = 0; i < 3; i++) {
        v[i] = ts_gaussian(rng);
        n += v[i] * v[i];
    }
    n = sqrt(n);
    /* half the rows are unit, half are off by up to +/-3 % (drifting DCM) */
    double scale = (ts_uniform(rng, 0, 1) < 0.5) ? 1.0 : ts_uniform(rng, 0.97, 1.03);
    in->x = ts_fix16(v[0] / n * scale, 14);
    in->y = ts_fix16(v[1] / n * scale, 14);
    in->z = ts_fix16(v[2] / n * scale, 14);
    const int wide = (regime == REGIME_WIDE);
    in->turn_rate_rad_s = ts_fix16(ts_uniform(rng, wide ? -10 : -1, wide ? 10 : 1), 11);
    in->airspeed_cm_s = (int16_t)lround(ts_uniform(rng, 0, 6000));
    double u = ts_uniform(rng, 0, 1);
    double pmax = (u < 0.5 || !wide) ? 1.0 : ((u < 0.8) ? 10.0 : 50.0);
    in->pitch_ratio = ts_fix32(ts_uniform(rng, -pmax, pmax), 16);
    for (int i = 0; i < 3; i++) {
        in->gyro_rad_s[i] = ts_fix16(ts_uniform(rng, wide ? -6 : -2, wide ? 6 : 2), 11);
    }
    in->inverted = (uint8_t)(ts_rng_next(rng) & 1u);
}

static int on_branch_boundary(const ht_ref_output_t *r, const ht_ref_params_t *p)
{
    if (fabs(r->ratio_margin) < BRANCH_EPS) {
        return 1;
    }
    if (fabs(r->roll_dot) < BRANCH_EPS || (r->roll_dot <= 0 && fabs(r->roll_cross) < BRANCH_EPS)) {
        return 1;
    }
    if (p->pitch_mode == HT_PITCH_EARTH_FRAME &&
        (fabs(r->pitch_agree) < BRANCH_EPS ||
         (r->pitch_agree <= 0 && fabs(r->pitch_raw) < BRANCH_EPS))) {
        return 1;
    }
    return 0;
}

static void sweep_gain_set_regime(int set, regime_t regime)
{
    ht_controller_t ctl;
    ht_param_id_t bad;
    TEST_ASSERT_EQUAL_INT(HT_OK, ht_init(&ctl, &ts_gain_sets[set].params, &bad));
    ht_ref_params_t rp;
    ht_ref_params_from_controller(&ctl, &rp);

    ts_err_t errs[TS_N_OUTPUTS];
    ts_errs_init(errs);
    uint64_t rng = 0x5EED0000u + (uint64_t)set + ((regime == REGIME_CRUISE) ? 0x100u : 0u);
    long skipped = 0, limited = 0, beyond90 = 0;
    for (long k = 0; k < STEPS_PER_SET; k++) {
        ht_input_t in;
        random_input(&rng, &in, regime);
        ht_output_t out;
        ht_step(&ctl, &in, &out);
        ht_ref_input_t ri;
        ht_ref_output_t ro;
        ht_ref_input_from_fixed(&in, &ri);
        ht_ref_step(&rp, &ri, &ro);
        if (on_branch_boundary(&ro, &rp)) {
            skipped++;
            continue;
        }
        limited += (out.flags & HT_F_TILT_LIMITED) != 0;
        beyond90 += (out.flags & (HT_F_ROLL_BEYOND_90 | HT_F_PITCH_BEYOND_90)) != 0;
        ts_errs_add_step(errs, &out, &ro);
    }
    printf("[%s regime]\n", (regime == REGIME_WIDE) ? "wide" : "cruise");
    ts_errs_print(ts_gain_sets[set].name, errs);
    printf("  skipped on a branch boundary: %ld; tilt-limited: %ld; beyond 90 deg: %ld\n", skipped,
           limited, beyond90);
    /* The sweep must reach the branches it claims to cover (the cruise
     * regime: mostly the unlimited law, fewer than 10 % limited). */
    if (regime == REGIME_WIDE) {
        TEST_ASSERT_GREATER_THAN(STEPS_PER_SET / 10, limited);
    } else {
        TEST_ASSERT_LESS_THAN(STEPS_PER_SET / 10, limited);
    }
    TEST_ASSERT_GREATER_THAN(STEPS_PER_SET / 10, beyond90);
    TEST_ASSERT_LESS_THAN(STEPS_PER_SET / 100, skipped);
    for (int i = 0; i < TS_N_OUTPUTS; i++) {
        int is_rate = (i == 0 || (i >= 4 && i <= 6));
        int is_surface = (i >= 13);
        double limit =
            is_rate ? LIMIT_RATES_LSB : (is_surface ? LIMIT_SURFACES_LSB : LIMIT_ANGLES_LSB);
        if (errs[i].worst > limit) {
            printf("  FAIL %s: %.2f LSB > %.1f\n", errs[i].name, errs[i].worst, limit);
        }
        TEST_ASSERT_TRUE(errs[i].worst <= limit);
    }
}

static void sweep_gain_set(int set)
{
    sweep_gain_set_regime(set, REGIME_WIDE);
    sweep_gain_set_regime(set, REGIME_CRUISE);
}

static void test_sweep_default(void)
{
    sweep_gain_set(0);
}
static void test_sweep_c172p(void)
{
    sweep_gain_set(1);
}
static void test_sweep_t37(void)
{
    sweep_gain_set(2);
}
static void test_sweep_scheduled(void)
{
    sweep_gain_set(3);
}
static void test_sweep_tilt_cross(void)
{
    sweep_gain_set(4);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_sweep_default);
    RUN_TEST(test_sweep_c172p);
    RUN_TEST(test_sweep_t37);
    RUN_TEST(test_sweep_scheduled);
    RUN_TEST(test_sweep_tilt_cross);
    return UNITY_END();
}
