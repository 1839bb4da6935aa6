/*
 * libFuzzer target: arbitrary bytes into the UBX decoder (src/ubx.c).
 * Checks at every byte: the byte accounting of frame_counts.h (every byte
 * fed is in exactly one counter or the window), the window bound, at most
 * one well-formed frame per 8 bytes (the smallest frame);
 * and that feeding the same bytes in chunks (sizes taken from the input)
 * through ubx_feed gives the same results at the same bytes, the same
 * messages and the same counters as ubx_push one byte at a time.
 * ASan and UBSan (scripts/fuzz.sh) catch any access out of bounds.
 */
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "helical/ubx.h"

static void check(int ok)
{
    if (!ok) {
        abort();
    }
}

static uint64_t accounted(const ht_frame_counts_t *c, unsigned held)
{
    return (uint64_t)c->frame_bytes + c->bad_length + c->bad_checksum + c->bad_end + c->truncated +
           c->discarded_bytes + held;
}

/* A decoded message: a known kind, gnss_fix_ok consistent with flags. */
static void check_msg(ubx_result_t r, const ubx_msg_t *m)
{
    check(r == UBX_NAV_PVT || r == UBX_ACK_ACK || r == UBX_ACK_NAK);
    if (r == UBX_NAV_PVT) {
        check(m->pvt.gnss_fix_ok == ((m->pvt.flags & 1u) != 0u));
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size > 100000) {
        return 0;
    }
    /* pass 1: chunked, recording where each message was decoded */
    size_t cap = size / 8u + 1u;
    size_t *at = malloc(cap * sizeof *at);
    ubx_result_t *res = malloc(cap * sizeof *res);
    ubx_msg_t *msg = malloc(cap * sizeof *msg);
    check(at != NULL && res != NULL && msg != NULL);
    ubx_decoder_t b;
    ubx_msg_t m;
    memset(&m, 0, sizeof m);
    ubx_init(&b);
    size_t nb = 0, pos = 0, ci = 0;
    while (pos < size) {
        size_t chunk = 1u + (size_t)(data[ci % size] % 23u);
        ci++;
        if (chunk > size - pos) {
            chunk = size - pos;
        }
        ubx_result_t r;
        size_t used = ubx_feed(&b, &data[pos], chunk, &m, &r);
        check(used >= 1u && used <= chunk);
        pos += used;
        if (r != UBX_NONE) {
            check(nb < cap);
            at[nb] = pos - 1u;
            res[nb] = r;
            msg[nb] = m;
            nb++;
        } else {
            check(used == chunk);
        }
    }

    /* pass 2: byte at a time, checked at every byte and against pass 1 */
    ubx_decoder_t a;
    ubx_msg_t ma;
    memset(&ma, 0, sizeof ma);
    ubx_init(&a);
    size_t na = 0;
    for (size_t i = 0; i < size; i++) {
        ubx_result_t r = ubx_push(&a, data[i], &ma);
        check(a.held <= UBX_FRAME_MAX);
        check(accounted(&a.counts, a.held) == i + 1u);
        uint32_t frames = a.counts.frames_ok + a.counts.unknown_type + a.counts.wrong_length;
        check((uint64_t)frames * 8u <= a.counts.frame_bytes);
        check(a.counts.frames_ok <= frames);
        check(a.counts.bad_end == 0u);
        if (r != UBX_NONE) {
            check_msg(r, &ma);
            check(na < nb && at[na] == i && res[na] == r);
            check(memcmp(&msg[na], &ma, sizeof ma) == 0);
            na++;
        }
    }
    check(na == nb);
    check(memcmp(&a.counts, &b.counts, sizeof a.counts) == 0 && a.held == b.held);
    free(at);
    free(res);
    free(msg);
    return 0;
}
