/* Unit tests of fly-by-wire (include/helical/guidance/fbw.h): the stick with its
 * deadband against a double reference for every pulse 0..2500 us, the turn
 * rate and pitch scaling, the inverted switch, and parameter checks. */
#include "unity.h"

#include "helical/guidance/fbw.h"

#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <string.h>

static ht_fbw_params_t prm;
static ht_fbw_t fbw;
static os_rc_map_t map;

void setUp(void)
{
    const ht_fbw_params_t d = HT_FBW_PARAMS_DEFAULT;
    prm = d;
    TEST_ASSERT_EQUAL_INT(0, ht_fbw_init(&fbw, &prm, NULL));
    const os_rc_cal_t stick = {0u, 0u, 0u, 1500u, 500u};
    map.aileron = stick;
    map.elevator = stick;
    map.elevator.input = 1u;
    map.rudder = stick;
    map.rudder.input = 3u;
    map.throttle = stick;
    map.throttle.input = 2u;
}

void tearDown(void) {}

/* The stick in double: the spec of fbw.h. */
static double ref_stick(double pulse, double centre, double travel, double db, int reversed)
{
    if (pulse < 800.0 || pulse > 2200.0 || travel <= db) {
        return 0.0;
    }
    double s = pulse - centre;
    if (reversed) {
        s = -s;
    }
    if (fabs(s) <= db) {
        return 0.0;
    }
    double v = (fabs(s) - db) / (travel - db);
    if (v > 1.0) {
        v = 1.0;
    }
    return (s < 0) ? -v : v;
}

static void test_stick_exhaustive_against_reference(void)
{
    /* Every pulse 0..2500 us, several calibrations: exact to 1/2 LSB. */
    const uint16_t centres[] = {1500u, 1520u, 1479u, 1000u};
    const uint16_t travels[] = {500u, 400u, 350u, 100u};
    const uint16_t dbs[] = {0u, 8u, 25u, 90u};
    double worst = 0.0;
    long n = 0;
    for (unsigned c = 0; c < 4u; c++) {
        for (unsigned d = 0; d < 4u; d++) {
            for (int rev = 0; rev < 2; rev++) {
                os_rc_cal_t cal = {0u, (uint8_t)rev, 0u, centres[c], travels[c]};
                for (unsigned p = 0; p <= 2500u; p++) {
                    q14_t got = ht_fbw_stick_q14(&cal, dbs[d], (uint16_t)p);
                    double want = ref_stick(p, centres[c], travels[c], dbs[d], rev) * 16384.0;
                    double err = fabs((double)got - want);
                    if (err > worst) {
                        worst = err;
                    }
                    n++;
                    TEST_ASSERT_TRUE_MESSAGE(err <= 0.5 + 1e-9, "stick off by more than 1/2 LSB");
                }
            }
        }
    }
    printf("stick: %ld pulses, worst error %.3f LSB of Q14\n", n, worst);
}

static void test_stick_deadband_edges_and_continuity(void)
{
    os_rc_cal_t cal = {0u, 0u, 0u, 1500u, 500u};
    TEST_ASSERT_EQUAL_INT16(0, ht_fbw_stick_q14(&cal, 8u, 1508u));
    TEST_ASSERT_EQUAL_INT16(0, ht_fbw_stick_q14(&cal, 8u, 1492u));
    /* one microsecond past the edge: 1 / 492 of full, continuous */
    TEST_ASSERT_EQUAL_INT16(33, ht_fbw_stick_q14(&cal, 8u, 1509u)); /* 16384/492 = 33.3 */
    TEST_ASSERT_EQUAL_INT16(-33, ht_fbw_stick_q14(&cal, 8u, 1491u));
    TEST_ASSERT_EQUAL_INT16(Q14_ONE, ht_fbw_stick_q14(&cal, 8u, 2000u));
    TEST_ASSERT_EQUAL_INT16(-Q14_ONE, ht_fbw_stick_q14(&cal, 8u, 1000u));
    TEST_ASSERT_EQUAL_INT16(Q14_ONE, ht_fbw_stick_q14(&cal, 8u, 2200u)); /* clamped */
    /* monotone over the whole valid window */
    q14_t prev = -Q14_ONE;
    for (uint16_t p = 800u; p <= 2200u; p++) {
        q14_t v = ht_fbw_stick_q14(&cal, 8u, p);
        TEST_ASSERT_TRUE(v >= prev);
        TEST_ASSERT_TRUE(v - prev <= 34);
        prev = v;
    }
}

static void test_stick_no_signal_bad_cal_and_null_read_centre(void)
{
    os_rc_cal_t cal = {0u, 0u, 0u, 1500u, 500u};
    TEST_ASSERT_EQUAL_INT16(0, ht_fbw_stick_q14(&cal, 8u, 0u));
    TEST_ASSERT_EQUAL_INT16(0, ht_fbw_stick_q14(&cal, 8u, 799u));
    TEST_ASSERT_EQUAL_INT16(0, ht_fbw_stick_q14(&cal, 8u, 2201u));
    TEST_ASSERT_EQUAL_INT16(0, ht_fbw_stick_q14(&cal, 8u, UINT16_MAX));
    TEST_ASSERT_EQUAL_INT16(0, ht_fbw_stick_q14(NULL, 8u, 2000u));
    cal.travel_us = 8u;
    TEST_ASSERT_EQUAL_INT16(0, ht_fbw_stick_q14(&cal, 8u, 2000u));
}

static void test_turn_rate_and_pitch_every_pulse(void)
{
    /* Every aileron and elevator pulse 800..2200: turn = stick * 60 deg/s,
     * pitch = stick * 0.5, within 1 LSB of Q16 of the double formula. */
    const double wmax = 60.0 * 3.14159265358979323846 / 180.0;
    uint16_t rc[8] = {1500u, 1500u, 1000u, 1500u, 1500u, 1000u, 1500u, 1500u};
    double worst_t = 0.0, worst_p = 0.0;
    for (uint16_t p = 800u; p <= 2200u; p++) {
        rc[0] = p;
        rc[1] = p;
        ht_fbw_output_t o;
        ht_fbw_step(&fbw, &map, rc, 8u, &o);
        double stick = o.aileron_stick / 16384.0;
        double et = fabs(o.turn_rate_rad_s / 65536.0 - stick * wmax) * 65536.0;
        double ep = fabs(o.pitch_ratio / 65536.0 - stick * 0.5) * 65536.0;
        worst_t = fmax(worst_t, et);
        worst_p = fmax(worst_p, ep);
        TEST_ASSERT_TRUE(et <= 1.0);
        TEST_ASSERT_TRUE(ep <= 1.0);
        double ref = ref_stick(p, 1500, 500, 8, 0);
        TEST_ASSERT_TRUE(fabs(stick - ref) <= 0.5 / 16384.0 + 1e-12);
        TEST_ASSERT_EQUAL_UINT8(0u, o.inverted);
    }
    rc[0] = 2000u;
    ht_fbw_output_t o;
    ht_fbw_step(&fbw, &map, rc, 8u, &o);
    TEST_ASSERT_INT32_WITHIN(1, (int32_t)lround(wmax * 65536.0), o.turn_rate_rad_s);
    printf("fbw: worst turn-rate error %.3f, pitch %.3f LSB of Q16\n", worst_t, worst_p);
}

static void test_inverted_switch_threshold_and_loss(void)
{
    /* the default threshold 1750 us: a centred switch channel (1500 us)
     * is upright, one microsecond below the threshold too */
    uint16_t rc[8] = {1500u, 1500u, 1000u, 1500u, 1500u, 1500u, 1500u, 1500u};
    ht_fbw_output_t o;
    ht_fbw_step(&fbw, &map, rc, 8u, &o);
    TEST_ASSERT_EQUAL_UINT8(0u, o.inverted);
    rc[5] = 1749u;
    ht_fbw_step(&fbw, &map, rc, 8u, &o);
    TEST_ASSERT_EQUAL_UINT8(0u, o.inverted);
    rc[5] = 1750u;
    ht_fbw_step(&fbw, &map, rc, 8u, &o);
    TEST_ASSERT_EQUAL_UINT8(1u, o.inverted);
    rc[5] = 2000u;
    ht_fbw_step(&fbw, &map, rc, 8u, &o);
    TEST_ASSERT_EQUAL_UINT8(1u, o.inverted);
    rc[5] = 2300u; /* no signal: upright */
    ht_fbw_step(&fbw, &map, rc, 8u, &o);
    TEST_ASSERT_EQUAL_UINT8(0u, o.inverted);
    rc[5] = 2000u; /* input beyond the count given: upright, sticks centred */
    rc[0] = 2000u;
    ht_fbw_step(&fbw, &map, rc, 1u, &o);
    TEST_ASSERT_EQUAL_UINT8(0u, o.inverted);
    TEST_ASSERT_EQUAL_INT16(Q14_ONE, o.aileron_stick);
    TEST_ASSERT_EQUAL_INT16(0, o.elevator_stick);
}

static void test_same_stick_same_command_inverted(void)
{
    uint16_t rc[8] = {1800u, 1300u, 1000u, 1500u, 1500u, 1000u, 1500u, 1500u};
    ht_fbw_output_t up, inv;
    ht_fbw_step(&fbw, &map, rc, 8u, &up);
    rc[5] = 2000u;
    ht_fbw_step(&fbw, &map, rc, 8u, &inv);
    TEST_ASSERT_EQUAL_INT32(up.turn_rate_rad_s, inv.turn_rate_rad_s);
    TEST_ASSERT_EQUAL_INT32(up.pitch_ratio, inv.pitch_ratio);
    TEST_ASSERT_TRUE(up.turn_rate_rad_s > 0);
    TEST_ASSERT_TRUE(up.pitch_ratio < 0); /* stick down (1300) = descend */
}

static void test_init_rejects_each_field_by_name(void)
{
    ht_fbw_param_id_t bad;
    ht_fbw_params_t b;
    struct {
        int field;
        const char *name;
    } cases[] = {{HT_FBW_P_DEADBAND, "deadband_us"},
                 {HT_FBW_P_TURN_RATE_MAX, "turn_rate_max_deg_s"},
                 {HT_FBW_P_TURN_RATE_MAX, "turn_rate_max_deg_s"},
                 {HT_FBW_P_PITCH_MAX, "pitch_max"},
                 {HT_FBW_P_PITCH_MAX, "pitch_max"},
                 {HT_FBW_P_INVERTED_INPUT, "inverted_input"},
                 {HT_FBW_P_INVERTED_THRESHOLD, "inverted_threshold_us"},
                 {HT_FBW_P_INVERTED_THRESHOLD, "inverted_threshold_us"}};
    for (unsigned i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        b = prm;
        switch (i) {
        case 0:
            b.deadband_us = 91u;
            break;
        case 1:
            b.turn_rate_max_deg_s = 0;
            break;
        case 2:
            b.turn_rate_max_deg_s = 361;
            break;
        case 3:
            b.pitch_max = 0;
            break;
        case 4:
            b.pitch_max = 4 * Q16_ONE + 1;
            break;
        case 5:
            b.inverted_input = 16u;
            break;
        case 6:
            b.inverted_threshold_us = 799u;
            break;
        default:
            b.inverted_threshold_us = 2201u;
            break;
        }
        ht_fbw_t f;
        TEST_ASSERT_EQUAL_INT(2, ht_fbw_init(&f, &b, &bad));
        TEST_ASSERT_EQUAL_INT(cases[i].field, (int)bad);
        TEST_ASSERT_EQUAL_STRING(cases[i].name, ht_fbw_param_name(bad));
        TEST_ASSERT_EQUAL_UINT8(0u, f.ready);
        /* an unready fbw gives zero */
        uint16_t rc[8] = {2000u, 2000u, 1000u, 1500u, 1500u, 2000u, 1500u, 1500u};
        ht_fbw_output_t o;
        ht_fbw_step(&f, &map, rc, 8u, &o);
        TEST_ASSERT_EQUAL_INT32(0, o.turn_rate_rad_s);
        TEST_ASSERT_EQUAL_UINT8(0u, o.inverted);
    }
    TEST_ASSERT_EQUAL_INT(1, ht_fbw_init(NULL, &prm, &bad));
    TEST_ASSERT_EQUAL_STRING("", ht_fbw_param_name(HT_FBW_P_COUNT));
    b = prm;
    b.deadband_us = 90u;
    b.turn_rate_max_deg_s = 360;
    b.pitch_max = 4 * Q16_ONE;
    TEST_ASSERT_EQUAL_INT(0, ht_fbw_init(&fbw, &b, &bad)); /* the edges are allowed */
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_stick_exhaustive_against_reference);
    RUN_TEST(test_stick_deadband_edges_and_continuity);
    RUN_TEST(test_stick_no_signal_bad_cal_and_null_read_centre);
    RUN_TEST(test_turn_rate_and_pitch_every_pulse);
    RUN_TEST(test_inverted_switch_threshold_and_loss);
    RUN_TEST(test_same_stick_same_command_inverted);
    RUN_TEST(test_init_rejects_each_field_by_name);
    return UNITY_END();
}
