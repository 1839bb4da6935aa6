/*
 * The HIL link's framing: CRC check value, every payload length, garbage and
 * resynchronisation, every single-bit corruption, unknown ids and lengths,
 * and a long seeded stream of frames mixed with noise.
 */
#include <string.h>

#include "helical/protocols/hil_frame.h"
#include "ht_test_support.h"
#include "unity.h"

/* ids 0..3 known: 0 any length, 1 exactly 8 bytes, 2 exactly 0, 3 any */
static const uint8_t lengths[4] = {0xFF, 8, 0, 0xFF};
static const hil_msg_table_t table = {lengths, 4};
static hil_decoder_t dec;

void setUp(void)
{
    hil_decoder_init(&dec, table);
}
void tearDown(void) {}

/* Push bytes; return how many frames completed, copying the last one. */
static int push_all(const uint8_t *b, size_t n)
{
    int frames = 0;
    for (size_t i = 0; i < n; i++) {
        frames += hil_decoder_push(&dec, b[i]);
    }
    return frames;
}

static void test_crc_check_value(void)
{
    const uint8_t s[] = "123456789";
    TEST_ASSERT_EQUAL_HEX16(0x29B1, hil_crc16(0xFFFFu, s, 9));
    TEST_ASSERT_EQUAL_HEX16(0xFFFF, hil_crc16(0xFFFFu, s, 0));
}

static void test_every_length_round_trips(void)
{
    uint64_t rng = 7;
    for (unsigned len = 0; len <= HIL_PAYLOAD_MAX; len++) {
        uint8_t payload[HIL_PAYLOAD_MAX], frame[HIL_FRAME_MAX];
        for (unsigned i = 0; i < len; i++) {
            payload[i] = (uint8_t)ts_rng_next(&rng);
        }
        size_t n = hil_encode(3, payload, (uint8_t)len, frame, sizeof frame);
        TEST_ASSERT_EQUAL_UINT64((uint64_t)(len + HIL_OVERHEAD), (uint64_t)n);
        TEST_ASSERT_EQUAL_INT(1, push_all(frame, n));
        TEST_ASSERT_EQUAL_UINT8(3, dec.id);
        TEST_ASSERT_EQUAL_UINT8(len, dec.len);
        if (len > 0) {
            TEST_ASSERT_EQUAL_UINT8_ARRAY(payload, dec.payload, len);
        }
    }
    TEST_ASSERT_EQUAL_UINT16(HIL_PAYLOAD_MAX + 1, dec.stats.frames_ok);
}

static void test_encode_refuses_what_does_not_fit(void)
{
    uint8_t payload[HIL_PAYLOAD_MAX + 1] = {0}, frame[HIL_FRAME_MAX + 1];
    TEST_ASSERT_EQUAL_UINT64(
        (uint64_t)(0), (uint64_t)hil_encode(0, payload, HIL_PAYLOAD_MAX + 1, frame, sizeof frame));
    TEST_ASSERT_EQUAL_UINT64((uint64_t)(0), (uint64_t)hil_encode(0, payload, 10, frame, 15));
    TEST_ASSERT_EQUAL_UINT64((uint64_t)(16), (uint64_t)hil_encode(0, payload, 10, frame, 16));
    TEST_ASSERT_EQUAL_UINT64((uint64_t)(0), (uint64_t)hil_encode(0, NULL, 1, frame, sizeof frame));
    TEST_ASSERT_EQUAL_UINT64((uint64_t)(6), (uint64_t)hil_encode(2, NULL, 0, frame, sizeof frame));
    TEST_ASSERT_EQUAL_UINT64((uint64_t)(0), (uint64_t)hil_encode(0, payload, 1, NULL, 100));
}

/* Garbage (including sync bytes and half frames) before a frame is skipped. */
static void test_resynchronises_after_garbage(void)
{
    const uint8_t garbage[] = {0x00, 0xA5, 0x00, 0xA5, 0xA5, 0x5A, 0xFF, 0x13, 0xA5, 0x5A, 0x03};
    uint8_t payload[8] = {1, 2, 3, 4, 5, 6, 7, 8}, frame[HIL_FRAME_MAX];
    size_t n = hil_encode(1, payload, 8, frame, sizeof frame);
    TEST_ASSERT_EQUAL_INT(0, push_all(garbage, sizeof garbage));
    /* The garbage ended inside a would-be frame of length 3: the good frame's
     * first bytes are consumed by it; send it twice, the second must land. */
    int got = push_all(frame, n);
    got += push_all(frame, n);
    TEST_ASSERT_GREATER_OR_EQUAL_INT(1, got);
    TEST_ASSERT_EQUAL_UINT8_ARRAY(payload, dec.payload, 8);
    TEST_ASSERT_GREATER_THAN_UINT16(0, dec.stats.skipped_bytes);
}

/* Every single-bit error in a frame is caught; the very next frame lands, at
 * its own last byte. */
static void test_every_single_bit_error_is_dropped(void)
{
    uint8_t payload[8] = {10, 20, 30, 40, 50, 60, 70, 80}, frame[HIL_FRAME_MAX];
    size_t n = hil_encode(1, payload, 8, frame, sizeof frame);
    for (size_t byte = 0; byte < n; byte++) {
        for (unsigned bit = 0; bit < 8; bit++) {
            hil_decoder_init(&dec, table);
            uint8_t bad[HIL_FRAME_MAX];
            memcpy(bad, frame, n);
            bad[byte] ^= (uint8_t)(1u << bit);
            TEST_ASSERT_EQUAL_INT(0, push_all(bad, n));
            TEST_ASSERT_EQUAL_INT(0, push_all(frame, n - 1u));
            TEST_ASSERT_EQUAL_INT(1, hil_decoder_push(&dec, frame[n - 1u]));
            TEST_ASSERT_EQUAL_UINT8_ARRAY(payload, dec.payload, 8);
            TEST_ASSERT_EQUAL_UINT16(1, dec.stats.frames_ok);
        }
    }
}

/* The case: a length byte corrupted to 64 used to swallow the next 64
 * bytes, eleven 6-byte frames. Now every one of them lands at its last byte,
 * and the bad frame is counted once. */
static void test_corrupted_length_loses_only_its_frame(void)
{
    uint8_t frame[HIL_FRAME_MAX], bad[HIL_FRAME_MAX];
    size_t n = hil_encode(2, NULL, 0, frame, sizeof frame); /* 6 bytes */
    memcpy(bad, frame, n);
    bad[2] = HIL_PAYLOAD_MAX;
    TEST_ASSERT_EQUAL_INT(0, push_all(bad, n));
    for (int k = 0; k < 12; k++) {
        TEST_ASSERT_EQUAL_INT(0, push_all(frame, n - 1u));
        TEST_ASSERT_EQUAL_INT(1, hil_decoder_push(&dec, frame[n - 1u]));
        TEST_ASSERT_EQUAL_UINT8(2, dec.id);
    }
    TEST_ASSERT_EQUAL_UINT16(12, dec.stats.frames_ok);
    TEST_ASSERT_EQUAL_UINT16(1, dec.stats.bad_crc); /* cut short by the first good one */
    /* its other five bytes, searched again, start no frame */
    TEST_ASSERT_EQUAL_UINT16(5, dec.stats.skipped_bytes);
    TEST_ASSERT_EQUAL_UINT8(0, dec.held);
}

/* A frame cut short: the next frame starts inside the span the bad one
 * claimed, and lands at its own last byte. */
static void test_truncated_frame_loses_only_itself(void)
{
    uint8_t payload[8] = {1, 2, 3, 4, 5, 6, 7, 8}, frame[HIL_FRAME_MAX];
    size_t n = hil_encode(1, payload, 8, frame, sizeof frame);
    for (size_t cut = 1; cut < n; cut++) {
        hil_decoder_init(&dec, table);
        TEST_ASSERT_EQUAL_INT(0, push_all(frame, cut));
        TEST_ASSERT_EQUAL_INT(0, push_all(frame, n - 1u));
        TEST_ASSERT_EQUAL_INT(1, hil_decoder_push(&dec, frame[n - 1u]));
        TEST_ASSERT_EQUAL_UINT16(cut >= 3 ? 1 : 0, dec.stats.bad_crc);
    }
}

/* The price of taking every frame at its own last byte: a whole valid frame
 * inside a payload ends first and is taken; the frame around it is counted
 * as cut short (hil_frame.h). A candidate inside a good frame that would end
 * after it is not a frame: the outer one is taken when it ends. */
static void test_frame_inside_a_payload(void)
{
    uint8_t inner[HIL_FRAME_MAX], outer[HIL_FRAME_MAX], next[HIL_FRAME_MAX];
    const uint8_t two[2] = {0xA5, 0x5A};
    size_t ni = hil_encode(3, two, 2, inner, sizeof inner);
    TEST_ASSERT_EQUAL_UINT64(8, (uint64_t)ni);
    size_t no = hil_encode(0, inner, (uint8_t)ni, outer, sizeof outer);
    int got = 0;
    for (size_t i = 0; i < no; i++) {
        if (hil_decoder_push(&dec, outer[i])) {
            got++;
            TEST_ASSERT_EQUAL_UINT64(4 + ni, (uint64_t)(i + 1)); /* the inner frame's end */
            TEST_ASSERT_EQUAL_UINT8(3, dec.id);
            TEST_ASSERT_EQUAL_HEX8(0xA5, dec.payload[0]);
        }
    }
    TEST_ASSERT_EQUAL_INT(1, got);
    TEST_ASSERT_EQUAL_UINT16(1, dec.stats.bad_crc); /* the outer frame, cut short */
    /* its header but the counted sync byte, and its CRC */
    TEST_ASSERT_EQUAL_UINT16(3 + 2, dec.stats.skipped_bytes);
    size_t nn = hil_encode(1, outer, 8, next, sizeof next);
    TEST_ASSERT_EQUAL_INT(1, push_all(next, nn));

    /* An "A5 5A 40" inside a payload claims 64 bytes past the frame's end:
     * the frame is taken at its end, and the claim is dropped with it. */
    hil_decoder_init(&dec, table);
    uint8_t p[8] = {0xA5, 0x5A, 0x40, 0x00, 0xA5, 0x5A, 0x00, 0x02};
    nn = hil_encode(1, p, 8, next, sizeof next);
    TEST_ASSERT_EQUAL_INT(1, push_all(next, nn));
    TEST_ASSERT_EQUAL_UINT8(0, dec.held);
    TEST_ASSERT_EQUAL_INT(1, push_all(next, nn));
    TEST_ASSERT_EQUAL_UINT16(2, dec.stats.frames_ok);
    TEST_ASSERT_EQUAL_UINT16(0, dec.stats.bad_crc);
    TEST_ASSERT_EQUAL_UINT16(0, dec.stats.skipped_bytes);
}

static void test_unknown_ids_and_wrong_lengths_are_counted(void)
{
    uint8_t payload[8] = {0}, frame[HIL_FRAME_MAX];
    size_t n = hil_encode(9, payload, 2, frame, sizeof frame); /* id beyond the table */
    TEST_ASSERT_EQUAL_INT(0, push_all(frame, n));
    n = hil_encode(1, payload, 7, frame, sizeof frame); /* id 1 wants 8 bytes */
    TEST_ASSERT_EQUAL_INT(0, push_all(frame, n));
    n = hil_encode(2, payload, 1, frame, sizeof frame); /* id 2 wants 0 */
    TEST_ASSERT_EQUAL_INT(0, push_all(frame, n));
    TEST_ASSERT_EQUAL_UINT16(3, dec.stats.unknown_id);
    const uint8_t too_long[] = {0xA5, 0x5A, HIL_PAYLOAD_MAX + 1, 0};
    TEST_ASSERT_EQUAL_INT(0, push_all(too_long, sizeof too_long));
    TEST_ASSERT_EQUAL_UINT16(1, dec.stats.bad_length);
    /* a decoder with no table accepts nothing */
    hil_msg_table_t none = {NULL, 0};
    hil_decoder_init(&dec, none);
    n = hil_encode(0, payload, 2, frame, sizeof frame);
    TEST_ASSERT_EQUAL_INT(0, push_all(frame, n));
    TEST_ASSERT_EQUAL_UINT16(1, dec.stats.unknown_id);
}

static void test_counters_saturate(void)
{
    uint8_t junk = 0x00;
    for (long i = 0; i < 70000; i++) {
        (void)hil_decoder_push(&dec, junk);
    }
    TEST_ASSERT_EQUAL_UINT16(UINT16_MAX, dec.stats.skipped_bytes);
}

static void test_field_helpers_round_trip_at_the_edges(void)
{
    uint8_t b[4];
    const int32_t i32[] = {INT32_MIN, -1, 0, 1, INT32_MAX, 0x12345678};
    for (size_t i = 0; i < sizeof i32 / sizeof i32[0]; i++) {
        hil_put_i32(b, i32[i]);
        TEST_ASSERT_EQUAL_INT32(i32[i], hil_get_i32(b));
    }
    hil_put_i32(b, 0x12345678);
    TEST_ASSERT_EQUAL_HEX8(0x78, b[0]); /* little-endian */
    TEST_ASSERT_EQUAL_HEX8(0x12, b[3]);
    const int16_t i16[] = {INT16_MIN, -1, 0, INT16_MAX};
    for (size_t i = 0; i < 4; i++) {
        hil_put_i16(b, i16[i]);
        TEST_ASSERT_EQUAL_INT16(i16[i], hil_get_i16(b));
    }
    hil_put_u16(b, 0xFFFFu);
    TEST_ASSERT_EQUAL_UINT16(0xFFFFu, hil_get_u16(b));
}

/* 20 000 frames with random noise between them (fixed seed): every frame
 * delivered is one that was sent, in order, and nearly all are delivered. */
static void test_long_noisy_stream(void)
{
    uint64_t rng = 12345;
    uint16_t next_expected = 0;
    long delivered = 0;
    const long frames = 20000;
    for (long k = 0; k < frames; k++) {
        uint8_t payload[8], frame[HIL_FRAME_MAX];
        hil_put_u16(payload, (uint16_t)k);
        for (int i = 2; i < 8; i++) {
            payload[i] = (uint8_t)ts_rng_next(&rng);
        }
        size_t n = hil_encode(1, payload, 8, frame, sizeof frame);
        if ((ts_rng_next(&rng) % 10u) == 0u) { /* one in ten: noise before it */
            unsigned noise = (unsigned)(ts_rng_next(&rng) % 20u);
            for (unsigned i = 0; i < noise; i++) {
                (void)hil_decoder_push(&dec, (uint8_t)ts_rng_next(&rng));
            }
        }
        for (size_t i = 0; i < n; i++) {
            if (hil_decoder_push(&dec, frame[i])) {
                uint16_t seq = hil_get_u16(dec.payload);
                TEST_ASSERT_TRUE(seq >= next_expected && seq <= (uint16_t)k);
                TEST_ASSERT_EQUAL_UINT8_ARRAY(payload + 2, dec.payload + 2, 6);
                next_expected = (uint16_t)(seq + 1u);
                delivered++;
            }
        }
    }
    TEST_ASSERT_GREATER_THAN(frames * 95 / 100, delivered);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_crc_check_value);
    RUN_TEST(test_every_length_round_trips);
    RUN_TEST(test_encode_refuses_what_does_not_fit);
    RUN_TEST(test_resynchronises_after_garbage);
    RUN_TEST(test_every_single_bit_error_is_dropped);
    RUN_TEST(test_corrupted_length_loses_only_its_frame);
    RUN_TEST(test_truncated_frame_loses_only_itself);
    RUN_TEST(test_frame_inside_a_payload);
    RUN_TEST(test_unknown_ids_and_wrong_lengths_are_counted);
    RUN_TEST(test_counters_saturate);
    RUN_TEST(test_field_helpers_round_trip_at_the_edges);
    RUN_TEST(test_long_noisy_stream);
    return UNITY_END();
}
