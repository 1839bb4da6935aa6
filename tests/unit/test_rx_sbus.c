/*
 * The SBUS decoder (src/protocols/rx_sbus.c). Frames are built here (bit-by-bit
 * packer of frame_test_util.h) and decoded; values checked exactly:
 *
 *   - a frame captured from a Futaba SBUS2 receiver, worked out by hand;
 *   - the flags: ch17, ch18, frame lost, failsafe (channels not usable);
 *   - the end bytes: 0x00 and the SBUS2 0x04/0x14/0x24/0x34 taken, all
 *     251 others counted as bad_end and dropped;
 *   - 10^5 random frames with garbage between them (no 0x0F in it) and
 *     false frames (a 0x0F and 24 bytes with a bad end byte): each frame at
 *     its own last byte, every counter, byte-wise == chunked feeding;
 *   - a frame cut at every point then a good frame; sbus_line_gap();
 *   - corrupting the start or end byte is rejected; SBUS has no checksum,
 *     so corrupted data bytes are not detectable (documented);
 *   - NULL pointers.
 */
#include <stdlib.h>

#include "frame_test_util.h"
#include "helical/protocols/rx_sbus.h"
#include "unity.h"

void setUp(void) {}
void tearDown(void) {}

static void enc(const uint16_t t[16], uint8_t flags, uint8_t end, uint8_t f[25])
{
    f[0] = 0x0F;
    ft_pack11(t, &f[1]);
    f[23] = flags;
    f[24] = end;
}

static int end_ok(unsigned e)
{
    return e == 0x00 || e == 0x04 || e == 0x14 || e == 0x24 || e == 0x34;
}

static void test_captured_frame(void)
{
    /* Futaba receiver, SBUS2 (end 0x04), Futaba centre 1024 = 1520 us */
    const uint8_t f[25] = {0x0F, 0x79, 0xD3, 0xD8, 0x35, 0x01, 0x08, 0xE8, 0x7E,
                           0x81, 0x05, 0x2C, 0x60, 0x81, 0x2C, 0x58, 0xC0, 0x02,
                           0x07, 0x38, 0x00, 0x10, 0x80, 0x00, 0x04};
    const uint16_t ticks[16] = {889, 794,  1239, 1024, 1664, 765, 352,  352,
                                352, 1424, 352,  352,  112,  112, 1024, 1024};
    const uint16_t us[16] = {1436, 1376, 1654, 1520, 1920, 1358, 1100, 1100,
                             1100, 1770, 1100, 1100, 950,  950,  1520, 1520};
    sbus_decoder_t d;
    sbus_frame_t out;
    sbus_init(&d);
    for (int i = 0; i < 24; i++) {
        TEST_ASSERT_EQUAL_INT(SBUS_NONE, sbus_push(&d, f[i], &out));
    }
    TEST_ASSERT_EQUAL_INT(SBUS_FRAME, sbus_push(&d, f[24], &out));
    TEST_ASSERT_EQUAL_UINT16_ARRAY(ticks, out.ticks, 16);
    TEST_ASSERT_EQUAL_UINT16_ARRAY(us, out.pulse_us, 16);
    TEST_ASSERT_FALSE(out.failsafe);
    TEST_ASSERT_FALSE(out.frame_lost);
    TEST_ASSERT_TRUE(out.channels_usable);
    TEST_ASSERT_EQUAL_HEX8(0x04, out.end_byte);
}

static void test_flags(void)
{
    uint16_t t[16];
    for (int k = 0; k < 16; k++) {
        t[k] = (uint16_t)(172 + 100 * k);
    }
    for (unsigned flags = 0; flags < 256u; flags++) {
        uint8_t f[25];
        enc(t, (uint8_t)flags, 0x00, f);
        sbus_decoder_t d;
        sbus_frame_t out;
        sbus_result_t r;
        sbus_init(&d);
        TEST_ASSERT_EQUAL_UINT64(25, sbus_feed(&d, f, 25, &out, &r));
        TEST_ASSERT_EQUAL_INT(SBUS_FRAME, r);
        TEST_ASSERT_EQUAL(!!(flags & 1u), out.ch17);
        TEST_ASSERT_EQUAL(!!(flags & 2u), out.ch18);
        TEST_ASSERT_EQUAL(!!(flags & 4u), out.frame_lost);
        TEST_ASSERT_EQUAL(!!(flags & 8u), out.failsafe);
        TEST_ASSERT_EQUAL(!(flags & 8u), out.channels_usable);
        TEST_ASSERT_EQUAL_UINT16_ARRAY(t, out.ticks, 16);
        for (int k = 0; k < 16; k++) {
            TEST_ASSERT_EQUAL_INT(ft_pulse_ref(t[k]), out.pulse_us[k]);
        }
    }
}

static void test_end_bytes(void)
{
    uint16_t t[16] = {0};
    int taken = 0;
    for (unsigned e = 0; e < 256u; e++) {
        uint8_t f[25];
        enc(t, 0, (uint8_t)e, f);
        sbus_decoder_t d;
        sbus_frame_t out;
        sbus_result_t r;
        sbus_init(&d);
        sbus_feed(&d, f, 25, &out, &r);
        if (end_ok(e)) {
            TEST_ASSERT_EQUAL_INT(SBUS_FRAME, r);
            TEST_ASSERT_EQUAL_HEX8(e, out.end_byte);
            taken++;
        } else {
            TEST_ASSERT_EQUAL_INT(SBUS_NONE, r);
            TEST_ASSERT_EQUAL_UINT32(1, d.counts.bad_end);
            /* no 0x0F inside, except an end byte of 0x0F: held as a start */
            TEST_ASSERT_EQUAL_UINT32(e == 0x0Fu ? 23 : 24, d.counts.discarded_bytes);
            TEST_ASSERT_EQUAL_UINT8(e == 0x0Fu ? 1 : 0, d.held);
            TEST_ASSERT_EQUAL_UINT64(25, ft_accounted(&d.counts, d.held));
        }
    }
    TEST_ASSERT_EQUAL_INT(5, taken);
}

#define SWEEP_FRAMES 100000

static uint8_t non_start(uint64_t *s)
{
    uint8_t b;
    do {
        b = ft_byte(s);
    } while (b == 0x0F);
    return b;
}

static void test_random_frames_with_garbage(void)
{
    uint64_t s = 777;
    size_t cap = (size_t)SWEEP_FRAMES * 70u;
    uint8_t *st = malloc(cap);
    uint16_t(*ticks)[16] = malloc(sizeof(*ticks) * SWEEP_FRAMES);
    uint8_t *flags = malloc(SWEEP_FRAMES);
    size_t *last = malloc(sizeof(size_t) * SWEEP_FRAMES);
    TEST_ASSERT_TRUE(st && ticks && flags && last);
    size_t n = 0;
    uint32_t garbage = 0, bad_end = 0;
    static const uint8_t ends[5] = {0x00, 0x04, 0x14, 0x24, 0x34};
    for (int i = 0; i < SWEEP_FRAMES; i++) {
        unsigned g = ft_below(&s, 6);
        for (unsigned k = 0; k < g; k++) {
            st[n++] = non_start(&s);
            garbage++;
        }
        if (ft_below(&s, 10) == 0) { /* a false frame: 0x0F, 23 bytes, bad end */
            st[n++] = 0x0F;
            for (int k = 0; k < 23; k++) {
                st[n++] = non_start(&s);
            }
            uint8_t e;
            do {
                e = non_start(&s);
            } while (end_ok(e));
            st[n++] = e;
            bad_end++;
            garbage += 24;
        }
        uint8_t f[25];
        do {
            for (int k = 0; k < 16; k++) {
                ticks[i][k] = (uint16_t)ft_below(&s, 2048);
            }
            flags[i] = (uint8_t)ft_below(&s, 16);
            enc(ticks[i], flags[i], ends[ft_below(&s, 5)], f);
        } while (memchr(&f[1], 0x0F, 24) != NULL);
        memcpy(&st[n], f, 25);
        n += 25;
        last[i] = n - 1;
    }
    sbus_decoder_t d, d2;
    sbus_frame_t out;
    sbus_init(&d);
    int k = 0;
    for (size_t i = 0; i < n; i++) {
        if (sbus_push(&d, st[i], &out) == SBUS_FRAME) {
            TEST_ASSERT_TRUE(k < SWEEP_FRAMES);
            TEST_ASSERT_EQUAL_UINT64(last[k], i);
            TEST_ASSERT_EQUAL_UINT16_ARRAY(ticks[k], out.ticks, 16);
            TEST_ASSERT_EQUAL(!!(flags[k] & 8u), out.failsafe);
            TEST_ASSERT_EQUAL(!!(flags[k] & 4u), out.frame_lost);
            TEST_ASSERT_EQUAL(!(flags[k] & 8u), out.channels_usable);
            k++;
        }
    }
    TEST_ASSERT_EQUAL_INT(SWEEP_FRAMES, k);
    TEST_ASSERT_EQUAL_UINT32(SWEEP_FRAMES, d.counts.frames_ok);
    TEST_ASSERT_EQUAL_UINT32(25u * SWEEP_FRAMES, d.counts.frame_bytes);
    TEST_ASSERT_EQUAL_UINT32(bad_end, d.counts.bad_end);
    TEST_ASSERT_EQUAL_UINT32(garbage, d.counts.discarded_bytes);
    TEST_ASSERT_EQUAL_UINT32(0, d.counts.bad_checksum + d.counts.bad_length + d.counts.truncated +
                                    d.counts.unknown_type + d.counts.wrong_length);
    TEST_ASSERT_EQUAL_UINT64(n, ft_accounted(&d.counts, d.held));

    sbus_init(&d2);
    size_t pos = 0;
    int k2 = 0;
    while (pos < n) {
        size_t chunk = 1 + ft_below(&s, 100);
        if (chunk > n - pos) {
            chunk = n - pos;
        }
        sbus_result_t r;
        size_t used = sbus_feed(&d2, &st[pos], chunk, &out, &r);
        TEST_ASSERT_TRUE(used >= 1 && used <= chunk);
        pos += used;
        if (r == SBUS_FRAME) {
            TEST_ASSERT_EQUAL_UINT64(last[k2], pos - 1);
            TEST_ASSERT_EQUAL_UINT16_ARRAY(ticks[k2], out.ticks, 16);
            k2++;
        } else {
            TEST_ASSERT_EQUAL_UINT64(chunk, used);
        }
    }
    TEST_ASSERT_EQUAL_INT(k, k2);
    ft_assert_counts_equal(&d.counts, &d2.counts);
    free(st);
    free(ticks);
    free(flags);
    free(last);
}

static const uint16_t fixed[16] = {172,  1811, 992, 1000, 500, 1500, 2047, 0,
                                   1234, 321,  992, 992,  600, 1700, 800,  1100};

static void test_every_truncation_point_and_line_gap(void)
{
    uint8_t a[25], s[50];
    enc(fixed, 0, 0x00, a);
    TEST_ASSERT_NULL(memchr(&a[1], 0x0F, 24));
    for (size_t k = 1; k < 25; k++) {
        memcpy(s, a, k);
        memcpy(&s[k], a, 25);
        sbus_decoder_t d;
        sbus_frame_t out;
        sbus_init(&d);
        int frames = 0;
        size_t at = 0;
        for (size_t i = 0; i < k + 25; i++) {
            if (sbus_push(&d, s[i], &out) == SBUS_FRAME) {
                frames++;
                at = i;
            }
        }
        /* the cut frame's candidate ends inside the good one with its end byte
         * s[24]: a frame by chance only if that byte is an allowed end byte */
        int phantom = end_ok(s[24]) && k < 25;
        if (!phantom) {
            TEST_ASSERT_EQUAL_INT(1, frames);
            TEST_ASSERT_EQUAL_UINT64(k + 24, at);
            TEST_ASSERT_EQUAL_UINT16_ARRAY(fixed, out.ticks, 16);
            TEST_ASSERT_EQUAL_UINT32(1, d.counts.bad_end);
        }
        /* with the line gap the driver sees before the good frame: always */
        sbus_init(&d);
        frames = 0;
        for (size_t i = 0; i < k + 25; i++) {
            if (i == k) {
                sbus_line_gap(&d);
            }
            if (sbus_push(&d, s[i], &out) == SBUS_FRAME) {
                frames++;
                at = i;
            }
        }
        TEST_ASSERT_EQUAL_INT(1, frames);
        TEST_ASSERT_EQUAL_UINT64(k + 24, at);
        TEST_ASSERT_EQUAL_UINT16_ARRAY(fixed, out.ticks, 16);
        TEST_ASSERT_EQUAL_UINT32(1, d.counts.truncated);
        TEST_ASSERT_EQUAL_UINT64(k + 25, ft_accounted(&d.counts, d.held));
    }
}

static void test_start_and_end_byte_corruption_rejected(void)
{
    uint8_t a[25], s[25];
    enc(fixed, 0, 0x00, a);
    for (unsigned v = 0; v < 256u; v++) {
        for (int pos = 0; pos < 25; pos += 24) {
            if (v == a[pos] || (pos == 24 && end_ok(v))) {
                continue;
            }
            memcpy(s, a, 25);
            s[pos] = (uint8_t)v;
            sbus_decoder_t d;
            sbus_frame_t out;
            sbus_result_t r;
            sbus_init(&d);
            size_t used = sbus_feed(&d, s, 25, &out, &r);
            TEST_ASSERT_EQUAL_UINT64(25, used);
            TEST_ASSERT_EQUAL_INT(SBUS_NONE, r);
            TEST_ASSERT_EQUAL_UINT64(25, ft_accounted(&d.counts, d.held));
        }
    }
}

static void test_null_pointers(void)
{
    sbus_decoder_t d;
    sbus_frame_t out;
    sbus_result_t r = SBUS_NONE;
    uint8_t b = 0x0F;
    sbus_init(NULL);
    sbus_line_gap(NULL);
    sbus_init(&d);
    TEST_ASSERT_EQUAL_INT(SBUS_ERR_NULL, sbus_push(NULL, b, &out));
    TEST_ASSERT_EQUAL_INT(SBUS_ERR_NULL, sbus_push(&d, b, NULL));
    TEST_ASSERT_EQUAL_UINT64(0, sbus_feed(&d, NULL, 3, &out, &r));
    TEST_ASSERT_EQUAL_INT(SBUS_ERR_NULL, r);
    TEST_ASSERT_EQUAL_UINT64(0, sbus_feed(&d, &b, 1, &out, NULL));
    TEST_ASSERT_EQUAL_UINT64(0, ft_accounted(&d.counts, d.held));
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_captured_frame);
    RUN_TEST(test_flags);
    RUN_TEST(test_end_bytes);
    RUN_TEST(test_random_frames_with_garbage);
    RUN_TEST(test_every_truncation_point_and_line_gap);
    RUN_TEST(test_start_and_end_byte_corruption_rejected);
    RUN_TEST(test_null_pointers);
    return UNITY_END();
}
