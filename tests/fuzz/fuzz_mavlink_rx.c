/*
 * libFuzzer target: arbitrary bytes into the MAVLink link's receive path
 * (firmware/link/fw_link.c and its protocols), between firmware steps. The first
 * byte chooses the mode:
 *   even: the rest is the raw stream, fed in chunks of (first byte / 2 + 1);
 *   odd:  the rest is records (selector, length, payload...) that are packed
 *         into frames with a good CRC (the generated finalize) for one of the
 *         ids the link handles, addressed to it, so that the protocols
 *         themselves are reached with any field values.
 * A firmware step and fw_link_after_step run after every chunk or record.
 * Checks after each (the last two after the whole input):
 *   - the drop counters add up (rx_dropped = bad CRC + garbled + unknown id
 *     + wrong target);
 *   - the transmit queue is within its bound and everything the link sends
 *     parses as good frames (the generated parser, no CRC error, no loss);
 *   - the live configuration is still one fw_init accepts, every parameter
 *     within its row, the step still flies (pulses), the waypoint list within
 *     the store.
 * ASan and UBSan (scripts/fuzz.sh) catch any access out of bounds.
 */
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "link/fw_link.h"
#include "mavlink/common/mavlink.h" /* the messages, to build and read frames */

static void check(int ok)
{
    if (!ok) {
        abort();
    }
}

static fw_config_t cfg;
static fw_t fw;
static fw_link_t lk;
static fw_inputs_t in;
static fw_output_t out;
static uint32_t now_ms;
static mavlink_status_t tx_parse;
static mavlink_message_t tx_msg;

static const uint32_t ids[] = {MAVLINK_MSG_ID_PARAM_REQUEST_LIST,
                               MAVLINK_MSG_ID_PARAM_REQUEST_READ,
                               MAVLINK_MSG_ID_PARAM_SET,
                               MAVLINK_MSG_ID_MISSION_COUNT,
                               MAVLINK_MSG_ID_MISSION_ITEM_INT,
                               MAVLINK_MSG_ID_MISSION_REQUEST_LIST,
                               MAVLINK_MSG_ID_MISSION_REQUEST_INT,
                               MAVLINK_MSG_ID_MISSION_REQUEST,
                               MAVLINK_MSG_ID_MISSION_CLEAR_ALL,
                               MAVLINK_MSG_ID_MISSION_SET_CURRENT,
                               MAVLINK_MSG_ID_MISSION_ACK,
                               MAVLINK_MSG_ID_COMMAND_LONG,
                               MAVLINK_MSG_ID_SET_MODE,
                               MAVLINK_MSG_ID_HEARTBEAT};

static void start(void)
{
    fw_config_default(&cfg);
    check(fw_init(&fw, &cfg) == 1);
    check(fw_link_init(&lk, &fw, &cfg, 1u, 1u) == 0);
    memset(&in, 0, sizeof in);
    in.sensors.imu_fresh = 1u;
    in.sensors.imu.accel_g[2] = -Q16_ONE;
    in.sensors.airspeed_fresh = 1u;
    in.sensors.airspeed_cm_s = 1500;
    in.sensors.baro_fresh = 1u;
    in.sensors.baro_alt_cm = 20000;
    in.sensors.gps.fix = 3u;
    in.sensors.gps.fresh = 1u;
    in.sensors.gps.lat_e7 = 470000000;
    in.sensors.gps.lon_e7 = 80000000;
    in.rc_count = 6u;
    for (unsigned i = 0u; i < 6u; ++i) {
        in.rc_us[i] = 1500u;
    }
    in.rc_fresh = 1u;
    now_ms = 0u;
    memset(&tx_parse, 0, sizeof tx_parse);
}

static void step_and_check(void)
{
    int ran = 0;
    for (unsigned k = 0u; k < 10u && ran == 0; ++k) {
        ran = fw_step(&fw, &in, &out);
    }
    now_ms += 25u;
    fw_link_after_step(&lk, &out, now_ms);

    const fw_link_counters_t *c = &lk.count;
    check(c->rx_dropped == c->rx_bad_crc + c->rx_garbled + c->rx_unknown_id + c->rx_wrong_target);
    check(lk.tx_len <= FW_LINK_TX_BYTES);
    uint8_t buf[97];
    size_t n;
    while ((n = fw_link_tx(&lk, buf, sizeof buf)) > 0u) {
        for (size_t i = 0u; i < n; ++i) {
            const uint8_t r = mavlink_frame_char_buffer(&tx_msg, &tx_parse, buf[i], NULL, NULL);
            check(r != MAVLINK_FRAMING_BAD_CRC && r != MAVLINK_FRAMING_BAD_SIGNATURE);
        }
    }
    check(fw.ready == 1u && fw.modes.ready == 1u && out.pulse_count == cfg.out.count);
    check(cfg.waypoint_count <= FW_LINK_MAX_WAYPOINTS);
}

/* after the whole input: the configuration as a whole */
static void check_config(void)
{
    for (uint16_t i = 0u; i < fw_link_param_count(); ++i) {
        int32_t raw = 0;
        const ht_param_info_t *row = NULL;
        check(fw_link_param_get(&lk, i, &raw, &row) == 0 && row != NULL);
        check(raw >= row->min_raw && raw <= row->max_raw);
    }
    static fw_t scratch;
    check(fw_init(&scratch, &cfg) == 1);
}

/* a record packed into a frame with a good CRC, addressed to the link */
static size_t record(const uint8_t *d, size_t n)
{
    if (n < 2u) {
        return n;
    }
    const uint32_t id = ids[d[0] % (sizeof ids / sizeof ids[0])];
    const mavlink_msg_entry_t *e = mavlink_get_msg_entry(id);
    check(e != NULL);
    size_t len = d[1];
    if (len > e->max_msg_len) {
        len = e->max_msg_len;
    }
    if (len > n - 2u) {
        len = n - 2u;
    }
    mavlink_message_t m;
    memset(&m, 0, sizeof m);
    m.msgid = id;
    memcpy(_MAV_PAYLOAD_NON_CONST(&m), &d[2], len);
    if ((d[0] & 0x80u) == 0u) { /* mostly to us */
        if ((e->flags & MAV_MSG_ENTRY_FLAG_HAVE_TARGET_SYSTEM) != 0u) {
            _MAV_PAYLOAD_NON_CONST(&m)[e->target_system_ofs] = 1;
        }
        if ((e->flags & MAV_MSG_ENTRY_FLAG_HAVE_TARGET_COMPONENT) != 0u) {
            _MAV_PAYLOAD_NON_CONST(&m)[e->target_component_ofs] = 1;
        }
    }
    mavlink_status_t st;
    memset(&st, 0, sizeof st);
    (void)mavlink_finalize_message_buffer(&m, 255u, 190u, &st, e->min_msg_len, e->max_msg_len,
                                          e->crc_extra);
    uint8_t frame[MAVLINK_MAX_PACKET_LEN];
    const uint16_t fl = mavlink_msg_to_send_buffer(frame, &m);
    fw_link_rx(&lk, frame, fl);
    return 2u + len;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size < 1u) {
        return 0;
    }
    start();
    const uint8_t mode = data[0];
    data++;
    size--;
    if ((mode & 1u) == 0u) {
        const size_t chunk = (size_t)(mode / 2u) + 1u;
        for (size_t i = 0u; i < size; i += chunk) {
            fw_link_rx(&lk, &data[i], (size - i < chunk) ? size - i : chunk);
            step_and_check();
        }
    } else {
        size_t i = 0u;
        while (i < size) {
            i += record(&data[i], size - i);
            step_and_check();
        }
    }
    check_config();
    return 0;
}
