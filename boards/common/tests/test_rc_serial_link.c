/*
 * test_rc_serial_link.c - SBUS and CRSF bytes to RC pulses, freshness,
 * failsafe and the SBUS line gap.
 *
 * Worked values (rc_channels.h: pulse_us = (5 ticks + 7044) >> 3, i.e.
 * 1500 + (ticks - 992) * 5 / 8 rounded half up):
 *   ticks  172 -> 988     992 -> 1500    1811 -> 2012    500 -> 1192.5 -> 1193
 *   ticks 1000 -> 1505   1500 -> 1817.5 -> 1818   2000 -> 2130.5 -> 2130   0 -> 880
 * SBUS frame: 0x0F, 22 packed bytes, flags (bit 2 frame lost, bit 3
 * failsafe), end 0x00 (rx_sbus.h). 25 bytes at 100 kbaud 8E2 = 12 bits each:
 * 120 us a byte, 3000 us a frame; frames every 7000 us here.
 * CRSF frame: 0xC8, len, type, payload, CRC-8/DVB-S2 over type and payload;
 * RC_CHANNELS_PACKED len 24 (26 bytes), LINK_STATISTICS len 12 (14 bytes),
 * uplink LQ at payload byte 2 (rx_crsf.h).
 */
#include "unity.h"

#include "rc_serial_link.h"

#include <string.h>

static rc_serial_link_t link;

static const uint16_t TICKS[16] = {172u, 992u, 1811u, 500u, 1000u, 1500u, 2000u, 0u,
                                   992u, 992u, 992u,  992u, 992u,  992u,  992u,  992u};
static const uint16_t PULSES[8] = {988u, 1500u, 2012u, 1193u, 1505u, 1818u, 2130u, 880u};

void setUp(void)
{
    memset(&link, 0, sizeof link);
}

void tearDown(void) {}

static void sbus_frame(uint8_t out[25], const uint16_t ticks[16], uint8_t flags)
{
    out[0] = 0x0Fu;
    rc_pack_11bit(ticks, &out[1]);
    out[23] = flags;
    out[24] = 0x00u;
}

static void crsf_channels(uint8_t out[26], const uint16_t ticks[16])
{
    out[0] = 0xC8u;
    out[1] = 24u;
    out[2] = 0x16u;
    rc_pack_11bit(ticks, &out[3]);
    out[25] = crsf_crc8(&out[2], 23u);
}

static void crsf_link_stats(uint8_t out[14], uint8_t lq_pct)
{
    const uint8_t payload[10] = {60u, 62u, lq_pct, 9u, 0u, 4u, 2u, 70u, 100u, 8u};
    out[0] = 0xC8u;
    out[1] = 12u;
    out[2] = 0x14u;
    memcpy(&out[3], payload, sizeof payload);
    out[13] = crsf_crc8(&out[2], 11u);
}

static void test_init(void)
{
    uint16_t out[8];
    TEST_ASSERT_EQUAL(BOARD_ERR_NULL, rc_serial_link_init(NULL, RC_SERIAL_SBUS, 1000u, 0u));
    TEST_ASSERT_EQUAL(BOARD_ERR_RANGE,
                      rc_serial_link_init(&link, (rc_serial_protocol_t)0, 1000u, 0u));
    TEST_ASSERT_EQUAL(BOARD_ERR_RANGE, rc_serial_link_init(&link, RC_SERIAL_SBUS, 0u, 0u));
    TEST_ASSERT_EQUAL(BOARD_OK, rc_serial_link_init(&link, RC_SERIAL_SBUS, 100000u, 5u));
    TEST_ASSERT_EQUAL_UINT8(1u, link.lost);
    memset(out, 0xFF, sizeof out);
    TEST_ASSERT_EQUAL(BOARD_ERR_NO_DATA, rc_serial_link_read_us(&link, out, 8u));
    TEST_ASSERT_EQUAL_UINT16(0u, out[0]);
    TEST_ASSERT_EQUAL_UINT16(0u, out[7]);
    TEST_ASSERT_EQUAL(BOARD_ERR_RANGE, rc_serial_link_read_us(&link, out, 9u));
    TEST_ASSERT_EQUAL(BOARD_ERR_NULL, rc_serial_link_read_us(&link, NULL, 8u));
    TEST_ASSERT_EQUAL(BOARD_ERR_NULL, rc_serial_link_read_us(NULL, out, 8u));
    static const uint8_t one = 0x0Fu;
    rc_serial_link_poll(NULL, &one, 1u, 0u);
    rc_serial_link_poll(&link, NULL, 3u, 0u); /* nothing */
}

static void test_sbus_frames_to_pulses(void)
{
    uint8_t f[25];
    uint16_t out[8];
    TEST_ASSERT_EQUAL(BOARD_OK, rc_serial_link_init(&link, RC_SERIAL_SBUS, 100000u, 0u));
    sbus_frame(f, TICKS, 0u);
    rc_serial_link_poll(&link, f, 10u, 1000u); /* part of it */
    TEST_ASSERT_EQUAL(BOARD_ERR_NO_DATA, rc_serial_link_read_us(&link, out, 8u));
    rc_serial_link_poll(&link, &f[10], 15u, 2000u);
    TEST_ASSERT_EQUAL(BOARD_OK, rc_serial_link_read_us(&link, out, 8u));
    TEST_ASSERT_EQUAL_UINT16_ARRAY(PULSES, out, 8);
    TEST_ASSERT_EQUAL_UINT8(0u, link.lost);
    memset(out, 0, sizeof out);
    TEST_ASSERT_EQUAL(BOARD_ERR_NO_DATA, rc_serial_link_read_us(&link, out, 8u));
    TEST_ASSERT_EQUAL_UINT16_ARRAY(PULSES, out, 8); /* held */
    /* fewer channels asked: only those written */
    uint16_t three[4] = {7u, 7u, 7u, 7u};
    rc_serial_link_poll(&link, f, 25u, 9000u);
    TEST_ASSERT_EQUAL(BOARD_OK, rc_serial_link_read_us(&link, three, 3u));
    TEST_ASSERT_EQUAL_UINT16(2012u, three[2]);
    TEST_ASSERT_EQUAL_UINT16(7u, three[3]);
    TEST_ASSERT_EQUAL_UINT32(2u, link.frames_usable);
}

static void test_sbus_failsafe_and_frame_lost(void)
{
    uint8_t f[25];
    uint16_t out[8];
    uint16_t other[16];
    for (unsigned i = 0; i < 16u; ++i) {
        other[i] = 1811u;
    }
    TEST_ASSERT_EQUAL(BOARD_OK, rc_serial_link_init(&link, RC_SERIAL_SBUS, 100000u, 0u));
    sbus_frame(f, TICKS, 0u);
    rc_serial_link_poll(&link, f, 25u, 1000u);
    TEST_ASSERT_EQUAL(BOARD_OK, rc_serial_link_read_us(&link, out, 8u));
    /* frame lost: not fresh, the pulses stay the last usable ones */
    sbus_frame(f, other, SBUS_FLAG_FRAME_LOST);
    rc_serial_link_poll(&link, f, 25u, 8000u);
    TEST_ASSERT_EQUAL(BOARD_ERR_NO_DATA, rc_serial_link_read_us(&link, out, 8u));
    TEST_ASSERT_EQUAL_UINT16_ARRAY(PULSES, out, 8);
    TEST_ASSERT_EQUAL_UINT8(0u, link.lost);
    TEST_ASSERT_EQUAL_UINT32(1u, link.sbus_frame_lost);
    /* failsafe: not fresh, lost at once */
    sbus_frame(f, other, SBUS_FLAG_FAILSAFE | SBUS_FLAG_FRAME_LOST);
    rc_serial_link_poll(&link, f, 25u, 15000u);
    TEST_ASSERT_EQUAL(BOARD_ERR_NO_DATA, rc_serial_link_read_us(&link, out, 8u));
    TEST_ASSERT_EQUAL_UINT16_ARRAY(PULSES, out, 8);
    TEST_ASSERT_EQUAL_UINT8(1u, link.lost);
    TEST_ASSERT_EQUAL_UINT32(1u, link.sbus_failsafe);
    /* a usable frame then a failsafe one in the same poll: nothing fresh */
    uint8_t two[50];
    sbus_frame(two, TICKS, 0u);
    sbus_frame(&two[25], other, SBUS_FLAG_FAILSAFE);
    rc_serial_link_poll(&link, two, 50u, 22000u);
    TEST_ASSERT_EQUAL(BOARD_ERR_NO_DATA, rc_serial_link_read_us(&link, out, 8u));
    TEST_ASSERT_EQUAL_UINT8(1u, link.lost);
    /* back */
    sbus_frame(f, other, 0u);
    rc_serial_link_poll(&link, f, 25u, 29000u);
    TEST_ASSERT_EQUAL(BOARD_OK, rc_serial_link_read_us(&link, out, 8u));
    TEST_ASSERT_EQUAL_UINT16(2012u, out[0]);
    TEST_ASSERT_EQUAL_UINT8(0u, link.lost);
}

static void test_timeout(void)
{
    uint8_t f[25];
    TEST_ASSERT_EQUAL(BOARD_OK, rc_serial_link_init(&link, RC_SERIAL_SBUS, 100000u, 0u));
    sbus_frame(f, TICKS, 0u);
    rc_serial_link_poll(&link, f, 25u, 50000u);
    rc_serial_link_poll(&link, NULL, 0u, 150000u); /* exactly the timeout: not yet */
    TEST_ASSERT_EQUAL_UINT8(0u, link.lost);
    rc_serial_link_poll(&link, NULL, 0u, 150001u);
    TEST_ASSERT_EQUAL_UINT8(1u, link.lost);
    TEST_ASSERT_EQUAL_UINT32(1u, link.timeouts);
    rc_serial_link_poll(&link, NULL, 0u, 250001u);
    TEST_ASSERT_EQUAL_UINT32(1u, link.timeouts); /* counted once */
    /* garbage is not a frame: still lost */
    const uint8_t junk[5] = {1u, 2u, 3u, 4u, 5u};
    rc_serial_link_poll(&link, junk, 5u, 260000u);
    TEST_ASSERT_EQUAL_UINT8(1u, link.lost);
    /* the timeout across the 2^32 us wrap */
    TEST_ASSERT_EQUAL(BOARD_OK, rc_serial_link_init(&link, RC_SERIAL_SBUS, 100000u, 0u));
    rc_serial_link_poll(&link, f, 25u, 0xFFFF0000u);
    rc_serial_link_poll(&link, NULL, 0u, 0x00000100u); /* 65792 us later */
    TEST_ASSERT_EQUAL_UINT8(0u, link.lost);
    rc_serial_link_poll(&link, NULL, 0u, 0x00010000u + 100000u);
    TEST_ASSERT_EQUAL_UINT8(1u, link.lost);
}

/* The SBUS byte stream as the UART delivers it: frames every 7000 us, bytes
 * 120 us apart, the receiver joined start_byte bytes into a frame. Polls
 * every poll_us, each with the bytes that arrived since the previous one. */
static void run_sbus_stream(const uint8_t frame[25], unsigned start_byte, uint32_t poll_us,
                            uint32_t until_us)
{
    uint32_t sent = start_byte; /* bytes of the endless stream consumed */
    for (uint32_t now = poll_us; now <= until_us; now += poll_us) {
        uint8_t chunk[256];
        size_t n = 0u;
        for (;;) {
            const uint32_t k = sent % 25u;
            const uint32_t arrival = (sent / 25u) * 7000u + k * 120u + 120u;
            if (arrival > now || n == sizeof chunk) {
                break;
            }
            chunk[n++] = frame[k];
            sent++;
        }
        rc_serial_link_poll(&link, chunk, n, now);
    }
}

/* A frame whose data holds a false start byte (0x0F at frame byte 5) with
 * an allowed end byte (0x00) 24 bytes later (byte 4 of the next frame). */
static void false_phase_frame(uint8_t f[25], uint16_t ticks_out[16])
{
    uint8_t packed[22];
    for (unsigned i = 0; i < 22u; ++i) {
        packed[i] = (uint8_t)(0x21u + 3u * i); /* no 0x0F, no flag bits at [2] */
    }
    packed[2] = 0x20u; /* the false frame's flags byte: no frame-lost, no failsafe */
    packed[3] = 0x00u; /* frame byte 4: the false frame's end */
    packed[4] = 0x0Fu; /* frame byte 5: the false start */
    f[0] = 0x0Fu;
    memcpy(&f[1], packed, sizeof packed);
    f[23] = 0x00u;
    f[24] = 0x00u;
    rc_unpack_11bit(packed, ticks_out);
}

static void test_sbus_gap_breaks_false_phase(void)
{
    uint8_t f[25];
    uint16_t ticks[16];
    uint16_t out[8];
    false_phase_frame(f, ticks);
    /* polled every 500 us: the gaps are seen, the real frames decoded */
    TEST_ASSERT_EQUAL(BOARD_OK, rc_serial_link_init(&link, RC_SERIAL_SBUS, 100000u, 0u));
    run_sbus_stream(f, 1u, 500u, 70000u);
    TEST_ASSERT_TRUE(link.line_gaps >= 9u);
    TEST_ASSERT_EQUAL(BOARD_OK, rc_serial_link_read_us(&link, out, 8u));
    for (unsigned i = 0; i < 8u; ++i) {
        TEST_ASSERT_EQUAL_UINT16(rc_ticks_to_pulse_us(ticks[i]), out[i]);
    }
    TEST_ASSERT_EQUAL_UINT32(9u, link.frames_usable); /* frames 2..10; frame 1 was cut */

    /* polled only every 25 ms (the control tick): every poll finds bytes, no
     * gap is seen, and the decoder stays on the false phase - the reason for
     * polling faster (rc_serial_link.h). */
    TEST_ASSERT_EQUAL(BOARD_OK, rc_serial_link_init(&link, RC_SERIAL_SBUS, 100000u, 0u));
    run_sbus_stream(f, 1u, 25000u, 200000u);
    TEST_ASSERT_EQUAL_UINT32(0u, link.line_gaps);
    TEST_ASSERT_EQUAL(BOARD_OK, rc_serial_link_read_us(&link, out, 8u));
    TEST_ASSERT_NOT_EQUAL(rc_ticks_to_pulse_us(ticks[0]), out[0]);
}

/* The gap is taken once per idle spell, and only after RC_SERIAL_SBUS_GAP_US. */
static void test_sbus_gap_timing(void)
{
    uint8_t f[25];
    TEST_ASSERT_EQUAL(BOARD_OK, rc_serial_link_init(&link, RC_SERIAL_SBUS, 100000u, 0u));
    sbus_frame(f, TICKS, 0u);
    rc_serial_link_poll(&link, f, 12u, 10000u); /* half a frame */
    rc_serial_link_poll(&link, NULL, 0u, 10999u);
    TEST_ASSERT_EQUAL_UINT32(0u, link.line_gaps);
    TEST_ASSERT_EQUAL_UINT32(0u, link.sbus.counts.truncated);
    rc_serial_link_poll(&link, NULL, 0u, 11000u);
    TEST_ASSERT_EQUAL_UINT32(1u, link.line_gaps);
    TEST_ASSERT_EQUAL_UINT32(1u, link.sbus.counts.truncated); /* the half frame dropped */
    TEST_ASSERT_EQUAL_UINT8(0u, link.sbus.held);
    rc_serial_link_poll(&link, NULL, 0u, 12000u);
    TEST_ASSERT_EQUAL_UINT32(1u, link.line_gaps);
    /* without the gap the rest of the frame would complete it: dropped */
    rc_serial_link_poll(&link, &f[12], 13u, 13000u);
    TEST_ASSERT_EQUAL_UINT32(0u, link.frames_usable);
    rc_serial_link_poll(&link, NULL, 0u, 14500u);
    rc_serial_link_poll(&link, f, 25u, 17000u);
    TEST_ASSERT_EQUAL_UINT32(1u, link.frames_usable);
    /* CRSF never calls the SBUS gap */
    TEST_ASSERT_EQUAL(BOARD_OK, rc_serial_link_init(&link, RC_SERIAL_CRSF, 100000u, 0u));
    rc_serial_link_poll(&link, f, 3u, 100u);
    rc_serial_link_poll(&link, NULL, 0u, 50000u);
    TEST_ASSERT_EQUAL_UINT32(0u, link.line_gaps);
}

static void test_crsf_frames_and_link_stats(void)
{
    uint8_t c[26];
    uint8_t s[14];
    uint16_t out[8];
    TEST_ASSERT_EQUAL(BOARD_OK, rc_serial_link_init(&link, RC_SERIAL_CRSF, 100000u, 0u));
    crsf_channels(c, TICKS);
    rc_serial_link_poll(&link, c, 26u, 4000u);
    TEST_ASSERT_EQUAL(BOARD_OK, rc_serial_link_read_us(&link, out, 8u));
    TEST_ASSERT_EQUAL_UINT16_ARRAY(PULSES, out, 8);
    /* LQ 100: nothing changes */
    crsf_link_stats(s, 100u);
    rc_serial_link_poll(&link, s, 14u, 8000u);
    TEST_ASSERT_EQUAL_UINT8(0u, link.lost);
    /* LQ 0: lost; channel frames after it are held values */
    crsf_link_stats(s, 0u);
    rc_serial_link_poll(&link, s, 14u, 12000u);
    TEST_ASSERT_EQUAL_UINT8(1u, link.lost);
    TEST_ASSERT_EQUAL_UINT32(1u, link.crsf_lq_zero);
    uint16_t other[16];
    for (unsigned i = 0; i < 16u; ++i) {
        other[i] = 172u;
    }
    crsf_channels(c, other);
    rc_serial_link_poll(&link, c, 26u, 16000u);
    TEST_ASSERT_EQUAL(BOARD_ERR_NO_DATA, rc_serial_link_read_us(&link, out, 8u));
    TEST_ASSERT_EQUAL_UINT16_ARRAY(PULSES, out, 8);
    TEST_ASSERT_EQUAL_UINT32(1u, link.crsf_held);
    /* LQ back above 0: the next channel frame is fresh */
    crsf_link_stats(s, 80u);
    rc_serial_link_poll(&link, s, 14u, 20000u);
    TEST_ASSERT_EQUAL(BOARD_ERR_NO_DATA, rc_serial_link_read_us(&link, out, 8u));
    rc_serial_link_poll(&link, c, 26u, 24000u);
    TEST_ASSERT_EQUAL(BOARD_OK, rc_serial_link_read_us(&link, out, 8u));
    TEST_ASSERT_EQUAL_UINT16(988u, out[0]);
    TEST_ASSERT_EQUAL_UINT8(0u, link.lost);
    /* a corrupted CRC: not a frame */
    c[25] ^= 0xFFu;
    rc_serial_link_poll(&link, c, 26u, 28000u);
    TEST_ASSERT_EQUAL(BOARD_ERR_NO_DATA, rc_serial_link_read_us(&link, out, 8u));
    /* silence: lost after the timeout */
    rc_serial_link_poll(&link, NULL, 0u, 124001u);
    TEST_ASSERT_EQUAL_UINT8(1u, link.lost);
    TEST_ASSERT_EQUAL_UINT32(1u, link.timeouts);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_init);
    RUN_TEST(test_sbus_frames_to_pulses);
    RUN_TEST(test_sbus_failsafe_and_frame_lost);
    RUN_TEST(test_timeout);
    RUN_TEST(test_sbus_gap_breaks_false_phase);
    RUN_TEST(test_sbus_gap_timing);
    RUN_TEST(test_crsf_frames_and_link_stats);
    return UNITY_END();
}
