/*
 * libFuzzer target: arbitrary bytes into the CRSF decoder (src/protocols/rx_crsf.c),
 * through frame_fuzz.h (the checks every frame decoder gets; the smallest
 * frame is 4 bytes). Here also: every decoded channel in 880..2159 us and the
 * mapping of its ticks, link_lost consistent, no end byte to be bad.
 */
#include "frame_fuzz.h"
#include "helical/protocols/rx_crsf.h"

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

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    return frame_fuzz_run(&crsf_fuzz_ops, data, size);
}
