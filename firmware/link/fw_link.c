/*
 * fw_link.c - the link's API (fw_link.h): initialisation, the receive side
 * (the generated parser on the link's own status and buffer, the drop
 * counters, the target check, the dispatch to the protocols), the steps'
 * scheduling of the protocols and the transmit queue's drain (the frames
 * are built and queued by fw_link_tx.c).
 */
#include "link/fw_link.h"

#include "link/fw_link_command.h"
#include "link/fw_link_mission.h"
#include "link/fw_link_param_proto.h"
#include "link/fw_link_telemetry.h"
#include "link/fw_link_tx.h"

int fw_link_init(fw_link_t *l, fw_t *fw, fw_config_t *cfg_live, uint8_t sysid, uint8_t compid)
{
    if ((l == NULL) || (fw == NULL) || (cfg_live == NULL) || (fw->cfg != cfg_live)) {
        return -1;
    }
    (void)memset(l, 0, sizeof *l);
    l->fw = fw;
    l->cfg = cfg_live;
    ht_link_params_default(&l->params);
    if (sysid != 0u) {
        l->params.sysid = sysid;
    }
    l->compid = compid;
    l->param_list_next = UINT16_MAX; /* idle */
    /* the configuration's list stays flown until a mission is uploaded */
    l->mission.last_current = UINT16_MAX;
    return 0;
}

/* --- transmit -------------------------------------------------------------- */

size_t fw_link_tx(fw_link_t *l, uint8_t *buf, size_t cap)
{
    if ((l == NULL) || (buf == NULL) || (cap == 0u)) {
        return 0u;
    }
    const size_t n = (cap < (size_t)l->tx_len) ? cap : (size_t)l->tx_len;
    (void)memcpy(buf, l->tx_buf, n);
    (void)memmove(l->tx_buf, &l->tx_buf[n], (size_t)l->tx_len - n);
    l->tx_len = (uint16_t)((size_t)l->tx_len - n);
    return n;
}

/* --- receive --------------------------------------------------------------- */

static void drop(fw_link_t *l, uint32_t *why)
{
    fw_link_count(why);
    fw_link_count(&l->count.rx_dropped);
}

/* addressed to us: no target field, or 0 (broadcast), or ours */
static int for_us(const fw_link_t *l, const mavlink_message_t *msg, const mavlink_msg_entry_t *e)
{
    const uint8_t *payload = (const uint8_t *)_MAV_PAYLOAD(msg);
    if ((e->flags & (uint8_t)MAV_MSG_ENTRY_FLAG_HAVE_TARGET_SYSTEM) != 0u) {
        const uint8_t ts = payload[e->target_system_ofs];
        if ((ts != 0u) && (ts != l->params.sysid)) {
            return 0;
        }
    }
    if ((e->flags & (uint8_t)MAV_MSG_ENTRY_FLAG_HAVE_TARGET_COMPONENT) != 0u) {
        const uint8_t tc = payload[e->target_component_ofs];
        if ((tc != 0u) && (tc != l->compid)) {
            return 0;
        }
    }
    return 1;
}

static void frame_ok(fw_link_t *l, const mavlink_message_t *msg)
{
    const mavlink_msg_entry_t *e = mavlink_get_msg_entry(msg->msgid);
    if (e == NULL) {
        drop(l, &l->count.rx_unknown_id); /* cannot happen: the CRC needs the entry */
        return;
    }
    if ((msg->incompat_flags & (uint8_t)MAVLINK_IFLAG_SIGNED) != 0u) {
        drop(l, &l->count.rx_garbled); /* signing is not supported: docs/mavlink.md */
        return;
    }
    if (for_us(l, msg, e) == 0) {
        drop(l, &l->count.rx_wrong_target);
        return;
    }
    fw_link_count(&l->count.rx_ok);
    fw_link_param_rx(l, msg);
    fw_link_mission_rx(l, msg);
    fw_link_command_rx(l, msg);
}

void fw_link_rx(fw_link_t *l, const uint8_t *bytes, size_t n)
{
    if ((l == NULL) || (bytes == NULL)) {
        return;
    }
    for (size_t i = 0u; i < n; ++i) {
        const mavlink_parse_state_t before = l->rx_status.parse_state;
        const uint8_t r =
            mavlink_frame_char_buffer(&l->rx_msg, &l->rx_status, bytes[i], NULL, NULL);
        if ((before == MAVLINK_PARSE_STATE_GOT_LENGTH) &&
            (l->rx_status.parse_state == MAVLINK_PARSE_STATE_IDLE)) {
            /* unknown incompat flags: the parser dropped the frame (its own
             * error count is cleared on return) */
            drop(l, &l->count.rx_garbled);
        }
        if (r == (uint8_t)MAVLINK_FRAMING_OK) {
            frame_ok(l, &l->rx_msg);
        } else if (r == (uint8_t)MAVLINK_FRAMING_BAD_CRC) {
            if (mavlink_get_msg_entry(l->rx_msg.msgid) == NULL) {
                drop(l, &l->count.rx_unknown_id);
            } else {
                drop(l, &l->count.rx_bad_crc);
            }
        } else if (r == (uint8_t)MAVLINK_FRAMING_BAD_SIGNATURE) {
            drop(l, &l->count.rx_garbled);
        } else {
            /* incomplete: more bytes to come */
        }
    }
}

/* --- after a step ---------------------------------------------------------- */

void fw_link_after_step(fw_link_t *l, const fw_output_t *out, uint32_t now_ms)
{
    if ((l == NULL) || (out == NULL)) {
        return;
    }
    l->now_ms = now_ms;
    l->last = *out;
    l->have_output = 1u;
    if ((l->have_home_alt == 0u) && (l->fw->have_home != 0u)) {
        l->home_alt_cm = out->nav.altitude_cm; /* the datum of relative mission altitudes */
        l->have_home_alt = 1u;
    }
    fw_link_mission_after_step(l);
    fw_link_param_after_step(l);
    fw_link_telemetry_after_step(l);
}
