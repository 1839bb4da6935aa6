/* Unit tests of the angle-of-attack and elevator-trim model
 * (include/helical/guidance/aoa_trim.h) against a double-precision reference of its
 * formulas: seeded random sweeps over tilt and airspeed, the int16 edges,
 * knife edge, the speed cut-off, normal and inverted coefficient sets, and
 * the parameter checks. */
#include "unity.h"

#include "helical/guidance/aoa_trim.h"
#include "ht_test_support.h"

#include <math.h>
#include <stddef.h>
#include <stdio.h>

#define PI 3.14159265358979323846

static ht_aoa_params_t prm;
static ht_aoa_t model;

void setUp(void)
{
    ht_aoa_params_t d = HT_AOA_PARAMS_DEFAULT;
    d.enabled = 1u;
    d.v_ref_cm_s = 1500;
    d.v_enable_cm_s = 800;
    d.load_max = 4 * Q16_ONE;
    d.aoa_normal_deg = Q16_FROM_REAL(1.0);
    d.aoa_normal_slope_deg = Q16_FROM_REAL(4.0);
    d.aoa_inverted_deg = Q16_FROM_REAL(-2.0);
    d.aoa_inverted_slope_deg = Q16_FROM_REAL(-5.0);
    d.trim_normal = Q14_FROM_REAL(0.02);
    d.trim_normal_slope = Q14_FROM_REAL(0.05);
    d.trim_inverted = Q14_FROM_REAL(-0.15);
    d.trim_inverted_slope = Q14_FROM_REAL(-0.1);
    prm = d;
    TEST_ASSERT_EQUAL_INT(0, ht_aoa_init(&model, &prm, NULL));
}

void tearDown(void) {}

typedef struct {
    double load, w, aoa, offset, trim;
    int active, inverted;
} ref_t;

/* The model in double, from the header's formulas. */
static ref_t ref_model(const ht_aoa_params_t *p, double x, double z, double v)
{
    ref_t r = {0};
    double lmax = p->load_max / 65536.0;
    double mag = (z == 0.0) ? lmax : fmin(fabs(z) + x * x / fabs(z), lmax);
    r.inverted = z < 0.0;
    r.load = r.inverted ? -mag : mag;
    if (!p->enabled || v < p->v_enable_cm_s / 100.0) {
        return r;
    }
    double vr = p->v_ref_cm_s / 100.0;
    r.w = mag * (vr / v) * (vr / v);
    double a0 = (r.inverted ? p->aoa_inverted_deg : p->aoa_normal_deg) / 65536.0;
    double a1 = (r.inverted ? p->aoa_inverted_slope_deg : p->aoa_normal_slope_deg) / 65536.0;
    r.aoa = (a0 + a1 * r.w) * PI / 180.0;
    r.offset = r.aoa * z;
    double t0 = (r.inverted ? p->trim_inverted : p->trim_normal) / 16384.0;
    double t1 = (r.inverted ? p->trim_inverted_slope : p->trim_normal_slope) / 16384.0;
    r.trim = fmax(-1.0, fmin(1.0, t0 + t1 * r.w));
    r.active = 1;
    return r;
}

static double worst_load, worst_w, worst_aoa, worst_off, worst_trim;

static void check_one(q14_t x, q14_t z, int16_t v)
{
    ht_aoa_output_t o;
    ht_aoa_step(&model, x, z, v, &o);
    ref_t r = ref_model(&prm, x / 16384.0, z / 16384.0, v / 100.0);
    /* load: X^2/|Z| is rounded to Q14 before the Q16 scale: 2^-14 + 2^-16 */
    double el = fabs(o.load / 65536.0 - r.load);
    double ew = fabs(o.loading / 65536.0 - r.w);
    double ea = fabs(o.aoa_rad / 65536.0 - r.aoa);
    double eo = fabs(o.pitch_offset / 65536.0 - r.offset);
    double et = fabs(o.elevator_trim / 16384.0 - r.trim);
    worst_load = fmax(worst_load, el);
    worst_w = fmax(worst_w, ew);
    worst_aoa = fmax(worst_aoa, ea);
    worst_off = fmax(worst_off, eo);
    worst_trim = fmax(worst_trim, et);
    char msg[160];
    snprintf(msg, sizeof msg, "x=%d z=%d v=%d load %.6f/%.6f w %.6f/%.6f", x, z, v,
             o.load / 65536.0, r.load, o.loading / 65536.0, r.w);
    TEST_ASSERT_TRUE_MESSAGE(el <= 1.0 / 16384 + 1.0 / 65536, msg);
    double r2 = pow(prm.v_ref_cm_s / (double)(v > 0 ? v : 1), 2.0);
    TEST_ASSERT_TRUE_MESSAGE(ew <= (1.0 / 16384 + 1.0 / 65536) * r2 + 8.0 / 65536, msg);
    /* the slope is converted to rad in Q16 at init: 1/2 LSB per unit of w */
    TEST_ASSERT_TRUE_MESSAGE(ea <= 0.1 * ew + (r.w + 4.0) / 65536, msg);
    TEST_ASSERT_TRUE_MESSAGE(eo <= ea * 2.0 + fabs(r.aoa) / 16384 + 2.0 / 65536, msg);
    TEST_ASSERT_TRUE_MESSAGE(et <= 0.15 * ew + 2.0 / 16384, msg);
    TEST_ASSERT_EQUAL_INT(r.active, o.active);
    TEST_ASSERT_EQUAL_INT(r.inverted, o.inverted);
}

static void test_random_sweep_against_reference(void)
{
    uint64_t seed = 0x5eed0a0aULL;
    worst_load = worst_w = worst_aoa = worst_off = worst_trim = 0.0;
    for (int i = 0; i < 200000; i++) {
        /* a random tilt (bank, pitch) and, one in four, any int16 pair */
        q14_t x, z;
        if (i % 4 == 3) {
            x = (q14_t)(int32_t)(ts_rng_next(&seed) & 0xFFFF);
            z = (q14_t)(int32_t)(ts_rng_next(&seed) & 0xFFFF);
        } else {
            double bank = ts_uniform(&seed, -PI, PI);
            double pitch = ts_uniform(&seed, -1.2, 1.2);
            x = ts_fix16(-sin(bank) * cos(pitch), 14);
            z = ts_fix16(cos(bank) * cos(pitch), 14);
        }
        int16_t v = (int16_t)ts_uniform(&seed, -100.0, 6000.0);
        check_one(x, z, v);
    }
    printf("aoa sweep: worst load %.2e, w %.2e, aoa %.2e rad, offset %.2e, trim %.2e\n", worst_load,
           worst_w, worst_aoa, worst_off, worst_trim);
}

static void test_level_bank_60_exact_load_2(void)
{
    /* 60 deg right bank: X = -sin 60, Z = cos 60: load = 1 / cos 60 = 2. */
    ht_aoa_output_t o;
    ht_aoa_step(&model, Q14_FROM_REAL(-0.8660254), Q14_FROM_REAL(0.5), 1500, &o);
    TEST_ASSERT_INT32_WITHIN(8, 2 * Q16_ONE, o.load);
    TEST_ASSERT_INT32_WITHIN(8, 2 * Q16_ONE, o.loading); /* at v_ref */
    /* aoa = 1 + 4 * 2 = 9 deg; offset = 9 deg * 0.5; trim = 0.02 + 0.05 * 2 */
    TEST_ASSERT_INT32_WITHIN(8, (int32_t)lround(9.0 * PI / 180.0 * 65536.0), o.aoa_rad);
    TEST_ASSERT_INT32_WITHIN(8, (int32_t)lround(4.5 * PI / 180.0 * 65536.0), o.pitch_offset);
    TEST_ASSERT_INT16_WITHIN(2, Q14_FROM_REAL(0.12), o.elevator_trim);
    /* the same bank at half v_ref: loading * 4 */
    ht_aoa_step(&model, Q14_FROM_REAL(-0.8660254), Q14_FROM_REAL(0.5), 750, &o);
    TEST_ASSERT_EQUAL_UINT8(0u, o.active); /* below v_enable = 8 m/s: off */
    TEST_ASSERT_EQUAL_INT32(0, o.pitch_offset);
    TEST_ASSERT_EQUAL_INT16(0, o.elevator_trim);
    ht_aoa_step(&model, Q14_FROM_REAL(-0.8660254), Q14_FROM_REAL(0.5), 800, &o);
    TEST_ASSERT_EQUAL_UINT8(1u, o.active); /* exactly v_enable: on */
}

static void test_inverted_level_uses_inverted_set(void)
{
    ht_aoa_output_t o;
    ht_aoa_step(&model, 0, -Q14_ONE, 1500, &o);
    TEST_ASSERT_EQUAL_INT32(-Q16_ONE, o.load);
    TEST_ASSERT_EQUAL_INT32(Q16_ONE, o.loading);
    TEST_ASSERT_EQUAL_UINT8(1u, o.inverted);
    /* aoa = -2 - 5 = -7 deg (body frame); offset = -7 deg * -1 = +7 deg: nose up */
    TEST_ASSERT_INT32_WITHIN(4, (int32_t)lround(-7.0 * PI / 180.0 * 65536.0), o.aoa_rad);
    TEST_ASSERT_INT32_WITHIN(4, (int32_t)lround(7.0 * PI / 180.0 * 65536.0), o.pitch_offset);
    TEST_ASSERT_INT16_WITHIN(2, Q14_FROM_REAL(-0.25), o.elevator_trim);
    /* upright level: +1 deg + 4 deg, nose up too */
    ht_aoa_step(&model, 0, Q14_ONE, 1500, &o);
    TEST_ASSERT_INT32_WITHIN(4, (int32_t)lround(5.0 * PI / 180.0 * 65536.0), o.pitch_offset);
}

static void test_knife_edge_and_int16_edges_saturate(void)
{
    ht_aoa_output_t o;
    const q14_t vals[] = {INT16_MIN, -Q14_ONE, -1, 0, 1, Q14_ONE, INT16_MAX};
    const int16_t speeds[] = {INT16_MIN, -1, 0, 799, 800, 1500, INT16_MAX};
    for (unsigned i = 0; i < 7u; i++) {
        for (unsigned j = 0; j < 7u; j++) {
            for (unsigned k = 0; k < 7u; k++) {
                check_one(vals[i], vals[j], speeds[k]);
                ht_aoa_step(&model, vals[i], vals[j], speeds[k], &o);
                TEST_ASSERT_TRUE(o.load <= 4 * Q16_ONE && o.load >= -4 * Q16_ONE);
                TEST_ASSERT_TRUE(o.elevator_trim <= Q14_ONE && o.elevator_trim >= -Q14_ONE);
            }
        }
    }
    ht_aoa_step(&model, Q14_ONE, 0, 1500, &o); /* 90 deg bank: the limit */
    TEST_ASSERT_EQUAL_INT32(4 * Q16_ONE, o.load);
    ht_aoa_step(&model, Q14_ONE, 1, 1500, &o);
    TEST_ASSERT_EQUAL_INT32(4 * Q16_ONE, o.load);
    ht_aoa_step(&model, Q14_ONE, -1, 1500, &o);
    TEST_ASSERT_EQUAL_INT32(-4 * Q16_ONE, o.load);
    /* V = INT16_MAX: loading tiny but defined */
    ht_aoa_step(&model, 0, Q14_ONE, INT16_MAX, &o);
    TEST_ASSERT_INT32_WITHIN(2, (int32_t)lround(65536.0 * pow(1500.0 / 32767.0, 2)), o.loading);
}

static void test_load_is_from_tilt_only(void)
{
    /* The load depends on X and Z only (no accelerometer input exists): a
     * pull-up that would read 3 g on an accelerometer reads 1 g here at
     * wings level, so the AoA offset cannot feed back on itself. */
    ht_aoa_output_t a, b;
    ht_aoa_step(&model, 0, Q14_ONE, 1500, &a);
    ht_aoa_step(&model, 0, Q14_ONE, 1500, &b);
    TEST_ASSERT_EQUAL_INT32(Q16_ONE, a.load);
    TEST_ASSERT_EQUAL_MEMORY(&a, &b, sizeof a);
}

static void test_disabled_and_null(void)
{
    ht_aoa_params_t p = prm;
    p.enabled = 0u;
    ht_aoa_t m;
    TEST_ASSERT_EQUAL_INT(0, ht_aoa_init(&m, &p, NULL));
    ht_aoa_output_t o;
    ht_aoa_step(&m, 0, Q14_ONE, 1500, &o);
    TEST_ASSERT_EQUAL_UINT8(0u, o.active);
    TEST_ASSERT_EQUAL_INT32(0, o.pitch_offset);
    TEST_ASSERT_EQUAL_INT16(0, o.elevator_trim);
    ht_aoa_step(NULL, 0, Q14_ONE, 1500, &o);
    TEST_ASSERT_EQUAL_INT32(0, o.load);
    ht_aoa_step(&model, 0, Q14_ONE, 1500, NULL); /* no crash */
    TEST_ASSERT_EQUAL_INT(1, ht_aoa_init(NULL, &p, NULL));
    TEST_ASSERT_EQUAL_INT(1, ht_aoa_init(&m, NULL, NULL));
}

static void test_init_names_each_bad_field(void)
{
    for (int f = 1; f < (int)HT_AOA_P_COUNT; f++) {
        ht_aoa_params_t b = prm;
        switch ((ht_aoa_param_id_t)f) {
        case HT_AOA_P_ENABLED:
            b.enabled = 2u;
            break;
        case HT_AOA_P_V_REF:
            b.v_ref_cm_s = 99;
            break;
        case HT_AOA_P_V_ENABLE:
            b.v_enable_cm_s = 187;
            break; /* 1500 > 8 * 187 */
        case HT_AOA_P_LOAD_MAX:
            b.load_max = Q16_ONE - 1;
            break;
        case HT_AOA_P_AOA_NORMAL:
            b.aoa_normal_deg = 45 * Q16_ONE + 1;
            break;
        case HT_AOA_P_AOA_NORMAL_SLOPE:
            b.aoa_normal_slope_deg = -45 * Q16_ONE - 1;
            break;
        case HT_AOA_P_AOA_INVERTED:
            b.aoa_inverted_deg = 46 * Q16_ONE;
            break;
        case HT_AOA_P_AOA_INVERTED_SLOPE:
            b.aoa_inverted_slope_deg = INT32_MIN;
            break;
        case HT_AOA_P_TRIM_NORMAL:
            b.trim_normal = Q14_ONE + 1;
            break;
        case HT_AOA_P_TRIM_NORMAL_SLOPE:
            b.trim_normal_slope = INT16_MIN;
            break;
        case HT_AOA_P_TRIM_INVERTED:
            b.trim_inverted = -Q14_ONE - 1;
            break;
        default:
            b.trim_inverted_slope = INT16_MAX;
            break;
        }
        ht_aoa_param_id_t bad = HT_AOA_P_NONE;
        ht_aoa_t m;
        TEST_ASSERT_EQUAL_INT(2, ht_aoa_init(&m, &b, &bad));
        TEST_ASSERT_EQUAL_INT(f, (int)bad);
        TEST_ASSERT_TRUE(ht_aoa_param_name(bad)[0] != 0);
        TEST_ASSERT_EQUAL_UINT8(0u, m.ready);
    }
    TEST_ASSERT_EQUAL_STRING("v_enable_m_s", ht_aoa_param_name(HT_AOA_P_V_ENABLE));
    TEST_ASSERT_EQUAL_STRING("", ht_aoa_param_name(HT_AOA_P_COUNT));
    ht_aoa_params_t e = prm;
    e.v_enable_cm_s = 188; /* 8 * 188 >= 1500: allowed */
    e.load_max = 8 * Q16_ONE;
    TEST_ASSERT_EQUAL_INT(0, ht_aoa_init(&model, &e, NULL));
    prm = e;
    check_one(Q14_ONE, 1, 188); /* the largest loading: 8 * (1500/188)^2 */
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_random_sweep_against_reference);
    RUN_TEST(test_level_bank_60_exact_load_2);
    RUN_TEST(test_inverted_level_uses_inverted_set);
    RUN_TEST(test_knife_edge_and_int16_edges_saturate);
    RUN_TEST(test_load_is_from_tilt_only);
    RUN_TEST(test_disabled_and_null);
    RUN_TEST(test_init_names_each_bad_field);
    return UNITY_END();
}
