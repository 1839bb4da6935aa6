/*
 * ubx_encode.c - UBX frame and configuration-message encoders: the GPS
 * driver's start-up messages as pure functions into the caller's buffer
 * (the checksum is the decoder's, ubx.c). See ubx.h.
 */
#include "helical/protocols/ubx.h"

size_t ubx_encode(uint8_t cls, uint8_t id, const uint8_t *payload, uint16_t len, uint8_t *out,
                  size_t out_size)
{
    if (out == NULL || (payload == NULL && len != 0u) || len > UBX_PAYLOAD_MAX ||
        out_size < (size_t)len + UBX_OVERHEAD) {
        return 0u;
    }
    out[0] = UBX_SYNC1;
    out[1] = UBX_SYNC2;
    out[2] = cls;
    out[3] = id;
    out[4] = (uint8_t)(len & 0xFFu);
    out[5] = (uint8_t)(len >> 8u);
    for (size_t i = 0u; i < (size_t)len; i++) {
        out[6u + i] = payload[i];
    }
    const uint16_t ck = ubx_checksum(&out[2], (size_t)len + 4u);
    out[6u + (size_t)len] = (uint8_t)(ck & 0xFFu);
    out[7u + (size_t)len] = (uint8_t)(ck >> 8u);
    return (size_t)len + UBX_OVERHEAD;
}

static void put_u16(uint8_t *p, uint16_t v)
{
    p[0] = (uint8_t)(v & 0xFFu);
    p[1] = (uint8_t)(v >> 8u);
}

static void put_u32(uint8_t *p, uint32_t v)
{
    put_u16(p, (uint16_t)(v & 0xFFFFu));
    put_u16(&p[2], (uint16_t)(v >> 16u));
}

size_t ubx_encode_cfg_rate(uint16_t meas_rate_ms, uint8_t *out, size_t out_size)
{
    if (meas_rate_ms == 0u) {
        return 0u;
    }
    uint8_t p[6];
    put_u16(&p[0], meas_rate_ms);
    put_u16(&p[2], 1u); /* navRate: a solution every measurement */
    put_u16(&p[4], 1u); /* timeRef: GPS time */
    return ubx_encode(UBX_CLASS_CFG, UBX_ID_CFG_RATE, p, 6u, out, out_size);
}

size_t ubx_encode_cfg_msg(uint8_t cls, uint8_t id, uint8_t rate, uint8_t *out, size_t out_size)
{
    /* The 3-byte form: the rate on the port the message arrives on, which
     * is the port the driver talks to. */
    const uint8_t p[3] = {cls, id, rate};
    return ubx_encode(UBX_CLASS_CFG, UBX_ID_CFG_MSG, p, 3u, out, out_size);
}

size_t ubx_encode_cfg_prt_uart(uint8_t port_id, uint32_t baud, uint8_t *out, size_t out_size)
{
    if (port_id != 1u && port_id != 2u) {
        return 0u;
    }
    uint8_t p[20] = {0};
    p[0] = port_id;
    /* mode: charLen (bits 7..6) 0b11 = 8 bits, parity (bits 11..9) 0b100 =
     * none, nStopBits (bits 13..12) 0 = 1 stop bit; bit 4 set as the older
     * receiver descriptions ask (the M8 ignores it). */
    put_u32(&p[4], 0x000008D0u);
    put_u32(&p[8], baud);
    put_u16(&p[12], 0x0001u); /* inProtoMask: UBX only */
    put_u16(&p[14], 0x0001u); /* outProtoMask: UBX only (no NMEA) */
    return ubx_encode(UBX_CLASS_CFG, UBX_ID_CFG_PRT, p, 20u, out, out_size);
}
