/*
 * The 11-bit channel packing and the ticks-to-microseconds mapping shared by
 * CRSF and SBUS (src/protocols/rc_channels.c): every one of the 2048 values against a
 * double-precision evaluation of 1500 + (ticks - 992) * 5 / 8 rounded half
 * up, the documented anchors, and unpacking against a bit-by-bit packer.
 */
#include "frame_test_util.h"
#include "helical/protocols/rc_channels.h"
#include "unity.h"

void setUp(void) {}
void tearDown(void) {}

static void test_pulse_all_2048_values_match_the_double_reference(void)
{
    for (unsigned t = 0; t <= 2047u; t++) {
        long want = ft_pulse_ref(t);
        TEST_ASSERT_EQUAL_INT_MESSAGE(want, rc_ticks_to_pulse_us((uint16_t)t), "ticks");
    }
}

static void test_pulse_anchors_and_range(void)
{
    TEST_ASSERT_EQUAL_UINT16(988, rc_ticks_to_pulse_us(172));   /* 987.5 rounds up */
    TEST_ASSERT_EQUAL_UINT16(1500, rc_ticks_to_pulse_us(992));  /* exact */
    TEST_ASSERT_EQUAL_UINT16(2012, rc_ticks_to_pulse_us(1811)); /* 2011.875 */
    TEST_ASSERT_EQUAL_UINT16(999, rc_ticks_to_pulse_us(191));   /* 999.375 */
    TEST_ASSERT_EQUAL_UINT16(2000, rc_ticks_to_pulse_us(1792)); /* 2000 */
    TEST_ASSERT_EQUAL_UINT16(RC_PULSE_US_AT_TICKS0, rc_ticks_to_pulse_us(0));
    TEST_ASSERT_EQUAL_UINT16(RC_PULSE_US_AT_MAX, rc_ticks_to_pulse_us(2047));
    /* bits above the 11th are ignored */
    TEST_ASSERT_EQUAL_UINT16(1500, rc_ticks_to_pulse_us((uint16_t)(992u | 0xF800u)));
    /* monotonic, steps of 0 or 1 us */
    for (unsigned t = 1; t <= 2047u; t++) {
        unsigned d = (unsigned)(rc_ticks_to_pulse_us((uint16_t)t) -
                                rc_ticks_to_pulse_us((uint16_t)(t - 1u)));
        TEST_ASSERT_TRUE(d <= 1u);
    }
}

static void test_unpack_matches_bitwise_packer_and_pack_round_trips(void)
{
    uint64_t s = 11;
    for (int trial = 0; trial < 20000; trial++) {
        uint16_t in[16], out[16];
        uint8_t ref[22], mine[22];
        for (int k = 0; k < 16; k++) {
            in[k] = (uint16_t)ft_below(&s, 2048u);
        }
        ft_pack11(in, ref);
        rc_unpack_11bit(ref, out);
        TEST_ASSERT_EQUAL_UINT16_ARRAY(in, out, 16);
        rc_pack_11bit(in, mine);
        TEST_ASSERT_EQUAL_UINT8_ARRAY(ref, mine, 22);
    }
}

static void test_unpack_single_bits(void)
{
    /* bit i of the 176 set alone lands in channel i / 11 as 1 << (i % 11) */
    for (unsigned i = 0; i < 176u; i++) {
        uint8_t p[22] = {0};
        uint16_t out[16];
        p[i / 8u] = (uint8_t)(1u << (i % 8u));
        rc_unpack_11bit(p, out);
        for (unsigned k = 0; k < 16u; k++) {
            const unsigned bit = (k == i / 11u) ? (1u << (i % 11u)) : 0u; /* < 2^11 */
            const uint16_t want = (uint16_t)bit;
            TEST_ASSERT_EQUAL_UINT16(want, out[k]);
        }
    }
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_pulse_all_2048_values_match_the_double_reference);
    RUN_TEST(test_pulse_anchors_and_range);
    RUN_TEST(test_unpack_matches_bitwise_packer_and_pack_round_trips);
    RUN_TEST(test_unpack_single_bits);
    return UNITY_END();
}
