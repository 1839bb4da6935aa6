/*
 * link_fixture.c - the ground station the link's tests talk to
 * (link_fixture.h): a firmware step with its link, fed level and at rest
 * at home with a fix and a receiver, and the generated pack / parse
 * helpers on the other side.
 */
#include "link_fixture.h"

#include <math.h>
#include <string.h>

fw_config_t cfg;
fw_t fw;
fw_link_t lk;
fw_inputs_t in;
fw_output_t out;
uint32_t now_ms;
uint32_t samples;
uint8_t gps_on;

mavlink_message_t rx[MAX_RX];
unsigned nrx;
mavlink_status_t rx_st;

void setUp(void)
{
    fw_config_default(&cfg);
    TEST_ASSERT_EQUAL_INT(1, fw_init(&fw, &cfg));
    TEST_ASSERT_EQUAL_INT(0, fw_link_init(&lk, &fw, &cfg, OUR_SYS, OUR_COMP));
    memset(&in, 0, sizeof in);
    memset(&out, 0, sizeof out);
    in.sensors.imu_fresh = 1u;
    in.sensors.imu.accel_g[2] = -Q16_ONE; /* level, at rest */
    in.sensors.airspeed_fresh = 1u;
    in.sensors.airspeed_cm_s = 1500;
    in.sensors.baro_fresh = 1u;
    in.sensors.baro_alt_cm = 50000;
    in.sensors.gps.fix = 3u;
    in.sensors.gps.lat_e7 = HOME_LAT;
    in.sensors.gps.lon_e7 = HOME_LON;
    in.sensors.gps.alt_cm = 50000;
    in.rc_count = 6u;
    for (unsigned i = 0u; i < 6u; ++i) {
        in.rc_us[i] = 1500u;
    }
    in.rc_us[2] = 1000u; /* throttle */
    in.rc_us[4] = 1000u; /* mode switch: manual */
    in.rc_fresh = 1u;
    now_ms = 1000u;
    samples = 0u;
    gps_on = 1u;
    nrx = 0u;
    memset(&rx_st, 0, sizeof rx_st);
}

void tearDown(void) {}

/* what the link sends, parsed by the generated parser */
void drain(void)
{
    uint8_t buf[61]; /* an odd size: frames split across reads */
    size_t n;
    while ((n = fw_link_tx(&lk, buf, sizeof buf)) > 0u) {
        for (size_t i = 0u; i < n; ++i) {
            mavlink_message_t m;
            if (mavlink_parse_char(MAVLINK_COMM_1, buf[i], &m, &rx_st) == MAVLINK_FRAMING_OK) {
                TEST_ASSERT_TRUE(nrx < MAX_RX);
                rx[nrx++] = m;
            }
        }
    }
}

/* k control steps (40 Hz), the link after each */
void steps(unsigned k)
{
    for (unsigned j = 0u; j < k; ++j) {
        int ran = 0;
        while (ran == 0) {
            in.sensors.gps.fresh = (gps_on != 0u && (samples % 40u) == 0u) ? 1u : 0u;
            ++samples;
            ran = fw_step(&fw, &in, &out);
        }
        now_ms += 25u;
        fw_link_after_step(&lk, &out, now_ms);
        drain();
    }
}

/* a param_id as the pack functions read it: 16 bytes, zero-padded */
const char *id16(const char *s)
{
    static char buf[4][16];
    static unsigned k;
    k = (k + 1u) % 4u;
    memset(buf[k], 0, sizeof buf[k]);
    strncpy(buf[k], s, sizeof buf[k]);
    return buf[k];
}

void send(const mavlink_message_t *m)
{
    uint8_t buf[MAVLINK_MAX_PACKET_LEN];
    const uint16_t n = mavlink_msg_to_send_buffer(buf, m);
    fw_link_rx(&lk, buf, n);
    drain();
}

unsigned count_id(uint32_t id, unsigned from)
{
    unsigned c = 0u;
    for (unsigned i = from; i < nrx; ++i) {
        c += (rx[i].msgid == id) ? 1u : 0u;
    }
    return c;
}

/* the last message of an id since from, or NULL */
const mavlink_message_t *last_id(uint32_t id, unsigned from)
{
    const mavlink_message_t *m = NULL;
    for (unsigned i = from; i < nrx; ++i) {
        if (rx[i].msgid == id) {
            m = &rx[i];
        }
    }
    return m;
}

float param_value_of(const char *id, unsigned from)
{
    for (unsigned i = nrx; i > from; --i) {
        if (rx[i - 1u].msgid == MAVLINK_MSG_ID_PARAM_VALUE) {
            mavlink_param_value_t pv;
            mavlink_msg_param_value_decode(&rx[i - 1u], &pv);
            if (strncmp(pv.param_id, id, 16) == 0) {
                return pv.param_value;
            }
        }
    }
    TEST_FAIL_MESSAGE("no PARAM_VALUE");
    return NAN;
}

void set_param(const char *id, float v)
{
    mavlink_message_t m;
    mavlink_msg_param_set_pack(GCS_SYS, GCS_COMP, &m, OUR_SYS, OUR_COMP, id16(id), v,
                               MAV_PARAM_TYPE_REAL32);
    send(&m);
}

void send_item(uint16_t seq, int32_t lat, int32_t lon, float z, uint8_t frame, uint16_t command)
{
    mavlink_message_t m;
    mavlink_msg_mission_item_int_pack(GCS_SYS, GCS_COMP, &m, OUR_SYS, OUR_COMP, seq, frame, command,
                                      0, 1, 0, 0, 0, 0, lat, lon, z, MAV_MISSION_TYPE_MISSION);
    send(&m);
}

void send_count(uint16_t n)
{
    mavlink_message_t m;
    mavlink_msg_mission_count_pack(GCS_SYS, GCS_COMP, &m, OUR_SYS, OUR_COMP, n,
                                   MAV_MISSION_TYPE_MISSION);
    send(&m);
}

int last_request(unsigned from)
{
    const mavlink_message_t *m = last_id(MAVLINK_MSG_ID_MISSION_REQUEST_INT, from);
    if (m == NULL) {
        return -1;
    }
    mavlink_mission_request_int_t r;
    mavlink_msg_mission_request_int_decode(m, &r);
    TEST_ASSERT_EQUAL_UINT8(GCS_SYS, r.target_system);
    return (int)r.seq;
}

int last_ack(unsigned from)
{
    const mavlink_message_t *m = last_id(MAVLINK_MSG_ID_MISSION_ACK, from);
    if (m == NULL) {
        return -1;
    }
    mavlink_mission_ack_t a;
    mavlink_msg_mission_ack_decode(m, &a);
    return (int)a.type;
}

const int32_t wp_lat[4] = {HOME_LAT + 10000, HOME_LAT + 10000, HOME_LAT - 10000, HOME_LAT - 10000};
const int32_t wp_lon[4] = {HOME_LON - 15000, HOME_LON + 15000, HOME_LON + 15000, HOME_LON - 15000};

void upload_square(void)
{
    unsigned from = nrx;
    send_count(4u);
    for (uint16_t i = 0u; i < 4u; ++i) {
        TEST_ASSERT_EQUAL_INT((int)i, last_request(from));
        from = nrx;
        send_item(i, wp_lat[i], wp_lon[i], 120.0f + (float)i,
                  (i == 3u) ? MAV_FRAME_GLOBAL_INT : MAV_FRAME_GLOBAL_RELATIVE_ALT_INT,
                  MAV_CMD_NAV_WAYPOINT);
    }
    TEST_ASSERT_EQUAL_INT(MAV_MISSION_ACCEPTED, last_ack(from));
    TEST_ASSERT_EQUAL_INT(-1, last_request(from));
}

int command_result(unsigned from, uint16_t command)
{
    const mavlink_message_t *m = last_id(MAVLINK_MSG_ID_COMMAND_ACK, from);
    if (m == NULL) {
        return -1;
    }
    mavlink_command_ack_t a;
    mavlink_msg_command_ack_decode(m, &a);
    TEST_ASSERT_EQUAL_UINT16(command, a.command);
    return (int)a.result;
}

void do_set_mode(uint32_t custom)
{
    mavlink_message_t m;
    mavlink_msg_command_long_pack(GCS_SYS, GCS_COMP, &m, OUR_SYS, OUR_COMP, MAV_CMD_DO_SET_MODE, 0,
                                  (float)MAV_MODE_FLAG_CUSTOM_MODE_ENABLED, (float)custom, 0, 0, 0,
                                  0, 0);
    send(&m);
}
