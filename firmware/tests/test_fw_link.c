/*
 * test_fw_link.c - the MAVLink link of the firmware step against a ground
 * station made of the generated pack / parse helpers (the frames the link
 * reads are packed by them, the frames it sends are parsed by them):
 * telemetry content and rates over a simulated second, the parameter
 * protocol over the whole table, the mission protocol (upload, download,
 * current, clear, retries, refusals), the mode commands against the RC
 * switch and the RC-loss failsafe, and the receive path's drop counters.
 */
#include "unity.h"

#include "helical/estimator/air_data.h"
#include "link_fixture.h"

#include <math.h>
#include <string.h>

/* --- telemetry ------------------------------------------------------------- */

static void test_telemetry_rates_over_one_second(void)
{
    steps(40u); /* a second: home, rates settled */
    const unsigned from = nrx;
    steps(40u);
    TEST_ASSERT_EQUAL_UINT(1u, count_id(MAVLINK_MSG_ID_HEARTBEAT, from));
    TEST_ASSERT_EQUAL_UINT(1u, count_id(MAVLINK_MSG_ID_SYS_STATUS, from));
    TEST_ASSERT_EQUAL_UINT(10u, count_id(MAVLINK_MSG_ID_ATTITUDE, from));
    TEST_ASSERT_EQUAL_UINT(5u, count_id(MAVLINK_MSG_ID_GLOBAL_POSITION_INT, from));
    TEST_ASSERT_EQUAL_UINT(4u, count_id(MAVLINK_MSG_ID_VFR_HUD, from));
    TEST_ASSERT_EQUAL_UINT(2u, count_id(MAVLINK_MSG_ID_SERVO_OUTPUT_RAW, from));
    TEST_ASSERT_EQUAL_UINT(2u, count_id(MAVLINK_MSG_ID_RC_CHANNELS, from));
    TEST_ASSERT_EQUAL_UINT(10u, count_id(MAVLINK_MSG_ID_DEBUG_VECT, from)); /* 2 per law tick */
    TEST_ASSERT_EQUAL_UINT32(0u, lk.count.tx_overflow);
    TEST_ASSERT_EQUAL_UINT32(nrx, lk.count.tx_frames);
    TEST_ASSERT_EQUAL_UINT32(0u, rx_st.packet_rx_drop_count);
    /* a rate that does not divide the control rate is met on average: 3 Hz */
    mavlink_message_t m;
    mavlink_msg_param_set_pack(GCS_SYS, GCS_COMP, &m, OUR_SYS, OUR_COMP, id16("LNK_ATTITUDE_HZ"),
                               3.0f, MAV_PARAM_TYPE_REAL32);
    send(&m);
    steps(40u);
    const unsigned from3 = nrx;
    steps(120u);
    TEST_ASSERT_EQUAL_UINT(9u, count_id(MAVLINK_MSG_ID_ATTITUDE, from3));
    /* 50 Hz is above the 40 Hz control rate: one per step */
    mavlink_msg_param_set_pack(GCS_SYS, GCS_COMP, &m, OUR_SYS, OUR_COMP, id16("LNK_ATTITUDE_HZ"),
                               50.0f, MAV_PARAM_TYPE_REAL32);
    send(&m);
    const unsigned from50 = nrx;
    steps(40u);
    TEST_ASSERT_EQUAL_UINT(40u, count_id(MAVLINK_MSG_ID_ATTITUDE, from50));
    /* SET_MESSAGE_INTERVAL 500 ms, then off */
    mavlink_msg_command_long_pack(GCS_SYS, GCS_COMP, &m, OUR_SYS, OUR_COMP,
                                  MAV_CMD_SET_MESSAGE_INTERVAL, 0, (float)MAVLINK_MSG_ID_VFR_HUD,
                                  500000.0f, 0, 0, 0, 0, 0);
    send(&m);
    steps(40u);
    const unsigned from_iv = nrx;
    steps(80u);
    TEST_ASSERT_EQUAL_UINT(4u, count_id(MAVLINK_MSG_ID_VFR_HUD, from_iv));
    mavlink_msg_command_long_pack(GCS_SYS, GCS_COMP, &m, OUR_SYS, OUR_COMP,
                                  MAV_CMD_SET_MESSAGE_INTERVAL, 0, (float)MAVLINK_MSG_ID_VFR_HUD,
                                  -1.0f, 0, 0, 0, 0, 0);
    send(&m);
    const unsigned from_off = nrx;
    steps(40u);
    TEST_ASSERT_EQUAL_UINT(0u, count_id(MAVLINK_MSG_ID_VFR_HUD, from_off));
}

static void test_telemetry_content(void)
{
    steps(80u);
    const mavlink_message_t *m = last_id(MAVLINK_MSG_ID_HEARTBEAT, 0u);
    TEST_ASSERT_NOT_NULL(m);
    mavlink_heartbeat_t hb;
    mavlink_msg_heartbeat_decode(m, &hb);
    TEST_ASSERT_EQUAL_UINT8(MAV_TYPE_FIXED_WING, hb.type);
    TEST_ASSERT_EQUAL_UINT8(MAV_AUTOPILOT_ARDUPILOTMEGA, hb.autopilot);
    TEST_ASSERT_EQUAL_UINT32(FW_LINK_CUSTOM_MANUAL, hb.custom_mode);
    TEST_ASSERT_TRUE((hb.base_mode & MAV_MODE_FLAG_MANUAL_INPUT_ENABLED) != 0u);
    TEST_ASSERT_TRUE((hb.base_mode & MAV_MODE_FLAG_CUSTOM_MODE_ENABLED) != 0u);
    TEST_ASSERT_EQUAL_UINT8(MAV_STATE_ACTIVE, hb.system_status);
    TEST_ASSERT_EQUAL_UINT8(OUR_SYS, m->sysid);
    TEST_ASSERT_EQUAL_UINT8(OUR_COMP, m->compid);

    mavlink_global_position_int_t g;
    mavlink_msg_global_position_int_decode(last_id(MAVLINK_MSG_ID_GLOBAL_POSITION_INT, 0u), &g);
    TEST_ASSERT_INT32_WITHIN(1, HOME_LAT, g.lat);
    TEST_ASSERT_INT32_WITHIN(1, HOME_LON, g.lon);
    TEST_ASSERT_EQUAL_INT32(500000, g.alt); /* mm */
    TEST_ASSERT_EQUAL_INT32(0, g.relative_alt);

    mavlink_attitude_t a;
    mavlink_msg_attitude_decode(last_id(MAVLINK_MSG_ID_ATTITUDE, 0u), &a);
    TEST_ASSERT_FLOAT_WITHIN(0.002f, (float)out.est.roll_cdeg * 3.14159265f / 18000.0f, a.roll);
    TEST_ASSERT_FLOAT_WITHIN(0.002f, (float)out.est.pitch_cdeg * 3.14159265f / 18000.0f, a.pitch);
    TEST_ASSERT_FLOAT_WITHIN(0.01f, 0.0f, a.roll); /* level */

    mavlink_vfr_hud_t v;
    mavlink_msg_vfr_hud_decode(last_id(MAVLINK_MSG_ID_VFR_HUD, 0u), &v);
    /* the true airspeed the firmware flies: 15 m/s indicated at 500 m */
    TEST_ASSERT_EQUAL_FLOAT((float)ht_true_airspeed_cm_s(1500, 50000, 0, 0u) / 100.0f, v.airspeed);
    TEST_ASSERT_EQUAL_FLOAT(500.0f, v.alt);

    mavlink_servo_output_raw_t s;
    mavlink_msg_servo_output_raw_decode(last_id(MAVLINK_MSG_ID_SERVO_OUTPUT_RAW, 0u), &s);
    TEST_ASSERT_EQUAL_UINT16(out.pulse_us[0], s.servo1_raw);
    TEST_ASSERT_EQUAL_UINT16(out.pulse_us[4], s.servo5_raw);
    TEST_ASSERT_EQUAL_UINT16(0u, s.servo6_raw);

    mavlink_rc_channels_t r;
    mavlink_msg_rc_channels_decode(last_id(MAVLINK_MSG_ID_RC_CHANNELS, 0u), &r);
    TEST_ASSERT_EQUAL_UINT8(6u, r.chancount);
    TEST_ASSERT_EQUAL_UINT16(1000u, r.chan5_raw);
    TEST_ASSERT_EQUAL_UINT16(UINT16_MAX, r.chan7_raw);

    /* the law's state: roll and pitch error as the step computed them */
    unsigned seen = 0u;
    for (unsigned i = 0u; i < nrx; ++i) {
        if (rx[i].msgid == MAVLINK_MSG_ID_DEBUG_VECT) {
            mavlink_debug_vect_t d;
            mavlink_msg_debug_vect_decode(&rx[i], &d);
            seen |= (strncmp(d.name, "HT_ERR", 10) == 0) ? 1u : 0u;
            seen |= (strncmp(d.name, "HT_TILT", 10) == 0) ? 2u : 0u;
        }
    }
    TEST_ASSERT_EQUAL_UINT(3u, seen);
}

/* --- parameters ------------------------------------------------------------ */

static void test_param_ids_unique_and_short(void)
{
    const uint16_t n = fw_link_param_count();
    TEST_ASSERT_EQUAL_UINT16(HT_PARAM_LAW_COUNT + HT_PARAM_DCM_COUNT + HT_PARAM_GUIDE_COUNT +
                                 HT_PARAM_ALT_COUNT + HT_PARAM_SPEED_COUNT + HT_PARAM_MODES_COUNT +
                                 HT_PARAM_FBW_COUNT + HT_PARAM_NAV_COUNT + HT_PARAM_AOA_COUNT +
                                 HT_PARAM_LINK_COUNT,
                             n);
    for (uint16_t i = 0u; i < n; ++i) {
        char a[17];
        TEST_ASSERT_EQUAL_INT(0, fw_link_param_id(i, a));
        TEST_ASSERT_TRUE(strlen(a) <= 16u && strlen(a) > 4u);
        TEST_ASSERT_EQUAL_INT32((int32_t)i, fw_link_param_find(a));
        for (uint16_t j = 0u; j < i; ++j) {
            char b[17];
            (void)fw_link_param_id(j, b);
            TEST_ASSERT_TRUE(strcmp(a, b) != 0);
        }
    }
    char id[17];
    TEST_ASSERT_EQUAL_INT(-1, fw_link_param_id(n, id));
    TEST_ASSERT_EQUAL_STRING("", id);
    /* the rule: prefix + ID, vowels dropped from the end while too long */
    (void)fw_link_param_id(0u, id);
    TEST_ASSERT_EQUAL_STRING("LAW_KP_AILERON", id);
    TEST_ASSERT_TRUE(fw_link_param_find("GDE_TRN_TRM_MN_R") >= 0);
    TEST_ASSERT_TRUE(fw_link_param_find("ALT_PROTECT_VALD") >= 0);
    TEST_ASSERT_EQUAL_INT32(-1, fw_link_param_find("LAW_NO_SUCH"));
}

/* the link's own rows (params.def HT_PARAMS_LINK): defaults, names, and
 * every bound edge through the parameter protocol's setter */
static void test_link_rows_defaults_and_edges(void)
{
    fw_link_params_t d;
    ht_link_params_default(&d);
    TEST_ASSERT_EQUAL_INT(HT_LINK_P_NONE, ht_link_first_bad(&d));
    TEST_ASSERT_EQUAL_UINT8(1u, d.sysid);
    TEST_ASSERT_EQUAL_UINT8(10u, d.attitude_hz);
    TEST_ASSERT_EQUAL_UINT16(1500u, d.mission_timeout_ms);
    TEST_ASSERT_EQUAL_STRING("attitude_hz", ht_link_param_name(HT_LINK_P_ATTITUDE_HZ));
    TEST_ASSERT_NULL(ht_link_param_info(HT_LINK_P_COUNT));
    const uint16_t first = (uint16_t)(fw_link_param_count() - HT_PARAM_LINK_COUNT);
    for (int id = 1; id < (int)HT_LINK_P_COUNT; ++id) {
        const ht_param_info_t *row = ht_link_param_info((ht_link_param_id_t)id);
        TEST_ASSERT_NOT_NULL(row);
        const uint16_t index = (uint16_t)(first + (uint16_t)(id - 1));
        int32_t raw = 0;
        const ht_param_info_t *same = NULL;
        TEST_ASSERT_EQUAL_INT(0, fw_link_param_get(&lk, index, &raw, &same));
        TEST_ASSERT_EQUAL_PTR(row, same);
        TEST_ASSERT_EQUAL_INT32(row->default_raw, raw);
        TEST_ASSERT_NOT_EQUAL(0, fw_link_param_set(&lk, index, row->min_raw - 1));
        TEST_ASSERT_NOT_EQUAL(0, fw_link_param_set(&lk, index, row->max_raw + 1));
        TEST_ASSERT_EQUAL_INT(0, fw_link_param_set(&lk, index, row->max_raw));
        TEST_ASSERT_EQUAL_INT(0, fw_link_param_set(&lk, index, row->min_raw));
        TEST_ASSERT_EQUAL_INT(0, fw_link_param_get(&lk, index, &raw, NULL));
        TEST_ASSERT_EQUAL_INT32(row->min_raw, raw);
        TEST_ASSERT_EQUAL_INT(HT_LINK_P_NONE, ht_link_first_bad(&lk.params));
    }
}

static void test_param_list_and_read(void)
{
    steps(2u);
    mavlink_message_t m;
    mavlink_msg_param_request_list_pack(GCS_SYS, GCS_COMP, &m, OUR_SYS, OUR_COMP);
    send(&m);
    const unsigned from = nrx;
    steps(60u);
    const uint16_t n = fw_link_param_count();
    static uint8_t seen[512];
    memset(seen, 0, sizeof seen);
    unsigned values = 0u;
    for (unsigned i = from; i < nrx; ++i) {
        if (rx[i].msgid == MAVLINK_MSG_ID_PARAM_VALUE) {
            mavlink_param_value_t pv;
            mavlink_msg_param_value_decode(&rx[i], &pv);
            TEST_ASSERT_EQUAL_UINT16(n, pv.param_count);
            /* integer rows as their integer type, fixed-point ones as REAL32 */
            TEST_ASSERT_EQUAL_UINT8(fw_link_param_mav_type(pv.param_index), pv.param_type);
            TEST_ASSERT_TRUE(pv.param_index < n);
            ++seen[pv.param_index];
            ++values;
            /* each value is the row's stored value in its unit */
            int32_t raw = 0;
            const ht_param_info_t *row = NULL;
            TEST_ASSERT_EQUAL_INT(0, fw_link_param_get(&lk, pv.param_index, &raw, &row));
            TEST_ASSERT_EQUAL_FLOAT((float)((double)raw / row->scale), pv.param_value);
        }
    }
    TEST_ASSERT_EQUAL_UINT(n, values);
    for (uint16_t i = 0u; i < n; ++i) {
        TEST_ASSERT_EQUAL_UINT8(1u, seen[i]);
    }
    TEST_ASSERT_EQUAL_UINT32(0u, lk.count.tx_overflow);
    /* read by name and by index */
    mavlink_msg_param_request_read_pack(GCS_SYS, GCS_COMP, &m, OUR_SYS, OUR_COMP, id16("LAW_V_REF"),
                                        -1);
    send(&m);
    TEST_ASSERT_EQUAL_FLOAT(15.0f, param_value_of("LAW_V_REF", 0u));
    mavlink_msg_param_request_read_pack(GCS_SYS, GCS_COMP, &m, OUR_SYS, OUR_COMP, id16(""), 0);
    send(&m);
    TEST_ASSERT_EQUAL_FLOAT(1.0f, param_value_of("LAW_KP_AILERON", 0u));
}

static void test_param_set_applies_without_resetting_the_flight(void)
{
    steps(80u);
    ht_dcm_state_t dcm_before;
    ht_modes_state_t modes_before;
    memcpy(&dcm_before, &fw.dcm_state, sizeof dcm_before); /* padding too */
    memcpy(&modes_before, &fw.modes_state, sizeof modes_before);
    const unsigned from = nrx;
    set_param("LAW_KP_AILERON", 2.5f);
    TEST_ASSERT_EQUAL_FLOAT(2.5f, param_value_of("LAW_KP_AILERON", from));
    TEST_ASSERT_EQUAL_INT32(163840, cfg.law.kp_aileron);
    /* the running controllers are the ones ht_init builds from the new value */
    for (uint8_t mode = 0u; mode < 2u; ++mode) {
        ht_params_t p = cfg.law;
        p.pitch_mode = mode;
        ht_controller_t want;
        TEST_ASSERT_EQUAL_INT(HT_OK, ht_init(&want, &p, NULL));
        const ht_controller_t *have = &fw.law[mode];
        TEST_ASSERT_EQUAL_INT32_ARRAY(want.gains.kp, have->gains.kp, 3);
        TEST_ASSERT_EQUAL_INT32_ARRAY(want.gains.kff, have->gains.kff, 3);
        TEST_ASSERT_EQUAL_INT32_ARRAY(want.gains.kd, have->gains.kd, 3);
        TEST_ASSERT_EQUAL_INT16(want.v_ref_cm_s, have->v_ref_cm_s);
        TEST_ASSERT_EQUAL_INT16(want.v_min_cm_s, have->v_min_cm_s);
        TEST_ASSERT_EQUAL_INT32(want.max_tilt_g_q18, have->max_tilt_g_q18);
        TEST_ASSERT_EQUAL_UINT8(mode, have->pitch_mode);
        TEST_ASSERT_EQUAL_UINT8(1u, have->ready);
    }
    /* the estimator's and the modes' states are untouched */
    TEST_ASSERT_EQUAL_MEMORY(&dcm_before, &fw.dcm_state, sizeof dcm_before);
    TEST_ASSERT_EQUAL_MEMORY(&modes_before, &fw.modes_state, sizeof modes_before);
    /* a hold's gain reaches the modes (re-initialised), the estimator's gain its block */
    set_param("ALT_KP", 0.0625f);
    TEST_ASSERT_EQUAL_INT32(4096, cfg.modes.alt.kp_pitch_per_m);
    TEST_ASSERT_EQUAL_INT32(4096, fw.modes.alt.kp_pitch_per_m);
    set_param("DCM_KP_ROLLPITCH", 0.5f);
    TEST_ASSERT_EQUAL_INT32(32768, cfg.dcm.kp_rollpitch);
    TEST_ASSERT_EQUAL_MEMORY(&dcm_before, &fw.dcm_state, sizeof dcm_before);
    steps(4u);
    TEST_ASSERT_EQUAL_UINT8(1u, fw.ready);
    TEST_ASSERT_EQUAL_UINT8(5u, out.pulse_count);
}

static void test_param_set_refusals_answer_the_old_value(void)
{
    steps(2u);
    unsigned from = nrx;
    set_param("LAW_KP_AILERON", 65.0f); /* above the row's 64 */
    TEST_ASSERT_EQUAL_FLOAT(1.0f, param_value_of("LAW_KP_AILERON", from));
    TEST_ASSERT_EQUAL_INT32(65536, cfg.law.kp_aileron);
    from = nrx;
    set_param("LAW_KP_AILERON", NAN);
    TEST_ASSERT_EQUAL_FLOAT(1.0f, param_value_of("LAW_KP_AILERON", from));
    from = nrx;
    set_param("LAW_V_MIN", 20.0f); /* in its row, but v_min <= v_ref = 15 (joint) */
    TEST_ASSERT_EQUAL_FLOAT(5.0f, param_value_of("LAW_V_MIN", from));
    TEST_ASSERT_EQUAL_INT32(500, cfg.law.v_min_cm_s);
    TEST_ASSERT_EQUAL_INT16(500, fw.law[0].v_min_cm_s);
    from = nrx;
    set_param("DCM_IMU_RATE", 100.0f); /* the step's timing is the build's */
    TEST_ASSERT_EQUAL_FLOAT(200.0f, param_value_of("DCM_IMU_RATE", from));
    from = nrx;
    set_param("SPD_THROTTLE_MIN", 0.9f); /* above throttle_max? no: max is 1; fine */
    TEST_ASSERT_FLOAT_WITHIN(1e-4f, 0.9f, param_value_of("SPD_THROTTLE_MIN", from));
    from = nrx;
    set_param("SPD_THROTTLE_MAX", 0.5f); /* below throttle_min 0.9 (joint) */
    TEST_ASSERT_EQUAL_FLOAT(1.0f, param_value_of("SPD_THROTTLE_MAX", from));
    /* an unknown id is not answered, and counted */
    const uint32_t bad = lk.count.rx_bad_content;
    from = nrx;
    set_param("NO_SUCH_PARAM", 1.0f);
    TEST_ASSERT_EQUAL_UINT(0u, count_id(MAVLINK_MSG_ID_PARAM_VALUE, from));
    TEST_ASSERT_EQUAL_UINT32(bad + 1u, lk.count.rx_bad_content);
    steps(2u);
    TEST_ASSERT_EQUAL_UINT8(5u, out.pulse_count);
}

/* --- missions -------------------------------------------------------------- */

static void test_mission_upload_download_current_clear(void)
{
    steps(40u);
    upload_square();
    TEST_ASSERT_EQUAL_UINT16(4u, cfg.waypoint_count);
    TEST_ASSERT_EQUAL_PTR(lk.waypoints, cfg.waypoints);
    TEST_ASSERT_EQUAL_UINT16(4u, fw.modes.nav.count);
    for (unsigned i = 0u; i < 4u; ++i) {
        int32_t n_cm = 0;
        int32_t e_cm = 0;
        ht_geo_to_local(&fw.home, wp_lat[i], wp_lon[i], &n_cm, &e_cm);
        TEST_ASSERT_EQUAL_INT32((int32_t)lround(n_cm / 100.0), cfg.waypoints[i].north_m);
        TEST_ASSERT_EQUAL_INT32((int32_t)lround(e_cm / 100.0), cfg.waypoints[i].east_m);
        TEST_ASSERT_INT32_WITHIN(120, 111 * (i < 2u ? 1 : -1), cfg.waypoints[i].north_m / 10);
    }
    TEST_ASSERT_EQUAL_INT32(500 + 120, cfg.waypoints[0].alt_m); /* above home (500 m) */
    TEST_ASSERT_EQUAL_INT32(123, cfg.waypoints[3].alt_m);       /* above sea level */
    /* download */
    mavlink_message_t m;
    unsigned from = nrx;
    mavlink_msg_mission_request_list_pack(GCS_SYS, GCS_COMP, &m, OUR_SYS, OUR_COMP,
                                          MAV_MISSION_TYPE_MISSION);
    send(&m);
    mavlink_mission_count_t c;
    mavlink_msg_mission_count_decode(last_id(MAVLINK_MSG_ID_MISSION_COUNT, from), &c);
    TEST_ASSERT_EQUAL_UINT16(4u, c.count);
    for (uint16_t i = 0u; i < 4u; ++i) {
        from = nrx;
        mavlink_msg_mission_request_int_pack(GCS_SYS, GCS_COMP, &m, OUR_SYS, OUR_COMP, i,
                                             MAV_MISSION_TYPE_MISSION);
        send(&m);
        mavlink_mission_item_int_t it;
        mavlink_msg_mission_item_int_decode(last_id(MAVLINK_MSG_ID_MISSION_ITEM_INT, from), &it);
        TEST_ASSERT_EQUAL_UINT16(i, it.seq);
        TEST_ASSERT_EQUAL_INT32(wp_lat[i], it.x);
        TEST_ASSERT_EQUAL_INT32(wp_lon[i], it.y);
        TEST_ASSERT_EQUAL_FLOAT(120.0f + (float)i, it.z);
        TEST_ASSERT_EQUAL_UINT16(MAV_CMD_NAV_WAYPOINT, it.command);
        TEST_ASSERT_EQUAL_UINT8(
            (i == 3u) ? MAV_FRAME_GLOBAL_INT : MAV_FRAME_GLOBAL_RELATIVE_ALT_INT, it.frame);
    }
    from = nrx;
    mavlink_msg_mission_request_int_pack(GCS_SYS, GCS_COMP, &m, OUR_SYS, OUR_COMP, 4u,
                                         MAV_MISSION_TYPE_MISSION);
    send(&m);
    TEST_ASSERT_EQUAL_INT(MAV_MISSION_INVALID_SEQUENCE, last_ack(from));
    /* set current */
    from = nrx;
    mavlink_msg_mission_set_current_pack(GCS_SYS, GCS_COMP, &m, OUR_SYS, OUR_COMP, 2u);
    send(&m);
    mavlink_mission_current_t mc;
    mavlink_msg_mission_current_decode(last_id(MAVLINK_MSG_ID_MISSION_CURRENT, from), &mc);
    TEST_ASSERT_EQUAL_UINT16(2u, mc.seq);
    TEST_ASSERT_EQUAL_UINT16(2u, fw.modes_state.nav.index);
    steps(2u);
    TEST_ASSERT_EQUAL_UINT16(2u, fw.modes_state.nav.index);
    /* clear */
    from = nrx;
    mavlink_msg_mission_clear_all_pack(GCS_SYS, GCS_COMP, &m, OUR_SYS, OUR_COMP,
                                       MAV_MISSION_TYPE_MISSION);
    send(&m);
    TEST_ASSERT_EQUAL_INT(MAV_MISSION_ACCEPTED, last_ack(from));
    TEST_ASSERT_EQUAL_UINT16(0u, cfg.waypoint_count);
    TEST_ASSERT_EQUAL_UINT16(0u, fw.modes.nav.count);
    steps(2u);
    TEST_ASSERT_EQUAL_UINT8(5u, out.pulse_count);
}

static void test_mission_waypoint_mode_flies_the_list(void)
{
    steps(40u);
    upload_square();
    in.rc_us[4] = 1800u; /* the switch: waypoint */
    steps(4u);
    TEST_ASSERT_EQUAL_UINT8(HT_MODE_WAYPOINT, out.modes.mode);
    TEST_ASSERT_EQUAL_UINT16(0u, out.modes.nav.index);
    /* the altitude target is item 0's: home 500 m + 120 m */
    TEST_ASSERT_EQUAL_INT32(62000, out.modes.nav.target_alt_cm);
}

static void test_mission_upload_retries_then_cancels(void)
{
    steps(40u);
    upload_square();
    unsigned from = nrx;
    send_count(2u);
    steps(400u); /* 10 s: 1.5 s timeout x (1 + 5 retries) = 9 s */
    TEST_ASSERT_EQUAL_UINT(6u, count_id(MAVLINK_MSG_ID_MISSION_REQUEST_INT, from));
    TEST_ASSERT_EQUAL_INT(MAV_MISSION_OPERATION_CANCELLED, last_ack(from));
    TEST_ASSERT_EQUAL_UINT16(4u, cfg.waypoint_count); /* the old list is still flown */
    /* a late item is not taken */
    send_item(0u, wp_lat[0], wp_lon[0], 50.0f, MAV_FRAME_GLOBAL_INT, MAV_CMD_NAV_WAYPOINT);
    TEST_ASSERT_EQUAL_INT32(620, cfg.waypoints[0].alt_m);
}

static void test_mission_refusals(void)
{
    steps(40u);
    unsigned from = nrx;
    send_count(FW_LINK_MAX_WAYPOINTS + 1u);
    TEST_ASSERT_EQUAL_INT(MAV_MISSION_NO_SPACE, last_ack(from));
    from = nrx;
    send_count(2u);
    send_item(0u, wp_lat[0], wp_lon[0], 50.0f, MAV_FRAME_GLOBAL_INT, MAV_CMD_NAV_LAND);
    TEST_ASSERT_EQUAL_INT(MAV_MISSION_UNSUPPORTED, last_ack(from));
    from = nrx;
    send_count(2u);
    send_item(0u, wp_lat[0], wp_lon[0], 50.0f, MAV_FRAME_LOCAL_NED, MAV_CMD_NAV_WAYPOINT);
    TEST_ASSERT_EQUAL_INT(MAV_MISSION_UNSUPPORTED_FRAME, last_ack(from));
    from = nrx;
    send_count(2u);
    send_item(0u, 910000000, wp_lon[0], 50.0f, MAV_FRAME_GLOBAL_INT, MAV_CMD_NAV_WAYPOINT);
    TEST_ASSERT_EQUAL_INT(MAV_MISSION_INVALID_PARAM5_X, last_ack(from));
    from = nrx;
    send_count(2u);
    send_item(0u, wp_lat[0], wp_lon[0], NAN, MAV_FRAME_GLOBAL_INT, MAV_CMD_NAV_WAYPOINT);
    TEST_ASSERT_EQUAL_INT(MAV_MISSION_INVALID_PARAM7, last_ack(from));
    /* an item out of turn is asked for again */
    from = nrx;
    send_count(2u);
    send_item(1u, wp_lat[0], wp_lon[0], 50.0f, MAV_FRAME_GLOBAL_INT, MAV_CMD_NAV_WAYPOINT);
    TEST_ASSERT_EQUAL_INT(0, last_request(from));
    TEST_ASSERT_EQUAL_UINT(2u, count_id(MAVLINK_MSG_ID_MISSION_REQUEST_INT, from));
    TEST_ASSERT_EQUAL_UINT16(0u, cfg.waypoint_count);
}

static void test_mission_before_home_waits_for_the_fix(void)
{
    gps_on = 0u;
    steps(10u);
    TEST_ASSERT_EQUAL_UINT8(0u, fw.have_home);
    upload_square();
    TEST_ASSERT_EQUAL_UINT16(0u, cfg.waypoint_count);
    gps_on = 1u;
    steps(10u);
    TEST_ASSERT_EQUAL_UINT16(4u, cfg.waypoint_count);
    TEST_ASSERT_EQUAL_INT32(620, cfg.waypoints[0].alt_m);
}

/* --- modes ----------------------------------------------------------------- */

/* custom_mode <-> ht_mode_t: the four fixed-wing numbers and nothing else,
 * over every number up to 1000 and the uint32 ends */
static void test_custom_mode_numbers(void)
{
    TEST_ASSERT_EQUAL_UINT(MAV_COMP_ID_AUTOPILOT1, FW_LINK_COMPID_AUTOPILOT);
    const uint32_t want[HT_MODE_COUNT] = {0u, 5u, 10u, 11u};
    for (uint8_t m = 0u; m < (uint8_t)HT_MODE_COUNT; ++m) {
        TEST_ASSERT_EQUAL_UINT32(want[m], fw_link_custom_mode(m));
        TEST_ASSERT_EQUAL_INT32(m, fw_link_mode_of_custom(want[m]));
    }
    TEST_ASSERT_EQUAL_UINT32(0u, fw_link_custom_mode((uint8_t)HT_MODE_COUNT));
    TEST_ASSERT_EQUAL_UINT32(0u, fw_link_custom_mode(UINT8_MAX));
    unsigned named = 0u;
    for (uint32_t c = 0u; c <= 1000u; ++c) {
        named += (fw_link_mode_of_custom(c) >= 0) ? 1u : 0u;
    }
    TEST_ASSERT_EQUAL_UINT(4u, named);
    TEST_ASSERT_EQUAL_INT32(-1, fw_link_mode_of_custom(UINT32_MAX));
}

static void test_mode_commands(void)
{
    steps(40u);
    unsigned from = nrx;
    do_set_mode(FW_LINK_CUSTOM_FBW);
    TEST_ASSERT_EQUAL_INT(MAV_RESULT_ACCEPTED, command_result(from, MAV_CMD_DO_SET_MODE));
    steps(40u);
    TEST_ASSERT_EQUAL_UINT8(HT_MODE_FBW, out.modes.mode);
    mavlink_heartbeat_t hb;
    mavlink_msg_heartbeat_decode(last_id(MAVLINK_MSG_ID_HEARTBEAT, from), &hb);
    TEST_ASSERT_EQUAL_UINT32(FW_LINK_CUSTOM_FBW, hb.custom_mode);
    TEST_ASSERT_TRUE((hb.base_mode & MAV_MODE_FLAG_STABILIZE_ENABLED) != 0u);

    mavlink_message_t m;
    from = nrx;
    mavlink_msg_command_long_pack(GCS_SYS, GCS_COMP, &m, OUR_SYS, OUR_COMP,
                                  MAV_CMD_NAV_RETURN_TO_LAUNCH, 0, 0, 0, 0, 0, 0, 0, 0);
    send(&m);
    TEST_ASSERT_EQUAL_INT(MAV_RESULT_ACCEPTED, command_result(from, MAV_CMD_NAV_RETURN_TO_LAUNCH));
    steps(2u);
    TEST_ASSERT_EQUAL_UINT8(HT_MODE_RTH, out.modes.mode);

    mavlink_msg_set_mode_pack(GCS_SYS, GCS_COMP, &m, OUR_SYS, MAV_MODE_FLAG_CUSTOM_MODE_ENABLED,
                              FW_LINK_CUSTOM_WAYPOINT);
    send(&m);
    steps(2u);
    TEST_ASSERT_EQUAL_UINT8(HT_MODE_WAYPOINT, out.modes.mode);
    from = nrx;
    do_set_mode(9u);
    TEST_ASSERT_EQUAL_INT(MAV_RESULT_DENIED, command_result(from, MAV_CMD_DO_SET_MODE));
    steps(2u);
    TEST_ASSERT_EQUAL_UINT8(HT_MODE_WAYPOINT, out.modes.mode);
    do_set_mode(FW_LINK_CUSTOM_MANUAL);
    steps(2u);
    TEST_ASSERT_EQUAL_UINT8(HT_MODE_MANUAL, out.modes.mode);

    /* the RC-loss failsafe wins over the ground station */
    do_set_mode(FW_LINK_CUSTOM_FBW);
    steps(2u);
    TEST_ASSERT_EQUAL_UINT8(HT_MODE_FBW, out.modes.mode);
    in.rc_fresh = 0u;
    steps(cfg.modes.rc_loss_ticks + 1u);
    TEST_ASSERT_EQUAL_UINT8(HT_MODE_RTH, out.modes.mode);
    TEST_ASSERT_EQUAL_UINT8(1u, out.modes.failsafe);
    in.rc_fresh = 1u;
    steps(cfg.modes.rc_recover_ticks + 1u);
    TEST_ASSERT_EQUAL_UINT8(HT_MODE_FBW, out.modes.mode); /* the station's mode again */

    /* the pilot takes it back by moving the switch */
    in.rc_us[4] = 1800u; /* waypoint */
    steps(2u);
    TEST_ASSERT_EQUAL_UINT8(HT_MODE_WAYPOINT, out.modes.mode);
    TEST_ASSERT_EQUAL_UINT8(0u, fw.gcs_mode);
    in.rc_us[4] = 1000u;
    steps(2u);
    TEST_ASSERT_EQUAL_UINT8(HT_MODE_MANUAL, out.modes.mode);

    /* unsupported commands are answered so */
    from = nrx;
    mavlink_msg_command_long_pack(GCS_SYS, GCS_COMP, &m, OUR_SYS, OUR_COMP, MAV_CMD_NAV_LAND, 0, 0,
                                  0, 0, 0, 0, 0, 0);
    send(&m);
    TEST_ASSERT_EQUAL_INT(MAV_RESULT_UNSUPPORTED, command_result(from, MAV_CMD_NAV_LAND));
}

static int saved;
static int save_hook(void *ctx, const fw_config_t *c, const fw_link_params_t *p)
{
    (void)ctx;
    TEST_ASSERT_EQUAL_PTR(&cfg, c);
    TEST_ASSERT_EQUAL_PTR(&lk.params, p);
    ++saved;
    return 0;
}

static void test_preflight_storage_calls_the_board(void)
{
    in.sensors.airspeed_cm_s = 0; /* on the ground: storage is refused in flight */
    steps(2u);
    mavlink_message_t m;
    unsigned from = nrx;
    mavlink_msg_command_long_pack(GCS_SYS, GCS_COMP, &m, OUR_SYS, OUR_COMP,
                                  MAV_CMD_PREFLIGHT_STORAGE, 0, 1, 0, 0, 0, 0, 0, 0);
    send(&m);
    TEST_ASSERT_EQUAL_INT(MAV_RESULT_UNSUPPORTED, command_result(from, MAV_CMD_PREFLIGHT_STORAGE));
    lk.save = save_hook;
    saved = 0;
    from = nrx;
    send(&m);
    TEST_ASSERT_EQUAL_INT(MAV_RESULT_ACCEPTED, command_result(from, MAV_CMD_PREFLIGHT_STORAGE));
    TEST_ASSERT_EQUAL_INT(1, saved);
}

/* --- the receive path ------------------------------------------------------ */

static uint16_t frame_read(uint8_t *buf, int16_t index, uint8_t target)
{
    mavlink_message_t m;
    mavlink_msg_param_request_read_pack(GCS_SYS, GCS_COMP, &m, target, OUR_COMP, id16(""), index);
    return mavlink_msg_to_send_buffer(buf, &m);
}

static void test_rx_drops_and_counts_bad_frames(void)
{
    steps(2u);
    uint8_t a[MAVLINK_MAX_PACKET_LEN];
    const uint16_t na = frame_read(a, 3, OUR_SYS);
    unsigned from = nrx;
    /* byte by byte */
    for (uint16_t i = 0u; i < na; ++i) {
        fw_link_rx(&lk, &a[i], 1u);
    }
    drain();
    TEST_ASSERT_EQUAL_UINT(1u, count_id(MAVLINK_MSG_ID_PARAM_VALUE, from));
    TEST_ASSERT_EQUAL_UINT32(1u, lk.count.rx_ok);

    /* a wrong CRC */
    uint8_t b[MAVLINK_MAX_PACKET_LEN];
    memcpy(b, a, na);
    b[na - 1u] ^= 0x5Au;
    from = nrx;
    fw_link_rx(&lk, b, na);
    TEST_ASSERT_EQUAL_UINT32(1u, lk.count.rx_bad_crc);
    /* a payload bit flipped */
    memcpy(b, a, na);
    b[12] ^= 0x01u;
    fw_link_rx(&lk, b, na);
    TEST_ASSERT_EQUAL_UINT32(2u, lk.count.rx_bad_crc);
    drain();
    TEST_ASSERT_EQUAL_UINT(0u, count_id(MAVLINK_MSG_ID_PARAM_VALUE, from));

    /* addressed to another system */
    const uint16_t nw = frame_read(b, 3, 42u);
    fw_link_rx(&lk, b, nw);
    TEST_ASSERT_EQUAL_UINT32(1u, lk.count.rx_wrong_target);

    /* an id common.xml does not have (length check at the id) */
    uint8_t u[16] = {0xFD, 3, 0, 0, 7, GCS_SYS, GCS_COMP, 0x21, 0x43, 0x0F, 1, 2, 3, 0x11, 0x22};
    fw_link_rx(&lk, u, 15u);
    TEST_ASSERT_EQUAL_UINT32(1u, lk.count.rx_unknown_id);
    /* unknown incompat flags */
    uint8_t f[4] = {0xFD, 5, 0x80, 0};
    fw_link_rx(&lk, f, 4u);
    TEST_ASSERT_EQUAL_UINT32(1u, lk.count.rx_garbled);
    /* a signed frame (signing is not supported): dropped whatever its signature */
    mavlink_message_t sm;
    mavlink_msg_param_request_read_pack(GCS_SYS, GCS_COMP, &sm, OUR_SYS, OUR_COMP, id16(""), 3);
    sm.incompat_flags = MAVLINK_IFLAG_SIGNED;
    uint8_t sb[MAVLINK_MAX_PACKET_LEN];
    uint8_t hdr[10] = {0xFD,
                       sm.len,
                       MAVLINK_IFLAG_SIGNED,
                       0,
                       sm.seq,
                       GCS_SYS,
                       GCS_COMP,
                       (uint8_t)MAVLINK_MSG_ID_PARAM_REQUEST_READ,
                       0,
                       0};
    memcpy(sb, hdr, 10u);
    memcpy(&sb[10], _MAV_PAYLOAD(&sm), sm.len);
    uint16_t ck = crc_calculate(&sb[1], 9u);
    crc_accumulate_buffer(&ck, _MAV_PAYLOAD(&sm), sm.len);
    crc_accumulate(MAVLINK_MSG_ID_PARAM_REQUEST_READ_CRC, &ck);
    sb[10u + sm.len] = (uint8_t)(ck & 0xFFu);
    sb[11u + sm.len] = (uint8_t)(ck >> 8u);
    memset(&sb[12u + sm.len], 0x42, MAVLINK_SIGNATURE_BLOCK_LEN);
    from = nrx;
    fw_link_rx(&lk, sb, 12u + sm.len + MAVLINK_SIGNATURE_BLOCK_LEN);
    drain();
    TEST_ASSERT_EQUAL_UINT32(2u, lk.count.rx_garbled);
    TEST_ASSERT_EQUAL_UINT(0u, count_id(MAVLINK_MSG_ID_PARAM_VALUE, from));
    TEST_ASSERT_EQUAL_UINT32(1u, lk.count.rx_ok);

    /* garbage between frames, a truncated frame, then good frames resync */
    from = nrx;
    static const uint8_t junk[] = {0x00, 0xFF, 0x13, 0x37, 0xFD};
    fw_link_rx(&lk, junk, sizeof junk); /* ends on a start byte: a frame begins */
    fw_link_rx(&lk, a, 10u);            /* cut after its header */
    for (unsigned k = 0u; k < 4u; ++k) {
        fw_link_rx(&lk, a, na);
    }
    drain();
    /* the broken start swallows bytes until its length and CRC fail; the
     * stream then resyncs on a later start byte */
    TEST_ASSERT_TRUE(count_id(MAVLINK_MSG_ID_PARAM_VALUE, from) >= 2u);
    TEST_ASSERT_TRUE(lk.count.rx_bad_crc + lk.count.rx_garbled + lk.count.rx_unknown_id > 5u);
    TEST_ASSERT_EQUAL_UINT32(lk.count.rx_bad_crc + lk.count.rx_garbled + lk.count.rx_unknown_id +
                                 lk.count.rx_wrong_target,
                             lk.count.rx_dropped);
}

static void test_tx_queue_overflow_is_counted_not_split(void)
{
    /* no draining: a full queue refuses whole frames */
    for (unsigned k = 0u; k < 200u; ++k) {
        int ran = 0;
        while (ran == 0) {
            ran = fw_step(&fw, &in, &out);
        }
        now_ms += 25u;
        fw_link_after_step(&lk, &out, now_ms);
    }
    TEST_ASSERT_TRUE(lk.count.tx_overflow > 0u);
    TEST_ASSERT_TRUE(lk.tx_len <= FW_LINK_TX_BYTES);
    drain();
    TEST_ASSERT_EQUAL_UINT32(lk.count.tx_frames, nrx); /* every queued frame parses */
    TEST_ASSERT_EQUAL_UINT32(0u, rx_st.packet_rx_drop_count);
    /* NULL and empty calls are harmless */
    fw_link_rx(NULL, NULL, 5u);
    fw_link_rx(&lk, NULL, 5u);
    fw_link_after_step(&lk, NULL, 0u);
    uint8_t one;
    TEST_ASSERT_EQUAL_UINT64(0u, fw_link_tx(&lk, &one, 0u));
    TEST_ASSERT_EQUAL_INT(-1, fw_link_init(&lk, &fw, NULL, 1u, 1u));
    fw_config_t other = cfg;
    TEST_ASSERT_EQUAL_INT(-1, fw_link_init(&lk, &fw, &other, 1u, 1u));
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_telemetry_rates_over_one_second);
    RUN_TEST(test_telemetry_content);
    RUN_TEST(test_param_ids_unique_and_short);
    RUN_TEST(test_link_rows_defaults_and_edges);
    RUN_TEST(test_param_list_and_read);
    RUN_TEST(test_param_set_applies_without_resetting_the_flight);
    RUN_TEST(test_param_set_refusals_answer_the_old_value);
    RUN_TEST(test_mission_upload_download_current_clear);
    RUN_TEST(test_mission_waypoint_mode_flies_the_list);
    RUN_TEST(test_mission_upload_retries_then_cancels);
    RUN_TEST(test_mission_refusals);
    RUN_TEST(test_mission_before_home_waits_for_the_fix);
    RUN_TEST(test_custom_mode_numbers);
    RUN_TEST(test_mode_commands);
    RUN_TEST(test_preflight_storage_calls_the_board);
    RUN_TEST(test_rx_drops_and_counts_bad_frames);
    RUN_TEST(test_tx_queue_overflow_is_counted_not_split);
    return UNITY_END();
}
