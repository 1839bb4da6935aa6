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
        if (ts_on_branch_boundary(&ro, &rp)) {
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

/*
 * The legal extremes (issue 18). With gains at their limit and the airspeed
 * scale v_ref / S large, the demand of almost every random step is far beyond
 * the [-1, 1] clamp, where both laws give the same +/-1 and an error cannot
 * show. The balanced inputs below therefore solve each axis' gyro (a free
 * input the rate damping weights by kd * s_p) so that the reference demand
 * lands at a random point of [-1.2, 1.2]: the fraction of unsaturated
 * surfaces is then large (asserted), and the error there is the core's
 * error at the full amplification of its gains.
 */
#define EXTREME_STEPS 100000L
#define RANDOM_SETS   400
#define RANDOM_STEPS  2500L

/* The airspeed S of the spec (step 1) and s_p (step 9), from the reference's
 * own inputs. */
static double ref_s_p(const ht_ref_params_t *rp, const ht_ref_input_t *ri)
{
    const double s = (ri->airspeed > rp->v_min) ? ri->airspeed : rp->v_min;
    return rp->schedule ? rp->v_ref / s : 1.0;
}

static void balance_gyros(uint64_t *rng, const ht_ref_params_t *rp, ht_input_t *in)
{
    ht_ref_input_t ri;
    ht_ref_output_t ro;
    ht_ref_input_from_fixed(in, &ri);
    ht_ref_step(rp, &ri, &ro);
    const double s_p = ref_s_p(rp, &ri);
    for (int i = 0; i < 3; i++) {
        const double k = rp->kd[i] * s_p; /* d(demand) / d(gyro) = -k */
        const double u = ts_uniform(rng, -1.2, 1.2);
        if (k > 0.0) {
            in->gyro_rad_s[i] = ts_fix16(ri.gyro[i] + (ro.demand[i] - u) / k, 11);
        }
    }
}

typedef struct {
    ts_err_t errs[TS_N_OUTPUTS];
    long steps, skipped, unsaturated[3];
} extreme_stats_t;

static void extreme_stats_init(extreme_stats_t *st)
{
    ts_errs_init(st->errs);
    st->steps = st->skipped = 0;
    st->unsaturated[0] = st->unsaturated[1] = st->unsaturated[2] = 0;
}

/* Accumulate the worst errors of `steps` balanced steps of one parameter set;
 * with any_row, the tilt row is drawn over the whole int16 range (an
 * unnormalized row up to 2 per element doubles every tilt error, the case
 * fuzz_ht_step found). */
static void sweep_extreme_rows(const ht_params_t *params, uint64_t seed, long steps, int any_row,
                               extreme_stats_t *st)
{
    ht_controller_t ctl;
    ht_param_id_t bad;
    TEST_ASSERT_EQUAL_INT(HT_OK, ht_init(&ctl, params, &bad));
    ht_ref_params_t rp;
    ht_ref_params_from_controller(&ctl, &rp);
    uint64_t rng = seed;
    for (long k = 0; k < steps; k++) {
        ht_input_t in;
        random_input(&rng, &in, (k & 1) ? REGIME_WIDE : REGIME_CRUISE);
        if (any_row) {
            in.x = (int16_t)(uint16_t)ts_rng_next(&rng);
            in.y = (int16_t)(uint16_t)ts_rng_next(&rng);
            in.z = (int16_t)(uint16_t)ts_rng_next(&rng);
        }
        balance_gyros(&rng, &rp, &in);
        ht_output_t out;
        ht_step(&ctl, &in, &out);
        ht_ref_input_t ri;
        ht_ref_output_t ro;
        ht_ref_input_from_fixed(&in, &ri);
        ht_ref_step(&rp, &ri, &ro);
        st->steps++;
        if (ts_on_branch_boundary(&ro, &rp)) {
            st->skipped++;
            continue;
        }
        for (int i = 0; i < 3; i++) {
            st->unsaturated[i] += fabs(ro.demand[i]) < 1.0;
        }
        ts_errs_add_step(st->errs, &out, &ro);
    }
}

static void sweep_extreme(const ht_params_t *params, uint64_t seed, long steps, extreme_stats_t *st)
{
    sweep_extreme_rows(params, seed, steps, 0, st);
}

/* Print the worst errors; 0 when one is beyond its limit. */
static int report_extreme(const char *title, const extreme_stats_t *st)
{
    int ok = 1;
    ts_errs_print(title, st->errs);
    printf("  unsaturated demands X/Y/Z: %ld / %ld / %ld of %ld; skipped on a branch "
           "boundary: %ld\n",
           st->unsaturated[0], st->unsaturated[1], st->unsaturated[2], st->steps, st->skipped);
    ok &= st->skipped <= st->steps / 100;
    for (int i = 0; i < TS_N_OUTPUTS; i++) {
        int is_rate = (i == 0 || (i >= 4 && i <= 6));
        int is_surface = (i >= 13);
        double limit =
            is_rate ? LIMIT_RATES_LSB : (is_surface ? LIMIT_SURFACES_LSB : LIMIT_ANGLES_LSB);
        if (st->errs[i].worst > limit) {
            printf("  FAIL %s: %.2f LSB > %.1f\n", st->errs[i].name, st->errs[i].worst, limit);
            ok = 0;
        }
    }
    return ok;
}

/* The smallest legal v_min for a v_ref of v_ref_cm_s, and the largest v_ref
 * for a v_min (the ends of the scale v_ref / v_min). */
static int32_t ht_v_min_for_scale(int32_t v_ref_cm_s)
{
    return (v_ref_cm_s + HT_SCALE_MAX - 1) / HT_SCALE_MAX;
}

static int32_t ht_v_ref_max_for(int32_t v_min_cm_s)
{
    return v_min_cm_s * HT_SCALE_MAX;
}

/* The corners of the legal space: kp at its limit everywhere, the rate gain
 * kff * v_ref / v_min + kd * s_p,max at its limit (512) split every way at
 * the largest scale v_ref / v_min (32), schedule on and off, both pitch
 * modes; every gain at 64 where the scale allows it (<= 4 scheduled);
 * v_ref = v_min at either end of the airspeed range (s_ff down to
 * 1 m/s / 327 m/s); the tilt limit at its smallest. */
static void test_sweep_legal_corners(void)
{
    const q16_t g = HT_GAIN_MAX_Q16;
    const q16_t t = HT_MAX_TILT_LIMIT_Q16;
    const int32_t v_hi = HT_V_REF_MAX_CM_S, v_lo = HT_V_MIN_LOWEST_CM_S;
    const int32_t v_min_32 = ht_v_min_for_scale(v_hi);
    const struct {
        const char *name;
        ht_params_t p;
    } corners[] = {
        {"kp 64, kff 8, kd 8, schedule, scale 32",
         ts_gains3(g, 8 * Q16_ONE, 8 * Q16_ONE, v_hi, v_min_32, 1, t, HT_PITCH_EARTH_FRAME)},
        {"kp 64, kff 1, kd 15, schedule, scale 32",
         ts_gains3(g, Q16_ONE, 15 * Q16_ONE, v_hi, v_min_32, 1, t, HT_PITCH_EARTH_FRAME)},
        {"kp 64, kff 15, kd 1, schedule, scale 32, tilt cross",
         ts_gains3(g, 15 * Q16_ONE, Q16_ONE, v_hi, v_min_32, 1, t, HT_PITCH_TILT_CROSS)},
        {"kp 64, kff 14, kd 64, no schedule, scale 32",
         ts_gains3(g, 14 * Q16_ONE, g, v_hi, v_min_32, 0, t, HT_PITCH_EARTH_FRAME)},
        {"kp 64, kff 8, kd 8, schedule, scale 32, smallest v_min",
         ts_gains3(g, 8 * Q16_ONE, 8 * Q16_ONE, ht_v_ref_max_for(v_lo), v_lo, 1, t,
                   HT_PITCH_EARTH_FRAME)},
        {"all gains 64, schedule, scale 4",
         ts_gains3(g, g, g, v_hi, (v_hi + 3) / 4, 1, t, HT_PITCH_EARTH_FRAME)},
        {"all gains 64, schedule, v_ref = v_min = 1 m/s",
         ts_gains3(g, g, g, v_lo, v_lo, 1, t, HT_PITCH_EARTH_FRAME)},
        {"all gains 64, schedule, v_ref = v_min = 327.67 m/s",
         ts_gains3(g, g, g, v_hi, v_hi, 1, t, HT_PITCH_EARTH_FRAME)},
        {"kp 64, kff 8, kd 8, schedule, scale 32, max_tilt 1 LSB",
         ts_gains3(g, 8 * Q16_ONE, 8 * Q16_ONE, v_hi, v_min_32, 1, 1, HT_PITCH_EARTH_FRAME)},
    };
    const int n = (int)(sizeof corners / sizeof corners[0]);
    int failed = 0;
    for (int c = 0; c < n; c++) {
        extreme_stats_t st;
        extreme_stats_init(&st);
        sweep_extreme(&corners[c].p, 0xC0C0E000u + (uint64_t)c, EXTREME_STEPS, &st);
        failed |= !report_extreme(corners[c].name, &st);
        /* the balance must put a good share of the surfaces inside [-1, 1] */
        for (int i = 0; i < 3; i++) {
            TEST_ASSERT_GREATER_THAN(EXTREME_STEPS / 20, st.unsaturated[i]);
        }
    }
    TEST_ASSERT_FALSE(failed);
}

/* A uniformly random value of [lo, hi], hitting each end 1 time in 8. */
static int32_t draw_i32(uint64_t *rng, int32_t lo, int32_t hi)
{
    const uint64_t r = ts_rng_next(rng);
    if ((r & 7u) == 0u) {
        return ((r >> 3) & 1u) ? hi : lo;
    }
    return lo + (int32_t)((r >> 8) % (uint64_t)((int64_t)hi - lo + 1));
}

/* A random parameter set drawn over the whole legal space: each gain in
 * [0, 64] (its ends 1 time in 8), v_min and v_ref log-uniform over their
 * ranges, schedule, max_tilt and pitch mode at random. Draws that ht_init
 * refuses (v_ref beyond the scale limit) are drawn again. */
static ht_params_t random_legal_params(uint64_t *rng)
{
    for (;;) {
        ht_params_t p = HT_PARAMS_DEFAULT; /* a table row this draw does not know: its default */
        q16_t *gains[9] = {&p.kp_aileron,  &p.kp_elevator,  &p.kp_rudder,
                           &p.kff_aileron, &p.kff_elevator, &p.kff_rudder,
                           &p.kd_aileron,  &p.kd_elevator,  &p.kd_rudder};
        for (int i = 0; i < 9; i++) {
            *gains[i] = draw_i32(rng, 0, HT_GAIN_MAX_Q16);
        }
        const double lv_min = ts_uniform(rng, log(HT_V_MIN_LOWEST_CM_S), log(32767.0));
        p.v_min_cm_s = (int32_t)lround(exp(lv_min));
        const double lv_ref = ts_uniform(rng, log((double)p.v_min_cm_s), log(32767.0));
        p.v_ref_cm_s = (ts_rng_next(rng) & 7u) ? (int32_t)lround(exp(lv_ref)) : p.v_min_cm_s;
        p.schedule = (uint8_t)(ts_rng_next(rng) & 1u);
        p.max_tilt = draw_i32(rng, 1, HT_MAX_TILT_LIMIT_Q16);
        p.pitch_mode = (uint8_t)(ts_rng_next(rng) & 1u);
        ht_controller_t c;
        if (ht_init(&c, &p, NULL) == HT_OK) {
            return p;
        }
    }
}

static void test_sweep_random_legal_parameters(void)
{
    uint64_t rng = 0x1E6A15E7u;
    extreme_stats_t st;
    extreme_stats_init(&st);
    for (int set = 0; set < RANDOM_SETS; set++) {
        const ht_params_t p = random_legal_params(&rng);
        sweep_extreme(&p, 0x5E7000u + (uint64_t)set, RANDOM_STEPS, &st);
    }
    TEST_ASSERT_TRUE(
        report_extreme("random legal parameter sets (400 x 2500 balanced steps)", &st));
    for (int i = 0; i < 3; i++) {
        TEST_ASSERT_GREATER_THAN(st.steps / 10, st.unsaturated[i]);
    }
}

/* Four corners at scale 32 (three scheduled, both pitch modes) with the tilt
 * row drawn over the whole int16 range (elements up to 2: a row no estimator
 * gives, but ht_step takes any input, and fuzz_ht_step draws it so). */
static void test_sweep_corners_any_row(void)
{
    const q16_t g = HT_GAIN_MAX_Q16;
    const q16_t t = HT_MAX_TILT_LIMIT_Q16;
    const int32_t v_hi = HT_V_REF_MAX_CM_S, v_lo = HT_V_MIN_LOWEST_CM_S;
    const int32_t v_min_32 = ht_v_min_for_scale(v_hi);
    const struct {
        const char *name;
        ht_params_t p;
    } corners[] = {
        {"any row: kp 64, kff 8, kd 8, schedule, scale 32",
         ts_gains3(g, 8 * Q16_ONE, 8 * Q16_ONE, v_hi, v_min_32, 1, t, HT_PITCH_EARTH_FRAME)},
        {"any row: kp 64, kff 1, kd 15, schedule, scale 32, tilt cross",
         ts_gains3(g, Q16_ONE, 15 * Q16_ONE, v_hi, v_min_32, 1, t, HT_PITCH_TILT_CROSS)},
        {"any row: kp 64, kff 8, kd 8, schedule, scale 32, smallest v_min, tilt cross",
         ts_gains3(g, 8 * Q16_ONE, 8 * Q16_ONE, ht_v_ref_max_for(v_lo), v_lo, 1, t,
                   HT_PITCH_TILT_CROSS)},
        {"any row: kp 64, kff 14, kd 64, no schedule, scale 32",
         ts_gains3(g, 14 * Q16_ONE, g, v_hi, v_min_32, 0, t, HT_PITCH_EARTH_FRAME)},
    };
    const int n = (int)(sizeof corners / sizeof corners[0]);
    int failed = 0;
    for (int c = 0; c < n; c++) {
        extreme_stats_t st;
        extreme_stats_init(&st);
        sweep_extreme_rows(&corners[c].p, 0xA11120u + (uint64_t)c, EXTREME_STEPS, 1, &st);
        failed |= !report_extreme(corners[c].name, &st);
        for (int i = 0; i < 3; i++) {
            TEST_ASSERT_GREATER_THAN(EXTREME_STEPS / 20, st.unsaturated[i]);
        }
    }
    TEST_ASSERT_FALSE(failed);
}

/*
 * The input fuzz_ht_step found at a legal corner (tests/fuzz/corpus/ht_step/
 * f9da17b26812b034d774784b6e5d9f2dd75c7d57): kp_rudder 63.99, kd_rudder 16,
 * schedule on, v_ref 104.34 m/s over v_min 3.30 m/s with the airspeed floored
 * (s_ff = 31.6, kp_rudder * s_ff = 2023), tilt cross product, and the
 * unnormalized row (-1.95, 1.93, -1.25). The rudder was 2.03 LSB off: the
 * ratio's Q24 rounding (0.4 LSB of Q24) reached the yaw error through Y = 1.93
 * (1.3 LSB after the gain), and the three Q20 terms of the demand were each
 * rounded before the scale of 31.6 (0.2 LSB more). Now 0.03 LSB.
 */
static void test_fuzz_regression_rudder_at_scale_32(void)
{
    ht_params_t p = HT_PARAMS_DEFAULT;
    p.kp_aileron = 13364;
    p.kp_elevator = 11518;
    p.kp_rudder = 4194097;
    p.kff_aileron = 11565;
    p.kff_elevator = 11565;
    p.kff_rudder = 11566;
    p.kd_aileron = 78893;
    p.kd_elevator = 65785;
    p.kd_rudder = 1048565;
    p.v_min_cm_s = 330;
    p.v_ref_cm_s = 10434;
    p.schedule = 1;
    p.max_tilt = 423827;
    p.pitch_mode = HT_PITCH_TILT_CROSS;
    ht_controller_t ctl;
    ht_param_id_t bad;
    TEST_ASSERT_EQUAL_INT(HT_OK, ht_init(&ctl, &p, &bad));
    ht_input_t in = {0};
    in.x = -31877;
    in.y = 31627;
    in.z = -20481;
    in.turn_rate_rad_s = -1;
    in.pitch_ratio = -1;
    in.airspeed_cm_s = -1;
    in.gyro_rad_s[0] = in.gyro_rad_s[1] = in.gyro_rad_s[2] = -1;
    in.inverted = 255;
    ht_output_t out;
    ht_step(&ctl, &in, &out);
    ht_ref_params_t rp;
    ht_ref_input_t ri;
    ht_ref_output_t ro;
    ht_ref_params_from_controller(&ctl, &rp);
    ht_ref_input_from_fixed(&in, &ri);
    ht_ref_step(&rp, &ri, &ro);
    TEST_ASSERT_FALSE(ts_on_branch_boundary(&ro, &rp));
    TEST_ASSERT_TRUE(fabs(ro.demand[2]) < 1.0); /* the rudder is unsaturated */
    const double err[3] = {fabs(out.aileron - ro.aileron * 16384.0),
                           fabs(out.elevator - ro.elevator * 16384.0),
                           fabs(out.rudder - ro.rudder * 16384.0)};
    printf("fuzz regression: rudder %d, reference %.4f, error %.3f LSB (was 2.03)\n", out.rudder,
           ro.rudder * 16384.0, err[2]);
    for (int i = 0; i < 3; i++) {
        TEST_ASSERT_TRUE(err[i] <= LIMIT_SURFACES_LSB);
    }
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_sweep_default);
    RUN_TEST(test_sweep_c172p);
    RUN_TEST(test_sweep_t37);
    RUN_TEST(test_sweep_scheduled);
    RUN_TEST(test_sweep_tilt_cross);
    RUN_TEST(test_sweep_legal_corners);
    RUN_TEST(test_sweep_random_legal_parameters);
    RUN_TEST(test_sweep_corners_any_row);
    RUN_TEST(test_fuzz_regression_rudder_at_scale_32);
    return UNITY_END();
}
