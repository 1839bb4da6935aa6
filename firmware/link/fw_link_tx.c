/*
 * fw_link_tx.c - the base of the link's files (fw_link_tx.h): the transmit
 * queue's frame building (whole frames, first in first out; fw_link_tx in
 * fw_link.c takes them out) and the mode the link reports.
 */
#include "link/fw_link_tx.h"

/* Room for a frame of this payload length (header, CRC). */
static int fw_link_has_room(const fw_link_t *l, uint8_t len)
{
    const uint32_t overhead = MAVLINK_NUM_NON_PAYLOAD_BYTES; /* header and CRC */
    const uint32_t need = overhead + (uint32_t)len;
    return ((uint32_t)l->tx_len + need <= (uint32_t)FW_LINK_TX_BYTES) ? 1 : 0;
}

int fw_link_queue(fw_link_t *l, uint32_t msgid, const void *pkt, uint8_t len, uint8_t min_len,
                  uint8_t crc_extra)
{
    if (fw_link_has_room(l, len) == 0) {
        fw_link_count(&l->count.tx_overflow);
        return 1;
    }
    mavlink_message_t *msg = &l->tx_msg;
    msg->msgid = msgid & 0xFFFFFFu; /* a 24-bit field */
    (void)memcpy(_MAV_PAYLOAD_NON_CONST(msg), pkt, len);
    (void)mavlink_finalize_message_buffer(msg, l->params.sysid, l->compid, &l->tx_status, min_len,
                                          len, crc_extra);
    const uint16_t n = mavlink_msg_to_send_buffer(&l->tx_buf[l->tx_len], msg);
    l->tx_len = (uint16_t)(l->tx_len + n);
    fw_link_count(&l->count.tx_frames);
    return 0;
}

uint8_t fw_link_mode(const fw_link_t *l)
{
    return (l->have_output != 0u) ? l->last.modes.mode : (uint8_t)HT_MODE_MANUAL;
}

int fw_link_armed(const fw_link_t *l)
{
    return ((l->have_output != 0u) && (l->last.pulse_count > 0u)) ? 1 : 0;
}
