/*
 * fw_link_param_proto.c - the MAVLink parameter protocol over the one
 * parameter table (fw_link_param_table.c): PARAM_REQUEST_LIST (the list is
 * streamed a few values per step, as the transmit queue has room),
 * PARAM_REQUEST_READ (by index or id), PARAM_SET (range-checked, applied,
 * answered with the value in force: the old one when refused), all
 * answered with PARAM_VALUE, REAL32 in the row's engineering unit.
 */
#include "link/fw_link_param_proto.h"

#include "link/fw_link_f32.h"
#include "link/fw_link_param_table.h"
#include "link/fw_link_tx.h"

/* values per step while a list is streamed, and the queue kept free for
 * telemetry meanwhile */
#define LIST_PER_STEP 3u
#define LIST_RESERVE  256u

int fw_link_send_param_value(fw_link_t *l, uint16_t index)
{
    int32_t raw = 0;
    const ht_param_info_t *row = NULL;
    char id[17];
    if ((fw_link_param_get(l, index, &raw, &row) != 0) || (row == NULL) ||
        (fw_link_param_id(index, id) != 0)) {
        return -1;
    }
    mavlink_param_value_t pv;
    (void)memset(&pv, 0, sizeof pv);
    (void)memcpy(pv.param_id, id, strlen(id)); /* <= 16: not terminated at 16 */
    pv.param_count = fw_link_param_count();
    pv.param_index = index;
    pv.param_type = (uint8_t)MAV_PARAM_TYPE_REAL32;
    fw_link_put_f32(&pv, offsetof(mavlink_param_value_t, param_value),
                    fw_f32_from_ratio((int64_t)raw, (uint32_t)row->scale));
    return FW_LINK_QUEUE(l, PARAM_VALUE, pv);
}

static int32_t index_of(int16_t index, const char param_id[16])
{
    if (index >= 0) {
        return ((uint16_t)index < fw_link_param_count()) ? (int32_t)index : -1;
    }
    return fw_link_param_find(param_id);
}

static void param_set(fw_link_t *l, const mavlink_message_t *msg)
{
    mavlink_param_set_t ps;
    mavlink_msg_param_set_decode(msg, &ps);
    const int32_t index = fw_link_param_find(ps.param_id);
    if (index < 0) {
        fw_link_count(&l->count.rx_bad_content); /* no such parameter: no answer (the spec) */
        return;
    }
    const ht_param_info_t *row = NULL;
    int32_t raw = 0;
    (void)fw_link_param_get(l, (uint16_t)index, NULL, &row);
    const uint32_t bits = fw_link_get_f32(&ps, offsetof(mavlink_param_set_t, param_value));
    /* refused: NaN or infinity, or out of the row's range, or a joint check */
    if ((row == NULL) || (fw_f32_to_fixed(bits, row->scale, &raw) < 0) ||
        (fw_link_param_set(l, (uint16_t)index, raw) != 0)) {
        fw_link_count(&l->count.rx_bad_content);
    }
    (void)fw_link_send_param_value(l, (uint16_t)index); /* the value in force */
}

void fw_link_param_rx(fw_link_t *l, const mavlink_message_t *msg)
{
    switch (msg->msgid) {
    case MAVLINK_MSG_ID_PARAM_REQUEST_LIST:
        l->param_list_next = 0u;
        break;
    case MAVLINK_MSG_ID_PARAM_REQUEST_READ: {
        mavlink_param_request_read_t rr;
        mavlink_msg_param_request_read_decode(msg, &rr);
        const int32_t index = index_of(rr.param_index, rr.param_id);
        if (index >= 0) {
            (void)fw_link_send_param_value(l, (uint16_t)index);
        } else {
            fw_link_count(&l->count.rx_bad_content);
        }
        break;
    }
    case MAVLINK_MSG_ID_PARAM_SET:
        param_set(l, msg);
        break;
    default:
        break;
    }
}

void fw_link_param_after_step(fw_link_t *l)
{
    const uint16_t count = fw_link_param_count();
    unsigned k = 0u;
    /* while the queue has room beyond the reserve; else the list waits for the
     * queue to drain, and telemetry keeps flowing */
    while ((k < LIST_PER_STEP) && (l->param_list_next < count) &&
           (((uint32_t)l->tx_len + LIST_RESERVE) <= (uint32_t)FW_LINK_TX_BYTES) &&
           (fw_link_send_param_value(l, l->param_list_next) == 0)) {
        l->param_list_next = (uint16_t)(l->param_list_next + 1u);
        ++k;
    }
}
