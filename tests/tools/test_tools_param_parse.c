/*
 * Unit tests of ht_replay's --param parser (tools/ht_replay/param_parse.c):
 * every name reaches its field with the right conversion, and every bad
 * argument is refused with a message naming it and *p left unchanged.
 */
#include <string.h>

#include "helical/law/helical_turn.h"
#include "param_parse.h"
#include "unity.h"

static ht_params_t p;
static char msg[256];

void setUp(void)
{
    static const ht_params_t defaults = HT_PARAMS_DEFAULT;
    p = defaults;
    msg[0] = '\0';
}

void tearDown(void) {}

static void ok(const char *arg, ht_param_id_t expected_id)
{
    ht_param_id_t id = HT_P_NONE;
    if (ht_param_parse(&p, arg, &id, msg, sizeof msg) != 0) {
        TEST_FAIL_MESSAGE(msg);
    }
    TEST_ASSERT_EQUAL_INT_MESSAGE(expected_id, id, arg);
}

/* Refused, *p untouched, and the message contains what. */
static void bad(const char *arg, const char *what)
{
    static const ht_params_t defaults = HT_PARAMS_DEFAULT;
    ht_param_id_t id = HT_P_COUNT;
    TEST_ASSERT_EQUAL_INT_MESSAGE(-1, ht_param_parse(&p, arg, &id, msg, sizeof msg), arg);
    TEST_ASSERT_EQUAL_INT_MESSAGE(HT_P_COUNT, id, arg);
    TEST_ASSERT_EQUAL_MEMORY_MESSAGE(&defaults, &p, sizeof p, arg);
    if (strstr(msg, what) == NULL) {
        TEST_FAIL_MESSAGE(msg);
    }
}

static void test_gains_are_q16(void)
{
    ok("kp_aileron=3", HT_P_KP_AILERON);
    TEST_ASSERT_EQUAL_INT32(3 * 65536, p.kp_aileron);
    ok("kp_elevator=0.5", HT_P_KP_ELEVATOR);
    TEST_ASSERT_EQUAL_INT32(32768, p.kp_elevator);
    ok("kp_rudder=2.25", HT_P_KP_RUDDER);
    TEST_ASSERT_EQUAL_INT32(147456, p.kp_rudder);
    ok("kff_aileron=0.1", HT_P_KFF_AILERON);
    TEST_ASSERT_EQUAL_INT32(6554, p.kff_aileron); /* 6553.6 rounds up */
    ok("kff_elevator=1", HT_P_KFF_ELEVATOR);
    TEST_ASSERT_EQUAL_INT32(65536, p.kff_elevator);
    ok("kff_rudder=64", HT_P_KFF_RUDDER);
    TEST_ASSERT_EQUAL_INT32(64 * 65536, p.kff_rudder);
    ok("kd_aileron=0.75", HT_P_KD_AILERON);
    TEST_ASSERT_EQUAL_INT32(49152, p.kd_aileron);
    ok("kd_elevator=1e-1", HT_P_KD_ELEVATOR);
    TEST_ASSERT_EQUAL_INT32(6554, p.kd_elevator);
    ok("kd_rudder=0", HT_P_KD_RUDDER);
    TEST_ASSERT_EQUAL_INT32(0, p.kd_rudder);
    ok("max_tilt=2.5", HT_P_MAX_TILT);
    TEST_ASSERT_EQUAL_INT32(163840, p.max_tilt);
    /* Range is ht_init's business: a negative gain fits Q16 and passes here. */
    ok("kp_aileron=-1", HT_P_KP_AILERON);
    TEST_ASSERT_EQUAL_INT32(-65536, p.kp_aileron);
}

static void test_speeds_are_cm_s(void)
{
    ok("v_ref=20", HT_P_V_REF);
    TEST_ASSERT_EQUAL_INT32(2000, p.v_ref_cm_s);
    ok("v_min=5.55", HT_P_V_MIN);
    TEST_ASSERT_EQUAL_INT32(555, p.v_min_cm_s);
    ok("v_min=0.004", HT_P_V_MIN);
    TEST_ASSERT_EQUAL_INT32(0, p.v_min_cm_s);
}

static void test_schedule_and_pitch_mode(void)
{
    ok("schedule=1", HT_P_SCHEDULE);
    TEST_ASSERT_EQUAL_UINT8(1, p.schedule);
    ok("schedule=0", HT_P_SCHEDULE);
    TEST_ASSERT_EQUAL_UINT8(0, p.schedule);
    ok("pitch_mode=cross", HT_P_PITCH_MODE);
    TEST_ASSERT_EQUAL_UINT8(HT_PITCH_TILT_CROSS, p.pitch_mode);
    ok("pitch_mode=earth", HT_P_PITCH_MODE);
    TEST_ASSERT_EQUAL_UINT8(HT_PITCH_EARTH_FRAME, p.pitch_mode);
    ok("pitch_mode=1", HT_P_PITCH_MODE);
    TEST_ASSERT_EQUAL_UINT8(HT_PITCH_TILT_CROSS, p.pitch_mode);
    ok("pitch_mode=0", HT_P_PITCH_MODE);
    TEST_ASSERT_EQUAL_UINT8(HT_PITCH_EARTH_FRAME, p.pitch_mode);
}

static void test_bad_arguments(void)
{
    bad("kp_aileron", "expected NAME=VALUE");
    bad("=3", "expected NAME=VALUE");
    bad("", "expected NAME=VALUE");
    bad("kp_ailerons=1", "unknown parameter \"kp_ailerons\"");
    bad("KP_AILERON=1", "unknown parameter \"KP_AILERON\"");
    bad("kp_aileron =1", "unknown parameter \"kp_aileron \"");
    bad("kp_aileron=", "kp_aileron: empty field");
    bad("kp_aileron=abc", "kp_aileron: not a number: \"abc\"");
    bad("kd_rudder=nan", "kd_rudder: not finite");
    bad("kd_rudder=1e999", "kd_rudder: too large");
    bad("kff_elevator=40000", "kff_elevator: 40000 does not fit Q16");
    bad("v_ref=3e7", "v_ref: 3e7 m/s does not fit");
    bad("schedule=0.5", "schedule: \"0.5\" is not 0 or 1");
    bad("schedule=yes", "schedule: not a number");
    bad("pitch_mode=EARTH", "pitch_mode: \"EARTH\" is not earth, cross, 0 or 1");
    bad("pitch_mode=2", "pitch_mode: \"2\"");
    bad("max_tilt=1=2", "max_tilt: not a number: \"1=2\"");
}

static void test_long_and_hostile_text_is_cut_and_cleaned(void)
{
    char arg[300];
    memset(arg, 'n', sizeof arg);
    memcpy(arg + 200, "=1", 3);
    bad(arg, "nnn...\"");
    TEST_ASSERT_TRUE(strlen(msg) < 200);
    bad("kp_aileron=\x1b[2J", "not a number: \"?[2J\"");
}

static void test_names_match_the_core(void)
{
    for (int i = (int)HT_P_NONE + 1; i < (int)HT_P_COUNT; i++) {
        ht_param_id_t id = (ht_param_id_t)i;
        TEST_ASSERT_EQUAL_STRING(ht_param_name(id), ht_param_tool_name(id));
        /* ... and every name parses back to its id. */
        char arg[64];
        (void)snprintf(arg, sizeof arg, "%s=1", ht_param_tool_name(id));
        ok(arg, id);
    }
    TEST_ASSERT_EQUAL_STRING("", ht_param_tool_name(HT_P_NONE));
    TEST_ASSERT_EQUAL_STRING("", ht_param_tool_name(HT_P_COUNT));
}

static void test_format_value_and_defaults_table(void)
{
    char buf[32];
    TEST_ASSERT_EQUAL_INT(0, ht_param_format_value(&p, HT_P_V_REF, buf, sizeof buf));
    TEST_ASSERT_EQUAL_STRING("15", buf);
    TEST_ASSERT_EQUAL_INT(0, ht_param_format_value(&p, HT_P_MAX_TILT, buf, sizeof buf));
    TEST_ASSERT_EQUAL_STRING("4", buf);
    TEST_ASSERT_EQUAL_INT(0, ht_param_format_value(&p, HT_P_PITCH_MODE, buf, sizeof buf));
    TEST_ASSERT_EQUAL_STRING("earth", buf);
    ok("kd_aileron=0.125", HT_P_KD_AILERON);
    TEST_ASSERT_EQUAL_INT(0, ht_param_format_value(&p, HT_P_KD_AILERON, buf, sizeof buf));
    TEST_ASSERT_EQUAL_STRING("0.125", buf);
    TEST_ASSERT_EQUAL_INT(-1, ht_param_format_value(&p, HT_P_NONE, buf, sizeof buf));
    TEST_ASSERT_EQUAL_STRING("?", buf);

    /* The --help table shows the header's defaults. */
    static const ht_params_t defaults = HT_PARAMS_DEFAULT;
    FILE *f = tmpfile();
    TEST_ASSERT_NOT_NULL(f);
    ht_param_print_table(f, &defaults);
    rewind(f);
    char text[2048];
    size_t n = fread(text, 1, sizeof text - 1, f);
    text[n] = '\0';
    (void)fclose(f);
    TEST_ASSERT_NOT_NULL(strstr(text, "  kp_aileron    per unit error       default 1\n"));
    TEST_ASSERT_NOT_NULL(strstr(text, "  v_min         m/s                  default 5\n"));
    TEST_ASSERT_NOT_NULL(strstr(text, "  pitch_mode    earth|cross          default earth\n"));
}

/* The bounds the tool quotes are the table's, in --param units. */
static void test_ranges_quote_the_table(void)
{
    char buf[96];
    TEST_ASSERT_EQUAL_INT(0, ht_param_format_range(HT_P_KP_AILERON, buf, sizeof buf));
    TEST_ASSERT_EQUAL_STRING("kp_aileron in [0, 64] per unit error (Q16)", buf);
    TEST_ASSERT_EQUAL_INT(0, ht_param_format_range(HT_P_V_MIN, buf, sizeof buf));
    TEST_ASSERT_EQUAL_STRING("v_min in [1, 327.67] m/s (int32 x100)", buf);
    TEST_ASSERT_EQUAL_INT(0, ht_param_format_range(HT_P_PITCH_MODE, buf, sizeof buf));
    TEST_ASSERT_EQUAL_STRING("pitch_mode in [earth, cross] earth|cross (uint8)", buf);
    TEST_ASSERT_EQUAL_INT(-1, ht_param_format_range(HT_P_COUNT, buf, sizeof buf));
    TEST_ASSERT_EQUAL_STRING("?", buf);
    /* an integer field outside the table's range is refused while parsing */
    bad("schedule=-1", "schedule: \"-1\" is not 0 or 1");
}

/* The whole path the tool takes: parse, then let ht_init judge the range. */
static void test_parsed_values_reach_ht_init(void)
{
    ht_controller_t ctl;
    ht_param_id_t badf = HT_P_NONE;
    ok("kp_aileron=100", HT_P_KP_AILERON);
    TEST_ASSERT_EQUAL_INT(HT_ERR_PARAM, ht_init(&ctl, &p, &badf));
    TEST_ASSERT_EQUAL_INT(HT_P_KP_AILERON, badf);
    setUp();
    ok("kp_aileron=2", HT_P_KP_AILERON);
    ok("v_ref=25", HT_P_V_REF);
    TEST_ASSERT_EQUAL_INT(HT_OK, ht_init(&ctl, &p, &badf));
    TEST_ASSERT_EQUAL_INT32(2 * 65536, ctl.gains.kp[1]); /* body Y = aileron */
    TEST_ASSERT_EQUAL_INT16(2500, ctl.v_ref_cm_s);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_gains_are_q16);
    RUN_TEST(test_speeds_are_cm_s);
    RUN_TEST(test_schedule_and_pitch_mode);
    RUN_TEST(test_bad_arguments);
    RUN_TEST(test_long_and_hostile_text_is_cut_and_cleaned);
    RUN_TEST(test_names_match_the_core);
    RUN_TEST(test_format_value_and_defaults_table);
    RUN_TEST(test_parsed_values_reach_ht_init);
    RUN_TEST(test_ranges_quote_the_table);
    return UNITY_END();
}
