/*
 * hil_frame.c - the HIL link's framing: encoder, byte-wise decoder with
 * resynchronisation, CRC-16/CCITT-FALSE. See hil_frame.h.
 */
#include "helical/protocols/hil_frame.h"

uint16_t hil_crc16(uint16_t crc, const uint8_t *data, size_t n)
{
    /* Bitwise rather than a 512-byte table: a frame is at most 66 bytes, and
     * flash is the scarcer resource on the smallest boards. */
    uint16_t c = crc;
    for (size_t i = 0; i < n; i++) {
        c ^= (uint16_t)((uint16_t)data[i] << 8);
        for (unsigned bit = 0; bit < 8u; bit++) {
            c = ((c & 0x8000u) != 0u) ? (uint16_t)(((unsigned)c << 1) ^ 0x1021u)
                                      : (uint16_t)((unsigned)c << 1);
        }
    }
    return c;
}

size_t hil_encode(uint8_t id, const uint8_t *payload, uint8_t len, uint8_t *out, size_t out_size)
{
    if (out == NULL || len > HIL_PAYLOAD_MAX || (payload == NULL && len != 0u) ||
        out_size < (size_t)len + HIL_OVERHEAD) {
        return 0u;
    }
    out[0] = HIL_SYNC1;
    out[1] = HIL_SYNC2;
    out[2] = len;
    out[3] = id;
    for (uint8_t i = 0; i < len; i++) {
        out[4u + i] = payload[i];
    }
    uint16_t crc = hil_crc16(0xFFFFu, &out[2], (size_t)len + 2u);
    out[4u + len] = (uint8_t)(crc & 0xFFu);
    out[5u + len] = (uint8_t)(crc >> 8);
    return (size_t)len + HIL_OVERHEAD;
}

static void count(uint16_t *c)
{
    if (*c != UINT16_MAX) {
        (*c)++;
    }
}

void hil_decoder_init(hil_decoder_t *d, hil_msg_table_t table)
{
    hil_decoder_t zero = {0};
    *d = zero;
    d->table = table;
}

/* A frame of this id and length is one the caller expects. */
static int known(const hil_msg_table_t *t, uint8_t id, uint8_t len)
{
    if (t->expected_len == NULL || id >= t->id_count) {
        return 0;
    }
    uint8_t want = t->expected_len[id];
    return want == 0xFFu || want == len;
}

/*
 * The held bytes are w[0..n). A candidate frame starts at every i with
 * w[i] == SYNC1 and, as far as the bytes go, w[i + 1] == SYNC2 and a length
 * byte w[i + 2] <= HIL_PAYLOAD_MAX. It ends at i + len + HIL_OVERHEAD; before
 * that it is open.
 */
typedef enum { CAND_NONE, CAND_BAD_LENGTH, CAND_OPEN, CAND_ENDED } cand_t;

static cand_t candidate(const uint8_t *w, unsigned n, unsigned i)
{
    if (w[i] != HIL_SYNC1 || (i + 1u < n && w[i + 1u] != HIL_SYNC2)) {
        return CAND_NONE;
    }
    if (i + 2u >= n) {
        return CAND_OPEN;
    }
    if (w[i + 2u] > HIL_PAYLOAD_MAX) {
        return CAND_BAD_LENGTH;
    }
    return (n - i < (unsigned)w[i + 2u] + HIL_OVERHEAD) ? CAND_OPEN : CAND_ENDED;
}

/* The candidate at i ends exactly at n with a good CRC. */
static int good_frame_ends_here(const uint8_t *w, unsigned n, unsigned i)
{
    if (candidate(w, n, i) != CAND_ENDED || n - i != (unsigned)w[i + 2u] + HIL_OVERHEAD) {
        return 0;
    }
    uint16_t crc = hil_crc16(0xFFFFu, &w[i + 2u], n - i - 4u);
    return crc == (uint16_t)(w[n - 2u] | ((uint16_t)w[n - 1u] << 8));
}

/* Account for w[0..end), bytes that precede a well-formed frame: the sync
 * byte of each dropped candidate in its counter, the rest skipped. A
 * candidate still open here is cut short by the frame and counts as a bad
 * CRC (it cannot be both intact and overlap an intact frame). */
static void drop_before(hil_decoder_t *d, unsigned end)
{
    for (unsigned i = 0; i < end; i++) {
        cand_t c = candidate(d->window, d->held, i);
        count(c == CAND_NONE         ? &d->stats.skipped_bytes
              : c == CAND_BAD_LENGTH ? &d->stats.bad_length
                                     : &d->stats.bad_crc);
    }
}

/* While the oldest candidate (at 0) has failed, count it and move the held
 * bytes down to the next possible frame start, so that every byte after a
 * failed sync byte is searched again. Iterative: each pass drops >= 1 byte. */
static void drop_failed(hil_decoder_t *d)
{
    while (d->held > 0u) {
        cand_t c = candidate(d->window, d->held, 0u);
        if (c == CAND_OPEN) {
            return;
        }
        /* A candidate that has ended without being taken had a bad CRC: one
         * with a good CRC is taken at its last byte, in hil_decoder_push. */
        count(c == CAND_NONE         ? &d->stats.skipped_bytes
              : c == CAND_BAD_LENGTH ? &d->stats.bad_length
                                     : &d->stats.bad_crc);
        unsigned next = 1u;
        while (next < d->held && d->window[next] != HIL_SYNC1) {
            count(&d->stats.skipped_bytes);
            next++;
        }
        unsigned keep = d->held - next;
        // cppcheck-suppress knownConditionTrueFalse ; false positive: keep >= 1 after a held SYNC1
        for (unsigned k = 0; k < keep; k++) {
            d->window[k] = d->window[next + k];
        }
        d->held = (uint8_t)keep;
    }
}

int hil_decoder_push(hil_decoder_t *d, uint8_t byte)
{
    if (d->held == 0u && byte != HIL_SYNC1) {
        count(&d->stats.skipped_bytes);
        return 0;
    }
    /* Room: the oldest candidate is open, so held < its length <= FRAME_MAX. */
    d->window[d->held] = byte;
    d->held++;
    const unsigned n = d->held;

    /* The earliest candidate that this byte completes with a good CRC is a
     * frame; later ones lie inside it and are not frames. */
    for (unsigned i = 0; i + HIL_OVERHEAD <= n; i++) {
        if (!good_frame_ends_here(d->window, n, i)) {
            continue;
        }
        drop_before(d, i);
        uint8_t len = d->window[i + 2u];
        uint8_t id = d->window[i + 3u];
        d->held = 0u;
        if (!known(&d->table, id, len)) {
            count(&d->stats.unknown_id);
            return 0;
        }
        d->id = id;
        d->len = len;
        for (unsigned k = 0; k < len; k++) {
            d->payload[k] = d->window[i + 4u + k];
        }
        count(&d->stats.frames_ok);
        return 1;
    }
    drop_failed(d);
    return 0;
}

void hil_put_u16(uint8_t *p, uint16_t v)
{
    p[0] = (uint8_t)(v & 0xFFu);
    p[1] = (uint8_t)(v >> 8);
}

void hil_put_i16(uint8_t *p, int16_t v)
{
    hil_put_u16(p, (uint16_t)v);
}

void hil_put_i32(uint8_t *p, int32_t v)
{
    uint32_t u = (uint32_t)v;
    hil_put_u16(p, (uint16_t)(u & 0xFFFFu));
    hil_put_u16(&p[2], (uint16_t)(u >> 16));
}

uint16_t hil_get_u16(const uint8_t *p)
{
    return (uint16_t)(p[0] | ((uint16_t)p[1] << 8));
}

int16_t hil_get_i16(const uint8_t *p)
{
    return (int16_t)hil_get_u16(p);
}

int32_t hil_get_i32(const uint8_t *p)
{
    uint32_t u = (uint32_t)hil_get_u16(p) | ((uint32_t)hil_get_u16(&p[2]) << 16);
    return (int32_t)u;
}
