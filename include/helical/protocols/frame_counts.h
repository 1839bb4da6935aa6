/*
 * frame_counts.h - what a byte-stream frame decoder (UBX, CRSF, SBUS) did
 * with the bytes it was fed: one counter per reason, shared by the three
 * decoders so that a driver, a test or a fuzz target checks them alike.
 *
 * Every byte fed ends up in exactly one place:
 *
 *   fed == frame_bytes                  (bytes of frames with a good check)
 *        + bad_length + bad_checksum + bad_end + truncated
 *                                       (one byte each: the start byte of a
 *                                        dropped candidate frame)
 *        + discarded_bytes              (bytes that start no frame)
 *        + held                         (the decoder's window, not decided yet)
 *
 * and every frame with a good check is exactly one of frames_ok,
 * unknown_type or wrong_length. The unit tests and the fuzz targets check
 * both identities. A counter that a protocol cannot produce stays 0 (SBUS
 * has no checksum, UBX and CRSF have no end byte). Counters saturate at
 * UINT32_MAX (more than 2^32 bytes: days of a 420 kbaud link), so the sums
 * hold until then.
 */
#ifndef HELICAL_FRAME_COUNTS_H
#define HELICAL_FRAME_COUNTS_H

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef struct {
    uint32_t frames_ok;       /* good check, a type decoded, delivered to the caller */
    uint32_t unknown_type;    /* good check, a type (class/id) the decoder does not decode */
    uint32_t wrong_length;    /* good check, a decoded type with the wrong payload length */
    uint32_t frame_bytes;     /* all bytes of the frames above */
    uint32_t bad_length;      /* a declared length the protocol does not allow */
    uint32_t bad_checksum;    /* a complete frame whose checksum / CRC does not match */
    uint32_t bad_end;         /* a complete frame whose end byte is not one allowed (SBUS) */
    uint32_t truncated;       /* a frame cut short: a good frame started inside it */
    uint32_t discarded_bytes; /* bytes that are no frame's start and in no good frame */
} ht_frame_counts_t;

#ifdef __cplusplus
}
#endif

#endif /* HELICAL_FRAME_COUNTS_H */
