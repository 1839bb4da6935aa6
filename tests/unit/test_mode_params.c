/*
 * test_mode_params.c - the flight modes' rows of the parameter table
 * (params.def HT_PARAMS_MODES, HT_PARAMS_FBW, HT_PARAMS_NAV, HT_PARAMS_AOA)
 * against ht_modes_init: the defaults, and every bound edge of every row
 * (min and max accepted, one stored step beyond refused, the refusal naming
 * the field as "fbw.deadband_us", "nav.l1_m", "aoa.v_ref_m_s" or, for the
 * modes' own rows, "rc_loss_ticks"), and the AoA model's joint limit.
 *
 * Worked defaults (the formats: CM16 m/s x 100, Q16 x 65536, Q14 x 16384):
 * cruise 15 m/s -> 1500 cm/s; pitch slew 1 -> 65536; fbw pitch_max 0.5 ->
 * 32768; nav v_floor 5 m/s -> 500, course_min 2 m/s -> 200; aoa v_ref 15 m/s
 * -> 1500, v_enable 8 m/s -> 800, load_max 4 -> 262144.
 */
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "helical/guidance/modes.h"
#include "unity.h"

void setUp(void) {}

void tearDown(void) {}

#define SET_FIELD(prefix, obj, id, field, fmt)                                                     \
    case prefix##id: {                                                                             \
        const HT_PFMT_TYPE_##fmt t = (HT_PFMT_TYPE_##fmt)v;                                        \
        if ((int64_t)t != v) {                                                                     \
            return 0;                                                                              \
        }                                                                                          \
        p->obj field = t;                                                                          \
        return 1;                                                                                  \
    }
#define SET_MODES(id, name, field, unit, fmt, lo, hi, def, desc)                                   \
    SET_FIELD(HT_MODES_P_, , id, field, fmt)
#define SET_FBW(id, name, field, unit, fmt, lo, hi, def, desc)                                     \
    SET_FIELD(HT_FBW_P_, fbw., id, field, fmt)
#define SET_NAV(id, name, field, unit, fmt, lo, hi, def, desc)                                     \
    SET_FIELD(HT_NAV_P_, nav., id, field, fmt)
#define SET_AOA(id, name, field, unit, fmt, lo, hi, def, desc)                                     \
    SET_FIELD(HT_AOA_P_, aoa., id, field, fmt)

enum { GROUP_MODES, GROUP_FBW, GROUP_NAV, GROUP_AOA, GROUP_COUNT };

/* Row id of a group into p; 0 when v does not fit the field's type. */
static int set_row(ht_modes_params_t *p, int group, int id, int64_t v)
{
    switch (group) {
    case GROUP_MODES:
        switch ((ht_modes_param_id_t)id) {
            HT_PARAMS_MODES(SET_MODES)
        default:
            break;
        }
        break;
    case GROUP_FBW:
        switch ((ht_fbw_param_id_t)id) {
            HT_PARAMS_FBW(SET_FBW)
        default:
            break;
        }
        break;
    case GROUP_NAV:
        switch ((ht_nav_param_id_t)id) {
            HT_PARAMS_NAV(SET_NAV)
        default:
            break;
        }
        break;
    default:
        switch ((ht_aoa_param_id_t)id) {
            HT_PARAMS_AOA(SET_AOA)
        default:
            break;
        }
        break;
    }
    return 0;
}

static const ht_param_info_t *row_info(int group, int id)
{
    switch (group) {
    case GROUP_MODES:
        return ht_modes_param_info((ht_modes_param_id_t)id);
    case GROUP_FBW:
        return ht_fbw_param_info((ht_fbw_param_id_t)id);
    case GROUP_NAV:
        return ht_nav_param_info((ht_nav_param_id_t)id);
    default:
        return ht_aoa_param_info((ht_aoa_param_id_t)id);
    }
}

static const int counts[GROUP_COUNT] = {HT_PARAM_MODES_COUNT, HT_PARAM_FBW_COUNT,
                                        HT_PARAM_NAV_COUNT, HT_PARAM_AOA_COUNT};
static const char *const prefixes[GROUP_COUNT] = {"", "fbw.", "nav.", "aoa."};

static ht_controller_t ctl;

/* The defaults with the AoA model's joint partners at their widest (v_ref
 * at its minimum, v_enable at its maximum), so each row reaches its edges. */
static void permissive(ht_modes_params_t *p)
{
    ht_modes_params_default(p);
    p->aoa.v_ref_cm_s = 100;
    p->aoa.v_enable_cm_s = 32767;
    /* the sticks away from the switches' rows' edges (inputs 0 and 15) and
     * full travel to 2500 us, so that each switch row's edge meets no joint
     * rule (config_check.h) but the threshold's 800 us, at or below centre */
    p->rc.aileron.input = 6u;
    p->rc.elevator.input = 7u;
    p->rc.throttle.input = 8u;
    p->rc.rudder.input = 9u;
    p->rc.aileron.travel_us = 1000u;
}

static void test_defaults_are_the_documented_ones(void)
{
    ht_modes_params_t p;
    memset(&p, 0xA5, sizeof p);
    ht_modes_params_default(&p);
    TEST_ASSERT_EQUAL_UINT8(4u, p.mode_input);
    TEST_ASSERT_EQUAL_UINT16(20u, p.rc_loss_ticks);
    TEST_ASSERT_EQUAL_UINT16(20u, p.rc_recover_ticks);
    TEST_ASSERT_EQUAL_UINT16(20u, p.blend_ticks);
    TEST_ASSERT_EQUAL_INT16(180, p.turn_slew_deg_s2);
    TEST_ASSERT_EQUAL_INT32(65536, p.pitch_slew_per_s);
    TEST_ASSERT_EQUAL_INT16(1500, p.cruise_cm_s);
    TEST_ASSERT_EQUAL_UINT16(8u, p.fbw.deadband_us);
    TEST_ASSERT_EQUAL_INT16(60, p.fbw.turn_rate_max_deg_s);
    TEST_ASSERT_EQUAL_INT32(32768, p.fbw.pitch_max);
    TEST_ASSERT_EQUAL_UINT8(5u, p.fbw.inverted_input);
    TEST_ASSERT_EQUAL_UINT16(1750u, p.fbw.inverted_threshold_us);
    TEST_ASSERT_EQUAL_UINT8(16u, p.rc_channels);
    TEST_ASSERT_EQUAL_UINT8(HT_GUIDE_HEADING, p.nav.law);
    TEST_ASSERT_EQUAL_UINT16(60u, p.nav.l1_m);
    TEST_ASSERT_EQUAL_UINT16(20u, p.nav.arrival_radius_m);
    TEST_ASSERT_EQUAL_UINT16(60u, p.nav.loiter_radius_m);
    TEST_ASSERT_EQUAL_INT32(100, p.nav.home_alt_m);
    TEST_ASSERT_EQUAL_INT16(500, p.nav.v_floor_cm_s);
    TEST_ASSERT_EQUAL_INT16(200, p.nav.course_min_cm_s);
    TEST_ASSERT_EQUAL_UINT8(1u, p.nav.loop);
    TEST_ASSERT_EQUAL_UINT8(0u, p.aoa.enabled);
    TEST_ASSERT_EQUAL_INT16(1500, p.aoa.v_ref_cm_s);
    TEST_ASSERT_EQUAL_INT16(800, p.aoa.v_enable_cm_s);
    TEST_ASSERT_EQUAL_INT32(262144, p.aoa.load_max);
    TEST_ASSERT_EQUAL_INT32(0, p.aoa.aoa_normal_deg | p.aoa.trim_inverted_slope);
    /* the info rows say the same, and the defaults are accepted */
    TEST_ASSERT_EQUAL_INT32(1500, ht_modes_param_info(HT_MODES_P_CRUISE)->default_raw);
    TEST_ASSERT_EQUAL_INT32(500, ht_nav_param_info(HT_NAV_P_V_FLOOR)->default_raw);
    TEST_ASSERT_EQUAL_INT32(800, ht_aoa_param_info(HT_AOA_P_V_ENABLE)->default_raw);
    ht_modes_t m;
    TEST_ASSERT_EQUAL_INT(0, ht_modes_init(&m, &p, &ctl, NULL, 0u, NULL));
}

static void test_every_bound_edge_is_checked_and_named(void)
{
    int checked = 0;
    int skipped = 0;
    for (int g = 0; g < GROUP_COUNT; ++g) {
        for (int id = 1; id <= counts[g]; ++id) {
            const ht_param_info_t *info = row_info(g, id);
            TEST_ASSERT_NOT_NULL(info);
            const int64_t edges[4] = {info->min_raw, info->max_raw, (int64_t)info->min_raw - 1,
                                      (int64_t)info->max_raw + 1};
            for (int k = 0; k < 4; ++k) {
                ht_modes_params_t p;
                permissive(&p);
                if (!set_row(&p, g, id, edges[k])) {
                    /* only a step beyond a bound at its C type's own limit */
                    TEST_ASSERT_TRUE_MESSAGE((k == 2 && info->min_raw == 0) ||
                                                 (k == 3 && info->max_raw == INT16_MAX),
                                             info->name);
                    skipped++;
                    continue;
                }
                char msg[96];
                (void)snprintf(msg, sizeof msg, "%s%s = %lld", prefixes[g], info->name,
                               (long long)edges[k]);
                ht_modes_t m;
                ht_modes_bad_t bad;
                const int rc = ht_modes_init(&m, &p, &ctl, NULL, 0u, &bad);
                if ((g == GROUP_FBW) && (id == (int)HT_FBW_P_INVERTED_THRESHOLD) && (k == 0)) {
                    /* in its row's range, not above the centre: the joint rule */
                    char got[64];
                    ht_modes_bad_name(&bad, got, (unsigned)sizeof got);
                    TEST_ASSERT_EQUAL_INT_MESSAGE(2, rc, msg);
                    TEST_ASSERT_EQUAL_STRING_MESSAGE(
                        "joint.inverted_threshold_us not in (centre, full]", got, msg);
                } else if (k < 2) {
                    TEST_ASSERT_EQUAL_INT_MESSAGE(0, rc, msg);
                } else {
                    char want[64];
                    char got[64];
                    (void)snprintf(want, sizeof want, "%s%s", prefixes[g], info->name);
                    ht_modes_bad_name(&bad, got, (unsigned)sizeof got);
                    TEST_ASSERT_EQUAL_INT_MESSAGE(2, rc, msg);
                    TEST_ASSERT_EQUAL_STRING_MESSAGE(want, got, msg);
                }
                checked++;
            }
        }
    }
    TEST_ASSERT_EQUAL_INT(
        4 * (HT_PARAM_MODES_COUNT + HT_PARAM_FBW_COUNT + HT_PARAM_NAV_COUNT + HT_PARAM_AOA_COUNT),
        checked + skipped);
    /* edges no field can hold: min - 1 of the unsigned rows at 0 (modes
     * mode_input; fbw deadband, inverted_input; nav law, loop; aoa enabled)
     * and max + 1 of the int16 rows at 327.67 m/s (cruise, aoa v_ref and
     * v_enable): 9 of the 4 x 33 */
    TEST_ASSERT_EQUAL_INT(9, skipped);
}

static void test_the_aoa_joint_limit(void)
{
    ht_modes_params_t p;
    ht_modes_params_default(&p);
    p.aoa.v_enable_cm_s = 1000;
    p.aoa.v_ref_cm_s = 8000; /* 8 x v_enable: accepted */
    ht_modes_t m;
    ht_modes_bad_t bad;
    TEST_ASSERT_EQUAL_INT(0, ht_modes_init(&m, &p, &ctl, NULL, 0u, &bad));
    p.aoa.v_ref_cm_s = 8001;
    TEST_ASSERT_EQUAL_INT(2, ht_modes_init(&m, &p, &ctl, NULL, 0u, &bad));
    char got[64];
    ht_modes_bad_name(&bad, got, (unsigned)sizeof got);
    TEST_ASSERT_EQUAL_STRING("aoa.v_enable_m_s", got);
    TEST_ASSERT_EQUAL_INT(HT_AOA_P_V_ENABLE, ht_aoa_first_bad(&p.aoa));
}

int main(void)
{
    const ht_params_t lp = HT_PARAMS_DEFAULT;
    if (ht_init(&ctl, &lp, NULL) != HT_OK) {
        return 1;
    }
    UNITY_BEGIN();
    RUN_TEST(test_defaults_are_the_documented_ones);
    RUN_TEST(test_every_bound_edge_is_checked_and_named);
    RUN_TEST(test_the_aoa_joint_limit);
    return UNITY_END();
}
