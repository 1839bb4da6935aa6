/*
 * The law's options beyond the seed (docs/control-law.md "Extensions beyond
 * the seed"; src/law/ht_options.c): roll-in, sideslip rudder, vertical fade.
 *
 *  - Off is the seed, bit for bit: with every option off, whatever the other
 *    option parameters and the option inputs, every output equals the
 *    default controller's (random sweeps, fixed seeds); with the options on
 *    and their inputs neutral, the surfaces are the seed's too.
 *  - On, against the double reference (tests/reference/ht_reference.c,
 *    extended by each option's equation): random sweeps with fixed seeds over
 *    the gain sets and the legal corners, inputs balanced so that the
 *    surfaces are mostly unsaturated, each output within its stated LSB
 *    bound (the core's own: 2 LSB for the surfaces, 1 LSB for Q14 values,
 *    0.51 LSB for Q11 rates).
 *  - Edges: every input at INT16_MIN / INT16_MAX, zero airspeed, a vertical
 *    fuselage, saturation of each option.
 *  - Signs and meaning: the sideslip rudder yaws toward the lateral force;
 *    the roll-in's damping is against the target's rotation (a roll at the
 *    target's bank rate is not resisted); the fade makes the aileron
 *    continuous across a vertical fuselage under sign-flipping noise and
 *    bounded by it.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ht_reference.h"
#include "ht_test_support.h"
#include "unity.h"

#define STEPS 100000L
#define PI    3.14159265358979323846

/* The bounds of test_ht_reference_sweep, and the options' own outputs. */
#define LIMIT_ANGLES_LSB   1.0
#define LIMIT_RATES_LSB    0.51
#define LIMIT_SURFACES_LSB 2.0

void setUp(void) {}
void tearDown(void) {}

static void step(const ht_controller_t *c, const ht_input_t *in, ht_output_t *out)
{
    memset(out, 0, sizeof *out); /* padding: the comparisons are whole-struct */
    ht_step(c, in, out);
}

/* A random input as the reference sweep draws it, plus the options' inputs
 * and, one time in four, a fuselage near the vertical (sqrt(X^2 + Z^2) below
 * 0.1, where the fade acts). */
static void random_input(uint64_t *rng, ht_input_t *in, int wide)
{
    memset(in, 0, sizeof *in);
    double v[3], n = 0.0;
    for (int i = 0; i < 3; i++) {
        v[i] = ts_gaussian(rng);
        n += v[i] * v[i];
    }
    n = sqrt(n);
    if (ts_uniform(rng, 0, 1) < 0.25) {
        const double a = ts_uniform(rng, 0.0, 0.1), th = ts_uniform(rng, -PI, PI);
        v[0] = a * sin(th);
        v[2] = a * cos(th);
        v[1] = ((ts_rng_next(rng) & 1u) ? 1.0 : -1.0) * sqrt(1.0 - a * a);
        n = 1.0;
    }
    const double scale = (ts_uniform(rng, 0, 1) < 0.5) ? 1.0 : ts_uniform(rng, 0.97, 1.03);
    in->x = ts_fix16(v[0] / n * scale, 14);
    in->y = ts_fix16(v[1] / n * scale, 14);
    in->z = ts_fix16(v[2] / n * scale, 14);
    in->turn_rate_rad_s = ts_fix16(ts_uniform(rng, wide ? -10 : -1, wide ? 10 : 1), 11);
    in->airspeed_cm_s = (int16_t)lround(ts_uniform(rng, 0, 6000));
    in->pitch_ratio = ts_fix32(ts_uniform(rng, wide ? -10 : -1, wide ? 10 : 1), 16);
    for (int i = 0; i < 3; i++) {
        in->gyro_rad_s[i] = ts_fix16(ts_uniform(rng, -2, 2), 11);
    }
    in->inverted = (uint8_t)(ts_rng_next(rng) & 1u);
    in->turn_accel_rad_s2 = ts_fix16(ts_uniform(rng, wide ? -16 : -2, wide ? 16 : 2), 11);
    in->accel_lat_g = ts_fix16(ts_uniform(rng, wide ? -2 : -0.3, wide ? 2 : 0.3), 14);
}

/* ------------------------------------------------------------------------ */
/* Off is the seed. */

static void test_options_off_is_the_default_controller_bit_for_bit(void)
{
    uint64_t rng = 0x0FF0FF00u;
    long compared = 0;
    for (int set = 0; set < ts_gain_set_count; set++) {
        ht_controller_t seed, off;
        TEST_ASSERT_EQUAL_INT(HT_OK, ht_init(&seed, &ts_gain_sets[set].params, NULL));
        /* the options off, their other parameters anywhere in range */
        ht_params_t p = ts_gain_sets[set].params;
        p.roll_in = 0u;
        p.roll_in_rate_max_rad_s = 5 * Q16_ONE;
        p.kp_sideslip = 0;
        p.vertical_fade = 0;
        TEST_ASSERT_EQUAL_INT(HT_OK, ht_init(&off, &p, NULL));
        for (long k = 0; k < STEPS / 4; k++) {
            ht_input_t in;
            random_input(&rng, &in, (int)(k & 1));
            ht_input_t zero_opt = in; /* what a caller of the seed's law gives */
            zero_opt.turn_accel_rad_s2 = 0;
            zero_opt.accel_lat_g = 0;
            ht_output_t a, b;
            step(&seed, &zero_opt, &a);
            step(&off, &in, &b);
            TEST_ASSERT_EQUAL_MEMORY(&a, &b, sizeof a);
            TEST_ASSERT_EQUAL_INT16(0, b.roll_in_rate_rad_s);
            TEST_ASSERT_EQUAL_INT16(Q14_ONE, b.roll_fade);
            TEST_ASSERT_EQUAL_INT16(0, b.sideslip_rudder);
            compared++;
        }
    }
    printf("options off = the default controller, bit for bit: %ld steps\n", compared);
}

/* Each option on, with its input neutral (no turn acceleration, no lateral
 * force, the fuselage at least vertical_fade from the vertical): the
 * surfaces are the seed's, bit for bit -- but the rudder with kp_sideslip
 * on, whose demand is then summed in a wider format before its one rounding
 * (room for the sideslip term): within 1 LSB of the seed's. */
static void test_options_on_with_neutral_inputs_are_the_seed(void)
{
    uint64_t rng = 0x0E0E0E0Eu;
    long compared = 0;
    int worst_rudder = 0;
    for (int set = 0; set < ts_gain_set_count; set++) {
        ht_controller_t seed, on;
        TEST_ASSERT_EQUAL_INT(HT_OK, ht_init(&seed, &ts_gain_sets[set].params, NULL));
        ht_params_t p = ts_gain_sets[set].params;
        p.roll_in = 1u;
        p.roll_in_rate_max_rad_s = 3 * Q16_ONE;
        p.kp_sideslip = 20 * Q16_ONE;
        p.vertical_fade = Q16_ONE / 10;
        TEST_ASSERT_EQUAL_INT(HT_OK, ht_init(&on, &p, NULL));
        for (long k = 0; k < STEPS / 4; k++) {
            ht_input_t in;
            random_input(&rng, &in, (int)(k & 1));
            in.turn_accel_rad_s2 = 0;
            in.accel_lat_g = 0;
            const double a = sqrt((double)in.x * in.x + (double)in.z * in.z) / 16384.0;
            if (a < 0.1) {
                continue;
            }
            ht_output_t o1, o2;
            step(&seed, &in, &o1);
            step(&on, &in, &o2);
            TEST_ASSERT_EQUAL_INT16(o1.aileron, o2.aileron);
            TEST_ASSERT_EQUAL_INT16(o1.elevator, o2.elevator);
            TEST_ASSERT_INT_WITHIN(1, o1.rudder, o2.rudder);
            worst_rudder = (abs(o1.rudder - o2.rudder) > worst_rudder) ? abs(o1.rudder - o2.rudder)
                                                                       : worst_rudder;
            TEST_ASSERT_EQUAL_INT16(o1.roll_error, o2.roll_error);
            const uint8_t sat = (uint8_t)HT_F_SURFACE_SATURATED; /* the rudder's 1 LSB */
            TEST_ASSERT_EQUAL_UINT8(o1.flags & ~sat, o2.flags & ~sat);
            compared++;
        }
    }
    printf("options on, inputs neutral: %ld steps, surfaces the seed's (rudder within %d LSB)\n",
           compared, worst_rudder);
    TEST_ASSERT_GREATER_THAN(STEPS / 2, compared);
}

/* ------------------------------------------------------------------------ */
/* On, against the double reference. */

typedef struct {
    ts_err_t errs[TS_N_OUTPUTS];
    ts_err_t roll_in, fade, sideslip;
    long steps, skipped, unsaturated[3], faded, roll_in_limited, roll_in_active;
} stats_t;

static void stats_init(stats_t *st)
{
    memset(st, 0, sizeof *st);
    ts_errs_init(st->errs);
    st->roll_in = (ts_err_t){"roll_in_rate", 1.0 / 2048.0, 0.0, 0};
    st->fade = (ts_err_t){"roll_fade", 1.0 / 16384.0, 0.0, 0};
    st->sideslip = (ts_err_t){"sideslip_rudder", 1.0 / 16384.0, 0.0, 0};
}

/* Solve each axis' gyro so that the reference demand lands in [-1.2, 1.2]
 * (test_ht_reference_sweep's balance): the error then shows at the full
 * amplification of the gains instead of hiding behind the clamp. */
static void balance_gyros(uint64_t *rng, const ht_ref_params_t *rp, ht_input_t *in)
{
    ht_ref_input_t ri;
    ht_ref_output_t ro;
    ht_ref_input_from_fixed(in, &ri);
    ht_ref_step(rp, &ri, &ro);
    const double s = (ri.airspeed > rp->v_min) ? ri.airspeed : rp->v_min;
    const double s_p = rp->schedule ? rp->v_ref / s : 1.0;
    for (int i = 0; i < 3; i++) {
        const double k = rp->kd[i] * s_p;
        const double u = ts_uniform(rng, -1.2, 1.2);
        if (k > 0.0) {
            in->gyro_rad_s[i] = ts_fix16(ri.gyro[i] + (ro.demand[i] - u) / k, 11);
        }
    }
}

static void sweep(const ht_params_t *params, uint64_t seed, long steps, stats_t *st)
{
    ht_controller_t ctl;
    ht_param_id_t bad = HT_P_NONE;
    TEST_ASSERT_EQUAL_INT_MESSAGE(HT_OK, ht_init(&ctl, params, &bad), ht_param_name(bad));
    ht_ref_params_t rp;
    ht_ref_params_from_controller(&ctl, &rp);
    uint64_t rng = seed;
    for (long k = 0; k < steps; k++) {
        ht_input_t in;
        random_input(&rng, &in, (int)(k & 1));
        balance_gyros(&rng, &rp, &in);
        ht_output_t out;
        step(&ctl, &in, &out);
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
        st->faded += (out.flags & HT_F_ROLL_FADED) != 0;
        st->roll_in_limited += (out.flags & HT_F_ROLL_IN_LIMITED) != 0;
        st->roll_in_active += out.roll_in_rate_rad_s != 0;
        ts_errs_add_step(st->errs, &out, &ro);
        ts_err_add(&st->roll_in, out.roll_in_rate_rad_s / 2048.0, ro.roll_in_rate);
        ts_err_add(&st->fade, out.roll_fade / 16384.0, ro.roll_fade);
        const double ss = fmax(-2.0, fmin(32767.0 / 16384.0, ro.sideslip_rudder));
        ts_err_add(&st->sideslip, out.sideslip_rudder / 16384.0, ss);
    }
}

static int report(const char *title, const stats_t *st)
{
    int ok = 1;
    ts_errs_print(title, st->errs);
    const ts_err_t *opt[3] = {&st->roll_in, &st->fade, &st->sideslip};
    const double opt_limit[3] = {LIMIT_RATES_LSB, LIMIT_ANGLES_LSB, LIMIT_RATES_LSB};
    for (int i = 0; i < 3; i++) {
        printf("  %-15s %6.2f LSB\n", opt[i]->name, opt[i]->worst);
        if (opt[i]->worst > opt_limit[i]) {
            printf("  FAIL %s: %.2f LSB > %.2f\n", opt[i]->name, opt[i]->worst, opt_limit[i]);
            ok = 0;
        }
    }
    printf("  unsaturated X/Y/Z: %ld / %ld / %ld of %ld; faded %ld, roll-in active %ld "
           "(limited %ld); skipped on a branch boundary: %ld\n",
           st->unsaturated[0], st->unsaturated[1], st->unsaturated[2], st->steps, st->faded,
           st->roll_in_active, st->roll_in_limited, st->skipped);
    ok &= st->skipped <= st->steps / 100;
    for (int i = 0; i < TS_N_OUTPUTS; i++) {
        const int is_rate = (i == 0 || (i >= 4 && i <= 6));
        const int is_surface = (i >= 13);
        const double limit =
            is_rate ? LIMIT_RATES_LSB : (is_surface ? LIMIT_SURFACES_LSB : LIMIT_ANGLES_LSB);
        if (st->errs[i].worst > limit) {
            printf("  FAIL %s: %.2f LSB > %.1f\n", st->errs[i].name, st->errs[i].worst, limit);
            ok = 0;
        }
    }
    return ok;
}

static ht_params_t with_options(ht_params_t p, q16_t rate_max, q16_t kp_ss, q16_t fade)
{
    p.roll_in = 1u;
    p.roll_in_rate_max_rad_s = rate_max;
    p.kp_sideslip = kp_ss;
    p.vertical_fade = fade;
    return p;
}

/* The gain sets of the reference sweep with every option on. */
static void test_options_on_match_the_reference_gain_sets(void)
{
    int failed = 0;
    for (int set = 0; set < ts_gain_set_count; set++) {
        stats_t st;
        stats_init(&st);
        const ht_params_t p = with_options(ts_gain_sets[set].params, 2 * Q16_ONE,
                                           Q16_FROM_REAL(1.5), Q16_FROM_REAL(0.05));
        sweep(&p, 0x0B7100u + (uint64_t)set, STEPS, &st);
        failed |= !report(ts_gain_sets[set].name, &st);
        TEST_ASSERT_GREATER_THAN(STEPS / 10, st.faded);
        TEST_ASSERT_GREATER_THAN(STEPS / 10, st.roll_in_active);
        TEST_ASSERT_GREATER_THAN(STEPS / 100, st.roll_in_limited);
        for (int i = 0; i < 3; i++) {
            TEST_ASSERT_GREATER_THAN(STEPS / 20, st.unsaturated[i]);
        }
    }
    TEST_ASSERT_FALSE(failed);
}

/* The legal corners with the options at theirs: the largest rate gain (512)
 * times the largest roll-in bound (8 rad/s), kp_sideslip 64, the smallest
 * and the largest fade. */
static void test_options_on_match_the_reference_legal_corners(void)
{
    const q16_t g = HT_GAIN_MAX_Q16;
    const int32_t v_hi = HT_V_REF_MAX_CM_S;
    const int32_t v_min_32 = (v_hi + HT_SCALE_MAX - 1) / HT_SCALE_MAX;
    const q16_t r8 = HT_ROLL_IN_RATE_LIMIT_Q16;
    const struct {
        const char *name;
        ht_params_t p;
    } corners[] = {
        {"options at their limits; kp 64, kff 8, kd 8, schedule, scale 32",
         with_options(
             ts_gains3(g, 8 * Q16_ONE, 8 * Q16_ONE, v_hi, v_min_32, 1, HT_MAX_TILT_LIMIT_Q16, 0),
             r8, g, Q16_ONE)},
        {"options at their limits; kp 64, kff 14, kd 64, no schedule, scale 32",
         with_options(ts_gains3(g, 14 * Q16_ONE, g, v_hi, v_min_32, 0, HT_MAX_TILT_LIMIT_Q16, 0),
                      r8, g, 1)},
        {"options at their limits; kp 64, kff 1, kd 15, schedule, scale 32, tilt cross",
         with_options(
             ts_gains3(g, Q16_ONE, 15 * Q16_ONE, v_hi, v_min_32, 1, HT_MAX_TILT_LIMIT_Q16, 1), r8,
             g, Q16_FROM_REAL(0.01))},
        {"options: roll-in bound 1 LSB, fade 0.5; all gains 64, schedule, scale 4",
         with_options(ts_gains3(g, g, g, v_hi, (v_hi + 3) / 4, 1, HT_MAX_TILT_LIMIT_Q16, 0), 1,
                      Q16_ONE, Q16_ONE / 2)},
        {"options: kp 1, kff 0, kd 1, sideslip 0.5, fade 0.1, v_ref = v_min = 1 m/s",
         with_options(ts_gains3(Q16_ONE, 0, Q16_ONE, 100, 100, 0, HT_MAX_TILT_LIMIT_Q16, 0),
                      Q16_ONE, Q16_ONE / 2, Q16_ONE / 10)},
    };
    const int n = (int)(sizeof corners / sizeof corners[0]);
    int failed = 0;
    for (int c = 0; c < n; c++) {
        stats_t st;
        stats_init(&st);
        sweep(&corners[c].p, 0xC0B7E000u + (uint64_t)c, STEPS, &st);
        failed |= !report(corners[c].name, &st);
        for (int i = 0; i < 3; i++) {
            TEST_ASSERT_GREATER_THAN(STEPS / 20, st.unsaturated[i]);
        }
    }
    TEST_ASSERT_FALSE(failed);
}

/* ------------------------------------------------------------------------ */
/* Edges. */

static void assert_bounded(const ht_output_t *o)
{
    TEST_ASSERT_TRUE(o->aileron >= -Q14_ONE && o->aileron <= Q14_ONE);
    TEST_ASSERT_TRUE(o->elevator >= -Q14_ONE && o->elevator <= Q14_ONE);
    TEST_ASSERT_TRUE(o->rudder >= -Q14_ONE && o->rudder <= Q14_ONE);
    TEST_ASSERT_TRUE(o->roll_fade >= 0 && o->roll_fade <= Q14_ONE);
}

/* Every input at either end of its range, every option at its largest,
 * every gain set: bounded outputs, the flags of what happened. */
static void test_extreme_inputs_with_options_on(void)
{
    const int16_t ends[2] = {INT16_MIN, INT16_MAX};
    for (int set = 0; set < ts_gain_set_count; set++) {
        ht_controller_t c;
        const ht_params_t p = with_options(ts_gain_sets[set].params, HT_ROLL_IN_RATE_LIMIT_Q16,
                                           HT_GAIN_MAX_Q16, Q16_ONE);
        TEST_ASSERT_EQUAL_INT(HT_OK, ht_init(&c, &p, NULL));
        for (unsigned bits = 0u; bits < 512u; bits++) {
            ht_input_t in;
            memset(&in, 0, sizeof in);
            in.x = ends[bits & 1u];
            in.y = ends[(bits >> 1) & 1u];
            in.z = ends[(bits >> 2) & 1u];
            in.turn_rate_rad_s = ends[(bits >> 3) & 1u];
            in.pitch_ratio = ((bits >> 4) & 1u) ? INT32_MAX : INT32_MIN;
            in.airspeed_cm_s = ends[(bits >> 5) & 1u];
            in.gyro_rad_s[0] = in.gyro_rad_s[1] = in.gyro_rad_s[2] = ends[(bits >> 6) & 1u];
            in.turn_accel_rad_s2 = ends[(bits >> 7) & 1u];
            in.accel_lat_g = ends[(bits >> 8) & 1u];
            in.inverted = (uint8_t)(bits & 1u);
            ht_output_t out;
            step(&c, &in, &out);
            assert_bounded(&out);
            /* the sideslip term is 64 * 2 g, beyond its output's format */
            TEST_ASSERT_EQUAL_INT16((in.accel_lat_g > 0) ? INT16_MAX : INT16_MIN,
                                    out.sideslip_rudder);
            /* a row of +/-2 is far from the vertical */
            TEST_ASSERT_EQUAL_INT16(Q14_ONE, out.roll_fade);
        }
    }
}

/* The roll-in at zero airspeed uses the floor v_min (as the tilt does), and
 * its value and bound are those of the equation. */
static void test_roll_in_zero_airspeed_and_bound(void)
{
    ht_params_t p = HT_PARAMS_DEFAULT; /* v_min 5 m/s */
    p.roll_in = 1u;
    p.roll_in_rate_max_rad_s = 8 * Q16_ONE;
    ht_controller_t c;
    TEST_ASSERT_EQUAL_INT(HT_OK, ht_init(&c, &p, NULL));
    ht_input_t in;
    memset(&in, 0, sizeof in);
    in.z = Q14_ONE;
    in.airspeed_cm_s = 0;
    in.turn_accel_rad_s2 = Q11_FROM_REAL(1.0);
    ht_output_t out;
    step(&c, &in, &out);
    /* wings level, no turn: 1 rad/s^2 * 5 m/s / g = 0.5099 rad/s */
    TEST_ASSERT_INT_WITHIN(1, (int)lround(5.0 / 9.80665 * 2048.0), out.roll_in_rate_rad_s);
    TEST_ASSERT_TRUE((out.flags & HT_F_AIRSPEED_FLOORED) != 0);
    TEST_ASSERT_FALSE((out.flags & HT_F_ROLL_IN_LIMITED) != 0);
    /* in a turn of ratio 1 (45 degrees) the bank moves at half that */
    in.turn_rate_rad_s = Q11_FROM_REAL(9.80665 / 5.0);
    step(&c, &in, &out);
    TEST_ASSERT_INT_WITHIN(2, (int)lround(0.5 * 5.0 / 9.80665 * 2048.0), out.roll_in_rate_rad_s);
    /* the bound */
    p.roll_in_rate_max_rad_s = Q16_FROM_REAL(0.25);
    TEST_ASSERT_EQUAL_INT(HT_OK, ht_init(&c, &p, NULL));
    in.turn_rate_rad_s = 0;
    in.turn_accel_rad_s2 = INT16_MIN;
    step(&c, &in, &out);
    TEST_ASSERT_EQUAL_INT16(-512, out.roll_in_rate_rad_s);
    TEST_ASSERT_TRUE((out.flags & HT_F_ROLL_IN_LIMITED) != 0);
    /* the tilt limit holds the target: no bank rate */
    in.turn_rate_rad_s = INT16_MAX;
    step(&c, &in, &out);
    TEST_ASSERT_TRUE((out.flags & HT_F_TILT_LIMITED) != 0);
    TEST_ASSERT_EQUAL_INT16(0, out.roll_in_rate_rad_s);
    /* a bound of 0 is a roll-in that adds nothing */
    p.roll_in_rate_max_rad_s = 0;
    TEST_ASSERT_EQUAL_INT(HT_OK, ht_init(&c, &p, NULL));
    in.turn_rate_rad_s = 0;
    step(&c, &in, &out);
    TEST_ASSERT_EQUAL_INT16(0, out.roll_in_rate_rad_s);
}

/* The rows' ranges are checked like every row's, naming the row. */
static void test_option_rows_are_range_checked(void)
{
    ht_params_t p = HT_PARAMS_DEFAULT;
    ht_controller_t c;
    ht_param_id_t bad = HT_P_NONE;
    p.roll_in = 2u;
    TEST_ASSERT_EQUAL_INT(HT_ERR_PARAM, ht_init(&c, &p, &bad));
    TEST_ASSERT_EQUAL_STRING("roll_in", ht_param_name(bad));
    p = (ht_params_t)HT_PARAMS_DEFAULT;
    p.roll_in_rate_max_rad_s = HT_ROLL_IN_RATE_LIMIT_Q16 + 1;
    TEST_ASSERT_EQUAL_INT(HT_ERR_PARAM, ht_init(&c, &p, &bad));
    TEST_ASSERT_EQUAL_STRING("roll_in_rate_max", ht_param_name(bad));
    p = (ht_params_t)HT_PARAMS_DEFAULT;
    p.kp_sideslip = -1;
    TEST_ASSERT_EQUAL_INT(HT_ERR_PARAM, ht_init(&c, &p, &bad));
    TEST_ASSERT_EQUAL_STRING("kp_sideslip", ht_param_name(bad));
    p = (ht_params_t)HT_PARAMS_DEFAULT;
    p.vertical_fade = Q16_ONE + 1;
    TEST_ASSERT_EQUAL_INT(HT_ERR_PARAM, ht_init(&c, &p, &bad));
    TEST_ASSERT_EQUAL_STRING("vertical_fade", ht_param_name(bad));
    p.vertical_fade = Q16_ONE; /* both ends legal */
    TEST_ASSERT_EQUAL_INT(HT_OK, ht_init(&c, &p, &bad));
    p.vertical_fade = 1;
    TEST_ASSERT_EQUAL_INT(HT_OK, ht_init(&c, &p, &bad));
}

/* ------------------------------------------------------------------------ */
/* Signs and meaning. */

/* Frames (helical_turn.h): X = left wing, rudder + yaws the nose right. A
 * sideslip with the relative wind from the right (the nose left of the
 * flight path: a slip in a right turn, the ball to the right) pushes the
 * fuselage left: specific force toward +X. Right rudder removes it. */
static void test_sideslip_rudder_yaws_toward_the_lateral_force(void)
{
    ht_params_t p = HT_PARAMS_DEFAULT;
    p.kp_sideslip = Q16_FROM_REAL(2.0);
    ht_controller_t c;
    TEST_ASSERT_EQUAL_INT(HT_OK, ht_init(&c, &p, NULL));
    ht_input_t in;
    memset(&in, 0, sizeof in);
    in.z = Q14_ONE;
    in.airspeed_cm_s = 1500;
    in.accel_lat_g = Q14_FROM_REAL(0.1);
    ht_output_t out;
    step(&c, &in, &out);
    /* 2 * 0.1 g (1638 LSB), level, no turn: nothing else */
    TEST_ASSERT_EQUAL_INT16(2 * Q14_FROM_REAL(0.1), out.rudder);
    TEST_ASSERT_EQUAL_INT16(2 * Q14_FROM_REAL(0.1), out.sideslip_rudder);
    in.accel_lat_g = -in.accel_lat_g;
    in.inverted = 1u; /* body-frame force, body-frame rudder: inverted alike */
    step(&c, &in, &out);
    TEST_ASSERT_EQUAL_INT16(-2 * Q14_FROM_REAL(0.1), out.sideslip_rudder);
}

/* The roll-in asks for a right roll when the turn command grows to the right
 * (aileron +), and its damping is against the target's rotation: rolling at
 * the target's own bank rate costs no aileron, where the seed's damping
 * (against Eq. 3 alone, which at wings level asks for no roll) resists it. */
static void test_roll_in_damps_against_the_target_rotation(void)
{
    ht_params_t p = HT_PARAMS_DEFAULT;
    p.kp_aileron = Q16_FROM_REAL(2.0);
    p.kff_aileron = 0;
    p.kd_aileron = Q16_FROM_REAL(0.5);
    ht_controller_t seed, on;
    TEST_ASSERT_EQUAL_INT(HT_OK, ht_init(&seed, &p, NULL));
    p.roll_in = 1u;
    p.roll_in_rate_max_rad_s = 2 * Q16_ONE;
    TEST_ASSERT_EQUAL_INT(HT_OK, ht_init(&on, &p, NULL));
    ht_input_t in;
    memset(&in, 0, sizeof in);
    in.z = Q14_ONE; /* wings level at the start of a right turn entry */
    in.airspeed_cm_s = 2000;
    in.turn_rate_rad_s = Q11_FROM_REAL(0.05);
    in.turn_accel_rad_s2 = Q11_FROM_REAL(0.5); /* bank rate 0.5 * 20 / g / (1 + r^2) */
    ht_output_t o_seed, o_on;
    step(&seed, &in, &o_seed);
    step(&on, &in, &o_on);
    TEST_ASSERT_GREATER_THAN(0, o_on.roll_in_rate_rad_s);
    TEST_ASSERT_GREATER_THAN(o_seed.aileron, o_on.aileron);
    /* rolling right at the target's bank rate: the seed damps it, roll-in does not */
    in.gyro_rad_s[1] = o_on.roll_in_rate_rad_s;
    ht_output_t d_seed, d_on;
    step(&seed, &in, &d_seed);
    step(&on, &in, &d_on);
    TEST_ASSERT_LESS_THAN(o_seed.aileron, d_seed.aileron);
    const double kp_only = 2.0 * (o_on.roll_error / 16384.0) * -1.0; /* -kp * e */
    /* -kp * e (e rounded to Q14: 1 LSB after kp = 2), and kd times the Q11
     * rounding of the gyro (0.5 * 2^-12: 2 LSB) */
    TEST_ASSERT_INT_WITHIN(3, (int)lround(kp_only * 16384.0), d_on.aileron);
}

/* Near a vertical fuselage (sqrt(X^2 + Z^2) -> 0, a vertical climb) the
 * target is wings level and the noise of X and Z flips the side the roll
 * is on: Eq. 9 then gives +/-1 (roll_dot <= 0) and the seed's aileron is
 * bang-bang at +/-kp. With vertical_fade the roll error's contribution is at
 * most kp * sqrt(X^2 + Z^2) / vertical_fade, so the aileron is continuous
 * (it goes to 0 with the distance from the vertical) and bounded by the
 * fade. The pitch error drives the elevator and rudder only. */
static void test_fade_makes_the_aileron_continuous_across_the_vertical(void)
{
    ht_params_t p = HT_PARAMS_DEFAULT;
    p.kp_aileron = Q16_FROM_REAL(1.0);
    ht_controller_t seed, fade;
    TEST_ASSERT_EQUAL_INT(HT_OK, ht_init(&seed, &p, NULL));
    p.vertical_fade = Q16_FROM_REAL(0.1);
    TEST_ASSERT_EQUAL_INT(HT_OK, ht_init(&fade, &p, NULL));
    uint64_t rng = 0xF1F1F1u;
    int seed_flips = 0, seed_full = 0;
    q14_t prev_seed = 0, prev_fade = 0;
    double prev_a = 0.0;
    double worst_ratio = 0.0;
    for (int k = 0; k < 20000; k++) {
        /* the fuselage sweeps through the vertical (a from 0.2 down to 0
         * and up again) with sign-flipping noise of 3 mrad on X and Z */
        const double a_path = fabs(0.2 * (1.0 - 2.0 * k / 19999.0));
        const double x = a_path * 0.3 + 0.003 * ts_gaussian(&rng);
        const double z = -a_path * 0.95 + 0.003 * ts_gaussian(&rng);
        ht_input_t in;
        memset(&in, 0, sizeof in);
        in.x = ts_fix16(x, 14);
        in.z = ts_fix16(z, 14);
        in.y = ts_fix16(-sqrt(fmax(0.0, 1.0 - x * x - z * z)), 14); /* nose up */
        in.airspeed_cm_s = 1500;
        in.pitch_ratio = Q16_FROM_REAL(0.0);
        ht_output_t os, of;
        step(&seed, &in, &os);
        step(&fade, &in, &of);
        const double a = sqrt((double)in.x * in.x + (double)in.z * in.z) / 16384.0;
        /* the seed: full aileron whenever the roll is beyond 90 degrees */
        seed_full += (os.aileron == Q14_ONE || os.aileron == -Q14_ONE);
        if (k > 0 && (os.aileron > 0) != (prev_seed > 0)) {
            seed_flips++;
        }
        /* the fade: |aileron| <= kp * a / fade (+1 LSB of rounding) */
        const double bound = 1.0 * a / 0.1;
        TEST_ASSERT_TRUE(fabs(of.aileron / 16384.0) <= fmin(1.0, bound) + 1.0 / 16384.0);
        if (a > 0.0) {
            worst_ratio = fmax(worst_ratio, fabs(of.aileron / 16384.0) / fmin(1.0, bound));
        }
        if (a < 0.1) {
            TEST_ASSERT_TRUE((of.flags & HT_F_ROLL_FADED) != 0);
        }
        /* continuity: a step of the noise moves the aileron by at most
         * kp * (a1 + a2) / fade, which vanishes at the vertical (the seed's
         * moves by 2 kp) */
        if (k > 0) {
            const double jump = fabs((double)of.aileron - (double)prev_fade) / 16384.0;
            TEST_ASSERT_TRUE(jump <= 1.0 * (a + prev_a) / 0.1 + 2.0 / 16384.0);
        }
        prev_seed = os.aileron;
        prev_fade = of.aileron;
        prev_a = a;
    }
    printf("vertical sweep: seed %d samples at full aileron, %d sign flips; "
           "fade worst |aileron| / bound %.3f\n",
           seed_full, seed_flips, worst_ratio);
    /* the seed's chatter is real in this sweep (else the test shows nothing) */
    TEST_ASSERT_GREATER_THAN(100, seed_flips);
    TEST_ASSERT_GREATER_THAN(1000, seed_full);
    /* exactly vertical: no roll authority, flagged */
    ht_input_t v;
    memset(&v, 0, sizeof v);
    v.y = -Q14_ONE;
    v.airspeed_cm_s = 1500;
    ht_output_t ov;
    step(&fade, &v, &ov);
    TEST_ASSERT_EQUAL_INT16(0, ov.roll_fade);
    TEST_ASSERT_EQUAL_INT16(0, ov.roll_error);
    TEST_ASSERT_EQUAL_INT16(0, ov.aileron);
    TEST_ASSERT_TRUE((ov.flags & HT_F_ROLL_FADED) != 0);
    TEST_ASSERT_TRUE((ov.flags & HT_F_FUSELAGE_VERTICAL) != 0);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_options_off_is_the_default_controller_bit_for_bit);
    RUN_TEST(test_options_on_with_neutral_inputs_are_the_seed);
    RUN_TEST(test_options_on_match_the_reference_gain_sets);
    RUN_TEST(test_options_on_match_the_reference_legal_corners);
    RUN_TEST(test_extreme_inputs_with_options_on);
    RUN_TEST(test_roll_in_zero_airspeed_and_bound);
    RUN_TEST(test_option_rows_are_range_checked);
    RUN_TEST(test_sideslip_rudder_yaws_toward_the_lateral_force);
    RUN_TEST(test_roll_in_damps_against_the_target_rotation);
    RUN_TEST(test_fade_makes_the_aileron_continuous_across_the_vertical);
    return UNITY_END();
}
