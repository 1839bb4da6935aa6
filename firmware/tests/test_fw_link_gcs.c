/*
 * test_fw_link_gcs.c - what the real ground stations need of the link
 * (issue 28) and the refusals that must leave everything as it was
 * (issue 33 items 5, 6, 7, 11): the ArduPilot identity, every command
 * answered (COMMAND_LONG and COMMAND_INT), STATUSTEXT with the reason at a
 * bounded rate, integer parameter types and param_type honoured, the echo
 * of a rounded set, storage refused in flight, the heartbeat's interval
 * bounded, missions in frames 0 / 3 and as legacy MISSION_ITEM, a refused
 * upload that leaves the flown mission untouched, a deferred one applied
 * or reported.
 */
#include "link_fixture.h"
#include "link/fw_link_text.h"
#include "link/fw_link_tx.h" /* fw_link_armed */

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* the texts of the STATUSTEXTs since from, joined by '|' */
static const char *texts(unsigned from)
{
    static char all[4096];
    all[0] = '\0';
    for (unsigned i = from; i < nrx; ++i) {
        if (rx[i].msgid == MAVLINK_MSG_ID_STATUSTEXT) {
            mavlink_statustext_t st;
            mavlink_msg_statustext_decode(&rx[i], &st);
            char t[51];
            memcpy(t, st.text, 50);
            t[50] = '\0';
            strncat(all, t, sizeof all - strlen(all) - 2u);
            strncat(all, "|", sizeof all - strlen(all) - 1u);
        }
    }
    return all;
}

static void command_long(uint16_t command, float p1, float p2)
{
    mavlink_message_t m;
    mavlink_msg_command_long_pack(GCS_SYS, GCS_COMP, &m, OUR_SYS, OUR_COMP, command, 0, p1, p2, 0,
                                  0, 0, 0, 0);
    send(&m);
}

static void command_int(uint16_t command, float p1, float p2)
{
    mavlink_message_t m;
    mavlink_msg_command_int_pack(GCS_SYS, GCS_COMP, &m, OUR_SYS, OUR_COMP, MAV_FRAME_GLOBAL,
                                 command, 0, 0, p1, p2, 0, 0, 0, 0, 0.0f);
    send(&m);
}

/* --- identity, commands ---------------------------------------------------- */

static void test_heartbeat_is_ardupilot_plane_and_armed_is_the_image_state(void)
{
    steps(1u);
    TEST_ASSERT_EQUAL_INT(1, fw_link_armed(&lk)); /* live from power-up: the truth */
    steps(80u);
    const mavlink_message_t *m = last_id(MAVLINK_MSG_ID_HEARTBEAT, 0u);
    TEST_ASSERT_NOT_NULL(m);
    mavlink_heartbeat_t hb;
    mavlink_msg_heartbeat_decode(m, &hb);
    TEST_ASSERT_EQUAL_UINT8(MAV_AUTOPILOT_ARDUPILOTMEGA, hb.autopilot);
    TEST_ASSERT_EQUAL_UINT8(MAV_TYPE_FIXED_WING, hb.type);
    TEST_ASSERT_TRUE((hb.base_mode & MAV_MODE_FLAG_SAFETY_ARMED) != 0u);
    TEST_ASSERT_TRUE((hb.base_mode & MAV_MODE_FLAG_CUSTOM_MODE_ENABLED) != 0u);
}

static void test_arm_disarm_is_denied_with_the_reason(void)
{
    steps(2u);
    for (int arm = 0; arm <= 1; ++arm) {
        const unsigned from = nrx;
        command_long(MAV_CMD_COMPONENT_ARM_DISARM, (float)arm, 0.0f);
        TEST_ASSERT_EQUAL_INT(MAV_RESULT_DENIED,
                              command_result(from, MAV_CMD_COMPONENT_ARM_DISARM));
        TEST_ASSERT_EQUAL_STRING("arm refused: not implemented, always armed|", texts(from));
    }
}

static void test_command_int_is_answered_like_command_long(void)
{
    steps(2u);
    in.rc_us[4] = 1500u; /* fly-by-wire on the switch */
    steps(2u);
    TEST_ASSERT_EQUAL_UINT8(HT_MODE_FBW, out.modes.mode);
    unsigned from = nrx;
    command_int(MAV_CMD_DO_SET_MODE, (float)MAV_MODE_FLAG_CUSTOM_MODE_ENABLED, 11.0f);
    TEST_ASSERT_EQUAL_INT(MAV_RESULT_ACCEPTED, command_result(from, MAV_CMD_DO_SET_MODE));
    steps(2u);
    TEST_ASSERT_EQUAL_UINT8(HT_MODE_RTH, out.modes.mode);
    from = nrx;
    command_int(MAV_CMD_DO_SET_MODE, (float)MAV_MODE_FLAG_CUSTOM_MODE_ENABLED, 5.0f);
    TEST_ASSERT_EQUAL_INT(MAV_RESULT_ACCEPTED, command_result(from, MAV_CMD_DO_SET_MODE));
    steps(2u);
    TEST_ASSERT_EQUAL_UINT8(HT_MODE_FBW, out.modes.mode);
    from = nrx;
    command_int(MAV_CMD_NAV_RETURN_TO_LAUNCH, 0.0f, 0.0f);
    TEST_ASSERT_EQUAL_INT(MAV_RESULT_ACCEPTED, command_result(from, MAV_CMD_NAV_RETURN_TO_LAUNCH));
    steps(2u);
    TEST_ASSERT_EQUAL_UINT8(HT_MODE_RTH, out.modes.mode);
    /* a command the link does not know: answered, once */
    from = nrx;
    command_int(MAV_CMD_NAV_LAND, 0.0f, 0.0f);
    TEST_ASSERT_EQUAL_INT(MAV_RESULT_UNSUPPORTED, command_result(from, MAV_CMD_NAV_LAND));
    TEST_ASSERT_EQUAL_UINT(1u, count_id(MAVLINK_MSG_ID_COMMAND_ACK, from));
}

static void test_do_set_mode_refuses_a_fraction(void)
{
    steps(2u);
    const float bad[] = {10.4f, 9.9999f, 10.5f, NAN, INFINITY, -1.0f, 1e10f};
    for (unsigned i = 0u; i < sizeof bad / sizeof bad[0]; ++i) {
        steps(8u); /* the text rate: one per 200 ms */
        const unsigned from = nrx;
        command_long(MAV_CMD_DO_SET_MODE, (float)MAV_MODE_FLAG_CUSTOM_MODE_ENABLED, bad[i]);
        TEST_ASSERT_EQUAL_INT(MAV_RESULT_DENIED, command_result(from, MAV_CMD_DO_SET_MODE));
        TEST_ASSERT_NOT_NULL(strstr(texts(from), "mode refused"));
        TEST_ASSERT_EQUAL_UINT8(0u, fw.gcs_mode);
    }
    const unsigned from = nrx;
    command_long(MAV_CMD_DO_SET_MODE, (float)MAV_MODE_FLAG_CUSTOM_MODE_ENABLED, 10.0f);
    TEST_ASSERT_EQUAL_INT(MAV_RESULT_ACCEPTED, command_result(from, MAV_CMD_DO_SET_MODE));
    TEST_ASSERT_EQUAL_UINT8(1u + HT_MODE_WAYPOINT, fw.gcs_mode);
}

static void test_heartbeat_interval_is_bounded(void)
{
    steps(2u);
    const float bad[] = {2147483648.0f, 1e12f, 1000001.0f, 19999.0f, -1.0f, 5e6f, 0.5f};
    for (unsigned i = 0u; i < sizeof bad / sizeof bad[0]; ++i) {
        const unsigned from = nrx;
        command_long(MAV_CMD_SET_MESSAGE_INTERVAL, (float)MAVLINK_MSG_ID_HEARTBEAT, bad[i]);
        TEST_ASSERT_EQUAL_INT(MAV_RESULT_DENIED,
                              command_result(from, MAV_CMD_SET_MESSAGE_INTERVAL));
        TEST_ASSERT_EQUAL_INT32(0, lk.interval_override_us[FW_LINK_S_HEARTBEAT]);
    }
    /* the bounds themselves are accepted; 1 Hz stays 1 Hz */
    unsigned from = nrx;
    command_long(MAV_CMD_SET_MESSAGE_INTERVAL, (float)MAVLINK_MSG_ID_HEARTBEAT, 20000.0f);
    TEST_ASSERT_EQUAL_INT(MAV_RESULT_ACCEPTED, command_result(from, MAV_CMD_SET_MESSAGE_INTERVAL));
    command_long(MAV_CMD_SET_MESSAGE_INTERVAL, (float)MAVLINK_MSG_ID_HEARTBEAT, 1000000.0f);
    from = nrx;
    steps(120u); /* 3 s */
    TEST_ASSERT_UINT_WITHIN(1u, 3u, count_id(MAVLINK_MSG_ID_HEARTBEAT, from));
    /* a stream at 2^31 us is refused too (saturated), not 35.8 min */
    from = nrx;
    command_long(MAV_CMD_SET_MESSAGE_INTERVAL, (float)MAVLINK_MSG_ID_ATTITUDE, 1e12f);
    TEST_ASSERT_EQUAL_INT(MAV_RESULT_DENIED, command_result(from, MAV_CMD_SET_MESSAGE_INTERVAL));
}

static void test_get_message_interval_answers_every_stream(void)
{
    steps(2u);
    const struct {
        uint32_t id;
        int32_t us;
    } want[] = {{MAVLINK_MSG_ID_HEARTBEAT, 1000000},
                {MAVLINK_MSG_ID_ATTITUDE, 100000},
                {MAVLINK_MSG_ID_GLOBAL_POSITION_INT, 200000},
                {MAVLINK_MSG_ID_VFR_HUD, 250000},
                {MAVLINK_MSG_ID_RAW_IMU, -1}};
    for (unsigned i = 0u; i < sizeof want / sizeof want[0]; ++i) {
        const unsigned from = nrx;
        command_long(MAV_CMD_GET_MESSAGE_INTERVAL, (float)want[i].id, 0.0f);
        TEST_ASSERT_EQUAL_INT(MAV_RESULT_ACCEPTED,
                              command_result(from, MAV_CMD_GET_MESSAGE_INTERVAL));
        const mavlink_message_t *m = last_id(MAVLINK_MSG_ID_MESSAGE_INTERVAL, from);
        TEST_ASSERT_NOT_NULL(m);
        mavlink_message_interval_t mi;
        mavlink_msg_message_interval_decode(m, &mi);
        TEST_ASSERT_EQUAL_UINT16(want[i].id, mi.message_id);
        TEST_ASSERT_EQUAL_INT32(want[i].us, mi.interval_us);
    }
}

static int saved;
static int save_hook(void *ctx, const fw_config_t *c, const fw_link_params_t *p)
{
    (void)ctx;
    (void)c;
    (void)p;
    ++saved;
    return 0;
}

static void test_storage_is_refused_while_flying(void)
{
    lk.save = save_hook;
    saved = 0;
    /* LAW_V_MIN is 5 m/s: 5 m/s of airspeed, or of ground speed, is flying.
     * At sea level (ISA) the step's true airspeed is the pitot's indicated
     * one, so the bound falls exactly between 500 and 499 cm/s. */
    in.sensors.baro_alt_cm = 0;
    in.sensors.airspeed_cm_s = 500;
    steps(2u);
    unsigned from = nrx;
    command_long(MAV_CMD_PREFLIGHT_STORAGE, 1.0f, 0.0f);
    TEST_ASSERT_EQUAL_INT(MAV_RESULT_DENIED, command_result(from, MAV_CMD_PREFLIGHT_STORAGE));
    TEST_ASSERT_EQUAL_STRING("storage refused: flying (speed >= LAW_V_MIN)|", texts(from));
    TEST_ASSERT_EQUAL_INT(0, saved);
    in.sensors.airspeed_cm_s = 499;
    steps(2u);
    from = nrx;
    command_long(MAV_CMD_PREFLIGHT_STORAGE, 1.0f, 0.0f);
    TEST_ASSERT_EQUAL_INT(MAV_RESULT_ACCEPTED, command_result(from, MAV_CMD_PREFLIGHT_STORAGE));
    TEST_ASSERT_EQUAL_INT(1, saved);
    in.sensors.baro_alt_cm = 50000;
}

/* --- STATUSTEXT ------------------------------------------------------------ */

static void test_statustext_rate_is_bounded(void)
{
    steps(2u);
    unsigned from = nrx;
    for (unsigned i = 0u; i < 20u; ++i) {
        command_long(MAV_CMD_COMPONENT_ARM_DISARM, 1.0f, 0.0f);
    }
    TEST_ASSERT_EQUAL_UINT(20u, count_id(MAVLINK_MSG_ID_COMMAND_ACK, from)); /* every one */
    TEST_ASSERT_EQUAL_UINT(FW_LINK_TEXT_BURST, count_id(MAVLINK_MSG_ID_STATUSTEXT, from));
    TEST_ASSERT_EQUAL_UINT32(20u - FW_LINK_TEXT_BURST, lk.count.tx_text_dropped);
    steps(8u); /* 200 ms: one more */
    from = nrx;
    command_long(MAV_CMD_COMPONENT_ARM_DISARM, 1.0f, 0.0f);
    command_long(MAV_CMD_COMPONENT_ARM_DISARM, 1.0f, 0.0f);
    TEST_ASSERT_EQUAL_UINT(1u, count_id(MAVLINK_MSG_ID_STATUSTEXT, from));
}

/* the builder's decimals against a double reference: every raw value of a
 * 16-bit range in each scale, and seeded random int32 ones */
static void check_fixed(int32_t raw, int32_t scale)
{
    fw_link_text_t t;
    fw_link_text_start(&t, "");
    fw_link_text_fixed(&t, raw, scale);
    const double want = (double)raw / (double)scale;
    const double step = (scale == 1) ? 1.0 : (scale == 100) ? 0.01 : (scale == 1000) ? 0.001 : 1e-5;
    char *end = NULL;
    const double got = strtod(t.s, &end);
    TEST_ASSERT_TRUE(*end == '\0');
    if (!(fabs(got - want) <= (step / 2.0) * (1.0 + 1e-9) + (fabs(want) * 1e-15))) {
        printf("raw %ld scale %ld: %s, want %.9f\n", (long)raw, (long)scale, t.s, want);
    }
    TEST_ASSERT_TRUE_MESSAGE(fabs(got - want) <= (step / 2.0) * (1.0 + 1e-9) + (fabs(want) * 1e-15),
                             t.s);
    TEST_ASSERT_TRUE(t.s[0] != '-' || want < 0.0);
    TEST_ASSERT_TRUE(strchr(t.s, '.') == NULL || t.s[strlen(t.s) - 1u] != '0'); /* trimmed */
}

static void test_text_fixed_against_double(void)
{
    const int32_t scales[] = {1, 100, 1000, 16384, 65536};
    for (unsigned s = 0u; s < 5u; ++s) {
        for (int32_t raw = -32768; raw <= 32767; ++raw) {
            check_fixed(raw, scales[s]);
        }
        srand(28u);
        for (unsigned i = 0u; i < 100000u; ++i) {
            const int32_t raw = (int32_t)(((uint32_t)rand() << 16) ^ (uint32_t)rand());
            check_fixed(raw, scales[s]);
        }
        check_fixed(INT32_MIN, scales[s]);
        check_fixed(INT32_MAX, scales[s]);
    }
    fw_link_text_t t;
    fw_link_text_start(&t, "0123456789012345678901234567890123456789");
    fw_link_text_str(&t, "abcdefghijklmnop");
    TEST_ASSERT_EQUAL_UINT8(FW_LINK_TEXT_MAX, t.n); /* cut at 50, terminated */
    TEST_ASSERT_EQUAL_STRING("0123456789012345678901234567890123456789abcdefghij", t.s);
}

/* --- parameters ------------------------------------------------------------ */

static void set_typed(const char *id, uint32_t bits, uint8_t type)
{
    float v;
    memcpy(&v, &bits, sizeof v);
    mavlink_message_t m;
    mavlink_msg_param_set_pack(GCS_SYS, GCS_COMP, &m, OUR_SYS, OUR_COMP, id16(id), v, type);
    send(&m);
}

static uint32_t bits_of(float f)
{
    uint32_t b;
    memcpy(&b, &f, sizeof b);
    return b;
}

static const mavlink_param_value_t *last_value(unsigned from)
{
    static mavlink_param_value_t pv;
    const mavlink_message_t *m = last_id(MAVLINK_MSG_ID_PARAM_VALUE, from);
    TEST_ASSERT_NOT_NULL(m);
    mavlink_msg_param_value_decode(m, &pv);
    return &pv;
}

static void test_integer_rows_travel_as_integer_types(void)
{
    const int32_t sysid = fw_link_param_find("LNK_SYSID");
    const int32_t l1 = fw_link_param_find("NAV_L1");
    const int32_t home = fw_link_param_find("NAV_HOME_ALT");
    const int32_t turn = fw_link_param_find("NAV_TURN_RATE_MX");
    const int32_t vmin = fw_link_param_find("LAW_V_MIN");
    TEST_ASSERT_EQUAL_UINT8(MAV_PARAM_TYPE_UINT8, fw_link_param_mav_type((uint16_t)sysid));
    TEST_ASSERT_EQUAL_UINT8(MAV_PARAM_TYPE_UINT16, fw_link_param_mav_type((uint16_t)l1));
    TEST_ASSERT_EQUAL_UINT8(MAV_PARAM_TYPE_INT32, fw_link_param_mav_type((uint16_t)home));
    TEST_ASSERT_EQUAL_UINT8(MAV_PARAM_TYPE_INT16, fw_link_param_mav_type((uint16_t)turn));
    TEST_ASSERT_EQUAL_UINT8(MAV_PARAM_TYPE_REAL32, fw_link_param_mav_type((uint16_t)vmin));
    TEST_ASSERT_EQUAL_UINT8(0u, fw_link_param_mav_type(fw_link_param_count()));
    /* every row: an integer type exactly for the formats of scale 1 */
    for (uint16_t i = 0u; i < fw_link_param_count(); ++i) {
        const ht_param_info_t *row = NULL;
        TEST_ASSERT_EQUAL_INT(0, fw_link_param_get(&lk, i, NULL, &row));
        const uint8_t t = fw_link_param_mav_type(i);
        TEST_ASSERT_EQUAL_INT(row->scale == 1, t != MAV_PARAM_TYPE_REAL32);
    }
    /* an integer set in the row's own type (C-cast: the number) */
    unsigned from = nrx;
    set_typed("NAV_L1", bits_of(200.0f), MAV_PARAM_TYPE_UINT16);
    const mavlink_param_value_t *pv = last_value(from);
    TEST_ASSERT_EQUAL_UINT8(MAV_PARAM_TYPE_UINT16, pv->param_type);
    TEST_ASSERT_EQUAL_FLOAT(200.0f, pv->param_value);
    TEST_ASSERT_EQUAL_UINT16(200u, cfg.modes.nav.l1_m);
}

static void test_param_type_is_honoured_or_the_set_refused(void)
{
    const uint16_t l1_before = cfg.modes.nav.l1_m;
    const int32_t vmin_before = cfg.law.v_min_cm_s;
    const uint8_t hz_before = lk.params.attitude_hz;
    struct {
        const char *id;
        uint32_t bits;
        uint8_t type;
        const char *why;
    } bad[] = {
        /* an INT32 3 sent byte-wise into a fixed-point row: the 0 */
        {"LAW_V_MIN", 3u, MAV_PARAM_TYPE_INT32, "LAW_V_MIN refused: type 6, not 9|"},
        {"LNK_ATTITUDE_HZ", 3u, MAV_PARAM_TYPE_UINT8, "LNK_ATTITUDE_HZ refused: not an integer|"},
        {"LNK_ATTITUDE_HZ", bits_of(3.0f), MAV_PARAM_TYPE_INT32,
         "LNK_ATTITUDE_HZ refused: type 6, not 1 or 9|"},
        {"LNK_ATTITUDE_HZ", bits_of(3.0f), 0u, "LNK_ATTITUDE_HZ refused: type 0, not 1 or 9|"},
        {"LNK_ATTITUDE_HZ", bits_of(3.0f), 255u, "LNK_ATTITUDE_HZ refused: type 255, not 1 or 9|"},
        {"NAV_L1", bits_of(200.5f), MAV_PARAM_TYPE_UINT16, "NAV_L1 refused: not an integer|"},
        {"NAV_L1", bits_of(601.0f), MAV_PARAM_TYPE_REAL32, "NAV_L1 refused: outside [5, 600] m|"},
        {"LAW_V_MIN", bits_of(NAN), MAV_PARAM_TYPE_REAL32, "LAW_V_MIN refused: not a number|"},
        {"LAW_V_MIN", bits_of(1e30f), MAV_PARAM_TYPE_REAL32,
         "LAW_V_MIN refused: outside [1, 327.67] m/s|"},
        {"LAW_V_MIN", bits_of(20.0f), MAV_PARAM_TYPE_REAL32, "LAW_V_MIN refused by a joint limit|"},
    };
    for (unsigned i = 0u; i < sizeof bad / sizeof bad[0]; ++i) {
        steps(8u); /* the text rate: one per 200 ms */
        const unsigned from = nrx;
        set_typed(bad[i].id, bad[i].bits, bad[i].type);
        TEST_ASSERT_EQUAL_STRING(bad[i].why, texts(from));
        /* answered with the value in force, unchanged */
        const mavlink_param_value_t *pv = last_value(from);
        TEST_ASSERT_EQUAL_STRING_LEN(bad[i].id, pv->param_id, strlen(bad[i].id));
        TEST_ASSERT_EQUAL_UINT16(l1_before, cfg.modes.nav.l1_m);
        TEST_ASSERT_EQUAL_INT32(vmin_before, cfg.law.v_min_cm_s);
        TEST_ASSERT_EQUAL_UINT8(hz_before, lk.params.attitude_hz);
    }
    /* an unknown id: no PARAM_VALUE (the spec), but the reason */
    steps(8u);
    const unsigned from = nrx;
    set_typed("NO_SUCH_PARAM", bits_of(1.0f), MAV_PARAM_TYPE_REAL32);
    TEST_ASSERT_EQUAL_UINT(0u, count_id(MAVLINK_MSG_ID_PARAM_VALUE, from));
    TEST_ASSERT_EQUAL_STRING("NO_SUCH_PARAM refused: no such parameter|", texts(from));
}

/* MAVProxy: |echo - sent| <= 1e-5; MAVSDK: the same float, the same type */
static void test_a_rounded_set_echoes_what_was_sent(void)
{
    const struct {
        const char *id;
        float sent;
        int32_t raw;
        float read;
    } cases[] = {{"LAW_V_MIN", 5.005f, 501, 5.01f},
                 {"NAV_L1", 200.5f, 201, 201.0f},
                 {"NAV_L1", 199.4f, 199, 199.0f}};
    for (unsigned i = 0u; i < 3u; ++i) {
        unsigned from = nrx;
        set_typed(cases[i].id, bits_of(cases[i].sent), MAV_PARAM_TYPE_REAL32);
        const mavlink_param_value_t *pv = last_value(from);
        TEST_ASSERT_EQUAL_HEX32(bits_of(cases[i].sent), bits_of(pv->param_value));
        TEST_ASSERT_EQUAL_UINT8(fw_link_param_mav_type((uint16_t)fw_link_param_find(cases[i].id)),
                                pv->param_type);
        int32_t raw = 0;
        TEST_ASSERT_EQUAL_INT(
            0, fw_link_param_get(&lk, (uint16_t)fw_link_param_find(cases[i].id), &raw, NULL));
        TEST_ASSERT_EQUAL_INT32(cases[i].raw, raw);
        /* a read gives the stored value */
        from = nrx;
        mavlink_message_t m;
        mavlink_msg_param_request_read_pack(GCS_SYS, GCS_COMP, &m, OUR_SYS, OUR_COMP,
                                            id16(cases[i].id), -1);
        send(&m);
        TEST_ASSERT_EQUAL_HEX32(bits_of(cases[i].read), bits_of(last_value(from)->param_value));
    }
}

static void test_param_read_index_minus_two_is_refused(void)
{
    steps(2u);
    mavlink_message_t m;
    unsigned from = nrx;
    mavlink_msg_param_request_read_pack(GCS_SYS, GCS_COMP, &m, OUR_SYS, OUR_COMP, id16("NAV_L1"),
                                        -2);
    send(&m);
    TEST_ASSERT_EQUAL_UINT(0u, count_id(MAVLINK_MSG_ID_PARAM_VALUE, from));
    TEST_ASSERT_EQUAL_STRING("param read refused: index -2|", texts(from));
    from = nrx;
    mavlink_msg_param_request_read_pack(GCS_SYS, GCS_COMP, &m, OUR_SYS, OUR_COMP, id16("NAV_L1"),
                                        -1);
    send(&m);
    TEST_ASSERT_EQUAL_UINT(1u, count_id(MAVLINK_MSG_ID_PARAM_VALUE, from));
}

/* a set the joint rule refuses (issue 33) says the rule's reason on the wire,
 * and the value in force stays */
static void test_joint_refusal_names_the_rule(void)
{
    steps(8u); /* the text rate: one per 200 ms */
    const int32_t index = fw_link_param_find(id16("MOD_MODE_INPUT"));
    TEST_ASSERT_TRUE(index >= 0);
    int32_t before = -1;
    TEST_ASSERT_EQUAL_INT(0, fw_link_param_get(&lk, (uint16_t)index, &before, NULL));
    TEST_ASSERT_NOT_EQUAL(0, before);
    unsigned from = nrx;
    set_param("MOD_MODE_INPUT", 0.0f); /* the aileron stick */
    TEST_ASSERT_EQUAL_STRING("joint.mode_input is a stick channel|", texts(from));
    TEST_ASSERT_EQUAL_FLOAT((float)before, param_value_of("MOD_MODE_INPUT", from));
}

/* --- missions -------------------------------------------------------------- */

static void test_mission_frames_0_and_3_are_accepted(void)
{
    steps(40u);
    unsigned from = nrx;
    send_count(2u);
    send_item(0u, wp_lat[0], wp_lon[0], 620.0f, MAV_FRAME_GLOBAL, MAV_CMD_NAV_WAYPOINT);
    send_item(1u, wp_lat[1], wp_lon[1], 120.0f, MAV_FRAME_GLOBAL_RELATIVE_ALT,
              MAV_CMD_NAV_WAYPOINT);
    TEST_ASSERT_EQUAL_INT(MAV_MISSION_ACCEPTED, last_ack(from));
    TEST_ASSERT_EQUAL_UINT16(2u, cfg.waypoint_count);
    TEST_ASSERT_EQUAL_INT32(620, cfg.waypoints[0].alt_m);
    TEST_ASSERT_EQUAL_INT32(620, cfg.waypoints[1].alt_m); /* 120 above home at 500 m */
}

static void test_legacy_mission_item_upload(void)
{
    steps(40u);
    unsigned from = nrx;
    send_count(2u);
    for (uint16_t i = 0u; i < 2u; ++i) {
        mavlink_message_t m;
        mavlink_msg_mission_item_pack(GCS_SYS, GCS_COMP, &m, OUR_SYS, OUR_COMP, i,
                                      MAV_FRAME_GLOBAL_RELATIVE_ALT, MAV_CMD_NAV_WAYPOINT, 0, 1, 0,
                                      0, 0, 0, (float)wp_lat[i] * 1e-7f, (float)wp_lon[i] * 1e-7f,
                                      100.0f, MAV_MISSION_TYPE_MISSION);
        send(&m);
    }
    /* asked in its own words after the first legacy item */
    TEST_ASSERT_EQUAL_UINT(1u, count_id(MAVLINK_MSG_ID_MISSION_REQUEST, from));
    TEST_ASSERT_EQUAL_INT(MAV_MISSION_ACCEPTED, last_ack(from));
    TEST_ASSERT_EQUAL_UINT16(2u, cfg.waypoint_count);
    /* float degrees: within a float's step (4e-6 deg at 47: 0.4 m) of the E7 */
    TEST_ASSERT_INT32_WITHIN(40, wp_lat[1], lk.items[1].lat_e7);
    TEST_ASSERT_INT32_WITHIN(40, wp_lon[1], lk.items[1].lon_e7);
    TEST_ASSERT_INT32_WITHIN(1, 111, cfg.waypoints[1].north_m); /* 1e-3 deg north: 111 m */
}

/* A refused upload leaves the flown mission and the download untouched. */
/* a list the joint rule refuses (a leg under twice the arrival radius) is
 * refused like an out-of-range one: the modes never re-initialised on it
 * (found by fuzz_mavlink_rx: the step was left unready) */
static void test_short_leg_upload_is_refused_and_the_step_stays_ready(void)
{
    steps(40u);
    upload_square();
    TEST_ASSERT_EQUAL_UINT16(4u, cfg.waypoint_count);
    ht_waypoint_t before[4];
    memcpy(before, cfg.waypoints, sizeof before);
    steps(8u);
    const unsigned from = nrx;
    send_count(2u);
    send_item(0u, wp_lat[0], wp_lon[0], 100.0f, MAV_FRAME_GLOBAL_RELATIVE_ALT_INT,
              MAV_CMD_NAV_WAYPOINT);
    send_item(1u, wp_lat[0] + 90, wp_lon[0], 100.0f, MAV_FRAME_GLOBAL_RELATIVE_ALT_INT,
              MAV_CMD_NAV_WAYPOINT); /* 1 m north */
    TEST_ASSERT_EQUAL_INT(MAV_MISSION_ERROR, last_ack(from));
    TEST_ASSERT_EQUAL_STRING("mission refused: leg < 2x arrival radius, item 1|", texts(from));
    TEST_ASSERT_EQUAL_UINT16(4u, cfg.waypoint_count);
    TEST_ASSERT_EQUAL_MEMORY(before, cfg.waypoints, sizeof before);
    steps(4u);
    TEST_ASSERT_EQUAL_UINT8(1u, fw.ready);
    TEST_ASSERT_EQUAL_UINT8(1u, fw.modes.ready);
}

static void test_refused_upload_keeps_the_flown_mission(void)
{
    steps(40u);
    upload_square();
    TEST_ASSERT_EQUAL_UINT16(4u, cfg.waypoint_count);
    ht_waypoint_t before[4];
    memcpy(before, cfg.waypoints, sizeof before);
    const struct {
        int32_t lat, lon;
        float z;
        uint8_t frame;
    } bad[] = {
        {-470000000, -1720000000, 100.0f, MAV_FRAME_GLOBAL_INT},             /* 10 450 km */
        {wp_lat[0], wp_lon[0], 99999.0f, MAV_FRAME_GLOBAL_RELATIVE_ALT_INT}, /* 100.5 km */
    };
    for (unsigned k = 0u; k < 2u; ++k) {
        steps(8u);
        unsigned from = nrx;
        send_count(2u);
        send_item(0u, wp_lat[0], wp_lon[0], 100.0f, MAV_FRAME_GLOBAL_RELATIVE_ALT_INT,
                  MAV_CMD_NAV_WAYPOINT);
        send_item(1u, bad[k].lat, bad[k].lon, bad[k].z, bad[k].frame, MAV_CMD_NAV_WAYPOINT);
        TEST_ASSERT_EQUAL_INT(MAV_MISSION_ERROR, last_ack(from));
        TEST_ASSERT_EQUAL_STRING("mission refused: out of range, item 1|", texts(from));
        TEST_ASSERT_EQUAL_UINT16(4u, cfg.waypoint_count);
        TEST_ASSERT_EQUAL_MEMORY(before, cfg.waypoints, sizeof before);
        /* the download is the flown list */
        from = nrx;
        mavlink_message_t m;
        mavlink_msg_mission_request_list_pack(GCS_SYS, GCS_COMP, &m, OUR_SYS, OUR_COMP,
                                              MAV_MISSION_TYPE_MISSION);
        send(&m);
        mavlink_mission_count_t c;
        mavlink_msg_mission_count_decode(last_id(MAVLINK_MSG_ID_MISSION_COUNT, from), &c);
        TEST_ASSERT_EQUAL_UINT16(4u, c.count);
        TEST_ASSERT_EQUAL_INT32(wp_lat[3], lk.items[3].lat_e7);
    }
    /* refused by item: the same */
    unsigned from = nrx;
    send_count(2u);
    send_item(0u, wp_lat[0], wp_lon[0], 100.0f, MAV_FRAME_GLOBAL_INT, MAV_CMD_NAV_LAND);
    TEST_ASSERT_EQUAL_INT(MAV_MISSION_UNSUPPORTED, last_ack(from));
    TEST_ASSERT_EQUAL_STRING("mission refused: item 0 command 21|", texts(from));
    TEST_ASSERT_EQUAL_UINT16(4u, cfg.waypoint_count);
    TEST_ASSERT_EQUAL_MEMORY(before, cfg.waypoints, sizeof before);
}

/* Accepted before the first fix: applied at the fix and said so, or (out of
 * range of where home turned out to be) reported, the earlier list kept. */
static void test_deferred_upload_is_applied_or_reported(void)
{
    gps_on = 0u;
    steps(10u);
    unsigned from = nrx;
    upload_square();
    TEST_ASSERT_EQUAL_STRING("mission accepted: flown at GPS fix|", texts(from));
    TEST_ASSERT_EQUAL_UINT16(0u, cfg.waypoint_count);
    gps_on = 1u;
    from = nrx;
    steps(10u);
    TEST_ASSERT_EQUAL_UINT16(4u, cfg.waypoint_count);
    TEST_ASSERT_EQUAL_STRING("mission flown from GPS fix|", texts(from));
}

static void test_deferred_upload_refused_at_the_fix_is_reported(void)
{
    gps_on = 0u;
    steps(10u);
    unsigned from = nrx;
    send_count(1u);
    send_item(0u, -470000000, -1720000000, 100.0f, MAV_FRAME_GLOBAL_INT, MAV_CMD_NAV_WAYPOINT);
    TEST_ASSERT_EQUAL_INT(MAV_MISSION_ACCEPTED, last_ack(from));
    gps_on = 1u;
    from = nrx;
    steps(10u);
    TEST_ASSERT_EQUAL_UINT16(0u, cfg.waypoint_count);
    TEST_ASSERT_EQUAL_UINT8(0u, lk.mission.apply_pending);
    TEST_ASSERT_EQUAL_STRING("mission refused at GPS fix, item 0|", texts(from));
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_heartbeat_is_ardupilot_plane_and_armed_is_the_image_state);
    RUN_TEST(test_arm_disarm_is_denied_with_the_reason);
    RUN_TEST(test_command_int_is_answered_like_command_long);
    RUN_TEST(test_do_set_mode_refuses_a_fraction);
    RUN_TEST(test_heartbeat_interval_is_bounded);
    RUN_TEST(test_get_message_interval_answers_every_stream);
    RUN_TEST(test_storage_is_refused_while_flying);
    RUN_TEST(test_statustext_rate_is_bounded);
    RUN_TEST(test_text_fixed_against_double);
    RUN_TEST(test_integer_rows_travel_as_integer_types);
    RUN_TEST(test_param_type_is_honoured_or_the_set_refused);
    RUN_TEST(test_a_rounded_set_echoes_what_was_sent);
    RUN_TEST(test_param_read_index_minus_two_is_refused);
    RUN_TEST(test_joint_refusal_names_the_rule);
    RUN_TEST(test_mission_frames_0_and_3_are_accepted);
    RUN_TEST(test_legacy_mission_item_upload);
    RUN_TEST(test_refused_upload_keeps_the_flown_mission);
    RUN_TEST(test_short_leg_upload_is_refused_and_the_step_stays_ready);
    RUN_TEST(test_deferred_upload_is_applied_or_reported);
    RUN_TEST(test_deferred_upload_refused_at_the_fix_is_reported);
    return UNITY_END();
}
