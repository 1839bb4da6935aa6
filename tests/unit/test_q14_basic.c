/*
 * Unit tests of the saturating and rounding primitives of q14.h:
 * q_sat16, q_clamp32, q14_add_sat, q14_sub_sat, q_add_sat32, q_sub_sat32,
 * q_rshift_round, q14_mul and the Q*_FROM_REAL macros.
 *
 * Every result is compared bit for bit with an exact reference computed in
 * int64 (floor division by C '/' plus a correction, never a shift), so the
 * only allowed error is zero. Each test prints its case count.
 */
#include "unity.h"

#include "helical/math/q14.h"

#include "q14_test_rng.h"

#include <inttypes.h>
#include <stdio.h>

void setUp(void) {}
void tearDown(void) {}

/* Edge values of int32 used by several sweeps. */
static const int32_t edges32[] = {INT32_MIN,
                                  INT32_MIN + 1,
                                  INT32_MIN + 2,
                                  INT32_MIN / 2,
                                  -1073741825,
                                  -65537,
                                  -65536,
                                  -32769,
                                  -32768,
                                  -32767,
                                  -16384,
                                  -3,
                                  -2,
                                  -1,
                                  0,
                                  1,
                                  2,
                                  3,
                                  16384,
                                  32766,
                                  32767,
                                  32768,
                                  32769,
                                  65535,
                                  65536,
                                  1073741823,
                                  1073741824,
                                  INT32_MAX / 2,
                                  INT32_MAX - 2,
                                  INT32_MAX - 1,
                                  INT32_MAX};
#define N_EDGES32 ((int)(sizeof edges32 / sizeof edges32[0]))

/* ---- q_sat16 --------------------------------------------------------------- */

static void check_sat16(q14t_check_t *c, int32_t x)
{
    int16_t want = q14t_sat16(x);
    int16_t got = q_sat16(x);
    c->cases++;
    if (got != want && c->failures++ == 0) {
        snprintf(c->first, sizeof c->first, "q_sat16(%" PRId32 ") = %d, expected %d", x, got, want);
    }
}

static void test_q_sat16_all_int16_and_int32_sweep(void)
{
    q14t_check_t c;
    q14t_check_init(&c, "q_sat16");
    /* Every value in [-2^17, 2^17] (covers every int16 and both clamp edges). */
    for (int32_t x = -131072; x <= 131072; x++) {
        check_sat16(&c, x);
    }
    /* A stride sweep over the whole int32 range (about 1.05e6 points). */
    for (int64_t x = INT32_MIN; x <= INT32_MAX; x += 4093) {
        check_sat16(&c, (int32_t)x);
    }
    for (int i = 0; i < N_EDGES32; i++) {
        check_sat16(&c, edges32[i]);
    }
    q14t_check_report(&c);
}

/* ---- q_clamp32 ------------------------------------------------------------- */

static void check_clamp(q14t_check_t *c, int32_t x, int32_t lo, int32_t hi)
{
    int32_t want = (x < lo) ? lo : ((x > hi) ? hi : x);
    int32_t got = q_clamp32(x, lo, hi);
    c->cases++;
    if (got != want && c->failures++ == 0) {
        snprintf(c->first, sizeof c->first,
                 "q_clamp32(%" PRId32 ", %" PRId32 ", %" PRId32 ") = %" PRId32
                 ", expected %" PRId32,
                 x, lo, hi, got, want);
    }
}

static void test_q_clamp32_edges_and_random(void)
{
    q14t_check_t c;
    q14t_check_init(&c, "q_clamp32");
    for (int i = 0; i < N_EDGES32; i++) {
        for (int j = 0; j < N_EDGES32; j++) {
            for (int k = j; k < N_EDGES32; k++) {
                check_clamp(&c, edges32[i], edges32[j], edges32[k]);
            }
        }
    }
    uint64_t rng = 0xC1A3D32ull;
    for (int i = 0; i < 1000000; i++) {
        int32_t x = q14t_i32_mixed(&rng);
        int32_t lo = q14t_i32_mixed(&rng);
        int32_t hi = q14t_i32_mixed(&rng);
        if (lo > hi) {
            int32_t t = lo;
            lo = hi;
            hi = t;
        }
        check_clamp(&c, x, lo, hi);
    }
    q14t_check_report(&c);
}

/* ---- q14_add_sat / q14_sub_sat ---------------------------------------------- */

static void check_addsub16(q14t_check_t *c, int16_t a, int16_t b)
{
    int16_t want_add = q14t_sat16((int64_t)a + b);
    int16_t want_sub = q14t_sat16((int64_t)a - b);
    int16_t got_add = q14_add_sat(a, b);
    int16_t got_sub = q14_sub_sat(a, b);
    c->cases += 2;
    if (got_add != want_add && c->failures++ == 0) {
        snprintf(c->first, sizeof c->first, "q14_add_sat(%d, %d) = %d, expected %d", a, b, got_add,
                 want_add);
    }
    if (got_sub != want_sub && c->failures++ == 0) {
        snprintf(c->first, sizeof c->first, "q14_sub_sat(%d, %d) = %d, expected %d", a, b, got_sub,
                 want_sub);
    }
}

static const int16_t edges16[] = {
    INT16_MIN, INT16_MIN + 1, -16385, -16384, -16383, -8192, -2,    -1,       0, 1,
    2,         8191,          8192,   16383,  16384,  16385, 32766, INT16_MAX};
#define N_EDGES16 ((int)(sizeof edges16 / sizeof edges16[0]))

static void test_q14_add_sub_sat_sweeps(void)
{
    q14t_check_t c;
    q14t_check_init(&c, "q14_add_sat/q14_sub_sat");
    uint64_t rng = 0xADD5A7ull;
    /* Every a against the edges and 16 random b, both argument orders. */
    int16_t bs[N_EDGES16 + 16];
    for (int i = 0; i < N_EDGES16; i++) {
        bs[i] = edges16[i];
    }
    for (int i = 0; i < 16; i++) {
        bs[N_EDGES16 + i] = q14t_as_i16(q14t_u32(&rng));
    }
    for (int j = 0; j < N_EDGES16 + 16; j++) {
        for (int32_t a = INT16_MIN; a <= INT16_MAX; a++) {
            check_addsub16(&c, (int16_t)a, bs[j]);
            check_addsub16(&c, bs[j], (int16_t)a);
        }
    }
    /* A coarse grid of all pairs (stride 97 in each argument). */
    for (int32_t a = INT16_MIN; a <= INT16_MAX; a += 97) {
        for (int32_t b = INT16_MIN; b <= INT16_MAX; b += 97) {
            check_addsub16(&c, (int16_t)a, (int16_t)b);
        }
    }
    for (int i = 0; i < 1000000; i++) {
        check_addsub16(&c, q14t_i16_mixed(&rng), q14t_i16_mixed(&rng));
    }
    q14t_check_report(&c);
}

/* ---- q_add_sat32 / q_sub_sat32 ---------------------------------------------- */

static void check_addsub32(q14t_check_t *c, int32_t a, int32_t b)
{
    int32_t want_add = q14t_sat32((int64_t)a + b);
    int32_t want_sub = q14t_sat32((int64_t)a - b);
    int32_t got_add = q_add_sat32(a, b);
    int32_t got_sub = q_sub_sat32(a, b);
    c->cases += 2;
    if (got_add != want_add && c->failures++ == 0) {
        snprintf(c->first, sizeof c->first,
                 "q_add_sat32(%" PRId32 ", %" PRId32 ") = %" PRId32 ", expected %" PRId32, a, b,
                 got_add, want_add);
    }
    if (got_sub != want_sub && c->failures++ == 0) {
        snprintf(c->first, sizeof c->first,
                 "q_sub_sat32(%" PRId32 ", %" PRId32 ") = %" PRId32 ", expected %" PRId32, a, b,
                 got_sub, want_sub);
    }
}

static void test_q_add_sub_sat32_edges_and_random(void)
{
    q14t_check_t c;
    q14t_check_init(&c, "q_add_sat32/q_sub_sat32");
    for (int i = 0; i < N_EDGES32; i++) {
        for (int j = 0; j < N_EDGES32; j++) {
            check_addsub32(&c, edges32[i], edges32[j]);
        }
    }
    /* Around the overflow boundary: a + b == INT32_MAX + d, a - b == INT32_MIN + d. */
    uint64_t rng = 0x5A7320ull;
    for (int i = 0; i < 200000; i++) {
        int32_t b = q14t_as_i32(q14t_u32(&rng));
        int64_t d = (int64_t)q14t_below(&rng, 5u) - 2;
        check_addsub32(&c, q14t_sat32((int64_t)INT32_MAX - b + d), b);
        check_addsub32(&c, q14t_sat32((int64_t)INT32_MIN - b + d), b);
        check_addsub32(&c, q14t_sat32((int64_t)INT32_MIN + b + d), b);
        check_addsub32(&c, q14t_sat32((int64_t)INT32_MAX + b + d), b);
    }
    for (int i = 0; i < 1000000; i++) {
        check_addsub32(&c, q14t_i32_mixed(&rng), q14t_i32_mixed(&rng));
    }
    q14t_check_report(&c);
}

/* ---- q_rshift_round ---------------------------------------------------------- */

static void check_rshift(q14t_check_t *c, int32_t x, unsigned s)
{
    /* round(x / 2^s), ties toward +inf == floor((x + 2^(s-1)) / 2^s). */
    int64_t want = q14t_floordiv64((int64_t)x + ((int64_t)1 << (s - 1u)), (int64_t)1 << s);
    int32_t got = q_rshift_round(x, s);
    c->cases++;
    if ((int64_t)got != want && c->failures++ == 0) {
        snprintf(c->first, sizeof c->first,
                 "q_rshift_round(%" PRId32 ", %u) = %" PRId32 ", expected %" PRId64, x, s, got,
                 want);
    }
}

static void test_q_rshift_round_all_shifts(void)
{
    q14t_check_t c;
    q14t_check_init(&c, "q_rshift_round");
    uint64_t rng = 0x5B1F7ull;
    for (unsigned s = 1u; s <= 31u; s++) {
        for (int i = 0; i < N_EDGES32; i++) {
            check_rshift(&c, edges32[i], s);
        }
        /* Exact ties and their neighbours: k * 2^s + 2^(s-1) + {-1, 0, 1}. */
        for (int i = 0; i < 4000; i++) {
            int64_t k = (int64_t)q14t_as_i32(q14t_u32(&rng)) >> s;
            for (int d = -1; d <= 1; d++) {
                int64_t x = k * ((int64_t)1 << s) + ((int64_t)1 << (s - 1u)) + d;
                check_rshift(&c, q14t_sat32(x), s);
            }
        }
        for (int i = 0; i < 40000; i++) {
            check_rshift(&c, q14t_i32_mixed(&rng), s);
        }
    }
    /* Every x in [-2^16, 2^16] at shifts 1, 2 and 14 (the ones the library uses). */
    for (int32_t x = -65536; x <= 65536; x++) {
        check_rshift(&c, x, 1u);
        check_rshift(&c, x, 2u);
        check_rshift(&c, x, 14u);
    }
    q14t_check_report(&c);
}

/* ---- q14_mul ------------------------------------------------------------------ */

static void check_mul(q14t_check_t *c, int16_t a, int16_t b)
{
    int16_t want = q14t_sat16(q14t_floordiv64((int64_t)a * b + 8192, 16384));
    int16_t got = q14_mul(a, b);
    c->cases++;
    if (got != want && c->failures++ == 0) {
        snprintf(c->first, sizeof c->first, "q14_mul(%d, %d) = %d, expected %d", a, b, got, want);
    }
}

static void test_q14_mul_exhaustive_rows_and_random(void)
{
    q14t_check_t c;
    q14t_check_init(&c, "q14_mul");
    static const int16_t rows[] = {
        INT16_MIN, INT16_MIN + 1, -16385, -16384, -8192,         -3,       -2, -1, 0, 1, 2, 3, 8191,
        8192,      16383,         16384,  16385,  INT16_MAX - 1, INT16_MAX};
    for (size_t j = 0; j < sizeof rows / sizeof rows[0]; j++) {
        for (int32_t a = INT16_MIN; a <= INT16_MAX; a++) {
            check_mul(&c, (int16_t)a, rows[j]);
            check_mul(&c, rows[j], (int16_t)a);
        }
    }
    uint64_t rng = 0x3017ull;
    for (int i = 0; i < 1000000; i++) {
        check_mul(&c, q14t_i16_mixed(&rng), q14t_i16_mixed(&rng));
    }
    /* Exact ties: a * b == odd * 2^13, a = odd * 2^t, b = 2^(13 - t), t in [0, 2]. */
    for (int i = 0; i < 100000; i++) {
        int32_t odd = (int32_t)(q14t_below(&rng, 4096u) * 2u + 1u); /* < 2^13 */
        unsigned t = q14t_below(&rng, 3u);
        int32_t a = odd << t;
        int32_t b = (int32_t)1 << (13u - t);
        check_mul(&c, (int16_t)((i & 1) ? -a : a), (int16_t)((i & 2) ? -b : b));
    }
    /* (-2.0)(-2.0) saturates to INT16_MAX, and so does every product >= 2.0. */
    TEST_ASSERT_EQUAL_INT16(INT16_MAX, q14_mul(INT16_MIN, INT16_MIN));
    TEST_ASSERT_EQUAL_INT16(INT16_MAX, q14_mul(INT16_MIN, INT16_MIN + 1));
    TEST_ASSERT_EQUAL_INT16(INT16_MIN, q14_mul(INT16_MIN, 16384));
    TEST_ASSERT_EQUAL_INT16(INT16_MIN, q14_mul(INT16_MAX, INT16_MIN));
    q14t_check_report(&c);
}

/* ---- the compile-time conversions ----------------------------------------------- */

static void test_from_real_macros(void)
{
    TEST_ASSERT_EQUAL_INT16(16384, Q14_FROM_REAL(1.0));
    TEST_ASSERT_EQUAL_INT16(-16384, Q14_FROM_REAL(-1.0));
    TEST_ASSERT_EQUAL_INT16(-32768, Q14_FROM_REAL(-2.0));
    TEST_ASSERT_EQUAL_INT16(11585, Q14_FROM_REAL(0.70710678118654752));
    TEST_ASSERT_EQUAL_INT16(-11585, Q14_FROM_REAL(-0.70710678118654752));
    TEST_ASSERT_EQUAL_INT16(2048, Q11_FROM_REAL(1.0));
    TEST_ASSERT_EQUAL_INT16(-6434, Q11_FROM_REAL(-3.14159265358979));
    TEST_ASSERT_EQUAL_INT32(65536, Q16_FROM_REAL(1.0));
    TEST_ASSERT_EQUAL_INT32(-19661, Q16_FROM_REAL(-0.3));
    TEST_ASSERT_EQUAL_INT32(Q14_ONE, Q14_FROM_REAL(1.0));
    TEST_ASSERT_EQUAL_INT32(Q11_ONE, Q11_FROM_REAL(1.0));
    TEST_ASSERT_EQUAL_INT32(Q16_ONE, Q16_FROM_REAL(1.0));
}

int main(void)
{
    double t0 = q14t_seconds();
    UNITY_BEGIN();
    RUN_TEST(test_q_sat16_all_int16_and_int32_sweep);
    RUN_TEST(test_q_clamp32_edges_and_random);
    RUN_TEST(test_q14_add_sub_sat_sweeps);
    RUN_TEST(test_q_add_sub_sat32_edges_and_random);
    RUN_TEST(test_q_rshift_round_all_shifts);
    RUN_TEST(test_q14_mul_exhaustive_rows_and_random);
    RUN_TEST(test_from_real_macros);
    int rc = UNITY_END();
    printf("[q14] test_q14_basic runtime %.2f s\n", q14t_seconds() - t0);
    return rc;
}
