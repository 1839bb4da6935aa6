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

#include "link/fw_link_f32.h"
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
    (void)FW_LINK_QUEUE(l, MISSION_REQUEST_INT, r);
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

/* The accepted list into the guidance. 0 = flown; 1 = waits for home;
 * 2 = the guidance refused it (an empty list is flown instead). */
static int apply_list(fw_link_t *l)
{
    fw_t *fw = l->fw;
    if ((l->item_count > 0u) && ((fw->have_home == 0u) || (l->have_home_alt == 0u))) {
        l->mission.apply_pending = 1u;
        return 1;
    }
    l->mission.apply_pending = 0u;
    for (uint16_t i = 0u; i < l->item_count; ++i) {
        const fw_link_item_t *it = &l->items[i];
        int32_t n_cm = 0;
        int32_t e_cm = 0;
        ht_geo_to_local(&fw->home, it->lat_e7, it->lon_e7, &n_cm, &e_cm);
        const int32_t alt_cm = (it->frame == (uint8_t)MAV_FRAME_GLOBAL_RELATIVE_ALT_INT)
                                   ? (l->home_alt_cm + it->z_cm)
                                   : it->z_cm;
        l->waypoints[i].north_m = cm_to_m(n_cm);
        l->waypoints[i].east_m = cm_to_m(e_cm);
        l->waypoints[i].alt_m = cm_to_m(alt_cm);
    }
    fw_config_t *cfg = l->cfg;
    cfg->waypoints = l->waypoints;
    cfg->waypoint_count = l->item_count;
    const uint8_t pm = (cfg->modes_pitch_mode != 0u) ? 1u : 0u;
    int status = 0;
    if (ht_modes_init(&fw->modes, &cfg->modes, &fw->law[pm], cfg->waypoints, cfg->waypoint_count,
                      &fw->modes_bad) != 0) {
        cfg->waypoint_count = 0u; /* e.g. a waypoint beyond the guidance's range */
        (void)ht_modes_init(&fw->modes, &cfg->modes, &fw->law[pm], cfg->waypoints, 0u,
                            &fw->modes_bad);
        status = 2;
    }
    restart_nav(l, 0u);
    return status;
}

/* the item's check: 0, or the MAV_MISSION_RESULT that refuses it */
static uint8_t check_item(const mavlink_mission_item_int_t *it, fw_link_item_t *out)
{
    if (it->command != (uint16_t)MAV_CMD_NAV_WAYPOINT) {
        return (uint8_t)MAV_MISSION_UNSUPPORTED;
    }
    if ((it->frame != (uint8_t)MAV_FRAME_GLOBAL_INT) &&
        (it->frame != (uint8_t)MAV_FRAME_GLOBAL_RELATIVE_ALT_INT)) {
        return (uint8_t)MAV_MISSION_UNSUPPORTED_FRAME;
    }
    if ((it->x < -900000000) || (it->x > 900000000)) {
        return (uint8_t)MAV_MISSION_INVALID_PARAM5_X;
    }
    if ((it->y < -1800000000) || (it->y > 1800000000)) {
        return (uint8_t)MAV_MISSION_INVALID_PARAM6_Y;
    }
    int32_t z_cm = 0;
    const uint32_t z = fw_link_get_f32(it, offsetof(mavlink_mission_item_int_t, z));
    if ((fw_f32_to_fixed(z, 100, &z_cm) != 0) || (z_cm < -ALT_LIMIT_CM) || (z_cm > ALT_LIMIT_CM)) {
        return (uint8_t)MAV_MISSION_INVALID_PARAM7;
    }
    out->lat_e7 = it->x;
    out->lon_e7 = it->y;
    out->z_cm = z_cm;
    out->frame = it->frame;
    return 0u;
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
        ack(l, msg->sysid, msg->compid, (uint8_t)MAV_MISSION_NO_SPACE, c.mission_type);
        return;
    }
    fw_link_mission_t *m = &l->mission;
    if (c.count == 0u) {
        m->uploading = 0u;
        l->item_count = 0u;
        (void)apply_list(l);
        ack(l, msg->sysid, msg->compid, (uint8_t)MAV_MISSION_ACCEPTED, c.mission_type);
        return;
    }
    m->uploading = 1u; /* a new count restarts an upload in progress */
    m->partner_sysid = msg->sysid;
    m->partner_compid = msg->compid;
    m->count = c.count;
    m->next = 0u;
    m->retries = 0u;
    request_item(l);
}

static void on_item(fw_link_t *l, const mavlink_message_t *msg)
{
    fw_link_mission_t *m = &l->mission;
    mavlink_mission_item_int_t it;
    mavlink_msg_mission_item_int_decode(msg, &it);
    if ((m->uploading == 0u) || (it.mission_type != (uint8_t)MAV_MISSION_TYPE_MISSION) ||
        (msg->sysid != m->partner_sysid)) {
        fw_link_count(&l->count.rx_bad_content);
        return;
    }
    if (it.seq != m->next) {
        fw_link_count(&l->count.rx_bad_content); /* a repeat or out of order: ask again */
        request_item(l);
        return;
    }
    const uint8_t refused = check_item(&it, &l->upload[it.seq]);
    if (refused != 0u) {
        m->uploading = 0u;
        ack(l, m->partner_sysid, m->partner_compid, refused, it.mission_type);
        return;
    }
    m->next = (uint16_t)(m->next + 1u);
    m->retries = 0u;
    if (m->next < m->count) {
        request_item(l);
        return;
    }
    m->uploading = 0u;
    (void)memcpy(l->items, l->upload, (size_t)m->count * sizeof l->items[0]);
    l->item_count = m->count;
    const uint8_t result =
        (apply_list(l) == 2) ? (uint8_t)MAV_MISSION_ERROR : (uint8_t)MAV_MISSION_ACCEPTED;
    ack(l, m->partner_sysid, m->partner_compid, result, it.mission_type);
}

static void on_request_list(fw_link_t *l, const mavlink_message_t *msg)
{
    mavlink_mission_request_list_t r;
    mavlink_msg_mission_request_list_decode(msg, &r);
    mavlink_mission_count_t c;
    (void)memset(&c, 0, sizeof c);
    c.target_system = msg->sysid;
    c.target_component = msg->compid;
    c.mission_type = r.mission_type;
    c.count = (r.mission_type == (uint8_t)MAV_MISSION_TYPE_MISSION) ? l->item_count : 0u;
    (void)FW_LINK_QUEUE(l, MISSION_COUNT, c);
}

static void send_item(fw_link_t *l, const mavlink_message_t *msg, uint16_t seq, uint8_t type)
{
    if ((type != (uint8_t)MAV_MISSION_TYPE_MISSION) || (seq >= l->item_count)) {
        ack(l, msg->sysid, msg->compid, (uint8_t)MAV_MISSION_INVALID_SEQUENCE, type);
        return;
    }
    const fw_link_item_t *s = &l->items[seq];
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
    fw_link_put_f32(&it, offsetof(mavlink_mission_item_int_t, z), fw_f32_from_ratio(s->z_cm, 100u));
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
        on_item(l, msg);
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
            l->item_count = 0u;
            (void)apply_list(l);
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
        (void)apply_list(l);
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
