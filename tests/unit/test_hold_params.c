/*
 * test_hold_params.c - the holds' rows of the parameter table
 * (params.def HT_PARAMS_ALT, HT_PARAMS_SPEED) against what holds.h does with
 * them: the defaults, the names, every bound edge of every row (min and max
 * accepted, one stored step beyond refused and named), the joint limits and
 * the step rate, and the modes' refusal naming the field.
 *
 * The expected numbers are worked by hand from the formats (Q16 x 65536,
 * Q14 x 16384, CM32 x 100, MS16 x 1000; halves away from zero):
 *   altitude hold: kp 0.03 -> 1966.08 -> 1966; ki 0.005 -> 327.68 -> 328;
 *     kd 0.05 -> 3276.8 -> 3277; max_pitch 0.3 -> 19660.8 -> 19661;
 *     max_integral 0.2 -> 13107.2 -> 13107; max_error 1000 m -> 100000 cm;
 *     band 10 m -> 1000 cm; protect, valid, kv, tau 0
 *   airspeed hold: trim 0.5 -> 8192; min 0; max 1 -> 16384; kp 0.1 ->
 *     6553.6 -> 6554; ki 0.02 -> 1310.72 -> 1311; kff 0.5 -> 32768;
 *     max_integral 0.5 -> 8192
 *   bounds: max_pitch 2^-16 .. 4 -> 1 .. 262144; max_error 1 .. 10000 m ->
 *     100 .. 1000000 cm; protect 0 .. 327.67 m/s -> 0 .. 32767 cm/s; tau
 *     0 .. 60 s -> 0 .. 60000 ms; throttle 0 .. 1 -> 0 .. 16384
 */
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "helical/guidance/holds.h"
#include "helical/guidance/modes.h"
#include "unity.h"

void setUp(void) {}

void tearDown(void) {}

/* Write v into the field of id; 0 when v does not fit the field's C type. */
#define SET_FIELD(prefix, id, field, fmt)                                                          \
    case prefix##id: {                                                                             \
        const HT_PFMT_TYPE_##fmt t = (HT_PFMT_TYPE_##fmt)v;                                        \
        if ((int64_t)t != v) {                                                                     \
            return 0;                                                                              \
        }                                                                                          \
        p->field = t;                                                                              \
        return 1;                                                                                  \
    }
#define SET_ALT(id, name, field, unit, fmt, lo, hi, def, desc) SET_FIELD(HT_ALT_P_, id, field, fmt)
#define SET_SPEED(id, name, field, unit, fmt, lo, hi, def, desc)                                   \
    SET_FIELD(HT_SPEED_P_, id, field, fmt)

static int set_alt(ht_alt_hold_params_t *p, ht_alt_param_id_t id, int64_t v)
{
    switch (id) {
        HT_PARAMS_ALT(SET_ALT)
    default:
        break;
    }
    return 0;
}

static int set_speed(ht_speed_hold_params_t *p, ht_speed_param_id_t id, int64_t v)
{
    switch (id) {
        HT_PARAMS_SPEED(SET_SPEED)
    default:
        break;
    }
    return 0;
}

static void test_alt_defaults_are_the_documented_ones(void)
{
    ht_alt_hold_params_t d;
    memset(&d, 0xA5, sizeof d);
    ht_alt_hold_params_default(&d, 40u);
    const int32_t expected[11] = {1966, 328, 3277, 19661, 13107, 100000, 1000, 0, 0, 0, 0};
    TEST_ASSERT_EQUAL_INT(11, HT_PARAM_ALT_COUNT);
    TEST_ASSERT_EQUAL_INT32(1966, d.kp_pitch_per_m);
    TEST_ASSERT_EQUAL_INT32(328, d.ki_pitch_per_m_s);
    TEST_ASSERT_EQUAL_INT32(3277, d.kd_pitch_per_m_s);
    TEST_ASSERT_EQUAL_INT32(19661, d.max_pitch);
    TEST_ASSERT_EQUAL_INT32(13107, d.max_integral_pitch);
    TEST_ASSERT_EQUAL_INT32(100000, d.max_error_cm);
    TEST_ASSERT_EQUAL_INT32(1000, d.integral_band_cm);
    TEST_ASSERT_EQUAL_INT32(0, d.protect_cm_s | d.protect_valid_cm_s | d.kv_pitch_per_m_s);
    TEST_ASSERT_EQUAL_UINT16(0u, d.protect_tau_ms);
    TEST_ASSERT_EQUAL_UINT16(40u, d.rate_hz);
    for (int i = 1; i < (int)HT_ALT_P_COUNT; ++i) {
        const ht_param_info_t *info = ht_alt_hold_param_info((ht_alt_param_id_t)i);
        TEST_ASSERT_NOT_NULL(info);
        TEST_ASSERT_EQUAL_INT32_MESSAGE(expected[i - 1], info->default_raw, info->name);
    }
    TEST_ASSERT_EQUAL_INT(HT_HOLD_OK, ht_alt_hold_check(&d));
}

static void test_speed_defaults_are_the_documented_ones(void)
{
    ht_speed_hold_params_t d;
    memset(&d, 0xA5, sizeof d);
    ht_speed_hold_params_default(&d, 50u);
    const int32_t expected[7] = {8192, 0, 16384, 6554, 1311, 32768, 8192};
    TEST_ASSERT_EQUAL_INT(7, HT_PARAM_SPEED_COUNT);
    TEST_ASSERT_EQUAL_INT16(8192, d.throttle_trim);
    TEST_ASSERT_EQUAL_INT16(0, d.throttle_min);
    TEST_ASSERT_EQUAL_INT16(16384, d.throttle_max);
    TEST_ASSERT_EQUAL_INT32(6554, d.kp_throttle_per_m_s);
    TEST_ASSERT_EQUAL_INT32(1311, d.ki_throttle_per_m);
    TEST_ASSERT_EQUAL_INT32(32768, d.kff_throttle_per_pitch);
    TEST_ASSERT_EQUAL_INT16(8192, d.max_integral_throttle);
    TEST_ASSERT_EQUAL_UINT16(50u, d.rate_hz);
    for (int i = 1; i < (int)HT_SPEED_P_COUNT; ++i) {
        const ht_param_info_t *info = ht_speed_hold_param_info((ht_speed_param_id_t)i);
        TEST_ASSERT_NOT_NULL(info);
        TEST_ASSERT_EQUAL_INT32_MESSAGE(expected[i - 1], info->default_raw, info->name);
    }
    TEST_ASSERT_EQUAL_INT(HT_HOLD_OK, ht_speed_hold_check(&d));
}

static void test_names_are_the_scenario_keys(void)
{
    static const char *const alt[11] = {"alt_kp",
                                        "alt_ki",
                                        "alt_kd",
                                        "alt_max_pitch",
                                        "alt_max_integral",
                                        "alt_max_error_m",
                                        "alt_integral_band_m",
                                        "alt_protect_m_s",
                                        "alt_protect_valid_m_s",
                                        "alt_kv",
                                        "alt_protect_tau_s"};
    static const char *const spd[7] = {"throttle_trim",   "throttle_min", "throttle_max",
                                       "spd_kp",          "spd_ki",       "spd_kff_pitch",
                                       "spd_max_integral"};
    for (int i = 0; i < 11; ++i) {
        TEST_ASSERT_EQUAL_STRING(alt[i], ht_alt_hold_param_name((ht_alt_param_id_t)(i + 1)));
    }
    for (int i = 0; i < 7; ++i) {
        TEST_ASSERT_EQUAL_STRING(spd[i], ht_speed_hold_param_name((ht_speed_param_id_t)(i + 1)));
    }
    TEST_ASSERT_EQUAL_STRING("rate_hz", ht_alt_hold_param_name(HT_ALT_P_RATE_HZ));
    TEST_ASSERT_EQUAL_STRING("rate_hz", ht_speed_hold_param_name(HT_SPEED_P_RATE_HZ));
    TEST_ASSERT_EQUAL_STRING("", ht_alt_hold_param_name(HT_ALT_P_NONE));
    TEST_ASSERT_EQUAL_STRING("", ht_speed_hold_param_name((ht_speed_param_id_t)99));
    TEST_ASSERT_NULL(ht_alt_hold_param_info(HT_ALT_P_RATE_HZ));
    TEST_ASSERT_NULL(ht_speed_hold_param_info(HT_SPEED_P_RATE_HZ));
}

/* Parameters that leave every field free to reach its own bounds: the joint
 * partners at their widest (band 0 under the largest error, valid 0 under
 * the largest protection, throttle 0 .. 1). */
static void permissive_alt(ht_alt_hold_params_t *p)
{
    ht_alt_hold_params_default(p, 40u);
    p->max_error_cm = 1000000;
    p->integral_band_cm = 0;
    p->protect_cm_s = 32767;
    p->protect_valid_cm_s = 0;
}

static void test_every_alt_bound_edge(void)
{
    int checked = 0;
    for (int i = 1; i < (int)HT_ALT_P_COUNT; ++i) {
        const ht_alt_param_id_t id = (ht_alt_param_id_t)i;
        const ht_param_info_t *info = ht_alt_hold_param_info(id);
        const int64_t edges[4] = {info->min_raw, info->max_raw, (int64_t)info->min_raw - 1,
                                  (int64_t)info->max_raw + 1};
        for (int k = 0; k < 4; ++k) {
            ht_alt_hold_params_t p;
            permissive_alt(&p);
            if (!set_alt(&p, id, edges[k])) {
                TEST_ASSERT_TRUE_MESSAGE(k == 2 && info->min_raw == 0, info->name);
                continue;
            }
            char msg[80];
            (void)snprintf(msg, sizeof msg, "%s = %lld", info->name, (long long)edges[k]);
            const ht_alt_param_id_t bad = ht_alt_hold_first_bad(&p);
            TEST_ASSERT_EQUAL_STRING_MESSAGE((k < 2) ? "" : info->name, ht_alt_hold_param_name(bad),
                                             msg);
            TEST_ASSERT_EQUAL_INT_MESSAGE((k < 2) ? HT_HOLD_OK : HT_HOLD_ERR_PARAM,
                                          ht_alt_hold_check(&p), msg);
            checked++;
        }
    }
    /* 11 rows x 4, less min - 1 of the unsigned protect_tau (min 0) */
    TEST_ASSERT_EQUAL_INT(43, checked);
}

static void test_every_speed_bound_edge(void)
{
    int checked = 0;
    for (int i = 1; i < (int)HT_SPEED_P_COUNT; ++i) {
        const ht_speed_param_id_t id = (ht_speed_param_id_t)i;
        const ht_param_info_t *info = ht_speed_hold_param_info(id);
        const int64_t edges[4] = {info->min_raw, info->max_raw, (int64_t)info->min_raw - 1,
                                  (int64_t)info->max_raw + 1};
        for (int k = 0; k < 4; ++k) {
            ht_speed_hold_params_t p;
            ht_speed_hold_params_default(&p, 40u);
            TEST_ASSERT_TRUE(set_speed(&p, id, edges[k])); /* all fit their types */
            char msg[80];
            (void)snprintf(msg, sizeof msg, "%s = %lld", info->name, (long long)edges[k]);
            const ht_speed_param_id_t bad = ht_speed_hold_first_bad(&p);
            /* throttle_max at its minimum 0 is legal alone and against min 0 */
            TEST_ASSERT_EQUAL_STRING_MESSAGE((k < 2) ? "" : info->name,
                                             ht_speed_hold_param_name(bad), msg);
            checked++;
        }
    }
    TEST_ASSERT_EQUAL_INT(28, checked);
}

static void test_joint_limits_and_rate(void)
{
    ht_alt_hold_params_t a;
    ht_alt_hold_params_default(&a, 40u);
    a.integral_band_cm = a.max_error_cm + 1; /* each in its own range */
    TEST_ASSERT_EQUAL_INT(HT_ALT_P_INTEGRAL_BAND, ht_alt_hold_first_bad(&a));
    a.integral_band_cm = a.max_error_cm;
    TEST_ASSERT_EQUAL_INT(HT_ALT_P_NONE, ht_alt_hold_first_bad(&a));
    a.protect_cm_s = 1000;
    a.protect_valid_cm_s = 1001;
    TEST_ASSERT_EQUAL_INT(HT_ALT_P_PROTECT_VALID, ht_alt_hold_first_bad(&a));
    a.protect_valid_cm_s = 1000;
    TEST_ASSERT_EQUAL_INT(HT_ALT_P_NONE, ht_alt_hold_first_bad(&a));
    a.rate_hz = 0u;
    TEST_ASSERT_EQUAL_INT(HT_ALT_P_RATE_HZ, ht_alt_hold_first_bad(&a));
    a.rate_hz = 1001u;
    TEST_ASSERT_EQUAL_INT(HT_ALT_P_RATE_HZ, ht_alt_hold_first_bad(&a));
    a.rate_hz = 1000u;
    TEST_ASSERT_EQUAL_INT(HT_ALT_P_NONE, ht_alt_hold_first_bad(&a));

    ht_speed_hold_params_t s;
    ht_speed_hold_params_default(&s, 40u);
    s.throttle_min = 8000;
    s.throttle_max = 7999;
    TEST_ASSERT_EQUAL_INT(HT_SPEED_P_THROTTLE_MAX, ht_speed_hold_first_bad(&s));
    s.throttle_max = 8000;
    TEST_ASSERT_EQUAL_INT(HT_SPEED_P_NONE, ht_speed_hold_first_bad(&s));
    s.rate_hz = 0u;
    TEST_ASSERT_EQUAL_INT(HT_SPEED_P_RATE_HZ, ht_speed_hold_first_bad(&s));
}

/* ht_modes_init names the hold's field (and a rate that is not the modes'). */
static void test_modes_refusal_names_the_field(void)
{
    ht_params_t lp = HT_PARAMS_DEFAULT;
    ht_controller_t ctl;
    TEST_ASSERT_EQUAL_INT(HT_OK, ht_init(&ctl, &lp, NULL));
    ht_modes_params_t p;
    ht_modes_params_default(&p);
    ht_modes_t m;
    ht_modes_bad_t bad;
    char name[64];
    TEST_ASSERT_EQUAL_INT(0, ht_modes_init(&m, &p, &ctl, NULL, 0u, &bad));

    p.alt.kd_pitch_per_m_s = -1;
    TEST_ASSERT_EQUAL_INT(2, ht_modes_init(&m, &p, &ctl, NULL, 0u, &bad));
    ht_modes_bad_name(&bad, name, (unsigned)sizeof name);
    TEST_ASSERT_EQUAL_STRING("alt.alt_kd", name);

    ht_modes_params_default(&p);
    p.speed.rate_hz = 41u; /* legal alone, not the modes' 40 Hz */
    TEST_ASSERT_EQUAL_INT(2, ht_modes_init(&m, &p, &ctl, NULL, 0u, &bad));
    ht_modes_bad_name(&bad, name, (unsigned)sizeof name);
    TEST_ASSERT_EQUAL_STRING("speed.rate_hz", name);

    ht_modes_params_default(&p);
    p.speed.throttle_max = (q14_t)(Q14_ONE + 1);
    TEST_ASSERT_EQUAL_INT(2, ht_modes_init(&m, &p, &ctl, NULL, 0u, &bad));
    ht_modes_bad_name(&bad, name, (unsigned)sizeof name);
    TEST_ASSERT_EQUAL_STRING("speed.throttle_max", name);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_alt_defaults_are_the_documented_ones);
    RUN_TEST(test_speed_defaults_are_the_documented_ones);
    RUN_TEST(test_names_are_the_scenario_keys);
    RUN_TEST(test_every_alt_bound_edge);
    RUN_TEST(test_every_speed_bound_edge);
    RUN_TEST(test_joint_limits_and_rate);
    RUN_TEST(test_modes_refusal_names_the_field);
    return UNITY_END();
}
