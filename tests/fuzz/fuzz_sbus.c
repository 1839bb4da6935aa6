/*
 * libFuzzer target: arbitrary bytes into the SBUS decoder (src/protocols/rx_sbus.c),
 * through frame_fuzz.h (the checks every frame decoder gets; every frame is
 * 25 bytes). Here also: every decoded channel in 880..2159 us and the mapping
 * of its ticks, failsafe frames marked unusable, one of the five end bytes;
 * no checksum, length or truncation counts (SBUS has none of them). And a
 * valid frame made from the input by the independent encoder of
 * rc_ref_frames.h decodes, at its last byte, to exactly its channels, flags
 * and end byte.
 */
#include "frame_fuzz.h"
#include "helical/protocols/rx_sbus.h"
#include "rc_ref_frames.h"

static void check_msg(int r, const void *p)
{
    const sbus_frame_t *f = p;
    check(r == (int)SBUS_FRAME);
    for (int k = 0; k < 16; k++) {
        check(f->ticks[k] <= RC_TICKS_MAX);
        check(f->pulse_us[k] >= RC_PULSE_US_AT_TICKS0 && f->pulse_us[k] <= RC_PULSE_US_AT_MAX);
        check(f->pulse_us[k] == rc_ticks_to_pulse_us(f->ticks[k]));
    }
    check(f->channels_usable == !f->failsafe);
    check(f->end_byte == 0x00u || f->end_byte == 0x04u || f->end_byte == 0x14u ||
          f->end_byte == 0x24u || f->end_byte == 0x34u);
}

static void check_counts(const ht_frame_counts_t *c)
{
    check(c->bad_checksum == 0u && c->bad_length == 0u && c->truncated == 0u);
    check(c->frames_ok * 25u == c->frame_bytes);
}

FRAME_FUZZ_OPS(sbus, sbus_decoder_t, sbus_frame_t, sbus_result_t, 25u, SBUS_FRAME_BYTES, check_msg,
               check_counts);

static void check_reference_frame(const uint8_t *data, size_t size)
{
    static const uint8_t ends[5] = {0x00u, 0x04u, 0x14u, 0x24u, 0x34u};
    uint16_t ticks[16];
    uint8_t extra = 0u;
    ref_channels_from(data, size, ticks, &extra);
    const uint8_t flags = (uint8_t)(extra & 0x0Fu);
    const uint8_t end = ends[(extra >> 4) % 5u];
    uint8_t f[25];
    ref_sbus_frame(ticks, flags, end, f);
    sbus_decoder_t d;
    sbus_init(&d);
    sbus_frame_t out;
    memset(&out, 0, sizeof out);
    for (unsigned i = 0u; i < 25u; ++i) {
        const sbus_result_t r = sbus_push(&d, f[i], &out);
        check(r == ((i == 24u) ? SBUS_FRAME : SBUS_NONE));
    }
    for (unsigned k = 0u; k < 16u; ++k) {
        check(out.ticks[k] == ticks[k]);
        check(out.pulse_us[k] == ref_pulse_us(ticks[k]));
    }
    check(out.ch17 == ((flags & 0x01u) != 0u) && out.ch18 == ((flags & 0x02u) != 0u));
    check(out.frame_lost == ((flags & 0x04u) != 0u) && out.failsafe == ((flags & 0x08u) != 0u));
    check(out.channels_usable == !out.failsafe && out.end_byte == end);
    check(d.counts.frames_ok == 1u && d.counts.frame_bytes == 25u);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    check_reference_frame(data, size);
    return frame_fuzz_run(&sbus_fuzz_ops, data, size);
}
