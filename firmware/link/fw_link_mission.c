/*
 * fw_link_mission.c - the MAVLink mission protocol (MISSION_INT items):
 * upload (MISSION_COUNT, then MISSION_REQUEST_INT for each item in turn,
 * re-sent after LNK_MISSION_TIMEOUT up to LNK_MISSION_RETRIES times, then
 * MISSION_ACK), download (MISSION_REQUEST_LIST -> MISSION_COUNT, then
 * MISSION_ITEM_INT for each request), MISSION_CLEAR_ALL, MISSION_SET_CURRENT
 * -> MISSION_CURRENT, and MISSION_ITEM_REACHED as the guidance passes them.
 *
 * Items: MAV_CMD_NAV_WAYPOINT in MAV_FRAME_GLOBAL_INT (altitude above mean
 * sea level) or MAV_FRAME_GLOBAL_RELATIVE_ALT_INT (above home), at most
 * FW_LINK_MAX_WAYPOINTS. An upload fills its own buffer: the list flown
 * changes only when the whole upload is accepted. The list is converted to
 * the guidance's local frame around the home position (the first 3-D fix,
 * fw_t.home), so a list uploaded before it is flown from the first fix on;
 * the modes are re-initialised on it (ht_modes_init keeps the flight state)
 * and the navigation restarts at item 0 from where the aircraft is.
 */
#include "link/fw_link_mission.h"

#include "helical/guidance/config_check.h"
#include "helical/math/f32_bits.h"
#include "link/fw_link_text.h"
#include "link/fw_link_tx.h"

#define ALT_LIMIT_CM (100000 * 100) /* +-100 km, the guidance's bound */

static void ack(fw_link_t *l, uint8_t sysid, uint8_t compid, uint8_t result, uint8_t type)
{
    mavlink_mission_ack_t a;
    (void)memset(&a, 0, sizeof a);
    a.target_system = sysid;
    a.target_component = compid;
    a.type = result;
    a.mission_type = type;
    (void)FW_LINK_QUEUE(l, MISSION_ACK, a);
}

static void request_item(fw_link_t *l)
{
    fw_link_mission_t *m = &l->mission;
    mavlink_mission_request_int_t r;
    (void)memset(&r, 0, sizeof r);
    r.target_system = m->partner_sysid;
    r.target_component = m->partner_compid;
    r.seq = m->next;
    r.mission_type = (uint8_t)MAV_MISSION_TYPE_MISSION;
    if (m->legacy != 0u) {
        /* a station that answers with MISSION_ITEM is asked in its own words */
        mavlink_mission_request_t rq;
        (void)memset(&rq, 0, sizeof rq);
        rq.target_system = r.target_system;
        rq.target_component = r.target_component;
        rq.seq = r.seq;
        rq.mission_type = r.mission_type;
        (void)FW_LINK_QUEUE(l, MISSION_REQUEST, rq);
    } else {
        (void)FW_LINK_QUEUE(l, MISSION_REQUEST_INT, r);
    }
    m->deadline_ms = l->now_ms + l->params.mission_timeout_ms;
}

static void send_current(fw_link_t *l)
{
    mavlink_mission_current_t mc;
    (void)memset(&mc, 0, sizeof mc);
    mc.seq = l->fw->modes_state.nav.index;
    mc.total = l->cfg->waypoint_count;
    (void)FW_LINK_QUEUE(l, MISSION_CURRENT, mc);
}

/* Start the guidance's list over from where the aircraft is. */
static void restart_nav(fw_link_t *l, uint16_t index)
{
    ht_nav_state_t *s = &l->fw->modes_state.nav;
    ht_nav_reset(s, l->last.nav.north_cm, l->last.nav.east_cm);
    s->index = index;
}

static int32_t cm_to_m(int32_t cm)
{
    return (cm >= 0) ? ((cm + 50) / 100) : -((50 - cm) / 100);
}

static int relative(uint8_t frame)
{
    return ((frame == (uint8_t)MAV_FRAME_GLOBAL_RELATIVE_ALT_INT) ||
            (frame == (uint8_t)MAV_FRAME_GLOBAL_RELATIVE_ALT))
               ? 1
               : 0;
}

static void mission_text(fw_link_t *l, uint8_t severity, const char *what, int32_t item)
{
    fw_link_text_t t;
    fw_link_text_start(&t, what);
    if (item >= 0) {
        fw_link_text_str(&t, " item ");
        fw_link_text_int(&t, item);
    }
    (void)fw_link_statustext(l, severity, &t);
}

/* The guidance takes the list flown: the modes re-initialised on it
 * (ht_modes_init keeps the flight state), the navigation from item 0. */
static void fly(fw_link_t *l, uint16_t count)
{
    fw_t *fw = l->fw;
    fw_config_t *cfg = l->cfg;
    cfg->waypoints = l->waypoints;
    cfg->waypoint_count = count;
    const uint8_t pm = (cfg->modes_pitch_mode != 0u) ? 1u : 0u;
    (void)ht_modes_init(&fw->modes, &cfg->modes, &fw->law[pm], cfg->waypoints, cfg->waypoint_count,
                        &fw->modes_bad);
    restart_nav(l, 0u);
}

/*
 * Replace the list flown by the upload (upload[], upload_count) - whole or
 * not at all. Converted around home into candidate[] and checked by the
 * guidance's own rule (ht_nav_init) before anything flown or listed
 * changes. 0 = flown; 1 = waits for the home position (upload[] kept,
 * apply_pending); 2 = refused by the guidance (the list flown unchanged;
 * *bad the item); 3 = refused by the joint rule (a leg shorter than twice
 * the arrival radius: the list flown unchanged, *bad the leg's item).
 */
static int replace_list(fw_link_t *l, uint16_t *bad)
{
    fw_t *fw = l->fw;
    const uint16_t n = l->upload_count;
    if ((n > 0u) && ((fw->have_home == 0u) || (l->have_home_alt == 0u))) {
        l->mission.apply_pending = 1u;
        return 1;
    }
    l->mission.apply_pending = 0u;
    for (uint16_t i = 0u; i < n; ++i) {
        const fw_link_item_t *it = &l->upload[i];
        int32_t n_cm = 0;
        int32_t e_cm = 0;
        ht_geo_to_local(&fw->home, it->lat_e7, it->lon_e7, &n_cm, &e_cm);
        const int64_t alt_cm =
            (relative(it->frame) != 0) ? ((int64_t)l->home_alt_cm + it->z_cm) : it->z_cm;
        l->candidate[i].north_m = cm_to_m(n_cm);
        l->candidate[i].east_m = cm_to_m(e_cm);
        l->candidate[i].alt_m = (int32_t)(alt_cm / 100); /* |z| <= 100 km: no overflow */
    }
    ht_nav_t check;
    ht_nav_param_id_t field = HT_NAV_P_NONE;
    uint16_t which = 0u;
    if ((n > 0u) &&
        (ht_nav_init(&check, &l->cfg->modes.nav, l->candidate, n, &field, &which) != 0)) {
        *bad = which; /* e.g. beyond 10 000 km of home */
        return 2;
    }
    /* the one joint rule (config_check.h) on the list as it would fly: the
     * modes re-initialised on a list it refuses would leave the step unready */
    uint16_t leg = 0u;
    if ((n > 0u) && (ht_config_check(&l->cfg->modes, l->candidate, n, &leg) != HT_CFG_OK)) {
        *bad = leg;
        return 3;
    }
    (void)memcpy(l->waypoints, l->candidate, (size_t)n * sizeof l->waypoints[0]);
    (void)memcpy(l->items, l->upload, (size_t)n * sizeof l->items[0]);
    l->item_count = n;
    fly(l, n);
    return 0;
}

/* the item's check: 0, or the MAV_MISSION_RESULT that refuses it */
static uint8_t check_item(uint16_t command, uint8_t frame, int32_t lat_e7, int32_t lon_e7,
                          uint32_t z_bits, fw_link_item_t *out)
{
    if (command != (uint16_t)MAV_CMD_NAV_WAYPOINT) {
        return (uint8_t)MAV_MISSION_UNSUPPORTED;
    }
    /* 0 / 3 and the superseded 5 / 6: the same datums, the planners write
     * either (QGroundControl, MAVProxy's WPL files and MAVSDK 0 and 3) */
    if ((frame != (uint8_t)MAV_FRAME_GLOBAL) && (frame != (uint8_t)MAV_FRAME_GLOBAL_INT) &&
        (relative(frame) == 0)) {
        return (uint8_t)MAV_MISSION_UNSUPPORTED_FRAME;
    }
    if ((lat_e7 < -900000000) || (lat_e7 > 900000000)) {
        return (uint8_t)MAV_MISSION_INVALID_PARAM5_X;
    }
    if ((lon_e7 < -1800000000) || (lon_e7 > 1800000000)) {
        return (uint8_t)MAV_MISSION_INVALID_PARAM6_Y;
    }
    int32_t z_cm = 0;
    if ((ht_f32_to_fixed(z_bits, 100, &z_cm) != 0) || (z_cm < -ALT_LIMIT_CM) ||
        (z_cm > ALT_LIMIT_CM)) {
        return (uint8_t)MAV_MISSION_INVALID_PARAM7;
    }
    out->lat_e7 = lat_e7;
    out->lon_e7 = lon_e7;
    out->z_cm = z_cm;
    out->frame = frame;
    return 0u;
}

/* the upload stops: nothing flown or listed changes */
static void cancel_pending(fw_link_t *l)
{
    if (l->mission.apply_pending != 0u) {
        l->mission.apply_pending = 0u;
        mission_text(l, (uint8_t)MAV_SEVERITY_NOTICE, "mission waiting for GPS replaced", -1);
    }
}

static void on_count(fw_link_t *l, const mavlink_message_t *msg)
{
    mavlink_mission_count_t c;
    mavlink_msg_mission_count_decode(msg, &c);
    if (c.mission_type != (uint8_t)MAV_MISSION_TYPE_MISSION) {
        ack(l, msg->sysid, msg->compid, (uint8_t)MAV_MISSION_UNSUPPORTED, c.mission_type);
        return;
    }
    if (c.count > FW_LINK_MAX_WAYPOINTS) {
        mission_text(l, (uint8_t)MAV_SEVERITY_WARNING, "mission refused: over 32 items", -1);
        ack(l, msg->sysid, msg->compid, (uint8_t)MAV_MISSION_NO_SPACE, c.mission_type);
        return;
    }
    fw_link_mission_t *m = &l->mission;
    cancel_pending(l);
    if (c.count == 0u) {
        m->uploading = 0u;
        l->upload_count = 0u;
        uint16_t bad = 0u;
        (void)replace_list(l, &bad); /* an empty list needs no home: always flown */
        ack(l, msg->sysid, msg->compid, (uint8_t)MAV_MISSION_ACCEPTED, c.mission_type);
        return;
    }
    m->uploading = 1u; /* a new count restarts an upload in progress */
    m->legacy = 0u;
    m->partner_sysid = msg->sysid;
    m->partner_compid = msg->compid;
    m->count = c.count;
    m->next = 0u;
    m->retries = 0u;
    request_item(l);
}

/* an item of the upload, from MISSION_ITEM_INT or the legacy MISSION_ITEM */
static void on_item(fw_link_t *l, const mavlink_message_t *msg, uint16_t seq, uint16_t command,
                    uint8_t frame, int32_t lat_e7, int32_t lon_e7, uint32_t z_bits,
                    uint8_t mission_type, uint8_t bad_xy)
{
    fw_link_mission_t *m = &l->mission;
    if ((m->uploading == 0u) || (mission_type != (uint8_t)MAV_MISSION_TYPE_MISSION) ||
        (msg->sysid != m->partner_sysid)) {
        fw_link_count(&l->count.rx_bad_content);
        return;
    }
    if (seq != m->next) {
        fw_link_count(&l->count.rx_bad_content); /* a repeat or out of order: ask again */
        request_item(l);
        return;
    }
    uint8_t refused = bad_xy;
    if (refused == 0u) {
        refused = check_item(command, frame, lat_e7, lon_e7, z_bits, &l->upload[seq]);
    }
    if (refused != 0u) {
        m->uploading = 0u;
        fw_link_text_t t;
        fw_link_text_start(&t, "mission refused: item ");
        fw_link_text_int(&t, (int32_t)seq);
        fw_link_text_str(&t, (refused == (uint8_t)MAV_MISSION_UNSUPPORTED)         ? " command "
                             : (refused == (uint8_t)MAV_MISSION_UNSUPPORTED_FRAME) ? " frame "
                                                                                   : " bad x/y/z");
        if (refused == (uint8_t)MAV_MISSION_UNSUPPORTED) {
            fw_link_text_int(&t, (int32_t)command);
        } else if (refused == (uint8_t)MAV_MISSION_UNSUPPORTED_FRAME) {
            fw_link_text_int(&t, (int32_t)frame);
        } else {
            /* the result code names the field */
        }
        (void)fw_link_statustext(l, (uint8_t)MAV_SEVERITY_WARNING, &t);
        ack(l, m->partner_sysid, m->partner_compid, refused, mission_type);
        return;
    }
    m->next = (uint16_t)(m->next + 1u);
    m->retries = 0u;
    if (m->next < m->count) {
        request_item(l);
        return;
    }
    m->uploading = 0u;
    l->upload_count = m->count;
    uint16_t bad = 0u;
    const int r = replace_list(l, &bad);
    if (r == 2) {
        mission_text(l, (uint8_t)MAV_SEVERITY_WARNING, "mission refused: out of range,",
                     (int32_t)bad);
    } else if (r == 3) {
        mission_text(l, (uint8_t)MAV_SEVERITY_WARNING, "mission refused: leg < 2x arrival radius,",
                     (int32_t)bad);
    } else if (r == 1) {
        mission_text(l, (uint8_t)MAV_SEVERITY_NOTICE, "mission accepted: flown at GPS fix", -1);
    } else {
        /* flown */
    }
    ack(l, m->partner_sysid, m->partner_compid,
        (r >= 2) ? (uint8_t)MAV_MISSION_ERROR : (uint8_t)MAV_MISSION_ACCEPTED, mission_type);
}

static void on_item_int(fw_link_t *l, const mavlink_message_t *msg)
{
    mavlink_mission_item_int_t it;
    mavlink_msg_mission_item_int_decode(msg, &it);
    l->mission.legacy = 0u;
    on_item(l, msg, it.seq, it.command, it.frame, it.x, it.y,
            fw_link_get_f32(&it, offsetof(mavlink_mission_item_int_t, z)), it.mission_type, 0u);
}

/* the legacy MISSION_ITEM: x, y in degrees as floats */
static void on_item_float(fw_link_t *l, const mavlink_message_t *msg)
{
    mavlink_mission_item_t it;
    mavlink_msg_mission_item_decode(msg, &it);
    int32_t lat_e7 = 0;
    int32_t lon_e7 = 0;
    uint8_t bad = 0u;
    if (ht_f32_to_fixed(fw_link_get_f32(&it, offsetof(mavlink_mission_item_t, x)), 10000000,
                        &lat_e7) != 0) {
        bad = (uint8_t)MAV_MISSION_INVALID_PARAM5_X;
    } else if (ht_f32_to_fixed(fw_link_get_f32(&it, offsetof(mavlink_mission_item_t, y)), 10000000,
                               &lon_e7) != 0) {
        bad = (uint8_t)MAV_MISSION_INVALID_PARAM6_Y;
    } else {
        /* converted */
    }
    l->mission.legacy = 1u;
    on_item(l, msg, it.seq, it.command, it.frame, lat_e7, lon_e7,
            fw_link_get_f32(&it, offsetof(mavlink_mission_item_t, z)), it.mission_type, bad);
}

/* The list a download answers: the flown one, or an accepted upload that
 * waits for the home position (what will be flown). */
static const fw_link_item_t *listed(const fw_link_t *l, uint16_t *count)
{
    if (l->mission.apply_pending != 0u) {
        *count = l->upload_count;
        return l->upload;
    }
    *count = l->item_count;
    return l->items;
}

static void on_request_list(fw_link_t *l, const mavlink_message_t *msg)
{
    uint16_t n = 0u;
    (void)listed(l, &n);
    mavlink_mission_request_list_t r;
    mavlink_msg_mission_request_list_decode(msg, &r);
    mavlink_mission_count_t c;
    (void)memset(&c, 0, sizeof c);
    c.target_system = msg->sysid;
    c.target_component = msg->compid;
    c.mission_type = r.mission_type;
    c.count = (r.mission_type == (uint8_t)MAV_MISSION_TYPE_MISSION) ? n : 0u;
    (void)FW_LINK_QUEUE(l, MISSION_COUNT, c);
}

static void send_item(fw_link_t *l, const mavlink_message_t *msg, uint16_t seq, uint8_t type)
{
    uint16_t n = 0u;
    const fw_link_item_t *list = listed(l, &n);
    if ((type != (uint8_t)MAV_MISSION_TYPE_MISSION) || (seq >= n)) {
        ack(l, msg->sysid, msg->compid, (uint8_t)MAV_MISSION_INVALID_SEQUENCE, type);
        return;
    }
    const fw_link_item_t *s = &list[seq];
    mavlink_mission_item_int_t it;
    (void)memset(&it, 0, sizeof it);
    it.target_system = msg->sysid;
    it.target_component = msg->compid;
    it.seq = seq;
    it.frame = s->frame;
    it.command = (uint16_t)MAV_CMD_NAV_WAYPOINT;
    it.current = (seq == l->fw->modes_state.nav.index) ? 1u : 0u;
    it.autocontinue = 1u;
    it.x = s->lat_e7;
    it.y = s->lon_e7;
    fw_link_put_f32(&it, offsetof(mavlink_mission_item_int_t, z), ht_f32_from_ratio(s->z_cm, 100u));
    it.mission_type = type;
    (void)FW_LINK_QUEUE(l, MISSION_ITEM_INT, it);
}

void fw_link_mission_rx(fw_link_t *l, const mavlink_message_t *msg)
{
    switch (msg->msgid) {
    case MAVLINK_MSG_ID_MISSION_COUNT:
        on_count(l, msg);
        break;
    case MAVLINK_MSG_ID_MISSION_ITEM_INT:
        on_item_int(l, msg);
        break;
    case MAVLINK_MSG_ID_MISSION_ITEM:
        on_item_float(l, msg);
        break;
    case MAVLINK_MSG_ID_MISSION_REQUEST_LIST:
        on_request_list(l, msg);
        break;
    case MAVLINK_MSG_ID_MISSION_REQUEST_INT: {
        mavlink_mission_request_int_t r;
        mavlink_msg_mission_request_int_decode(msg, &r);
        send_item(l, msg, r.seq, r.mission_type);
        break;
    }
    case MAVLINK_MSG_ID_MISSION_REQUEST: { /* deprecated: answered with the INT item */
        mavlink_mission_request_t r;
        mavlink_msg_mission_request_decode(msg, &r);
        send_item(l, msg, r.seq, r.mission_type);
        break;
    }
    case MAVLINK_MSG_ID_MISSION_CLEAR_ALL: {
        mavlink_mission_clear_all_t c;
        mavlink_msg_mission_clear_all_decode(msg, &c);
        if (c.mission_type == (uint8_t)MAV_MISSION_TYPE_MISSION) {
            l->mission.uploading = 0u;
            cancel_pending(l);
            l->upload_count = 0u;
            uint16_t bad = 0u;
            (void)replace_list(l, &bad);
        }
        ack(l, msg->sysid, msg->compid, (uint8_t)MAV_MISSION_ACCEPTED, c.mission_type);
        break;
    }
    case MAVLINK_MSG_ID_MISSION_SET_CURRENT: {
        mavlink_mission_set_current_t sc;
        mavlink_msg_mission_set_current_decode(msg, &sc);
        if (sc.seq < l->cfg->waypoint_count) {
            restart_nav(l, sc.seq);
        } else {
            fw_link_count(&l->count.rx_bad_content);
        }
        send_current(l);
        break;
    }
    default:
        break;
    }
}

void fw_link_mission_after_step(fw_link_t *l)
{
    fw_link_mission_t *m = &l->mission;
    if ((m->apply_pending != 0u) && (l->have_home_alt != 0u)) {
        /* the deferred acceptance: applied, or reported refused (the list
         * flown before it stays) */
        uint16_t bad = 0u;
        if (replace_list(l, &bad) >= 2) {
            mission_text(l, (uint8_t)MAV_SEVERITY_WARNING, "mission refused at GPS fix,",
                         (int32_t)bad);
        } else {
            mission_text(l, (uint8_t)MAV_SEVERITY_NOTICE, "mission flown from GPS fix", -1);
        }
    }
    if ((m->uploading != 0u) && (fw_link_reached(l->now_ms, m->deadline_ms) != 0)) {
        if (m->retries < l->params.mission_retries) {
            m->retries = (uint8_t)(m->retries + 1u);
            request_item(l);
        } else {
            m->uploading = 0u;
            ack(l, m->partner_sysid, m->partner_compid, (uint8_t)MAV_MISSION_OPERATION_CANCELLED,
                (uint8_t)MAV_MISSION_TYPE_MISSION);
        }
    }
    const uint16_t index = l->fw->modes_state.nav.index;
    if ((l->last.modes.nav.arrived != 0u) && (m->last_current != UINT16_MAX)) {
        mavlink_mission_item_reached_t r;
        (void)memset(&r, 0, sizeof r);
        r.seq = m->last_current;
        (void)FW_LINK_QUEUE(l, MISSION_ITEM_REACHED, r);
    }
    if (index != m->last_current) {
        m->last_current = index;
        if (l->have_output != 0u) {
            send_current(l);
        }
    }
}
