/*
 * frame_fuzz.h - the libFuzzer body the frame decoders share (fuzz_ubx.c,
 * fuzz_crsf.c, fuzz_sbus.c): each target describes its decoder in a
 * frame_fuzz_ops_t and calls frame_fuzz_run from LLVMFuzzerTestOneInput.
 *
 * Checked at every byte: the byte accounting of frame_counts.h (every byte
 * fed is in exactly one counter or the window), the window bound, at most one
 * well-formed frame per smallest frame, the target's own message and counter
 * invariants; and that feeding the same bytes in chunks (sizes taken from the
 * input) through feed gives the same results at the same bytes, the same
 * messages and the same counters as push one byte at a time. ASan and UBSan
 * (scripts/fuzz.sh) catch any access out of bounds.
 */
#ifndef FRAME_FUZZ_H
#define FRAME_FUZZ_H

#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "helical/protocols/frame_counts.h"

static void check(int ok)
{
    if (!ok) {
        abort();
    }
}

/* One decoder, through its own functions; results as int (0 = none). */
typedef struct {
    size_t decoder_size, msg_size;
    size_t min_frame; /* bytes of the smallest well-formed frame */
    unsigned held_max;
    void (*init)(void *d);
    int (*push)(void *d, uint8_t byte, void *msg);
    size_t (*feed)(void *d, const uint8_t *p, size_t n, void *msg, int *result);
    const ht_frame_counts_t *(*counts)(const void *d);
    unsigned (*held)(const void *d);
    void (*check_msg)(int result, const void *msg);   /* a decoded message */
    void (*check_counts)(const ht_frame_counts_t *c); /* may be NULL */
} frame_fuzz_ops_t;

static uint64_t frame_fuzz_accounted(const ht_frame_counts_t *c, unsigned held)
{
    return (uint64_t)c->frame_bytes + c->bad_length + c->bad_checksum + c->bad_end + c->truncated +
           c->discarded_bytes + held;
}

static int frame_fuzz_run(const frame_fuzz_ops_t *o, const uint8_t *data, size_t size)
{
    if (size > 100000) {
        return 0;
    }
    /* pass 1: chunked, recording where each message was decoded */
    const size_t cap = size / o->min_frame + 1u;
    size_t *at = malloc(cap * sizeof *at);
    int *res = malloc(cap * sizeof *res);
    uint8_t *msg = calloc(cap, o->msg_size);
    void *b = calloc(1u, o->decoder_size);
    void *a = calloc(1u, o->decoder_size);
    uint8_t *m = calloc(1u, o->msg_size);
    uint8_t *ma = calloc(1u, o->msg_size);
    check(at != NULL && res != NULL && msg != NULL && b != NULL && a != NULL && m != NULL &&
          ma != NULL);
    o->init(b);
    size_t nb = 0, pos = 0, ci = 0;
    while (pos < size) {
        size_t chunk = 1u + (size_t)(data[ci % size] % 23u);
        ci++;
        if (chunk > size - pos) {
            chunk = size - pos;
        }
        int r;
        const size_t used = o->feed(b, &data[pos], chunk, m, &r);
        check(used >= 1u && used <= chunk);
        pos += used;
        if (r != 0) {
            check(nb < cap);
            at[nb] = pos - 1u;
            res[nb] = r;
            memcpy(&msg[nb * o->msg_size], m, o->msg_size);
            nb++;
        } else {
            check(used == chunk);
        }
    }
    /* pass 2: byte at a time, checked at every byte and against pass 1 */
    o->init(a);
    size_t na = 0;
    for (size_t i = 0; i < size; i++) {
        const int r = o->push(a, data[i], ma);
        const ht_frame_counts_t *c = o->counts(a);
        check(o->held(a) <= o->held_max);
        check(frame_fuzz_accounted(c, o->held(a)) == i + 1u);
        const uint32_t frames = c->frames_ok + c->unknown_type + c->wrong_length;
        check((uint64_t)frames * o->min_frame <= c->frame_bytes);
        check(c->frames_ok <= frames);
        if (o->check_counts != NULL) {
            o->check_counts(c);
        }
        if (r != 0) {
            o->check_msg(r, ma);
            check(na < nb && at[na] == i && res[na] == r);
            check(memcmp(&msg[na * o->msg_size], ma, o->msg_size) == 0);
            na++;
        }
    }
    check(na == nb);
    check(memcmp(o->counts(a), o->counts(b), sizeof(ht_frame_counts_t)) == 0 &&
          o->held(a) == o->held(b));
    free(at);
    free(res);
    free(msg);
    free(a);
    free(b);
    free(m);
    free(ma);
    return 0;
}

/* The void-pointer adapters of one decoder (prefix_init, _push, _feed; a
 * decoder struct with held and counts) and its frame_fuzz_ops_t. */
#define FRAME_FUZZ_OPS(pfx, DEC, MSG, RES, MIN_FRAME, HELD_MAX, CHECK_MSG, CHECK_COUNTS)           \
    static void pfx##_init_v(void *d)                                                              \
    {                                                                                              \
        pfx##_init((DEC *)d);                                                                      \
    }                                                                                              \
    static int pfx##_push_v(void *d, uint8_t byte, void *m)                                        \
    {                                                                                              \
        return (int)pfx##_push((DEC *)d, byte, (MSG *)m);                                          \
    }                                                                                              \
    static size_t pfx##_feed_v(void *d, const uint8_t *p, size_t n, void *m, int *r)               \
    {                                                                                              \
        RES x;                                                                                     \
        const size_t used = pfx##_feed((DEC *)d, p, n, (MSG *)m, &x);                              \
        *r = (int)x;                                                                               \
        return used;                                                                               \
    }                                                                                              \
    static const ht_frame_counts_t *pfx##_counts_v(const void *d)                                  \
    {                                                                                              \
        return &((const DEC *)d)->counts;                                                          \
    }                                                                                              \
    static unsigned pfx##_held_v(const void *d)                                                    \
    {                                                                                              \
        return ((const DEC *)d)->held;                                                             \
    }                                                                                              \
    static const frame_fuzz_ops_t pfx##_fuzz_ops = {                                               \
        sizeof(DEC),  sizeof(MSG),    (MIN_FRAME),  (HELD_MAX),  pfx##_init_v,  pfx##_push_v,      \
        pfx##_feed_v, pfx##_counts_v, pfx##_held_v, (CHECK_MSG), (CHECK_COUNTS)}

#endif /* FRAME_FUZZ_H */
