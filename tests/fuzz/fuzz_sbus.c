/*
 * libFuzzer target: arbitrary bytes into the SBUS decoder (src/protocols/rx_sbus.c),
 * through frame_fuzz.h (the checks every frame decoder gets; every frame is
 * 25 bytes). Here also: every decoded channel in 880..2159 us and the mapping
 * of its ticks, failsafe frames marked unusable, one of the five end bytes;
 * no checksum, length or truncation counts (SBUS has none of them).
 */
#include "frame_fuzz.h"
#include "helical/protocols/rx_sbus.h"

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

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    return frame_fuzz_run(&sbus_fuzz_ops, data, size);
}
