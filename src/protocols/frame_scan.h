/*
 * frame_scan.h - the resynchronising frame search that the UBX, CRSF and
 * SBUS decoders share (internal to the library).
 *
 * The decoder keeps a window of at most one frame's worth of bytes, starting
 * at the start byte of the oldest candidate frame still possible. Every start
 * byte held is a candidate: the first candidate to end with a good check, at
 * the byte that ends it, is the frame. So a bad frame (a wrong length, a bad
 * checksum, a bad end byte, a frame cut short) costs that frame only: a good
 * frame that starts anywhere after the bad frame's start byte, a false start
 * byte inside a frame included, is found at its own last byte, never later,
 * unless it is a frame the decoder would not decode (fs_proto_t.decodes) and
 * an earlier candidate is still open: then the earlier one goes on.
 * (The same rule as the HIL link's decoder, src/protocols/hil_frame.c.)
 *
 * A protocol describes its frames with two functions; the window and its
 * length live in the decoder's state, which the caller owns.
 */
#ifndef HELICAL_FRAME_SCAN_H
#define HELICAL_FRAME_SCAN_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "helical/protocols/frame_counts.h"

typedef enum {
    FS_NONE,       /* w[0] (or a following sync byte) starts no frame */
    FS_BAD_LENGTH, /* the declared length is one the protocol does not allow */
    FS_OPEN,       /* a possible frame, not complete yet */
    FS_ENDED       /* complete: its size is known and held */
} fs_cand_t;

typedef struct {
    /* The candidate frame that starts at w[0], of which n >= 1 bytes are
     * held. Sets *size to its total size when FS_ENDED. Called with n == 1 to
     * ask whether a byte can start a frame at all (FS_NONE if not). */
    fs_cand_t (*classify)(const uint8_t *w, size_t n, size_t *size);
    /* The complete frame f[0..size) passes its checksum or end-byte test. */
    bool (*check)(const uint8_t *f, size_t size);
    /* A failed check is counted as bad_end (SBUS) rather than bad_checksum. */
    bool check_is_end_byte;
    /* May be NULL (every checked frame decodes). Else: the checked frame
     * f[0..size) is one the decoder decodes (a known type of the right
     * length). A checked frame that is not, starting inside an earlier
     * candidate still open, does not end that candidate: with an 8-bit CRC,
     * one candidate in 256 inside a frame's payload checks by chance (a
     * CRSF channel byte 0xC8, a length 4 and three zeros: the CRC of zeros
     * is 0), and it must not cost the real frame around it. */
    bool (*decodes)(const uint8_t *f, size_t size);
} fs_proto_t;

/*
 * Take one byte into the window w (capacity cap, the protocol's largest
 * frame; *held bytes in it). Returns the size of the frame this byte
 * completed with a good check, which is then at w[*start .. *start + size)
 * until the next call (and counted in frame_bytes), or 0. Every byte is
 * counted as in frame_counts.h.
 */
size_t fs_push(const fs_proto_t *p, uint8_t *w, size_t cap, uint8_t *held, ht_frame_counts_t *c,
               uint8_t byte, size_t *start);

/* Forget the held bytes (the candidate at w[0] counted as truncated, the
 * rest as discarded_bytes): for a line gap that no frame spans. */
void fs_drop_held(uint8_t *held, ht_frame_counts_t *c);

/* Add one to a counter unless it is at UINT32_MAX. */
void fs_count(uint32_t *counter);

#endif /* HELICAL_FRAME_SCAN_H */
