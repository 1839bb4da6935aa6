/*
 * test_param_table.c - the parameter table (include/helical/params.def)
 * against what the library does with it: the defaults, the names, and every
 * bound edge of every row (min and max accepted, one stored step beyond
 * refused, naming the field), through ht_init and ht_dcm_init.
 *
 * The rows are walked through the table itself (a new row is tested without
 * editing this file); the expected numbers below are worked by hand from the
 * formats (Q16 = x 65536, CM = m/s x 100, rounded half away from zero), so a
 * wrong scale, rounding or order in the expansion fails:
 *   law defaults (docs/control-law.md): kp 1 -> 65536; kff, kd 0; v_ref 15 m/s
 *     -> 1500; v_min 5 m/s -> 500; schedule 0; max_tilt 4 -> 262144; pitch 0
 *   law bounds: gains 64 -> 4194304; v_ref, v_min 1 .. 327.67 m/s -> 100 ..
 *     32767 (327.67 * 100 = 32767.000000000004, rounds to 32767); max_tilt
 *     2^-16 .. 8 -> 1 .. 524288
 *   estimator defaults (dcm.h): imu 200 Hz; kp_rollpitch 0.4 * 65536 =
 *     26214.4 -> 26214; ki_rollpitch 0.04 -> 2621.44 -> 2621; kp_yaw 0.5 ->
 *     32768; ki_yaw 0.02 -> 1310.72 -> 1311; bias max 0.1 -> 6553.6 -> 6554;
 *     gyro limit 34.9 -> 2287206.4 -> 2287206; accel limit 16 -> 1048576;
 *     band 0.5 -> 32768; gps min speed 3 m/s -> 300; centripetal 2; 100 ms
 *   estimator bounds: imu 50 .. 1000; gps_min_speed 0 .. 100 m/s -> 0 .. 10000;
 *     accel_band 2^-16 .. 4 -> 1 .. 262144; latency 0 .. 500
 */
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "helical/estimator/dcm.h"
#include "helical/law/helical_turn.h"
#include "unity.h"

void setUp(void) {}

void tearDown(void) {}

/* --- a field by id, from the table (so a new row is covered) --------------- */

/* Write v into the field of id; 0 when v does not fit the field's C type
 * (that edge cannot be expressed in the struct, so it cannot be given). */
#define SET_LAW(id, name, field, unit, fmt, lo, hi, def, desc)                                     \
    case HT_P_##id: {                                                                              \
        const HT_PFMT_TYPE_##fmt t = (HT_PFMT_TYPE_##fmt)v;                                        \
        if ((int64_t)t != v) {                                                                     \
            return 0;                                                                              \
        }                                                                                          \
        p->field = t;                                                                              \
        return 1;                                                                                  \
    }

static int set_law(ht_params_t *p, ht_param_id_t id, int64_t v)
{
    switch (id) {
        HT_PARAMS_LAW(SET_LAW)
    default:
        break;
    }
    return 0;
}

#define SET_DCM(id, name, field, unit, fmt, lo, hi, def, desc)                                     \
    case HT_DCM_P_##id: {                                                                          \
        const HT_PFMT_TYPE_##fmt t = (HT_PFMT_TYPE_##fmt)v;                                        \
        if ((int64_t)t != v) {                                                                     \
            return 0;                                                                              \
        }                                                                                          \
        p->field = t;                                                                              \
        return 1;                                                                                  \
    }

static int set_dcm(ht_dcm_params_t *p, ht_dcm_param_id_t id, int64_t v)
{
    switch (id) {
        HT_PARAMS_DCM(SET_DCM)
    default:
        break;
    }
    return 0;
}

/* --- defaults ---------------------------------------------------------------- */

static void test_law_defaults_are_the_documented_ones(void)
{
    const ht_params_t d = HT_PARAMS_DEFAULT;
    const int32_t expected[14] = {65536, 65536, 65536, 0, 0, 0, 0, 0, 0, 1500, 500, 0, 262144, 0};
    TEST_ASSERT_TRUE(HT_PARAM_LAW_COUNT >= 14); /* these 14, and any row added since */
    TEST_ASSERT_EQUAL_INT(HT_PARAM_LAW_COUNT + 1, HT_P_COUNT);
    TEST_ASSERT_EQUAL_INT32(expected[0], d.kp_aileron);
    TEST_ASSERT_EQUAL_INT32(expected[1], d.kp_elevator);
    TEST_ASSERT_EQUAL_INT32(expected[2], d.kp_rudder);
    TEST_ASSERT_EQUAL_INT32(0, d.kff_aileron | d.kff_elevator | d.kff_rudder);
    TEST_ASSERT_EQUAL_INT32(0, d.kd_aileron | d.kd_elevator | d.kd_rudder);
    TEST_ASSERT_EQUAL_INT32(1500, d.v_ref_cm_s);
    TEST_ASSERT_EQUAL_INT32(500, d.v_min_cm_s);
    TEST_ASSERT_EQUAL_UINT8(0u, d.schedule);
    TEST_ASSERT_EQUAL_INT32(262144, d.max_tilt);
    TEST_ASSERT_EQUAL_UINT8(HT_PITCH_EARTH_FRAME, d.pitch_mode);
    /* the info rows say the same */
    for (int i = 1; i <= 14; ++i) {
        const ht_param_info_t *info = ht_param_info((ht_param_id_t)i);
        TEST_ASSERT_NOT_NULL(info);
        TEST_ASSERT_EQUAL_INT32_MESSAGE(expected[i - 1], info->default_raw, info->name);
    }
    ht_controller_t ctl;
    TEST_ASSERT_EQUAL_INT(HT_OK, ht_init(&ctl, &d, NULL));
}

static void test_estimator_defaults_are_the_documented_ones(void)
{
    ht_dcm_params_t d;
    memset(&d, 0xA5, sizeof d);
    ht_dcm_params_default(&d);
    const int32_t expected[12] = {200,     26214,   2621,  32768, 1311, 6554,
                                  2287206, 1048576, 32768, 300,   2,    100};
    TEST_ASSERT_TRUE(HT_PARAM_DCM_COUNT >= 12);
    TEST_ASSERT_EQUAL_INT(HT_PARAM_DCM_COUNT + 1, HT_DCM_P_COUNT);
    TEST_ASSERT_EQUAL_UINT16(200u, d.imu_rate_hz);
    TEST_ASSERT_EQUAL_INT32(26214, d.kp_rollpitch);
    TEST_ASSERT_EQUAL_INT32(2621, d.ki_rollpitch);
    TEST_ASSERT_EQUAL_INT32(32768, d.kp_yaw);
    TEST_ASSERT_EQUAL_INT32(1311, d.ki_yaw);
    TEST_ASSERT_EQUAL_INT32(6554, d.gyro_bias_max_rad_s);
    TEST_ASSERT_EQUAL_INT32(2287206, d.gyro_limit_rad_s);
    TEST_ASSERT_EQUAL_INT32(1048576, d.accel_limit_g);
    TEST_ASSERT_EQUAL_INT32(32768, d.accel_band_g);
    TEST_ASSERT_EQUAL_INT16(300, d.gps_min_speed_cm_s);
    TEST_ASSERT_EQUAL_UINT8(HT_DCM_CF_AUTO, d.centripetal);
    TEST_ASSERT_EQUAL_UINT16(100u, d.gps_latency_ms);
    for (int i = 1; i <= 12; ++i) {
        const ht_param_info_t *info = ht_dcm_param_info((ht_dcm_param_id_t)i);
        TEST_ASSERT_NOT_NULL(info);
        TEST_ASSERT_EQUAL_INT32_MESSAGE(expected[i - 1], info->default_raw, info->name);
    }
    ht_dcm_t dcm;
    TEST_ASSERT_EQUAL_INT(0, ht_dcm_init(&dcm, &d, NULL));
}

/* --- names ------------------------------------------------------------------- */

static void test_names_are_the_published_ones(void)
{
    static const char *const law[14] = {"kp_aileron",   "kp_elevator", "kp_rudder",  "kff_aileron",
                                        "kff_elevator", "kff_rudder",  "kd_aileron", "kd_elevator",
                                        "kd_rudder",    "v_ref",       "v_min",      "schedule",
                                        "max_tilt",     "pitch_mode"};
    static const char *const dcm[12] = {"imu_rate_hz",   "kp_rollpitch", "ki_rollpitch",
                                        "kp_yaw",        "ki_yaw",       "gyro_bias_max",
                                        "gyro_limit",    "accel_limit",  "accel_band",
                                        "gps_min_speed", "centripetal",  "gps_latency"};
    for (int i = 0; i < 14; ++i) {
        TEST_ASSERT_EQUAL_STRING(law[i], ht_param_name((ht_param_id_t)(i + 1)));
        TEST_ASSERT_EQUAL_STRING(law[i], ht_param_info((ht_param_id_t)(i + 1))->name);
    }
    for (int i = 0; i < 12; ++i) {
        TEST_ASSERT_EQUAL_STRING(dcm[i], ht_dcm_param_name((ht_dcm_param_id_t)(i + 1)));
        TEST_ASSERT_EQUAL_STRING(dcm[i], ht_dcm_param_info((ht_dcm_param_id_t)(i + 1))->name);
    }
    TEST_ASSERT_NULL(ht_param_info(HT_P_NONE));
    TEST_ASSERT_NULL(ht_param_info(HT_P_COUNT));
    TEST_ASSERT_NULL(ht_dcm_param_info(HT_DCM_P_NONE));
    TEST_ASSERT_NULL(ht_dcm_param_info(HT_DCM_P_COUNT));
    TEST_ASSERT_EQUAL_STRING("m/s", ht_param_info(HT_P_V_REF)->unit);
    TEST_ASSERT_EQUAL_STRING("int32 x100", ht_param_info(HT_P_V_REF)->format);
    TEST_ASSERT_EQUAL_STRING("Q16", ht_dcm_param_info(HT_DCM_P_BIAS_MAX)->format);
    TEST_ASSERT_EQUAL_INT32(100, ht_dcm_param_info(HT_DCM_P_GPS_MIN_SPEED)->scale);
    TEST_ASSERT_EQUAL_UINT8(2u, ht_dcm_param_info(HT_DCM_P_GPS_MIN_SPEED)->bytes);
}

/* --- bounds ------------------------------------------------------------------ */

static void test_law_bounds_are_the_headers_limits(void)
{
    for (int i = (int)HT_P_KP_AILERON; i <= (int)HT_P_KD_RUDDER; ++i) {
        TEST_ASSERT_EQUAL_INT32(0, ht_param_info((ht_param_id_t)i)->min_raw);
        TEST_ASSERT_EQUAL_INT32(HT_GAIN_MAX_Q16, ht_param_info((ht_param_id_t)i)->max_raw);
    }
    TEST_ASSERT_EQUAL_INT32(4194304, HT_GAIN_MAX_Q16);
    TEST_ASSERT_EQUAL_INT32(HT_V_MIN_LOWEST_CM_S, ht_param_info(HT_P_V_MIN)->min_raw);
    TEST_ASSERT_EQUAL_INT32(100, ht_param_info(HT_P_V_REF)->min_raw);
    TEST_ASSERT_EQUAL_INT32(HT_V_REF_MAX_CM_S, ht_param_info(HT_P_V_REF)->max_raw);
    TEST_ASSERT_EQUAL_INT32(32767, ht_param_info(HT_P_V_MIN)->max_raw);
    TEST_ASSERT_EQUAL_INT32(1, ht_param_info(HT_P_MAX_TILT)->min_raw);
    TEST_ASSERT_EQUAL_INT32(HT_MAX_TILT_LIMIT_Q16, ht_param_info(HT_P_MAX_TILT)->max_raw);
    TEST_ASSERT_EQUAL_INT32(524288, HT_MAX_TILT_LIMIT_Q16);
}

/* A legal set where field id may sit at value v: the joint limits of
 * v_ref and v_min (v_min <= v_ref <= 32 v_min) follow it. */
static ht_params_t law_with(ht_param_id_t id, int64_t v, int *fits)
{
    ht_params_t p = HT_PARAMS_DEFAULT;
    *fits = set_law(&p, id, v);
    if (id == HT_P_V_REF && v >= 100 && v <= 32767) {
        const int64_t lowest = (v + 31) / 32; /* v_ref <= 32 v_min */
        p.v_min_cm_s = (lowest < 100) ? 100 : (int32_t)lowest;
    }
    if (id == HT_P_V_MIN && v >= 100 && v <= 32767) {
        p.v_ref_cm_s = (int32_t)v;
    }
    return p;
}

static void test_every_law_bound_edge(void)
{
    int checked = 0;
    int skipped = 0;
    for (int i = 1; i < (int)HT_P_COUNT; ++i) {
        const ht_param_id_t id = (ht_param_id_t)i;
        const ht_param_info_t *info = ht_param_info(id);
        const int64_t edges[4] = {info->min_raw, info->max_raw, (int64_t)info->min_raw - 1,
                                  (int64_t)info->max_raw + 1};
        for (int k = 0; k < 4; ++k) {
            int fits = 0;
            const ht_params_t p = law_with(id, edges[k], &fits);
            if (!fits) {
                /* min - 1 of an unsigned field at 0: not expressible */
                TEST_ASSERT_TRUE_MESSAGE(k == 2 && info->min_raw == 0, info->name);
                skipped++;
                continue;
            }
            ht_controller_t ctl;
            ht_param_id_t bad = HT_P_COUNT;
            const ht_status_t st = ht_init(&ctl, &p, &bad);
            char msg[80];
            (void)snprintf(msg, sizeof msg, "%s = %lld", info->name, (long long)edges[k]);
            if (k < 2) {
                TEST_ASSERT_EQUAL_INT_MESSAGE(HT_OK, st, msg);
                TEST_ASSERT_EQUAL_INT_MESSAGE(HT_P_NONE, bad, msg);
            } else {
                TEST_ASSERT_EQUAL_INT_MESSAGE(HT_ERR_PARAM, st, msg);
                TEST_ASSERT_EQUAL_STRING_MESSAGE(info->name, ht_param_name(bad), msg);
                TEST_ASSERT_EQUAL_UINT8_MESSAGE(0u, ctl.ready, msg);
            }
            checked++;
        }
    }
    /* every row's 4 edges, less min - 1 of an unsigned field at 0 (today the
     * two U8 fields: 14 x 4 - 2 = 54 checked) */
    TEST_ASSERT_EQUAL_INT(4 * HT_PARAM_LAW_COUNT, checked + skipped);
    TEST_ASSERT_TRUE(checked >= 54);
}

static void test_every_estimator_bound_edge(void)
{
    int checked = 0;
    int skipped = 0;
    for (int i = 1; i < (int)HT_DCM_P_COUNT; ++i) {
        const ht_dcm_param_id_t id = (ht_dcm_param_id_t)i;
        const ht_param_info_t *info = ht_dcm_param_info(id);
        const int64_t edges[4] = {info->min_raw, info->max_raw, (int64_t)info->min_raw - 1,
                                  (int64_t)info->max_raw + 1};
        for (int k = 0; k < 4; ++k) {
            ht_dcm_params_t p;
            ht_dcm_params_default(&p);
            if (!set_dcm(&p, id, edges[k])) {
                TEST_ASSERT_TRUE_MESSAGE(k == 2 && info->min_raw == 0, info->name);
                skipped++;
                continue;
            }
            ht_dcm_t d;
            ht_dcm_param_id_t bad = HT_DCM_P_COUNT;
            const int rc = ht_dcm_init(&d, &p, &bad);
            char msg[80];
            (void)snprintf(msg, sizeof msg, "%s = %lld", info->name, (long long)edges[k]);
            if (k < 2) {
                TEST_ASSERT_EQUAL_INT_MESSAGE(0, rc, msg);
            } else {
                TEST_ASSERT_EQUAL_INT_MESSAGE(2, rc, msg);
                TEST_ASSERT_EQUAL_STRING_MESSAGE(info->name, ht_dcm_param_name(bad), msg);
            }
            checked++;
        }
    }
    /* every row's 4 edges, less min - 1 of an unsigned field at 0 (today
     * centripetal and gps_latency; imu_rate's min is 50: 12 x 4 - 2 = 46) */
    TEST_ASSERT_EQUAL_INT(4 * HT_PARAM_DCM_COUNT, checked + skipped);
    TEST_ASSERT_TRUE(checked >= 46);
}

/* The joint limits the table cannot state stay in force. */
static void test_joint_limits_are_still_checked(void)
{
    ht_params_t p = HT_PARAMS_DEFAULT;
    ht_controller_t ctl;
    ht_param_id_t bad = HT_P_NONE;
    p.v_ref_cm_s = 499; /* below v_min = 500, each in its own range */
    TEST_ASSERT_EQUAL_INT(HT_ERR_PARAM, ht_init(&ctl, &p, &bad));
    TEST_ASSERT_EQUAL_INT(HT_P_V_REF, bad);
    p.v_ref_cm_s = 16001; /* 32 * 500 = 16000 */
    TEST_ASSERT_EQUAL_INT(HT_ERR_PARAM, ht_init(&ctl, &p, &bad));
    TEST_ASSERT_EQUAL_INT(HT_P_V_REF, bad);
    p.v_ref_cm_s = 16000; /* scale 32: kff 64 * 32 = 2048 > 512 */
    p.kff_rudder = 64 * Q16_ONE;
    TEST_ASSERT_EQUAL_INT(HT_ERR_PARAM, ht_init(&ctl, &p, &bad));
    TEST_ASSERT_EQUAL_INT(HT_P_KFF_RUDDER, bad);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_law_defaults_are_the_documented_ones);
    RUN_TEST(test_estimator_defaults_are_the_documented_ones);
    RUN_TEST(test_names_are_the_published_ones);
    RUN_TEST(test_law_bounds_are_the_headers_limits);
    RUN_TEST(test_every_law_bound_edge);
    RUN_TEST(test_every_estimator_bound_edge);
    RUN_TEST(test_joint_limits_are_still_checked);
    return UNITY_END();
}
