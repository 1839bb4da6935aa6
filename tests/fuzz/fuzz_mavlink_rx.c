/*
 * libFuzzer target: arbitrary bytes into the MAVLink link's receive path
 * (firmware/link/fw_link.c and its protocols), between firmware steps. The first
 * byte chooses the mode:
 *   even: the rest is the raw stream, fed in chunks of (first byte / 2 + 1);
 *   odd:  the rest is records (selector, length, payload...) that are packed
 *         into frames with a good CRC (the generated finalize) for one of the
 *         ids the link handles, addressed to it, so that the protocols
 *         themselves are reached with any field values.
 * Bit 1 of an odd first byte puts the aircraft at rest (airspeed 0), so that
 * PREFLIGHT_STORAGE reaches the board's hook (a stub that fails every other
 * call); else it flies at 15 m/s and storage is refused.
 * A firmware step and fw_link_after_step run after every chunk or record.
 * Checks after each record (one message each):
 *   - a command addressed to us is answered with one COMMAND_ACK of that
 *     command (unless the transmit queue overflowed); a refused one (not
 *     ACCEPTED) changed no parameter row, no mode and no stream interval;
 *   - a PARAM_SET changed no row but its own; every PARAM_VALUE sent is the
 *     value in force (the row's rounding of it is the stored value);
 *   - a MISSION_ACK that refuses left the flown list as it was.
 * Checks after each chunk or record (the last two after the whole input):
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

static const uint32_t ids[] = {MAVLINK_MSG_ID_PARAM_REQUEST_LIST, MAVLINK_MSG_ID_PARAM_REQUEST_READ,
                               MAVLINK_MSG_ID_PARAM_SET, MAVLINK_MSG_ID_MISSION_COUNT,
                               MAVLINK_MSG_ID_MISSION_ITEM_INT, MAVLINK_MSG_ID_MISSION_REQUEST_LIST,
                               MAVLINK_MSG_ID_MISSION_REQUEST_INT, MAVLINK_MSG_ID_MISSION_REQUEST,
                               MAVLINK_MSG_ID_MISSION_CLEAR_ALL, MAVLINK_MSG_ID_MISSION_SET_CURRENT,
                               MAVLINK_MSG_ID_MISSION_ACK, MAVLINK_MSG_ID_COMMAND_LONG,
                               MAVLINK_MSG_ID_SET_MODE, MAVLINK_MSG_ID_HEARTBEAT,
                               /* appended: the seeds' selectors above keep their ids */
                               MAVLINK_MSG_ID_COMMAND_INT, MAVLINK_MSG_ID_MISSION_ITEM};

#define MAX_ROWS 256u
static int32_t rows_before[MAX_ROWS];
static ht_waypoint_t wps_before[FW_LINK_MAX_WAYPOINTS];
static uint16_t wp_count_before;
/* what the link sent since the last snapshot */
static unsigned acks_seen, acks_refused, mission_refused;
static uint16_t ack_command;
static int saves;
static int record_mode; /* one message per record: the per-message checks apply */

static int save_stub(void *ctx, const fw_config_t *c, const fw_link_params_t *p)
{
    (void)ctx;
    (void)c;
    (void)p;
    ++saves;
    return saves % 2; /* every other write fails */
}

static void snapshot(void)
{
    check(fw_link_param_count() <= MAX_ROWS);
    for (uint16_t i = 0u; i < fw_link_param_count(); ++i) {
        check(fw_link_param_get(&lk, i, &rows_before[i], NULL) == 0);
    }
    wp_count_before = cfg.waypoint_count;
    if ((cfg.waypoints != NULL) && (cfg.waypoint_count <= FW_LINK_MAX_WAYPOINTS)) {
        memcpy(wps_before, cfg.waypoints, cfg.waypoint_count * sizeof wps_before[0]);
    }
    acks_seen = 0u;
    acks_refused = 0u;
    mission_refused = 0u;
}

/* the rows that differ from the snapshot, but except (-1: none excepted) */
static unsigned rows_changed(int32_t except)
{
    unsigned n = 0u;
    for (uint16_t i = 0u; i < fw_link_param_count(); ++i) {
        int32_t raw = 0;
        check(fw_link_param_get(&lk, i, &raw, NULL) == 0);
        n += ((raw != rows_before[i]) && ((int32_t)i != except)) ? 1u : 0u;
    }
    return n;
}

static int waypoints_unchanged(void)
{
    return (cfg.waypoint_count == wp_count_before) &&
           ((wp_count_before == 0u) ||
            (memcmp(wps_before, cfg.waypoints, wp_count_before * sizeof wps_before[0]) == 0));
}

/* a frame the link sent: the checks on its content */
static void sent(const mavlink_message_t *m)
{
    if (m->msgid == MAVLINK_MSG_ID_COMMAND_ACK) {
        mavlink_command_ack_t a;
        mavlink_msg_command_ack_decode(m, &a);
        ++acks_seen;
        ack_command = a.command;
        acks_refused += (a.result != MAV_RESULT_ACCEPTED) ? 1u : 0u;
    } else if (m->msgid == MAVLINK_MSG_ID_MISSION_ACK) {
        mavlink_mission_ack_t a;
        mavlink_msg_mission_ack_decode(m, &a);
        mission_refused += (a.type != MAV_MISSION_ACCEPTED) ? 1u : 0u;
    } else if ((m->msgid == MAVLINK_MSG_ID_PARAM_VALUE) && (record_mode != 0)) {
        /* the value in force: the row's rounding of it is what is stored */
        mavlink_param_value_t pv;
        mavlink_msg_param_value_decode(m, &pv);
        int32_t raw = 0;
        const ht_param_info_t *row = NULL;
        check(fw_link_param_get(&lk, pv.param_index, &raw, &row) == 0 && row != NULL);
        check(pv.param_type == fw_link_param_mav_type(pv.param_index));
        uint32_t bits;
        memcpy(&bits, &pv.param_value, sizeof bits);
        int32_t echoed = 0;
        check(ht_f32_to_fixed(bits, row->scale, &echoed) == 0 && echoed == raw);
    } else {
        /* telemetry */
    }
}

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
    lk.save = save_stub;
    saves = 0;
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
            if (r == MAVLINK_FRAMING_OK) {
                sent(&tx_msg);
            }
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

/* what a record sent: the id, to us or not, a PARAM_SET's row */
static uint32_t rec_id;
static int rec_to_us;
static int32_t rec_param_row;
static uint16_t rec_command;

/* a record packed into a frame with a good CRC, addressed to the link */
static size_t record(const uint8_t *d, size_t n)
{
    rec_id = UINT32_MAX;
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
    rec_id = id;
    rec_to_us = ((d[0] & 0x80u) == 0u) ? 1 : 0;
    rec_param_row = -1;
    rec_command = 0u;
    if (id == MAVLINK_MSG_ID_PARAM_SET) {
        mavlink_param_set_t ps;
        mavlink_msg_param_set_decode(&m, &ps);
        rec_param_row = fw_link_param_find(ps.param_id);
    } else if (id == MAVLINK_MSG_ID_COMMAND_LONG) {
        mavlink_command_long_t c;
        mavlink_msg_command_long_decode(&m, &c);
        rec_command = c.command;
    } else if (id == MAVLINK_MSG_ID_COMMAND_INT) {
        mavlink_command_int_t c;
        mavlink_msg_command_int_decode(&m, &c);
        rec_command = c.command;
    } else if (id == MAVLINK_MSG_ID_SET_MODE) {
        rec_command = MAV_CMD_DO_SET_MODE;
    } else {
        /* no command */
    }
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
    record_mode = ((mode & 1u) != 0u) ? 1 : 0;
    data++;
    size--;
    if ((mode & 1u) == 0u) {
        const size_t chunk = (size_t)(mode / 2u) + 1u;
        for (size_t i = 0u; i < size; i += chunk) {
            fw_link_rx(&lk, &data[i], (size - i < chunk) ? size - i : chunk);
            step_and_check();
        }
    } else {
        if ((mode & 2u) != 0u) {
            in.sensors.airspeed_cm_s = 0; /* at rest: storage reaches the hook */
        }
        size_t i = 0u;
        while (i < size) {
            snapshot();
            const uint8_t gcs_mode = fw.gcs_mode;
            int32_t intervals[FW_LINK_S_COUNT];
            memcpy(intervals, lk.interval_override_us, sizeof intervals);
            const uint32_t overflow = lk.count.tx_overflow;
            i += record(&data[i], size - i);
            step_and_check();
            const int command = (rec_id == MAVLINK_MSG_ID_COMMAND_LONG) ||
                                (rec_id == MAVLINK_MSG_ID_COMMAND_INT) ||
                                (rec_id == MAVLINK_MSG_ID_SET_MODE);
            if (command && rec_to_us && (lk.count.tx_overflow == overflow)) {
                /* every command answered, once, with its own number */
                check(acks_seen == 1u && ack_command == rec_command);
                if (acks_refused != 0u) {
                    check(rows_changed(-1) == 0u && fw.gcs_mode == gcs_mode &&
                          memcmp(intervals, lk.interval_override_us, sizeof intervals) == 0);
                }
            }
            if (rec_id == MAVLINK_MSG_ID_PARAM_SET) {
                check(rows_changed(rec_param_row) == 0u); /* no row but its own */
            }
            if (mission_refused != 0u) {
                check(waypoints_unchanged()); /* a refusal leaves the flown list */
            }
        }
    }
    check_config();
    return 0;
}
