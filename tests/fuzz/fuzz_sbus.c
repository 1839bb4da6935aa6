/*
 * libFuzzer target: arbitrary bytes into the SBUS decoder (src/rx_sbus.c).
 * Checks at every byte: the byte accounting of frame_counts.h (every byte
 * fed is in exactly one counter or the window), the window bound, at most
 * one well-formed frame per 25 bytes (the smallest frame), every decoded channel in 880..2159 us
 * and the mapping of its ticks, failsafe frames marked unusable; and that feeding the same bytes in
 * chunks (sizes taken from the input) through sbus_feed gives the same results at the same bytes,
 * the same messages and the same counters as sbus_push one byte at a time. ASan and UBSan
 * (scripts/fuzz.sh) catch any access out of bounds.
 */
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "helical/rx_sbus.h"

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

/* A decoded frame: channels in range and mapped, flags consistent. */
static void check_msg(sbus_result_t r, const sbus_frame_t *f)
{
    check(r == SBUS_FRAME);
    for (int k = 0; k < 16; k++) {
        check(f->ticks[k] <= RC_TICKS_MAX);
        check(f->pulse_us[k] >= RC_PULSE_US_AT_TICKS0 && f->pulse_us[k] <= RC_PULSE_US_AT_MAX);
        check(f->pulse_us[k] == rc_ticks_to_pulse_us(f->ticks[k]));
    }
    check(f->channels_usable == !f->failsafe);
    check(f->end_byte == 0x00u || f->end_byte == 0x04u || f->end_byte == 0x14u ||
          f->end_byte == 0x24u || f->end_byte == 0x34u);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size > 100000) {
        return 0;
    }
    /* pass 1: chunked, recording where each message was decoded */
    size_t cap = size / 25u + 1u;
    size_t *at = malloc(cap * sizeof *at);
    sbus_result_t *res = malloc(cap * sizeof *res);
    sbus_frame_t *msg = malloc(cap * sizeof *msg);
    check(at != NULL && res != NULL && msg != NULL);
    sbus_decoder_t b;
    sbus_frame_t m;
    memset(&m, 0, sizeof m);
    sbus_init(&b);
    size_t nb = 0, pos = 0, ci = 0;
    while (pos < size) {
        size_t chunk = 1u + (size_t)(data[ci % size] % 23u);
        ci++;
        if (chunk > size - pos) {
            chunk = size - pos;
        }
        sbus_result_t r;
        size_t used = sbus_feed(&b, &data[pos], chunk, &m, &r);
        check(used >= 1u && used <= chunk);
        pos += used;
        if (r != SBUS_NONE) {
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
    sbus_decoder_t a;
    sbus_frame_t ma;
    memset(&ma, 0, sizeof ma);
    sbus_init(&a);
    size_t na = 0;
    for (size_t i = 0; i < size; i++) {
        sbus_result_t r = sbus_push(&a, data[i], &ma);
        check(a.held <= SBUS_FRAME_BYTES);
        check(accounted(&a.counts, a.held) == i + 1u);
        uint32_t frames = a.counts.frames_ok + a.counts.unknown_type + a.counts.wrong_length;
        check((uint64_t)frames * 25u <= a.counts.frame_bytes);
        check(a.counts.frames_ok <= frames);
        check(a.counts.bad_checksum == 0u && a.counts.bad_length == 0u && a.counts.truncated == 0u);
        check(a.counts.frames_ok * 25u == a.counts.frame_bytes);
        if (r != SBUS_NONE) {
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
