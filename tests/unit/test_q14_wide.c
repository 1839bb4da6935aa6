/*
 * Unit tests of the wide multiply: q_mul32 (the core's choice: a hardware
 * 32x32->64 multiply where q14_target.h selects one) and q_mul32_portable
 * (four 16x16 partial products, what the dsPIC and the Cortex-M0 run), and
 * of q_mul32x16 / q_mul32x16_portable (int16 second factor, shifts 1..46:
 * exact reference and the same bits as q_mul32).
 *
 * For every shift in [1, 62]: 10^6 random pairs (2.5e5 in the HT_PORTABLE_ONLY
 * build) from a mixture (uniform, every magnitude, powers of two and their
 * neighbours, INT32_MIN/MAX, 0, +-1),
 * 20000 constructed exact ties (product == odd * 2^(shift-1), both signs) and
 * their +-1 neighbours, and every pair of a 40-value edge set. Both functions
 * are compared with an exact __int128 reference, floor((a*b + 2^(shift-1)) /
 * 2^shift) saturated to int32 (C division plus a correction, no shift), and
 * with each other bit for bit.
 *
 * tests/math builds the same file against a copy of the library compiled with
 * HT_PORTABLE_ONLY=1 (there q_mul32 is the portable code).
 */
#include "unity.h"

#include "helical/math/q14.h"

#include "q14_test_rng.h"

#include <inttypes.h>
#include <stdio.h>

#ifndef HT_PORTABLE_ONLY
#define HT_PORTABLE_ONLY 0
#endif
/* The test is compiled with the same HT_PORTABLE_ONLY as the library it links
 * (tests/math passes it to both), so this reports the path under test. */
#include "../../src/math/q14_target.h"

__extension__ typedef __int128 q14t_i128;

void setUp(void) {}
void tearDown(void) {}

static int32_t ref_mul32(int32_t a, int32_t b, unsigned shift)
{
    q14t_i128 p = (q14t_i128)a * (q14t_i128)b + ((q14t_i128)1 << (shift - 1u));
    q14t_i128 d = (q14t_i128)1 << shift;
    q14t_i128 q = p / d;
    if ((p % d) != 0 && p < 0) {
        q -= 1; /* floor */
    }
    if (q > INT32_MAX) {
        return INT32_MAX;
    }
    if (q < INT32_MIN) {
        return INT32_MIN;
    }
    return (int32_t)q;
}

typedef struct {
    q14t_check_t fast;     /* q_mul32 vs reference */
    q14t_check_t portable; /* q_mul32_portable vs reference */
    q14t_check_t same;     /* q_mul32 vs q_mul32_portable, bit for bit */
    q14t_check_t fit;      /* q_mul32_fit and q_mul32_fit_portable vs reference, where it fits */
    long long ties;        /* cases whose exact quotient ends in exactly 1/2 */
    long long saturated;   /* cases whose exact quotient does not fit an int32 */
} wide_checks_t;

static void record(q14t_check_t *c, const char *fn, int32_t a, int32_t b, unsigned shift,
                   int32_t got, int32_t want)
{
    c->cases++;
    if (got != want && c->failures++ == 0) {
        snprintf(c->first, sizeof c->first,
                 "%s(%" PRId32 ", %" PRId32 ", %u) = %" PRId32 ", expected %" PRId32, fn, a, b,
                 shift, got, want);
    }
}

static void check_wide(wide_checks_t *w, int32_t a, int32_t b, unsigned shift)
{
    int32_t want = ref_mul32(a, b, shift);
    int32_t fast = q_mul32(a, b, shift);
    int32_t port = q_mul32_portable(a, b, shift);
    record(&w->fast, "q_mul32", a, b, shift, fast, want);
    record(&w->portable, "q_mul32_portable", a, b, shift, port, want);
    record(&w->same, "q_mul32 vs q_mul32_portable", a, b, shift, fast, port);
    if (shift <= 46u && want != INT32_MAX && want != INT32_MIN) {
        /* the _fit forms promise the same bits whenever the result fits */
        record(&w->fit, "q_mul32_fit", a, b, shift, q_mul32_fit(a, b, shift), want);
        record(&w->fit, "q_mul32_fit_portable", a, b, shift, q_mul32_fit_portable(a, b, shift),
               want);
    }
    q14t_i128 p = (q14t_i128)a * (q14t_i128)b;
    q14t_i128 mask = ((q14t_i128)1 << shift) - 1;
    if ((p & mask) == ((q14t_i128)1 << (shift - 1u))) {
        w->ties++;
    }
    if (want == INT32_MAX || want == INT32_MIN) {
        w->saturated++;
    }
}

static const int32_t edges[] = {INT32_MIN,   INT32_MIN + 1,
                                -1073741825, -1073741824,
                                -1073741823, -65537,
                                -65536,      -65535,
                                -32769,      -32768,
                                -32767,      -3,
                                -2,          -1,
                                0,           1,
                                2,           3,
                                32767,       32768,
                                32769,       65535,
                                65536,       65537,
                                46340,       46341,
                                -46341,      1073741823,
                                1073741824,  1073741825,
                                0x55555555,  -0x55555555,
                                0x7FFF0000,  0x0000FFFF,
                                0x00010001,  0x7FFFFFFE,
                                INT32_MAX,   -1518500250,
                                1518500250,  2147418112};

/* One factor oa * 2^i with oa odd, |value| <= 2^31 (2^31 only as INT32_MIN). */
static int32_t odd_times_pow2(uint64_t *rng, unsigned i, int small)
{
    if (i == 31u) {
        return INT32_MIN;
    }
    uint32_t o = (q14t_u32(rng) >> (i + 1u)) | 1u; /* odd, o * 2^i < 2^31 */
    if (small) {
        o = (o & 0xFFu) | 1u;
    }
    int32_t v = (int32_t)(o << i);
    return q14t_below(rng, 2u) ? -v : v;
}

/* A product that is exactly odd * 2^(shift-1): a = oa * 2^i, b = ob * 2^j, i + j = shift - 1. */
static void make_tie(uint64_t *rng, unsigned shift, int32_t *a, int32_t *b)
{
    unsigned total = shift - 1u; /* in [0, 61] */
    unsigned lo = (total > 31u) ? total - 31u : 0u;
    unsigned hi = (total < 31u) ? total : 31u;
    unsigned i = lo + q14t_below(rng, hi - lo + 1u);
    /* Small odd factors half of the time (ties that do not saturate). */
    int small = (int)q14t_below(rng, 2u);
    *a = odd_times_pow2(rng, i, small);
    *b = odd_times_pow2(rng, total - i, small);
}

static void run_wide(const char *label, long pairs_per_shift)
{
    wide_checks_t w;
    q14t_check_init(&w.fast, "q_mul32 == exact");
    q14t_check_init(&w.portable, "q_mul32_portable == exact");
    q14t_check_init(&w.same, "q_mul32 == q_mul32_portable");
    q14t_check_init(&w.fit, "q_mul32_fit == q_mul32_fit_portable == exact (where it fits)");
    w.ties = 0;
    w.saturated = 0;
    uint64_t rng = 0x3132ull;
    const int n_edges = (int)(sizeof edges / sizeof edges[0]);
    double t0 = q14t_seconds();
    for (unsigned shift = 1u; shift <= 62u; shift++) {
        for (int i = 0; i < n_edges; i++) {
            for (int j = 0; j < n_edges; j++) {
                check_wide(&w, edges[i], edges[j], shift);
            }
        }
        for (long k = 0; k < pairs_per_shift; k++) {
            check_wide(&w, q14t_i32_mixed(&rng), q14t_i32_mixed(&rng), shift);
        }
        for (int k = 0; k < 20000; k++) {
            int32_t a;
            int32_t b;
            make_tie(&rng, shift, &a, &b);
            check_wide(&w, a, b, shift);
            /* The neighbours of the tie: (a +- 1) * b. */
            if (a != INT32_MAX) {
                check_wide(&w, a + 1, b, shift);
            }
            if (a != INT32_MIN) {
                check_wide(&w, a - 1, b, shift);
            }
        }
    }
    /* The ties of shift 1 and the saturation edges, spelled out. */
    TEST_ASSERT_EQUAL_INT32(2, q_mul32(3, 1, 1));   /* 1.5 -> 2 */
    TEST_ASSERT_EQUAL_INT32(-1, q_mul32(-3, 1, 1)); /* -1.5 -> -1 (toward +inf) */
    TEST_ASSERT_EQUAL_INT32(-1, q_mul32_portable(-3, 1, 1));
    TEST_ASSERT_EQUAL_INT32(0, q_mul32_portable(-1, 1, 1)); /* -0.5 -> 0 */
    TEST_ASSERT_EQUAL_INT32(INT32_MAX, q_mul32_portable(INT32_MIN, INT32_MIN, 31));
    TEST_ASSERT_EQUAL_INT32(1073741824, q_mul32_portable(INT32_MIN, INT32_MIN, 32));
    TEST_ASSERT_EQUAL_INT32(1, q_mul32_portable(INT32_MIN, INT32_MIN, 62));
    TEST_ASSERT_EQUAL_INT32(-1073741824, q_mul32_portable(INT32_MIN, 1, 1));
    TEST_ASSERT_EQUAL_INT32(INT32_MIN, q_mul32_portable(INT32_MIN, INT32_MAX, 30));
    TEST_ASSERT_EQUAL_INT32(INT32_MIN, q_mul32(INT32_MIN, INT32_MAX, 30));
    printf("[q14] %s: q_mul32 path = %s; %.2f s; ties=%lld saturated=%lld\n", label,
           Q_TARGET_HAS_MUL64 ? "hardware 32x32->64 (int64)" : "portable (16x16 partials)",
           q14t_seconds() - t0, w.ties, w.saturated);
    printf("[q14] worst error of both vs exact: 0 LSB required (bit-exact)\n");
    q14t_check_report(&w.fast);
    q14t_check_report(&w.portable);
    q14t_check_report(&w.same);
    q14t_check_report(&w.fit);
}

static void test_q_mul32_and_portable_vs_exact_all_shifts(void)
{
    /* 10^6 random pairs per shift against the default library. In the
     * HT_PORTABLE_ONLY build (tests/math) q_mul32 is the same portable code
     * that test_q14_wide checks against the exact reference with the full
     * count, so a quarter of it keeps the runtime down. */
    run_wide(HT_PORTABLE_ONLY ? "HT_PORTABLE_ONLY=1 library" : "default library",
             HT_PORTABLE_ONLY ? 250000L : 1000000L);
}

/* ---- q_mul32x16 / q_mul32x16_portable ------------------------------------------ */

/* An int16 factor ob * 2^j, ob odd, j in [0, 15] (2^15 only as INT16_MIN). */
static int16_t odd16_times_pow2(uint64_t *rng, unsigned j, int small)
{
    if (j == 15u) {
        return INT16_MIN;
    }
    uint32_t o = ((q14t_u32(rng) & 0xFFFFu) >> (j + 1u)) | 1u; /* o * 2^j < 2^15 */
    if (small) {
        o = (o & 0xFu) | 1u;
    }
    int32_t v = (int32_t)(o << j);
    return (int16_t)(q14t_below(rng, 2u) ? -v : v);
}

static const int16_t edges16[] = {
    INT16_MIN, INT16_MIN + 1, -16385, -16384, -256,  -3,       -2, -1, 0, 1, 2,
    3,         255,           16384,  16385,  32766, INT16_MAX};

static void test_q_mul32x16_and_portable_vs_exact_all_shifts(void)
{
    wide_checks_t w;
    q14t_check_init(&w.fast, "q_mul32x16 == exact");
    q14t_check_init(&w.portable, "q_mul32x16_portable == exact");
    q14t_check_init(&w.same, "q_mul32x16 == portable == q_mul32");
    q14t_check_init(&w.fit, "(the _fit forms are checked by run_wide)");
    w.ties = 0;
    w.saturated = 0;
    uint64_t rng = 0x3216ull;
    const int n_edges = (int)(sizeof edges / sizeof edges[0]);
    const int n_edges16 = (int)(sizeof edges16 / sizeof edges16[0]);
    double t0 = q14t_seconds();
    for (unsigned shift = 1u; shift <= 46u; shift++) {
        for (long k = 0; k < 200000L + (long)n_edges * n_edges16; k++) {
            int32_t a;
            int16_t b;
            if (k < (long)n_edges * n_edges16) {
                a = edges[k / n_edges16];
                b = edges16[k % n_edges16];
            } else if ((k & 7) == 0) {
                /* An exact tie: a * b == odd * 2^(shift-1). */
                unsigned total = shift - 1u;
                unsigned lo = (total > 31u) ? total - 31u : 0u;
                unsigned hi = (total < 15u) ? total : 15u;
                unsigned j = lo + q14t_below(&rng, hi - lo + 1u);
                int small = (int)q14t_below(&rng, 2u);
                b = odd16_times_pow2(&rng, j, small);
                a = odd_times_pow2(&rng, total - j, small);
                if (q14t_below(&rng, 4u) == 0u && a != INT32_MAX) {
                    a += 1; /* a neighbour of the tie */
                }
            } else {
                a = q14t_i32_mixed(&rng);
                b = q14t_i16_mixed(&rng);
            }
            int32_t want = ref_mul32(a, b, shift);
            int32_t fast = q_mul32x16(a, b, shift);
            int32_t port = q_mul32x16_portable(a, b, shift);
            int32_t wide = q_mul32(a, b, shift);
            record(&w.fast, "q_mul32x16", a, b, shift, fast, want);
            record(&w.portable, "q_mul32x16_portable", a, b, shift, port, want);
            record(&w.same, "q_mul32x16 vs portable", a, b, shift, fast, port);
            record(&w.same, "q_mul32x16_portable vs q_mul32", a, b, shift, port, wide);
            q14t_i128 p = (q14t_i128)a * b;
            if ((p & (((q14t_i128)1 << shift) - 1)) == ((q14t_i128)1 << (shift - 1u))) {
                w.ties++;
            }
            if (want == INT32_MAX || want == INT32_MIN) {
                w.saturated++;
            }
        }
    }
    printf("[q14] q_mul32x16: shifts 1..46, %.2f s; ties=%lld saturated=%lld\n",
           q14t_seconds() - t0, w.ties, w.saturated);
    TEST_ASSERT_EQUAL_INT32(INT32_MAX, q_mul32x16_portable(INT32_MIN, INT16_MIN, 1));
    TEST_ASSERT_EQUAL_INT32(1073741824, q_mul32x16_portable(INT32_MIN, INT16_MIN, 16));
    TEST_ASSERT_EQUAL_INT32(1, q_mul32x16_portable(INT32_MIN, INT16_MIN, 46));
    TEST_ASSERT_EQUAL_INT32(0, q_mul32x16_portable(-1, 1, 1));         /* -0.5 -> 0 */
    TEST_ASSERT_EQUAL_INT32(-1, q_mul32x16_portable(-3, 1, 1));        /* -1.5 -> -1 */
    TEST_ASSERT_EQUAL_INT32(-1, q_mul32x16_portable(-3, 1 << 14, 16)); /* -0.75 -> -1 */
    q14t_check_report(&w.fast);
    q14t_check_report(&w.portable);
    q14t_check_report(&w.same);
}

int main(void)
{
    double t0 = q14t_seconds();
    UNITY_BEGIN();
    RUN_TEST(test_q_mul32_and_portable_vs_exact_all_shifts);
    RUN_TEST(test_q_mul32x16_and_portable_vs_exact_all_shifts);
    int rc = UNITY_END();
    printf("[q14] test_q14_wide runtime %.2f s\n", q14t_seconds() - t0);
    return rc;
}
