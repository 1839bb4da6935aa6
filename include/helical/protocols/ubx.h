/*
 * ubx.h - u-blox UBX protocol: a streaming decoder of the GPS's UBX-NAV-PVT
 * (and of the ACK-ACK / ACK-NAK replies to configuration), and encoders of
 * the start-up configuration messages, so that a GPS driver only moves
 * bytes. Facts from the u-blox 8 / M8 receiver description (UBX-13003221).
 *
 * A frame on the wire:
 *
 *   0xB5 0x62 | class | id | length (u16, little-endian) | payload | CK_A CK_B
 *
 * CK_A, CK_B: the 8-bit Fletcher checksum over class, id, length and
 * payload (for each byte b: CK_A += b; CK_B += CK_A; modulo 256).
 * Multi-byte payload fields are little-endian.
 *
 * The decoder holds at most UBX_FRAME_MAX bytes: a frame declaring a payload
 * over UBX_PAYLOAD_MAX (100 bytes; NAV-PVT is 92) is counted as bad_length
 * and dropped, as is any frame with a bad checksum, and the search goes on
 * from the byte after its 0xB5 (frame_scan.h: a good frame starting inside a
 * bad one is found at its own last byte). Frames with a good checksum of
 * other classes/ids count as unknown_type, NAV-PVT or ACK frames of another
 * length as wrong_length. Counters: frame_counts.h (bad_end stays 0).
 * The state is the caller's ubx_decoder_t.
 */
#ifndef HELICAL_UBX_H
#define HELICAL_UBX_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "helical/protocols/frame_counts.h"

#ifdef __cplusplus
extern "C" {
#endif

#define UBX_SYNC1         0xB5u
#define UBX_SYNC2         0x62u
#define UBX_OVERHEAD      8u   /* sync x2, class, id, length x2, checksum x2 */
#define UBX_PAYLOAD_MAX   100u /* what the decoder holds; NAV-PVT is 92 */
#define UBX_FRAME_MAX     (UBX_PAYLOAD_MAX + UBX_OVERHEAD)
#define UBX_CLASS_NAV     0x01u
#define UBX_ID_NAV_PVT    0x07u
#define UBX_NAV_PVT_BYTES 92u
#define UBX_CLASS_ACK     0x05u
#define UBX_ID_ACK_NAK    0x00u
#define UBX_ID_ACK_ACK    0x01u
#define UBX_CLASS_CFG     0x06u
#define UBX_ID_CFG_PRT    0x00u
#define UBX_ID_CFG_MSG    0x01u
#define UBX_ID_CFG_RATE   0x08u

/* NAV-PVT fixType values */
#define UBX_FIX_NONE      0u
#define UBX_FIX_DEAD_RECK 1u
#define UBX_FIX_2D        2u
#define UBX_FIX_3D        3u
#define UBX_FIX_GNSS_DR   4u
#define UBX_FIX_TIME_ONLY 5u
/* NAV-PVT flags: bit 0 gnssFixOK (the fix is within the DOP and accuracy
 * masks: the only fix to navigate on) */
#define UBX_PVT_FLAG_GNSS_FIX_OK 0x01u

typedef enum {
    UBX_ERR_NULL = -1, /* a NULL pointer: nothing done */
    UBX_NONE = 0,      /* no message decoded at this byte */
    UBX_NAV_PVT = 1,   /* out->pvt written */
    UBX_ACK_ACK = 2,   /* out->ack written: the message was accepted */
    UBX_ACK_NAK = 3    /* out->ack written: the message was rejected */
} ubx_result_t;

/* UBX-NAV-PVT, the fields a fixed-wing needs (payload offset in brackets). */
typedef struct {
    uint32_t itow_ms;          /* [0] GPS time of week of the epoch */
    uint8_t fix_type;          /* [20] UBX_FIX_* */
    uint8_t flags;             /* [21] bit 0 gnssFixOK */
    bool gnss_fix_ok;          /* flags bit 0 */
    uint8_t num_sv;            /* [23] satellites used */
    int32_t lon_e7;            /* [24] longitude, 1e-7 deg */
    int32_t lat_e7;            /* [28] latitude, 1e-7 deg */
    int32_t height_mm;         /* [32] above the ellipsoid */
    int32_t hmsl_mm;           /* [36] above mean sea level */
    uint32_t h_acc_mm;         /* [40] horizontal accuracy estimate */
    uint32_t v_acc_mm;         /* [44] vertical accuracy estimate */
    int32_t vel_n_mm_s;        /* [48] NED velocity */
    int32_t vel_e_mm_s;        /* [52] */
    int32_t vel_d_mm_s;        /* [56] */
    int32_t ground_speed_mm_s; /* [60] 2-D */
    int32_t head_mot_e5;       /* [64] heading of motion, 1e-5 deg */
    uint32_t s_acc_mm_s;       /* [68] speed accuracy estimate */
} ubx_nav_pvt_t;

typedef struct {
    uint8_t cls, id; /* the message acknowledged */
} ubx_ack_t;

typedef struct {
    ubx_nav_pvt_t pvt; /* valid after UBX_NAV_PVT */
    ubx_ack_t ack;     /* valid after UBX_ACK_ACK / UBX_ACK_NAK */
} ubx_msg_t;

typedef struct {
    uint8_t window[UBX_FRAME_MAX];
    uint8_t held;
    ht_frame_counts_t counts;
} ubx_decoder_t;

/* Reset the decoder (no-op on NULL). */
void ubx_init(ubx_decoder_t *d);

/*
 * Feed one byte. Returns UBX_NAV_PVT, UBX_ACK_ACK or UBX_ACK_NAK when it
 * completed such a frame, written to out->pvt or out->ack (the other member
 * left as it was); UBX_NONE otherwise; UBX_ERR_NULL (doing nothing) if d or
 * out is NULL.
 */
ubx_result_t ubx_push(ubx_decoder_t *d, uint8_t byte, ubx_msg_t *out);

/*
 * Feed up to n bytes, stopping after the byte that decodes a message.
 * Returns how many bytes were taken; *result is what ubx_push returned for
 * the last (UBX_NONE when n == 0). The same bytes give the same results and
 * counters as ubx_push one at a time. With d, out or result NULL, or bytes
 * NULL and n > 0: returns 0, and *result = UBX_ERR_NULL when result is not
 * NULL.
 */
size_t ubx_feed(ubx_decoder_t *d, const uint8_t *bytes, size_t n, ubx_msg_t *out,
                ubx_result_t *result);

/* The Fletcher checksum of n bytes: CK_A in bits 0..7, CK_B in bits 8..15
 * (src/protocols/ubx.c: the decoder's, which the encoders use too). */
uint16_t ubx_checksum(const uint8_t *data, size_t n);

/* ---- encoders (src/protocols/ubx_encode.c) ------------------------------------------ */

/*
 * Write one frame into out (capacity out_size). Returns its length
 * (len + UBX_OVERHEAD), or 0 (writing nothing) if out is NULL, payload is
 * NULL while len > 0, len > UBX_PAYLOAD_MAX, or out_size is too small.
 */
size_t ubx_encode(uint8_t cls, uint8_t id, const uint8_t *payload, uint16_t len, uint8_t *out,
                  size_t out_size);

/* UBX-CFG-RATE: one measurement every meas_rate_ms (e.g. 200: 5 Hz), one
 * navigation solution per measurement, times aligned to GPS time. 14 bytes;
 * returns 0 if meas_rate_ms is 0 or as ubx_encode. */
size_t ubx_encode_cfg_rate(uint16_t meas_rate_ms, uint8_t *out, size_t out_size);

/* UBX-CFG-MSG: send message cls/id on the port this is received on, once
 * per rate navigation solutions (0: never). 11 bytes. */
size_t ubx_encode_cfg_msg(uint8_t cls, uint8_t id, uint8_t rate, uint8_t *out, size_t out_size);

/* UBX-CFG-PRT for UART port_id (1 or 2): 8N1 at baud, UBX in and out only
 * (NMEA off, so that only what CFG-MSG enables is sent). 28 bytes; returns
 * 0 for another port or as ubx_encode. */
size_t ubx_encode_cfg_prt_uart(uint8_t port_id, uint32_t baud, uint8_t *out, size_t out_size);

#ifdef __cplusplus
}
#endif

#endif /* HELICAL_UBX_H */
