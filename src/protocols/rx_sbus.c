/*
 * rx_sbus.c - SBUS frame decoder. See rx_sbus.h.
 */
#include "helical/protocols/rx_sbus.h"

#include "protocols/frame_scan.h"

static bool sbus_end_ok(uint8_t end)
{
    /* 0x00: SBUS; 0x04, 0x14, 0x24, 0x34: SBUS2 slot groups 0..3 */
    return end == 0x00u || (end & 0xCFu) == 0x04u;
}

static fs_cand_t sbus_classify(const uint8_t *w, size_t n, size_t *size)
{
    if (w[0] != SBUS_START_BYTE) {
        return FS_NONE;
    }
    *size = SBUS_FRAME_BYTES;
    return (n < SBUS_FRAME_BYTES) ? FS_OPEN : FS_ENDED;
}

static bool sbus_check(const uint8_t *f, size_t size)
{
    return size == SBUS_FRAME_BYTES && sbus_end_ok(f[SBUS_FRAME_BYTES - 1u]);
}

static const fs_proto_t sbus_proto = {sbus_classify, sbus_check, true, NULL};

void sbus_init(sbus_decoder_t *d)
{
    if (d != NULL) {
        sbus_decoder_t zero = {0};
        *d = zero;
    }
}

static void sbus_decode(const uint8_t *f, sbus_frame_t *out)
{
    rc_unpack_11bit(&f[1], out->ticks);
    for (unsigned k = 0u; k < RC_CHANNELS; k++) {
        out->pulse_us[k] = rc_ticks_to_pulse_us(out->ticks[k]);
    }
    uint8_t flags = f[23];
    out->ch17 = (flags & SBUS_FLAG_CH17) != 0u;
    out->ch18 = (flags & SBUS_FLAG_CH18) != 0u;
    out->frame_lost = (flags & SBUS_FLAG_FRAME_LOST) != 0u;
    out->failsafe = (flags & SBUS_FLAG_FAILSAFE) != 0u;
    out->channels_usable = !out->failsafe;
    out->end_byte = f[24];
}

sbus_result_t sbus_push(sbus_decoder_t *d, uint8_t byte, sbus_frame_t *out)
{
    if (d == NULL || out == NULL) {
        return SBUS_ERR_NULL;
    }
    size_t start = 0u;
    size_t size =
        fs_push(&sbus_proto, d->window, SBUS_FRAME_BYTES, &d->held, &d->counts, byte, &start);
    if (size == 0u) {
        return SBUS_NONE;
    }
    /* Every SBUS frame that passes the scan is a channel frame. */
    sbus_decode(&d->window[start], out);
    fs_count(&d->counts.frames_ok);
    return SBUS_FRAME;
}

size_t sbus_feed(sbus_decoder_t *d, const uint8_t *bytes, size_t n, sbus_frame_t *out,
                 sbus_result_t *result)
{
    if (result == NULL) {
        return 0u;
    }
    if (d == NULL || out == NULL || (bytes == NULL && n != 0u)) {
        *result = SBUS_ERR_NULL;
        return 0u;
    }
    *result = SBUS_NONE;
    size_t i = 0u;
    while (i < n && *result == SBUS_NONE) {
        *result = sbus_push(d, bytes[i], out);
        i++;
    }
    return i;
}

void sbus_line_gap(sbus_decoder_t *d)
{
    if (d != NULL) {
        fs_drop_held(&d->held, &d->counts);
    }
}
