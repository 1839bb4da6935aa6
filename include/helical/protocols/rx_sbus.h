/*
 * rx_sbus.h - decoder of SBUS receiver frames (Futaba SBUS, and the
 * channel frames of SBUS2), from the bytes a UART delivers (100 000 baud,
 * 8 data bits, even parity, 2 stop bits, inverted line: the UART and the
 * driver deal with all that; this decoder sees bytes only).
 *
 * A frame is 25 bytes:
 *
 *   0x0F | 22 bytes: 16 channels x 11 bits (rc_channels.h) | flags | end
 *
 *   flags: bit 0 digital channel 17, bit 1 digital channel 18,
 *          bit 2 frame lost (the receiver missed a radio frame),
 *          bit 3 failsafe (the receiver has lost the link: its channels are
 *          failsafe values, or stale), bits 4..7 unused.
 *   end:   0x00 (SBUS), or 0x04, 0x14, 0x24, 0x34 (SBUS2: the channel frame
 *          that announces telemetry slots 0-7, 8-15, 16-23, 24-31).
 *
 * SBUS has no checksum: a frame is a 0x0F, 23 bytes, and an allowed end
 * byte. The decoder searches every 0x0F it holds (frame_scan.h), so after
 * garbage, or a false 0x0F inside a frame, it finds the next frame whose
 * start and end bytes are right. A 0x0F and an allowed end byte 24 bytes
 * apart inside the data of two real frames look like a frame, too: with
 * still sticks the stream repeats every 25 bytes and the decoder could stay
 * on such a false phase. So the driver should call sbus_line_gap() when the
 * UART reports an idle line (SBUS sends a frame every 7 to 14 ms and the
 * frame's bytes back to back): frames start after a gap, and the held
 * partial frame is dropped. Then a false frame needs a false start byte at a
 * frame's first byte, which is the real one.
 *
 * Counters (frame_counts.h): bad_end for a complete frame with a wrong end
 * byte, truncated for one dropped by sbus_line_gap(), frames_ok,
 * discarded_bytes; the others stay 0. The state is the caller's
 * sbus_decoder_t; no function keeps any other state.
 */
#ifndef HELICAL_RX_SBUS_H
#define HELICAL_RX_SBUS_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "helical/protocols/frame_counts.h"
#include "helical/protocols/rc_channels.h"

#ifdef __cplusplus
extern "C" {
#endif

#define SBUS_FRAME_BYTES     25u
#define SBUS_START_BYTE      0x0Fu
#define SBUS_FLAG_CH17       0x01u
#define SBUS_FLAG_CH18       0x02u
#define SBUS_FLAG_FRAME_LOST 0x04u
#define SBUS_FLAG_FAILSAFE   0x08u

typedef enum {
    SBUS_ERR_NULL = -1, /* a NULL pointer: nothing done */
    SBUS_NONE = 0,      /* no frame completed by this byte */
    SBUS_FRAME = 1      /* a frame decoded into *out */
} sbus_result_t;

typedef struct {
    uint16_t ticks[RC_CHANNELS];    /* the 11-bit values as sent */
    uint16_t pulse_us[RC_CHANNELS]; /* rc_ticks_to_pulse_us of each */
    bool ch17, ch18;                /* the digital channels */
    bool frame_lost;                /* flags bit 2 */
    bool failsafe;                  /* flags bit 3 */
    /* false when failsafe is set: the channels are then the receiver's
     * failsafe or last values, not the pilot's, and must not be flown on */
    bool channels_usable;
    uint8_t end_byte; /* 0x00, or the SBUS2 slot group byte */
} sbus_frame_t;

typedef struct {
    uint8_t window[SBUS_FRAME_BYTES];
    uint8_t held;
    ht_frame_counts_t counts;
} sbus_decoder_t;

/* Reset the decoder (no-op on NULL). */
void sbus_init(sbus_decoder_t *d);

/*
 * Feed one byte. Returns SBUS_FRAME when it completed a frame, which is then
 * in *out (out is written only then); SBUS_NONE otherwise; SBUS_ERR_NULL
 * (and does nothing) if d or out is NULL.
 */
sbus_result_t sbus_push(sbus_decoder_t *d, uint8_t byte, sbus_frame_t *out);

/*
 * Feed up to n bytes, stopping after the byte that completes a frame.
 * Returns how many bytes were taken; *result is what sbus_push returned for
 * the last of them (SBUS_NONE when n == 0). Call again with the rest. The
 * same bytes give the same frames and counters as sbus_push one at a time.
 * With d, out or result NULL, or bytes NULL and n > 0: returns 0, and
 * *result = SBUS_ERR_NULL when result is not NULL.
 */
size_t sbus_feed(sbus_decoder_t *d, const uint8_t *bytes, size_t n, sbus_frame_t *out,
                 sbus_result_t *result);

/* The line was idle between two bytes: a frame cannot span it. Drops the
 * held bytes (counted, frame_counts.h); no-op on NULL. */
void sbus_line_gap(sbus_decoder_t *d);

#ifdef __cplusplus
}
#endif

#endif /* HELICAL_RX_SBUS_H */
