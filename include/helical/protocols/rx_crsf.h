/*
 * rx_crsf.h - decoder of CRSF receiver frames (TBS Crossfire, ExpressLRS),
 * from the bytes of the receiver's UART (420 000 baud 8N1 as usual; the
 * decoder sees bytes only).
 *
 * A frame on the wire:
 *
 *   sync | len | type | payload (len - 2 bytes) | crc
 *
 *   sync: 0xC8 (the flight controller's address, the sync byte receivers
 *         send); 0xEE (the transmitter module's address) is accepted too,
 *         because EdgeTX starts its outgoing frames with it.
 *   len:  the count of bytes after it: type + payload + crc, 2..62, so a
 *         frame is at most 64 bytes. Any other value is a bad length.
 *   crc:  CRC-8/DVB-S2 (polynomial 0xD5, initial value 0, no reflection,
 *         no final xor) over type and payload.
 *
 * Decoded types (a good CRC and another type counts as unknown_type; one of
 * these types with another payload length as wrong_length):
 *
 *   0x16 RC_CHANNELS_PACKED, 22 bytes: 16 channels x 11 bits
 *        (rc_channels.h), mapped to microseconds with rc_ticks_to_pulse_us:
 *        172 -> 988, 992 -> 1500, 1811 -> 2012 us.
 *   0x14 LINK_STATISTICS, 10 bytes: uplink RSSI antenna 1 and 2 (-dBm),
 *        uplink link quality (%), uplink SNR (dB, signed), active antenna,
 *        RF mode, uplink TX power (an index), downlink RSSI (-dBm), downlink
 *        link quality (%), downlink SNR (dB, signed).
 *
 * Failsafe: CRSF has no failsafe flag in its channel frame. A receiver that
 * loses the link stops sending channel frames (or, as configured, keeps
 * sending the last or failsafe values); link statistics then report an
 * uplink link quality of 0. So the driver declares failsafe on the age of
 * the last channel frame (its freshness) and on link quality 0
 * (crsf_link_stats_t.link_lost); the decoder reports frames, never time.
 *
 * Counters (frame_counts.h): bad_length, bad_checksum, truncated,
 * unknown_type, wrong_length, frames_ok, discarded_bytes; bad_end stays 0.
 * The state is the caller's crsf_decoder_t.
 */
#ifndef HELICAL_RX_CRSF_H
#define HELICAL_RX_CRSF_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "helical/protocols/frame_counts.h"
#include "helical/protocols/rc_channels.h"

#ifdef __cplusplus
extern "C" {
#endif

#define CRSF_SYNC_FC          0xC8u
#define CRSF_SYNC_TX_MODULE   0xEEu
#define CRSF_LEN_MIN          2u  /* type + crc */
#define CRSF_LEN_MAX          62u /* type + 60 payload bytes + crc */
#define CRSF_FRAME_MAX        64u /* sync + len + CRSF_LEN_MAX */
#define CRSF_TYPE_LINK_STATS  0x14u
#define CRSF_TYPE_RC_CHANNELS 0x16u
#define CRSF_LINK_STATS_BYTES 10u

typedef enum {
    CRSF_ERR_NULL = -1,   /* a NULL pointer: nothing done */
    CRSF_NONE = 0,        /* no frame decoded at this byte */
    CRSF_RC_CHANNELS = 1, /* out->rc written */
    CRSF_LINK_STATS = 2   /* out->link written */
} crsf_result_t;

typedef struct {
    uint16_t ticks[RC_CHANNELS];    /* the 11-bit values as sent */
    uint16_t pulse_us[RC_CHANNELS]; /* rc_ticks_to_pulse_us of each */
} crsf_channels_t;

typedef struct {
    int16_t uplink_rssi_ant1_dbm; /* the wire's byte is -dBm: 0..-255 */
    int16_t uplink_rssi_ant2_dbm;
    uint8_t uplink_lq_pct;
    int8_t uplink_snr_db;
    uint8_t active_antenna;
    uint8_t rf_mode;
    uint8_t uplink_tx_power_index; /* an index into the sender's power table */
    int16_t downlink_rssi_dbm;
    uint8_t downlink_lq_pct;
    int8_t downlink_snr_db;
    bool link_lost; /* uplink_lq_pct == 0: no radio frame received lately */
} crsf_link_stats_t;

typedef struct {
    crsf_channels_t rc;     /* valid after CRSF_RC_CHANNELS */
    crsf_link_stats_t link; /* valid after CRSF_LINK_STATS */
} crsf_msg_t;

typedef struct {
    uint8_t window[CRSF_FRAME_MAX];
    uint8_t held;
    ht_frame_counts_t counts;
} crsf_decoder_t;

/* CRC-8/DVB-S2 of n bytes (check value of "123456789": 0xBC). */
uint8_t crsf_crc8(const uint8_t *data, size_t n);

/* Reset the decoder (no-op on NULL). */
void crsf_init(crsf_decoder_t *d);

/*
 * Feed one byte. Returns CRSF_RC_CHANNELS or CRSF_LINK_STATS when it
 * completed a frame of that type, written to out->rc or out->link (the other
 * member is left as it was); CRSF_NONE otherwise; CRSF_ERR_NULL (doing
 * nothing) if d or out is NULL.
 */
crsf_result_t crsf_push(crsf_decoder_t *d, uint8_t byte, crsf_msg_t *out);

/*
 * Feed up to n bytes, stopping after the byte that decodes a frame. Returns
 * how many bytes were taken; *result is what crsf_push returned for the last
 * (CRSF_NONE when n == 0). The same bytes give the same results and counters
 * as crsf_push one at a time. With d, out or result NULL, or bytes NULL and
 * n > 0: returns 0, and *result = CRSF_ERR_NULL when result is not NULL.
 */
size_t crsf_feed(crsf_decoder_t *d, const uint8_t *bytes, size_t n, crsf_msg_t *out,
                 crsf_result_t *result);

#ifdef __cplusplus
}
#endif

#endif /* HELICAL_RX_CRSF_H */
