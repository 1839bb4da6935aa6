/*
 * fw_link_param_proto.c - the MAVLink parameter protocol over the one
 * parameter table (fw_link_param_table.c): PARAM_REQUEST_LIST (the list is
 * streamed a few values per step, as the transmit queue has room),
 * PARAM_REQUEST_READ (by index, or by id with index -1), PARAM_SET (type-
 * and range-checked, applied, answered with the value set or, refused, the
 * old one and a STATUSTEXT), all answered with PARAM_VALUE in the row's
 * engineering unit: integer rows as their integer type, fixed-point rows as
 * REAL32, the value C-cast into the float field
 * (MAV_PROTOCOL_CAPABILITY_PARAM_ENCODE_C_CAST, ArduPilot's convention).
 */
#include "link/fw_link_param_proto.h"

#include "helical/math/f32_bits.h"
#include "link/fw_link_param_table.h"
#include "link/fw_link_text.h"
#include "link/fw_link_tx.h"

/* values per step while a list is streamed, and the queue kept free for
 * telemetry meanwhile */
#define LIST_PER_STEP 3u
#define LIST_RESERVE  256u

/* PARAM_VALUE of row index carrying value_bits (binary32, C-cast: the
 * number itself, whatever the type) */
static int send_value_bits(fw_link_t *l, uint16_t index, uint32_t value_bits)
{
    char id[17];
    if (fw_link_param_id(index, id) != 0) {
        return -1;
    }
    mavlink_param_value_t pv;
    (void)memset(&pv, 0, sizeof pv);
    (void)memcpy(pv.param_id, id, strlen(id)); /* <= 16: not terminated at 16 */
    pv.param_count = fw_link_param_count();
    pv.param_index = index;
    pv.param_type = fw_link_param_mav_type(index);
    fw_link_put_f32(&pv, offsetof(mavlink_param_value_t, param_value), value_bits);
    return FW_LINK_QUEUE(l, PARAM_VALUE, pv);
}

int fw_link_send_param_value(fw_link_t *l, uint16_t index)
{
    int32_t raw = 0;
    const ht_param_info_t *row = NULL;
    if ((fw_link_param_get(l, index, &raw, &row) != 0) || (row == NULL)) {
        return -1;
    }
    return send_value_bits(l, index, ht_f32_from_ratio((int64_t)raw, (uint32_t)row->scale));
}

static int32_t index_of(int16_t index, const char param_id[16])
{
    if (index >= 0) {
        return ((uint16_t)index < fw_link_param_count()) ? (int32_t)index : -1;
    }
    if (index == -1) {
        return fw_link_param_find(param_id); /* -1: by id (the spec); other negatives: none */
    }
    return -1;
}

/* "<ID> refused: <why>" */
static void refused(const char *id, const char *why, fw_link_text_t *t)
{
    fw_link_text_start(t, id);
    fw_link_text_str(t, " refused: ");
    fw_link_text_str(t, why);
}

static void send_refusal(fw_link_t *l, fw_link_text_t *t)
{
    fw_link_count(&l->count.rx_bad_content);
    (void)fw_link_statustext(l, (uint8_t)MAV_SEVERITY_WARNING, t);
}

/* The set's value in the row's stored format (raw), or a refusal in *t:
 * the type must be REAL32 or the row's own integer type, whose value must
 * then be an exact integer (C-cast encoding: a byte-wise encoded integer
 * arrives as a tiny fraction and is refused, not read as 0). 0 = raw. */
static int set_value(const char *id, const ht_param_info_t *row, uint8_t row_type, uint8_t type,
                     uint32_t bits, int32_t *raw, fw_link_text_t *t)
{
    const uint8_t real32 = (uint8_t)MAV_PARAM_TYPE_REAL32;
    if ((type != real32) && (type != row_type)) {
        refused(id, "type ", t);
        fw_link_text_int(t, (int32_t)type);
        fw_link_text_str(t, ", not ");
        fw_link_text_int(t, (int32_t)row_type);
        if (row_type != real32) {
            fw_link_text_str(t, " or 9");
        }
        return -1;
    }
    const int r = ht_f32_to_fixed(bits, row->scale, raw);
    if (r < 0) {
        refused(id, "not a number", t);
        return -1;
    }
    if ((type != real32) && ((r != 0) || (ht_f32_from_ratio((int64_t)*raw, 1u) != bits)) &&
        !((*raw == 0) && (bits == 0x80000000u))) {
        refused(id, "not an integer", t);
        return -1;
    }
    if ((r != 0) || (*raw < row->min_raw) || (*raw > row->max_raw)) {
        refused(id, "outside [", t);
        fw_link_text_fixed(t, row->min_raw, row->scale);
        fw_link_text_str(t, ", ");
        fw_link_text_fixed(t, row->max_raw, row->scale);
        fw_link_text_str(t, "] ");
        fw_link_text_str(t, row->unit);
        return -1;
    }
    return 0;
}

/*
 * PARAM_SET. Answered with one PARAM_VALUE: refused, the value in force
 * (the old one) and a STATUSTEXT naming the row and why; accepted, the
 * value as it was sent (its bits) - the row's rounding of it is exactly the
 * value now in force, and MAVProxy (|echo - sent| <= 1e-5) and MAVSDK (the
 * same float and the same type) take only that as success
 * (docs/mavlink.md "What a set echoes"). Every later PARAM_VALUE (read,
 * list) carries the stored value.
 */
static void param_set(fw_link_t *l, const mavlink_message_t *msg)
{
    mavlink_param_set_t ps;
    mavlink_msg_param_set_decode(msg, &ps);
    fw_link_text_t t;
    const int32_t index = fw_link_param_find(ps.param_id);
    if (index < 0) {
        char id[17];
        (void)memcpy(id, ps.param_id, 16u);
        id[16] = '\0';
        refused(id, "no such parameter", &t);
        send_refusal(l, &t); /* no PARAM_VALUE: the spec */
        return;
    }
    const uint16_t i = (uint16_t)index;
    char id[17];
    (void)fw_link_param_id(i, id);
    const ht_param_info_t *row = NULL;
    int32_t raw = 0;
    (void)fw_link_param_get(l, i, NULL, &row);
    const uint32_t bits = fw_link_get_f32(&ps, offsetof(mavlink_param_set_t, param_value));
    if ((row == NULL) ||
        (set_value(id, row, fw_link_param_mav_type(i), ps.param_type, bits, &raw, &t) != 0)) {
        send_refusal(l, &t);
        (void)fw_link_send_param_value(l, i); /* the value in force: unchanged */
        return;
    }
    /* the one call site of a set: the row's range, the block's joint checks */
    if (fw_link_param_set(l, i, raw) != 0) {
        /* the joint rule's own reason (config_check.h, a whole text of at
         * most 49 characters), else the group's */
        const char *why = l->param_refusal;
        if (*why != '\0') {
            fw_link_text_start(&t, why);
        } else {
            refused(id, "joint check of its group", &t);
        }
        send_refusal(l, &t);
        (void)fw_link_send_param_value(l, i);
        return;
    }
    (void)send_value_bits(l, i, bits);
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
            fw_link_text_t t;
            fw_link_text_start(&t, "param read refused: index ");
            fw_link_text_int(&t, (int32_t)rr.param_index);
            fw_link_text_str(&t, (rr.param_index == -1) ? " (no such id)" : "");
            send_refusal(l, &t);
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
