/*
 * test_fw_log_f32.c - the PARM value's binary32 (log_f32.c) against the
 * host's division: every 16-bit raw value and a seeded sweep of 32-bit ones
 * at each scale of the parameter table (1, 100, 1000, 16384, 65536), and the
 * int32 edges. The host divides in double and rounds to float; for the
 * powers of two the double is exact, and for 100 and 1000 a quotient
 * num / den is never a float tie (a tie is a dyadic rational, and num / den
 * with 5 in den is not one unless exact), so its double cannot land on one
 * either: the host's bits are the correctly rounded ones.
 */
#include "unity.h"

#include "helical/math/f32_bits.h"

#include <stdint.h>
#include <stdio.h>
#include <string.h>

void setUp(void) {}
void tearDown(void) {}

static uint32_t host_ratio(int64_t num, uint32_t den)
{
    const float f = (float)((double)num / (double)den);
    uint32_t b;
    memcpy(&b, &f, sizeof b);
    return b;
}

static const uint32_t k_scales[] = {1u, 100u, 1000u, 16384u, 65536u};

static uint64_t rng = 0x9E3779B97F4A7C15ull;
static uint32_t next_u32(void)
{
    rng ^= rng << 13u;
    rng ^= rng >> 7u;
    rng ^= rng << 17u;
    return (uint32_t)(rng >> 16u);
}

static void check(int64_t num, uint32_t den)
{
    const uint32_t want = host_ratio(num, den);
    const uint32_t got = ht_f32_from_ratio(num, den);
    if (want != got) {
        char msg[96];
        (void)snprintf(msg, sizeof msg, "%lld / %u", (long long)num, den);
        TEST_ASSERT_EQUAL_HEX32_MESSAGE(want, got, msg);
    }
}

static void test_every_16_bit_value_at_every_scale(void)
{
    for (size_t k = 0u; k < sizeof k_scales / sizeof k_scales[0]; ++k) {
        for (int32_t v = -65536; v <= 65535; ++v) {
            check(v, k_scales[k]);
        }
    }
}

static void test_seeded_32_bit_sweep(void)
{
    for (int i = 0; i < 2000000; ++i) {
        const int32_t v = (int32_t)next_u32();
        check(v, k_scales[(unsigned)i % 5u]);
    }
}

static void test_edges(void)
{
    const int64_t edges[] = {
        INT32_MIN, INT32_MIN + 1, INT32_MAX, INT32_MAX - 1, 16777215, 16777216, 16777217,
        16777218,  16777219,      -16777217, 33554431,      33554433, 1,        -1};
    for (size_t k = 0u; k < sizeof k_scales / sizeof k_scales[0]; ++k) {
        for (size_t i = 0u; i < sizeof edges / sizeof edges[0]; ++i) {
            check(edges[i], k_scales[k]);
        }
    }
    /* the ties of the 24-bit mantissa go to even: 2^24 + 1 -> 2^24, + 3 -> + 4 */
    TEST_ASSERT_EQUAL_HEX32(0x4B800000u, ht_f32_from_ratio(16777217, 1u));
    TEST_ASSERT_EQUAL_HEX32(0x4B800002u, ht_f32_from_ratio(16777219, 1u));
    /* zero and a zero denominator are +0, never a NaN */
    TEST_ASSERT_EQUAL_HEX32(0u, ht_f32_from_ratio(0, 100u));
    TEST_ASSERT_EQUAL_HEX32(0u, ht_f32_from_ratio(5, 0u));
    /* 0.1 m/s as cm: 10 / 100 is the float nearest 0.1 */
    TEST_ASSERT_EQUAL_HEX32(0x3DCCCCCDu, ht_f32_from_ratio(10, 100u));
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_every_16_bit_value_at_every_scale);
    RUN_TEST(test_seeded_32_bit_sweep);
    RUN_TEST(test_edges);
    return UNITY_END();
}
