/*
 * hil_frame.c - the HIL link's framing: encoder, byte-wise decoder with
 * resynchronisation, CRC-16/CCITT-FALSE. See hil_frame.h.
 */
#include "helical/hil_frame.h"

uint16_t hil_crc16(uint16_t crc, const uint8_t *data, size_t n)
{
    /* Bitwise rather than a 512-byte table: a frame is at most 66 bytes, and
     * flash is the scarcer resource on the smallest boards. */
    uint16_t c = crc;
    for (size_t i = 0; i < n; i++) {
        c ^= (uint16_t)((uint16_t)data[i] << 8);
        for (unsigned bit = 0; bit < 8u; bit++) {
            c = ((c & 0x8000u) != 0u) ? (uint16_t)(((unsigned)c << 1) ^ 0x1021u)
                                      : (uint16_t)((unsigned)c << 1);
        }
    }
    return c;
}

size_t hil_encode(uint8_t id, const uint8_t *payload, uint8_t len, uint8_t *out, size_t out_size)
{
    if (out == NULL || len > HIL_PAYLOAD_MAX || (payload == NULL && len != 0u) ||
        out_size < (size_t)len + HIL_OVERHEAD) {
        return 0u;
    }
    out[0] = HIL_SYNC1;
    out[1] = HIL_SYNC2;
    out[2] = len;
    out[3] = id;
    for (uint8_t i = 0; i < len; i++) {
        out[4u + i] = payload[i];
    }
    uint16_t crc = hil_crc16(0xFFFFu, &out[2], (size_t)len + 2u);
    out[4u + len] = (uint8_t)(crc & 0xFFu);
    out[5u + len] = (uint8_t)(crc >> 8);
    return (size_t)len + HIL_OVERHEAD;
}

static void count(uint16_t *c)
{
    if (*c != UINT16_MAX) {
        (*c)++;
    }
}

void hil_decoder_init(hil_decoder_t *d, hil_msg_table_t table)
{
    hil_decoder_t zero = {0};
    *d = zero;
    d->table = table;
    d->state = (uint8_t)HIL_WAIT_SYNC1;
}

/* A frame of this id and length is one the caller expects. */
static int known(const hil_decoder_t *d)
{
    if (d->table.expected_len == NULL || d->id >= d->table.id_count) {
        return 0;
    }
    uint8_t want = d->table.expected_len[d->id];
    return want == 0xFFu || want == d->len;
}

/* After a frame has failed, look for a new start: a 0xA5 here may itself be
 * the first sync byte. */
static void resync(hil_decoder_t *d, uint8_t byte)
{
    d->state = (uint8_t)((byte == HIL_SYNC1) ? HIL_WAIT_SYNC2 : HIL_WAIT_SYNC1);
}

int hil_decoder_push(hil_decoder_t *d, uint8_t byte)
{
    switch ((hil_rx_state_t)d->state) {
    case HIL_WAIT_SYNC1:
        if (byte == HIL_SYNC1) {
            d->state = (uint8_t)HIL_WAIT_SYNC2;
        } else {
            count(&d->stats.skipped_bytes);
        }
        return 0;
    case HIL_WAIT_SYNC2:
        if (byte == HIL_SYNC2) {
            d->state = (uint8_t)HIL_WAIT_LEN;
        } else {
            count(&d->stats.skipped_bytes);
            resync(d, byte);
        }
        return 0;
    case HIL_WAIT_LEN:
        if (byte > HIL_PAYLOAD_MAX) {
            count(&d->stats.bad_length);
            resync(d, byte);
            return 0;
        }
        d->len = byte;
        d->crc = hil_crc16(0xFFFFu, &byte, 1u);
        d->state = (uint8_t)HIL_WAIT_ID;
        return 0;
    case HIL_WAIT_ID:
        d->id = byte;
        d->crc = hil_crc16(d->crc, &byte, 1u);
        d->count = 0u;
        d->state = (uint8_t)((d->len == 0u) ? HIL_WAIT_CRC_LO : HIL_IN_PAYLOAD);
        return 0;
    case HIL_IN_PAYLOAD:
        d->payload[d->count] = byte;
        d->count++;
        d->crc = hil_crc16(d->crc, &byte, 1u);
        if (d->count == d->len) {
            d->state = (uint8_t)HIL_WAIT_CRC_LO;
        }
        return 0;
    case HIL_WAIT_CRC_LO:
        d->crc_lo = byte;
        d->state = (uint8_t)HIL_WAIT_CRC_HI;
        return 0;
    case HIL_WAIT_CRC_HI:
    default:
        d->state = (uint8_t)HIL_WAIT_SYNC1;
        if ((uint16_t)(d->crc_lo | ((uint16_t)byte << 8)) != d->crc) {
            count(&d->stats.bad_crc);
            return 0;
        }
        if (!known(d)) {
            count(&d->stats.unknown_id);
            return 0;
        }
        count(&d->stats.frames_ok);
        return 1;
    }
}

void hil_put_u16(uint8_t *p, uint16_t v)
{
    p[0] = (uint8_t)(v & 0xFFu);
    p[1] = (uint8_t)(v >> 8);
}

void hil_put_i16(uint8_t *p, int16_t v)
{
    hil_put_u16(p, (uint16_t)v);
}

void hil_put_i32(uint8_t *p, int32_t v)
{
    uint32_t u = (uint32_t)v;
    hil_put_u16(p, (uint16_t)(u & 0xFFFFu));
    hil_put_u16(&p[2], (uint16_t)(u >> 16));
}

uint16_t hil_get_u16(const uint8_t *p)
{
    return (uint16_t)(p[0] | ((uint16_t)p[1] << 8));
}

int16_t hil_get_i16(const uint8_t *p)
{
    return (int16_t)hil_get_u16(p);
}

int32_t hil_get_i32(const uint8_t *p)
{
    uint32_t u = (uint32_t)hil_get_u16(p) | ((uint32_t)hil_get_u16(&p[2]) << 16);
    return (int32_t)u;
}
