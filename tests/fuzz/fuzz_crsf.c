/*
 * libFuzzer target: arbitrary bytes into the CRSF decoder (src/protocols/rx_crsf.c),
 * through frame_fuzz.h (the checks every frame decoder gets; the smallest
 * frame is 4 bytes). Here also: every decoded channel in 880..2159 us and the
 * mapping of its ticks, link_lost consistent, no end byte to be bad. And a
 * valid RC_CHANNELS_PACKED frame made from the input by the independent
 * encoder of rc_ref_frames.h (either sync byte) decodes, at its last byte, to
 * exactly its channels; with one of its bytes after the sync changed it
 * never decodes to those channels unnoticed (the CRC, the length or the
 * type refuses it, or the channels differ).
 */
#include "frame_fuzz.h"
#include "helical/protocols/rx_crsf.h"
#include "rc_ref_frames.h"

static void check_msg(int r, const void *p)
{
    const crsf_msg_t *m = p;
    check(r == (int)CRSF_RC_CHANNELS || r == (int)CRSF_LINK_STATS);
    if (r == (int)CRSF_RC_CHANNELS) {
        for (int k = 0; k < 16; k++) {
            check(m->rc.ticks[k] <= RC_TICKS_MAX);
            check(m->rc.pulse_us[k] >= RC_PULSE_US_AT_TICKS0 &&
                  m->rc.pulse_us[k] <= RC_PULSE_US_AT_MAX);
            check(m->rc.pulse_us[k] == rc_ticks_to_pulse_us(m->rc.ticks[k]));
        }
    } else {
        check(m->link.link_lost == (m->link.uplink_lq_pct == 0u));
        check(m->link.uplink_rssi_ant1_dbm <= 0 && m->link.downlink_rssi_dbm <= 0);
    }
}

static void check_counts(const ht_frame_counts_t *c)
{
    check(c->bad_end == 0u);
}

FRAME_FUZZ_OPS(crsf, crsf_decoder_t, crsf_msg_t, crsf_result_t, 4u, CRSF_FRAME_MAX, check_msg,
               check_counts);

static void check_reference_frame(const uint8_t *data, size_t size)
{
    uint16_t ticks[16];
    uint8_t extra = 0u;
    ref_channels_from(data, size, ticks, &extra);
    uint8_t f[26];
    ref_crsf_rc_frame(ticks, ((extra & 1u) != 0u) ? 0xEEu : 0xC8u, f);
    crsf_decoder_t d;
    crsf_init(&d);
    crsf_msg_t out;
    memset(&out, 0, sizeof out);
    for (unsigned i = 0u; i < 26u; ++i) {
        const crsf_result_t r = crsf_push(&d, f[i], &out);
        check(r == ((i == 25u) ? CRSF_RC_CHANNELS : CRSF_NONE));
    }
    for (unsigned k = 0u; k < 16u; ++k) {
        check(out.rc.ticks[k] == ticks[k]);
        check(out.rc.pulse_us[k] == ref_pulse_us(ticks[k]));
    }
    check(d.counts.frames_ok == 1u && d.counts.bad_checksum == 0u);
    /* one byte changed (not the sync: another sync is another frame's start) */
    const unsigned at = 1u + (unsigned)((extra >> 1) % 25u);
    const uint8_t flip = (uint8_t)(1u << ((extra >> 5) & 7u));
    f[at] = (uint8_t)(f[at] ^ flip);
    crsf_init(&d);
    for (unsigned i = 0u; i < 26u; ++i) {
        crsf_msg_t bad;
        memset(&bad, 0, sizeof bad);
        if (crsf_push(&d, f[i], &bad) == CRSF_RC_CHANNELS) {
            /* a single-bit error: CRC-8 detects every one, so never decoded */
            check(0);
        }
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    check_reference_frame(data, size);
    return frame_fuzz_run(&crsf_fuzz_ops, data, size);
}
