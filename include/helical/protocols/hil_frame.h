/*
 * hil_frame.h - the framing of the hardware/processor-in-the-loop serial link.
 *
 * A frame on the wire:
 *
 *   0xA5 0x5A | len | id | payload (len bytes, 0..HIL_PAYLOAD_MAX) | crc_lo crc_hi
 *
 * crc is CRC-16/CCITT-FALSE (polynomial 0x1021, initial value 0xFFFF, no
 * reflection, no final xor) over len, id and the payload. Multi-byte fields
 * inside payloads are little-endian (the hil_put and hil_get functions).
 *
 * The decoder takes one byte at a time (from a UART interrupt or a socket
 * read) and keeps at most one frame's worth of bytes. It never skips a byte
 * it has not looked at as a possible frame start: every 0xA5 0x5A in the
 * bytes it holds is a candidate frame, and the first candidate to end with a
 * good CRC, at the byte that ends it, is the frame. So a frame that fails
 * (a bad CRC, a length over the maximum, a length byte corrupted to a larger
 * value, a frame cut short) costs that frame only: a good frame starting
 * anywhere after the bad frame's sync byte is delivered at its own last byte,
 * never later. The price: a whole valid frame inside another frame's payload
 * ends first and is taken (the outer frame then counts as cut short); a
 * candidate inside a good frame that would end after it is dropped with it.
 * No HIL message carries frames in its payload.
 * Frames with a bad CRC, a length over the maximum or an id the caller does
 * not know are counted and dropped: the decoder never hands on a frame that
 * it has not checked (docs/hil-protocol.md, "The decoder").
 * All state is in the caller's hil_decoder_t.
 */
#ifndef HELICAL_HIL_FRAME_H
#define HELICAL_HIL_FRAME_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#define HIL_SYNC1       0xA5u
#define HIL_SYNC2       0x5Au
#define HIL_PAYLOAD_MAX 64u
#define HIL_OVERHEAD    6u /* sync x2, len, id, crc x2 */
#define HIL_FRAME_MAX   (HIL_PAYLOAD_MAX + HIL_OVERHEAD)

/* CRC-16/CCITT-FALSE of n bytes, continuing from crc (start with 0xFFFF).
 * The check value of "123456789" is 0x29B1. */
uint16_t hil_crc16(uint16_t crc, const uint8_t *data, size_t n);

/*
 * Write one frame into out (capacity out_size). Returns the frame's length,
 * or 0 (writing nothing) when len > HIL_PAYLOAD_MAX, out is too small, or a
 * pointer is NULL while its length is not zero.
 */
size_t hil_encode(uint8_t id, const uint8_t *payload, uint8_t len, uint8_t *out, size_t out_size);

/*
 * Counters of what the decoder dropped. They saturate at UINT16_MAX. Every
 * byte fed ends up in exactly one place: a well-formed frame (frames_ok, or
 * unknown_id: the frame's len + 6 bytes), the sync byte of a dropped frame
 * (bad_crc or bad_length: one byte each), skipped_bytes, or the bytes the
 * decoder still holds (hil_decoder_t.held). test_hil_resync checks this sum.
 */
typedef struct {
    uint16_t frames_ok;
    uint16_t bad_crc;       /* a bad CRC, or cut short by a good frame starting inside it */
    uint16_t bad_length;    /* a length byte over HIL_PAYLOAD_MAX */
    uint16_t unknown_id;    /* a good CRC, but an id or length the table does not accept */
    uint16_t skipped_bytes; /* bytes that start no frame and lie in no good one */
} hil_stats_t;

/* Which ids the caller accepts, and the payload length each must have
 * (0xFF: any length). Indexed by id; ids beyond the table are unknown. */
typedef struct {
    const uint8_t *expected_len;
    uint8_t id_count;
} hil_msg_table_t;

typedef struct {
    hil_msg_table_t table;
    uint8_t id, len;                  /* the frame last delivered */
    uint8_t payload[HIL_PAYLOAD_MAX]; /* its payload (valid until the next push) */
    /* The bytes from the sync byte of the oldest frame still possible on;
     * held <= HIL_FRAME_MAX (that frame is at most HIL_FRAME_MAX long). */
    uint8_t held;
    uint8_t window[HIL_FRAME_MAX];
    hil_stats_t stats;
} hil_decoder_t;

/* Reset the decoder; table may have id_count 0 (every id unknown). */
void hil_decoder_init(hil_decoder_t *d, hil_msg_table_t table);

/*
 * Feed one byte. Returns 1 when this byte completed a good frame of a known
 * id and the right length: its id and payload are then in d->id, d->len and
 * d->payload until the next call. Returns 0 otherwise.
 *
 * Work: a scan of the held bytes (at most HIL_FRAME_MAX compares) and one CRC
 * per candidate frame ending at this byte. Each candidate is checked once, at
 * its end, and candidates start at least 3 bytes apart, so the CRC work is at
 * most (HIL_PAYLOAD_MAX + 2) / 3 = 22 bytes per byte fed, amortised; a single
 * byte can end up to 22 candidates at once in a hostile stream.
 */
int hil_decoder_push(hil_decoder_t *d, uint8_t byte);

/* Little-endian field access for payloads (no alignment needed). */
void hil_put_u16(uint8_t *p, uint16_t v);
void hil_put_i16(uint8_t *p, int16_t v);
void hil_put_i32(uint8_t *p, int32_t v);
uint16_t hil_get_u16(const uint8_t *p);
int16_t hil_get_i16(const uint8_t *p);
int32_t hil_get_i32(const uint8_t *p);

#ifdef __cplusplus
}
#endif

#endif /* HELICAL_HIL_FRAME_H */
