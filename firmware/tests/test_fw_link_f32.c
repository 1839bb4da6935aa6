/*
 * test_fw_link_f32.c - the link's binary32 conversions without float
 * (fw_link_f32.c) against the host's float conversion: exhaustively over
 * the 16-bit fixed formats, at every binary32 exponent, at the rounding
 * ties and the saturation edges, and a fixed-seed random sweep.
 */
#include "unity.h"

#include "link/fw_link.h"

#include <math.h>
#include <string.h>

void setUp(void) {}
void tearDown(void) {}

static uint32_t bits_of(float f)
{
    uint32_t b;
    memcpy(&b, &f, sizeof b);
    return b;
}

static float float_of(uint32_t b)
{
    float f;
    memcpy(&f, &b, sizeof f);
    return f;
}

/* the host: num / den in double (exact or within 2^-53), then to float
 * (round to nearest even; no double rounding can reach a float tie for
 * these denominators: docs in the test's header) */
static uint32_t host_ratio(int64_t num, uint32_t den)
{
    return bits_of((float)((double)num / (double)den));
}

static uint64_t rng = 0x243F6A8885A308D3ull;
static uint64_t next_random(void)
{
    rng ^= rng << 13u;
    rng ^= rng >> 7u;
    rng ^= rng << 17u;
    return rng;
}

static void test_ratio_exhaustive_16_bit_formats(void)
{
    static const uint32_t dens[] = {1u, 100u, 1000u, 16384u, 65536u};
    uint32_t bad = 0u;
    for (unsigned d = 0u; d < sizeof dens / sizeof dens[0]; ++d) {
        for (int32_t raw = INT16_MIN; raw <= INT16_MAX; ++raw) {
            if (ht_f32_from_ratio(raw, dens[d]) != host_ratio(raw, dens[d])) {
                ++bad;
            }
        }
    }
    TEST_ASSERT_EQUAL_UINT32(0u, bad);
    TEST_ASSERT_EQUAL_HEX32(0u, ht_f32_from_ratio(0, 100u)); /* +0 */
}

static void test_ratio_random_int32_and_wide_numerators(void)
{
    static const uint32_t dens[] = {1u, 3u, 7u, 100u, 1000u, 16384u, 65536u, 1u << 30u, 999999937u};
    uint32_t bad = 0u;
    for (unsigned k = 0u; k < 2000000u; ++k) {
        const uint32_t den = dens[k % (sizeof dens / sizeof dens[0])];
        const uint64_t r = next_random();
        const unsigned width =
            (unsigned)(r >> 58u) + 2u; /* 2 .. 65 bits, clipped to 53: exact in double */
        int64_t num = (int64_t)(next_random() >> (64u - ((width > 53u) ? 53u : width)));
        if ((r & 1u) != 0u) {
            num = -num;
        }
        if (ht_f32_from_ratio(num, den) != host_ratio(num, den)) {
            ++bad;
        }
    }
    TEST_ASSERT_EQUAL_UINT32(0u, bad);
}

static void test_ratio_ties_round_to_even(void)
{
    /* 2^24 + 1 and 2^24 + 3 are ties between two floats */
    TEST_ASSERT_EQUAL_HEX32(bits_of(16777216.0f), ht_f32_from_ratio(16777217, 1u));
    TEST_ASSERT_EQUAL_HEX32(bits_of(16777220.0f), ht_f32_from_ratio(16777219, 1u));
    TEST_ASSERT_EQUAL_HEX32(bits_of(-16777216.0f), ht_f32_from_ratio(-16777217, 1u));
    /* just above a tie rounds up */
    TEST_ASSERT_EQUAL_HEX32(bits_of(16777218.0f), ht_f32_from_ratio(2 * 16777217 + 1, 2u));
    /* carry into the exponent: 2^25 - 1 -> 2^25 */
    TEST_ASSERT_EQUAL_HEX32(bits_of(33554432.0f), ht_f32_from_ratio(33554431, 1u));
    TEST_ASSERT_EQUAL_HEX32(host_ratio(INT32_MIN, 1u), ht_f32_from_ratio(INT32_MIN, 1u));
    TEST_ASSERT_EQUAL_HEX32(host_ratio(INT32_MAX, 65536u), ht_f32_from_ratio(INT32_MAX, 65536u));
}

/* the reference: value * scale, rounded half away from zero, saturated */
static int host_to_fixed(uint32_t b, int32_t scale, int32_t *out)
{
    const float f = float_of(b);
    if (isnan(f) || isinf(f)) {
        return -1;
    }
    const double v = (double)f * (double)scale; /* exact: 24 + 21 bits */
    const double r = round(v);                  /* half away from zero */
    if (r > (double)INT32_MAX) {
        *out = INT32_MAX;
        return 1;
    }
    if (r < (double)INT32_MIN) {
        *out = INT32_MIN;
        return 1;
    }
    *out = (int32_t)r;
    return 0;
}

static void check_to_fixed(uint32_t b, int32_t scale, uint32_t *bad)
{
    int32_t a = 12345;
    int32_t h = 12345;
    const int sa = ht_f32_to_fixed(b, scale, &a);
    const int sh = host_to_fixed(b, scale, &h);
    if ((sa != sh) || (a != h)) {
        ++*bad;
    }
}

static void test_to_fixed_every_exponent_and_random_mantissas(void)
{
    static const int32_t scales[] = {1, 100, 1000, 16384, 65536, 1 << 20};
    uint32_t bad = 0u;
    for (uint32_t e = 0u; e < 256u; ++e) {
        for (unsigned k = 0u; k < 4000u; ++k) {
            const uint32_t mant = (k < 4u) ? (uint32_t)(k * 0x2AAAAAu) : (uint32_t)next_random();
            const uint32_t b = ((uint32_t)(k & 1u) << 31u) | (e << 23u) | (mant & 0x7FFFFFu);
            check_to_fixed(b, scales[k % 6u], &bad);
        }
    }
    TEST_ASSERT_EQUAL_UINT32(0u, bad);
}

static void test_to_fixed_edges(void)
{
    int32_t v = 7;
    TEST_ASSERT_EQUAL_INT(-1, ht_f32_to_fixed(bits_of(NAN), 100, &v));
    TEST_ASSERT_EQUAL_INT(-1, ht_f32_to_fixed(bits_of(INFINITY), 100, &v));
    TEST_ASSERT_EQUAL_INT(-1, ht_f32_to_fixed(bits_of(-INFINITY), 100, &v));
    TEST_ASSERT_EQUAL_INT32(7, v); /* untouched */
    TEST_ASSERT_EQUAL_INT(0, ht_f32_to_fixed(bits_of(-0.0f), 100, &v));
    TEST_ASSERT_EQUAL_INT32(0, v);
    /* ties: half away from zero */
    TEST_ASSERT_EQUAL_INT(0, ht_f32_to_fixed(bits_of(0.5f), 1, &v));
    TEST_ASSERT_EQUAL_INT32(1, v);
    TEST_ASSERT_EQUAL_INT(0, ht_f32_to_fixed(bits_of(-2.5f), 1, &v));
    TEST_ASSERT_EQUAL_INT32(-3, v);
    TEST_ASSERT_EQUAL_INT(0, ht_f32_to_fixed(bits_of(0.49999997f), 1, &v));
    TEST_ASSERT_EQUAL_INT32(0, v);
    /* saturation at the int32 ends, exactly */
    TEST_ASSERT_EQUAL_INT(0, ht_f32_to_fixed(bits_of(-2147483648.0f), 1, &v));
    TEST_ASSERT_EQUAL_INT32(INT32_MIN, v);
    TEST_ASSERT_EQUAL_INT(1, ht_f32_to_fixed(bits_of(2147483648.0f), 1, &v));
    TEST_ASSERT_EQUAL_INT32(INT32_MAX, v);
    TEST_ASSERT_EQUAL_INT(1, ht_f32_to_fixed(bits_of(-3e38f), 65536, &v));
    TEST_ASSERT_EQUAL_INT32(INT32_MIN, v);
    TEST_ASSERT_EQUAL_INT(1, ht_f32_to_fixed(bits_of(40000.0f), 65536, &v));
    TEST_ASSERT_EQUAL_INT32(INT32_MAX, v);
    /* the smallest subnormal is 0 */
    TEST_ASSERT_EQUAL_INT(0, ht_f32_to_fixed(1u, 65536, &v));
    TEST_ASSERT_EQUAL_INT32(0, v);
    /* a bad scale is refused */
    TEST_ASSERT_EQUAL_INT(-1, ht_f32_to_fixed(bits_of(1.0f), 0, &v));
}

static void test_round_trip_every_16_bit_raw(void)
{
    static const int32_t scales[] = {1, 100, 1000, 16384, 65536};
    uint32_t bad = 0u;
    for (unsigned s = 0u; s < 5u; ++s) {
        for (int32_t raw = INT16_MIN; raw <= INT16_MAX; ++raw) {
            int32_t back = 0;
            if ((ht_f32_to_fixed(ht_f32_from_ratio(raw, (uint32_t)scales[s]), scales[s], &back) !=
                 0) ||
                (back != raw)) {
                ++bad;
            }
        }
    }
    TEST_ASSERT_EQUAL_UINT32(0u, bad);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_ratio_exhaustive_16_bit_formats);
    RUN_TEST(test_ratio_random_int32_and_wide_numerators);
    RUN_TEST(test_ratio_ties_round_to_even);
    RUN_TEST(test_to_fixed_every_exponent_and_random_mantissas);
    RUN_TEST(test_to_fixed_edges);
    RUN_TEST(test_round_trip_every_16_bit_raw);
    return UNITY_END();
}
