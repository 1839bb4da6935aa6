/*
 * libFuzzer target: arbitrary bytes into the UBX decoder (src/protocols/ubx.c), through
 * frame_fuzz.h (the checks every frame decoder gets; the smallest frame is
 * 8 bytes). Here also: a known message kind, gnss_fix_ok consistent with the
 * NAV-PVT flags, no end byte to be bad.
 */
#include "frame_fuzz.h"
#include "helical/protocols/ubx.h"

static void check_msg(int r, const void *p)
{
    const ubx_msg_t *m = p;
    check(r == (int)UBX_NAV_PVT || r == (int)UBX_ACK_ACK || r == (int)UBX_ACK_NAK);
    if (r == (int)UBX_NAV_PVT) {
        check(m->pvt.gnss_fix_ok == ((m->pvt.flags & 1u) != 0u));
    }
}

static void check_counts(const ht_frame_counts_t *c)
{
    check(c->bad_end == 0u);
}

FRAME_FUZZ_OPS(ubx, ubx_decoder_t, ubx_msg_t, ubx_result_t, 8u, UBX_FRAME_MAX, check_msg,
               check_counts);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    return frame_fuzz_run(&ubx_fuzz_ops, data, size);
}
