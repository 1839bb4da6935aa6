/*
 * rx_crsf.c - CRSF frame decoder: RC channels and link statistics. See
 * rx_crsf.h.
 */
#include "helical/protocols/rx_crsf.h"

#include "protocols/frame_scan.h"

uint8_t crsf_crc8(const uint8_t *data, size_t n)
{
    /* Bitwise rather than a 256-byte table: a frame is at most 63 bytes of
     * CRC, and flash is the scarcer resource on the smallest boards. */
    uint8_t c = 0u;
    for (size_t i = 0u; i < n; i++) {
        c ^= data[i];
        for (unsigned bit = 0u; bit < 8u; bit++) {
            if ((c & 0x80u) != 0u) {
                c = (uint8_t)((uint8_t)(c << 1u) ^ 0xD5u);
            } else {
                c = (uint8_t)(c << 1u);
            }
        }
    }
    return c;
}

static fs_cand_t crsf_classify(const uint8_t *w, size_t n, size_t *size)
{
    if (w[0] != CRSF_SYNC_FC && w[0] != CRSF_SYNC_TX_MODULE) {
        return FS_NONE;
    }
    if (n < 2u) {
        return FS_OPEN;
    }
    if (w[1] < CRSF_LEN_MIN || w[1] > CRSF_LEN_MAX) {
        return FS_BAD_LENGTH;
    }
    *size = (size_t)w[1] + 2u;
    return (n < *size) ? FS_OPEN : FS_ENDED;
}

static bool crsf_check(const uint8_t *f, size_t size)
{
    /* type .. last payload byte; the CRC is the frame's last byte */
    return crsf_crc8(&f[2], size - 3u) == f[size - 1u];
}

/* RC channels or link statistics of their lengths (decode_frame's) */
static bool crsf_decodes(const uint8_t *f, size_t size)
{
    const size_t payload_len = size - 4u;
    return ((f[2] == CRSF_TYPE_RC_CHANNELS) && (payload_len == RC_PACKED_BYTES)) ||
           ((f[2] == CRSF_TYPE_LINK_STATS) && (payload_len == CRSF_LINK_STATS_BYTES));
}

static const fs_proto_t crsf_proto = {crsf_classify, crsf_check, false, crsf_decodes};

void crsf_init(crsf_decoder_t *d)
{
    if (d != NULL) {
        crsf_decoder_t zero = {0};
        *d = zero;
    }
}

/* The wire's RSSI byte is minus the RSSI in dBm. */
static int16_t rssi_dbm(uint8_t neg_dbm)
{
    return (int16_t)(-(int16_t)neg_dbm);
}

static void decode_link_stats(const uint8_t *p, crsf_link_stats_t *out)
{
    out->uplink_rssi_ant1_dbm = rssi_dbm(p[0]);
    out->uplink_rssi_ant2_dbm = rssi_dbm(p[1]);
    out->uplink_lq_pct = p[2];
    out->uplink_snr_db = (int8_t)p[3];
    out->active_antenna = p[4];
    out->rf_mode = p[5];
    out->uplink_tx_power_index = p[6];
    out->downlink_rssi_dbm = rssi_dbm(p[7]);
    out->downlink_lq_pct = p[8];
    out->downlink_snr_db = (int8_t)p[9];
    out->link_lost = (p[2] == 0u);
}

static void decode_channels(const uint8_t *p, crsf_channels_t *out)
{
    rc_unpack_11bit(p, out->ticks);
    for (unsigned k = 0u; k < RC_CHANNELS; k++) {
        out->pulse_us[k] = rc_ticks_to_pulse_us(out->ticks[k]);
    }
}

/* A frame with a good CRC: decode it if its type and length are known. */
static crsf_result_t decode_frame(crsf_decoder_t *d, const uint8_t *f, size_t size, crsf_msg_t *out)
{
    const uint8_t type = f[2];
    const size_t payload_len = size - 4u;
    crsf_result_t r = CRSF_NONE;
    if (type == CRSF_TYPE_RC_CHANNELS) {
        if (payload_len == RC_PACKED_BYTES) {
            decode_channels(&f[3], &out->rc);
            r = CRSF_RC_CHANNELS;
        } else {
            fs_count(&d->counts.wrong_length);
        }
    } else if (type == CRSF_TYPE_LINK_STATS) {
        if (payload_len == CRSF_LINK_STATS_BYTES) {
            decode_link_stats(&f[3], &out->link);
            r = CRSF_LINK_STATS;
        } else {
            fs_count(&d->counts.wrong_length);
        }
    } else {
        fs_count(&d->counts.unknown_type);
    }
    if (r != CRSF_NONE) {
        fs_count(&d->counts.frames_ok);
    }
    return r;
}

crsf_result_t crsf_push(crsf_decoder_t *d, uint8_t byte, crsf_msg_t *out)
{
    if (d == NULL || out == NULL) {
        return CRSF_ERR_NULL;
    }
    size_t start = 0u;
    size_t size =
        fs_push(&crsf_proto, d->window, CRSF_FRAME_MAX, &d->held, &d->counts, byte, &start);
    if (size == 0u) {
        return CRSF_NONE;
    }
    return decode_frame(d, &d->window[start], size, out);
}

size_t crsf_feed(crsf_decoder_t *d, const uint8_t *bytes, size_t n, crsf_msg_t *out,
                 crsf_result_t *result)
{
    if (result == NULL) {
        return 0u;
    }
    if (d == NULL || out == NULL || (bytes == NULL && n != 0u)) {
        *result = CRSF_ERR_NULL;
        return 0u;
    }
    *result = CRSF_NONE;
    size_t i = 0u;
    while (i < n && *result == CRSF_NONE) {
        *result = crsf_push(d, bytes[i], out);
        i++;
    }
    return i;
}
