/*
 * libFuzzer target: arbitrary bytes into the HIL frame decoder
 * (src/protocols/hil_frame.c). The first input byte picks how many ids of the table the
 * decoder knows; the rest is the stream. Checks, at every byte:
 *
 *   - a frame reported is exactly the last len + 6 bytes of the stream
 *     (re-encoded with hil_encode: the sync bytes, the length and the CRC are
 *     right) with an id and a length the table accepts;
 *   - the decoder agrees with a plain model of the rule in hil_frame.h: a
 *     frame is the earliest 0xA5 0x5A ... with a good CRC that ends at this
 *     byte and starts after the last well-formed frame (found here by brute
 *     force over the whole stream);
 *   - it never holds more than HIL_FRAME_MAX bytes, and every byte fed is
 *     accounted for: bytes of well-formed frames + one per dropped frame
 *     (bad_crc, bad_length) + skipped_bytes + held == bytes fed.
 *
 * ASan and UBSan (scripts/fuzz.sh) catch any access out of bounds.
 */
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "helical/protocols/hil_frame.h"

static void check(int ok)
{
    if (!ok) {
        abort();
    }
}

/* ids 0..7: a mix of any length (0xFF) and fixed lengths, 0 and 64 included */
static const uint8_t lengths[8] = {0xFF, 0, 1, 8, 41, 64, 0xFF, 2};

/* Model: the earliest well-formed frame (any id) that ends at s[n - 1] and
 * starts at or after `from`; returns its start, or -1. (A frame is at most
 * HIL_FRAME_MAX bytes, so earlier starts need no look.) */
static long model_frame_ending_at(const uint8_t *s, size_t from, size_t n)
{
    size_t i = n > HIL_FRAME_MAX && n - HIL_FRAME_MAX > from ? n - HIL_FRAME_MAX : from;
    for (; i + HIL_OVERHEAD <= n; i++) {
        if (s[i] != HIL_SYNC1 || s[i + 1] != HIL_SYNC2 || s[i + 2] > HIL_PAYLOAD_MAX ||
            n - i != (size_t)s[i + 2] + HIL_OVERHEAD) {
            continue;
        }
        uint16_t crc = hil_crc16(0xFFFFu, &s[i + 2], n - i - 4u);
        if (crc == (uint16_t)(s[n - 2] | (s[n - 1] << 8))) {
            return (long)i;
        }
    }
    return -1;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size < 1 || size > 60000) { /* counters must not saturate here */
        return 0;
    }
    hil_msg_table_t table = {lengths, (uint8_t)(data[0] % 9u)};
    const uint8_t *s = data + 1;
    size_t n = size - 1;

    hil_decoder_t d;
    hil_decoder_init(&d, table);
    size_t from = 0;      /* the model: after the last well-formed frame */
    size_t framed = 0;    /* bytes in well-formed frames */
    uint16_t unknown = 0; /* the model's count of well-formed unknown frames */
    uint16_t delivered = 0;
    for (size_t k = 0; k < n; k++) {
        int got = hil_decoder_push(&d, s[k]);
        check(d.held <= HIL_FRAME_MAX);

        long start = model_frame_ending_at(s, from, k + 1);
        int model_known = 0;
        if (start >= 0) {
            uint8_t len = s[start + 2], id = s[start + 3];
            model_known = id < table.id_count && (lengths[id] == 0xFFu || lengths[id] == len);
            from = k + 1;
            framed += (size_t)len + HIL_OVERHEAD;
            unknown = (uint16_t)(unknown + !model_known);
        }
        check(got == model_known);
        if (got) {
            delivered++;
            uint8_t frame[HIL_FRAME_MAX];
            size_t m = hil_encode(d.id, d.payload, d.len, frame, sizeof frame);
            check(m == (size_t)d.len + HIL_OVERHEAD && m <= k + 1);
            check(memcmp(frame, &s[k + 1 - m], m) == 0);
            check(d.id < table.id_count);
            check(lengths[d.id] == 0xFFu || lengths[d.id] == d.len);
        }
        check(d.stats.frames_ok == delivered && d.stats.unknown_id == unknown);
        size_t sum = framed + d.stats.bad_crc + d.stats.bad_length + d.stats.skipped_bytes + d.held;
        check(sum == k + 1);
    }
    return 0;
}
