/*
 * Unit tests of division, reciprocal and square roots (q14.h):
 * q14_sqrt and q14_recip over every int16 input, q14_div over whole rows and
 * columns plus 10^6 random pairs, q_isqrt32 / q_isqrt32_round over every x in
 * [0, 2^24], every perfect square and its neighbours, 10^6 random x and
 * 0xFFFFFFFF; q_rsqrt_q28 over a stride-61 sweep of its whole range plus
 * every table knot and 10^6 random inputs, and q_recip_q30 (relative error
 * below 2^-28, what the control step's 1/airspeed needs without a Newton
 * step of its own, and the mantissa/exponent form). The references are exact integer
 * arithmetic or long double; the errors are printed.
 */
#include "unity.h"

#include "helical/math/q14.h"

#include "q14_test_rng.h"

#include <inttypes.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

void setUp(void) {}
void tearDown(void) {}

/* ---- q14_sqrt --------------------------------------------------------------- */

static void test_q14_sqrt_every_int16(void)
{
    q14t_check_t c;
    q14t_check_init(&c, "q14_sqrt");
    long double worst = 0.0L;
    int32_t worst_x = 0;
    for (int32_t x = INT16_MIN; x <= INT16_MAX; x++) {
        int16_t got = q14_sqrt((int16_t)x);
        int32_t want;
        if (x <= 0) {
            want = 0; /* negative inputs clamp to 0 (documented) */
        } else {
            /* sqrt(x / 2^14) * 2^14 = sqrt(x * 2^14), rounded to nearest. */
            want = (int32_t)q14t_isqrt64_round((uint64_t)x << 14);
            long double err = fabsl((long double)got - sqrtl((long double)x * 16384.0L));
            if (err > worst) {
                worst = err;
                worst_x = x;
            }
        }
        c.cases++;
        if (got != want && c.failures++ == 0) {
            snprintf(c.first, sizeof c.first, "q14_sqrt(%" PRId32 ") = %d, expected %" PRId32, x,
                     got, want);
        }
    }
    printf("[q14] q14_sqrt worst |err| vs long double = %.6Lf LSB Q14 at x=%" PRId32 "\n", worst,
           worst_x);
    TEST_ASSERT_TRUE_MESSAGE(worst <= 0.5L, "q14_sqrt error above 1/2 LSB");
    TEST_ASSERT_EQUAL_INT16(0, q14_sqrt(INT16_MIN));
    TEST_ASSERT_EQUAL_INT16(0, q14_sqrt(-1));
    TEST_ASSERT_EQUAL_INT16(0, q14_sqrt(0));
    TEST_ASSERT_EQUAL_INT16(16384, q14_sqrt(16384));
    TEST_ASSERT_EQUAL_INT16(23170, q14_sqrt(INT16_MAX)); /* sqrt(2 - 2^-14) = 1.41419... */
    q14t_check_report(&c);
}

/* ---- exact division reference ------------------------------------------------ */

/* round(n / d), ties away from zero, for d != 0 (exact). */
static int64_t div_round_away(int64_t n, int64_t d)
{
    int64_t an = (n < 0) ? -n : n;
    int64_t ad = (d < 0) ? -d : d;
    int64_t q = an / ad;
    int64_t r = an % ad;
    if (2 * r >= ad) {
        q++;
    }
    return ((n < 0) != (d < 0)) ? -q : q;
}

/* ---- q14_recip ---------------------------------------------------------------- */

static void test_q14_recip_every_int16(void)
{
    q14t_check_t c;
    q14t_check_init(&c, "q14_recip");
    double worst = 0.0;
    int32_t worst_x = 0;
    long long n_sat = 0;
    for (int32_t x = INT16_MIN; x <= INT16_MAX; x++) {
        int16_t got = q14_recip((int16_t)x);
        int16_t want;
        if (x == 0) {
            want = INT16_MAX;
        } else {
            int64_t q = div_round_away((int64_t)1 << 28, x);
            want = q14t_sat16(q);
            if (q == (int64_t)want) {
                double err = fabs((double)got - 268435456.0 / (double)x);
                if (err > worst) {
                    worst = err;
                    worst_x = x;
                }
            } else {
                n_sat++;
            }
        }
        c.cases++;
        if (got != want && c.failures++ == 0) {
            snprintf(c.first, sizeof c.first, "q14_recip(%" PRId32 ") = %d, expected %d", x, got,
                     want);
        }
    }
    printf("[q14] q14_recip worst |err| (unsaturated) = %.6f LSB Q14 at x=%" PRId32
           ", saturated cases=%lld\n",
           worst, worst_x, n_sat);
    TEST_ASSERT_TRUE(worst <= 0.5);
    TEST_ASSERT_EQUAL_INT16(INT16_MAX, q14_recip(0));
    TEST_ASSERT_EQUAL_INT16(INT16_MAX, q14_recip(8192)); /* 1/0.5 = 2.0 clamps */
    TEST_ASSERT_EQUAL_INT16(INT16_MIN, q14_recip(-8192));
    TEST_ASSERT_EQUAL_INT16(32764, q14_recip(8193));
    TEST_ASSERT_EQUAL_INT16(16384, q14_recip(16384));
    TEST_ASSERT_EQUAL_INT16(-8192, q14_recip(INT16_MIN));
    q14t_check_report(&c);
}

/* ---- q14_div -------------------------------------------------------------------- */

static void check_div(q14t_check_t *c, int16_t num, int16_t den, double *worst)
{
    int16_t want;
    int16_t got = q14_div(num, den);
    if (den == 0) {
        want = (num >= 0) ? INT16_MAX : INT16_MIN;
    } else {
        int64_t q = div_round_away((int64_t)num * 16384, den);
        want = q14t_sat16(q);
        if (q == (int64_t)want) {
            double err = fabs((double)got - (double)num * 16384.0 / (double)den);
            if (err > *worst) {
                *worst = err;
            }
        }
    }
    c->cases++;
    if (got != want && c->failures++ == 0) {
        snprintf(c->first, sizeof c->first, "q14_div(%d, %d) = %d, expected %d", num, den, got,
                 want);
    }
}

static void test_q14_div_rows_columns_random(void)
{
    q14t_check_t c;
    q14t_check_init(&c, "q14_div");
    double worst = 0.0;
    static const int16_t special[] = {
        INT16_MIN, INT16_MIN + 1, -16384, -8193, -8192, -8191,    -3, -2, -1, 0, 1, 2,
        3,         8191,          8192,   8193,  16384, INT16_MAX};
    for (size_t j = 0; j < sizeof special / sizeof special[0]; j++) {
        for (int32_t x = INT16_MIN; x <= INT16_MAX; x++) {
            check_div(&c, (int16_t)x, special[j], &worst); /* every numerator */
            check_div(&c, special[j], (int16_t)x, &worst); /* every denominator */
        }
    }
    uint64_t rng = 0xD1Dull;
    for (int i = 0; i < 1000000; i++) {
        check_div(&c, q14t_i16_mixed(&rng), q14t_i16_mixed(&rng), &worst);
    }
    /* Exact ties: num * 2^14 / den == k + 1/2 needs 2^15 | den, i.e. den == INT16_MIN and an
     * odd num; every one of them is in the INT16_MIN row above. Spot checks: */
    TEST_ASSERT_EQUAL_INT16(-1, q14_div(1, INT16_MIN)); /* -0.5 -> -1 (away from zero) */
    TEST_ASSERT_EQUAL_INT16(1, q14_div(-1, INT16_MIN)); /* +0.5 -> +1 */
    TEST_ASSERT_EQUAL_INT16(-2, q14_div(3, INT16_MIN)); /* -1.5 -> -2 */
    TEST_ASSERT_EQUAL_INT16(2, q14_div(-3, INT16_MIN)); /* +1.5 -> +2 */
    printf("[q14] q14_div worst |err| (unsaturated) = %.6f LSB Q14\n", worst);
    TEST_ASSERT_TRUE(worst <= 0.5);
    TEST_ASSERT_EQUAL_INT16(INT16_MAX, q14_div(0, 0));
    TEST_ASSERT_EQUAL_INT16(INT16_MAX, q14_div(INT16_MAX, 0));
    TEST_ASSERT_EQUAL_INT16(INT16_MIN, q14_div(-1, 0));
    TEST_ASSERT_EQUAL_INT16(INT16_MIN, q14_div(INT16_MIN, 0));
    TEST_ASSERT_EQUAL_INT16(INT16_MAX, q14_div(INT16_MIN, -1));
    TEST_ASSERT_EQUAL_INT16(INT16_MIN, q14_div(INT16_MIN, 1));
    TEST_ASSERT_EQUAL_INT16(16384, q14_div(INT16_MIN, INT16_MIN));
    TEST_ASSERT_EQUAL_INT16(-16384, q14_div(INT16_MAX, -INT16_MAX));
    TEST_ASSERT_EQUAL_INT16(1, q14_div(1, 32767)); /* 0.50002 -> 1 */
    q14t_check_report(&c);
}

/* ---- q_isqrt32 / q_isqrt32_round ------------------------------------------------ */

typedef struct {
    q14t_check_t floor_c;
    q14t_check_t round_c;
} isqrt_checks_t;

static void check_isqrt(isqrt_checks_t *k, uint32_t x)
{
    uint64_t s = q_isqrt32(x);
    uint64_t r = q_isqrt32_round(x);
    uint64_t x64 = x;
    k->floor_c.cases++;
    /* floor: s^2 <= x < (s + 1)^2 */
    if (!(s * s <= x64 && x64 < (s + 1u) * (s + 1u)) && k->floor_c.failures++ == 0) {
        snprintf(k->floor_c.first, sizeof k->floor_c.first,
                 "q_isqrt32(%" PRIu32 ") = %" PRIu64 ", expected %" PRIu64, x, s,
                 q14t_isqrt64(x64));
    }
    /* nearest: (r - 1/2)^2 <= x < (r + 1/2)^2  <=>  (2r - 1)^2 <= 4x < (2r + 1)^2 */
    k->round_c.cases++;
    int ok = (4u * x64 < (2u * r + 1u) * (2u * r + 1u)) &&
             (r == 0u || (2u * r - 1u) * (2u * r - 1u) <= 4u * x64);
    if (!ok && k->round_c.failures++ == 0) {
        snprintf(k->round_c.first, sizeof k->round_c.first,
                 "q_isqrt32_round(%" PRIu32 ") = %" PRIu64 ", expected %" PRIu64, x, r,
                 q14t_isqrt64_round(x64));
    }
}

static void test_q_isqrt32_exhaustive_2_24_squares_random(void)
{
    isqrt_checks_t k;
    q14t_check_init(&k.floor_c, "q_isqrt32");
    q14t_check_init(&k.round_c, "q_isqrt32_round");
    for (uint32_t x = 0u; x <= (1u << 24); x++) {
        check_isqrt(&k, x);
    }
    for (uint32_t s = 0u; s <= 65535u; s++) {
        uint32_t sq = s * s;
        if (s > 0u) {
            check_isqrt(&k, sq - 1u);
        }
        check_isqrt(&k, sq);
        check_isqrt(&k, sq + 1u);
        check_isqrt(&k, sq + s);      /* last value rounding down */
        check_isqrt(&k, sq + s + 1u); /* first value rounding up */
        check_isqrt(&k, sq + 2u * s); /* (s + 1)^2 - 1 */
    }
    uint64_t rng = 0x15A27ull;
    for (int i = 0; i < 1000000; i++) {
        check_isqrt(&k, q14t_u32(&rng));
    }
    for (uint32_t x = 0xFFFFFFFFu; x >= 0xFFFF0000u; x--) {
        check_isqrt(&k, x);
    }
    TEST_ASSERT_EQUAL_UINT32(65535u, q_isqrt32(0xFFFFFFFFu));
    TEST_ASSERT_EQUAL_UINT32(65536u, q_isqrt32_round(0xFFFFFFFFu));
    TEST_ASSERT_EQUAL_UINT32(65535u, q_isqrt32_round(0xFFFE0001u)); /* 65535^2 */
    TEST_ASSERT_EQUAL_UINT32(0u, q_isqrt32_round(0u));
    TEST_ASSERT_EQUAL_UINT32(1u, q_isqrt32_round(1u));
    TEST_ASSERT_EQUAL_UINT32(1u, q_isqrt32_round(2u)); /* 1.414 */
    TEST_ASSERT_EQUAL_UINT32(2u, q_isqrt32_round(3u)); /* 1.732 */
    q14t_check_report(&k.floor_c);
    q14t_check_report(&k.round_c);
}

/* ---- q_rsqrt_q28 ------------------------------------------------------------------ */

typedef struct {
    long long cases;
    long double worst_rel;
    int32_t worst_in;
    int32_t worst_out;
    long long over;
    char first[200];
} rel_stats_t;

/* q14.h: "a relative error below 2e-8 (the tests measure it over the whole
 * range)". */
#define RSQRT_REL_BOUND 2e-8L

static void rsqrt_case(rel_stats_t *r, int32_t s)
{
    int32_t y = q_rsqrt_q28(s);
    long double exact = 4398046511104.0L / sqrtl((long double)s); /* 2^42 / sqrt(s) */
    long double rel = fabsl((long double)y / exact - 1.0L);
    r->cases++;
    if (rel > r->worst_rel) {
        r->worst_rel = rel;
        r->worst_in = s;
        r->worst_out = y;
    }
    if (!(rel < RSQRT_REL_BOUND) && r->over++ == 0) {
        snprintf(r->first, sizeof r->first,
                 "q_rsqrt_q28(%" PRId32 ") = %" PRId32 ", exact %.3Lf, relative error %.3Le", s, y,
                 exact, rel);
    }
}

static void test_q_rsqrt_q28_whole_range(void)
{
    rel_stats_t r;
    memset(&r, 0, sizeof r);
    /* A stride-61 sweep of [2^26, 2^30) (16.5e6 points, every table cell many times). */
    for (int32_t s = 1 << 26; s < (1 << 30) && s >= (1 << 26); s += 61) {
        rsqrt_case(&r, s);
    }
    /* Every table knot of both octaves and its neighbours. */
    for (int32_t i = 0; i <= 48; i++) {
        for (int32_t d = -3; d <= 3; d++) {
            int64_t k1 = ((int64_t)1 << 28) + (int64_t)i * ((int64_t)1 << 24) + d;
            int64_t k0 = ((int64_t)1 << 26) + (int64_t)i * ((int64_t)1 << 22) + d;
            if (k1 >= (1 << 26) && k1 < (1 << 30)) {
                rsqrt_case(&r, (int32_t)k1);
            }
            if (k0 >= (1 << 26) && k0 < (1 << 30)) {
                rsqrt_case(&r, (int32_t)k0);
            }
        }
    }
    uint64_t rng = 0x7599ull;
    for (int i = 0; i < 1000000; i++) {
        rsqrt_case(&r, (int32_t)((1u << 26) + q14t_below(&rng, (1u << 30) - (1u << 26))));
    }
    printf("[q14] q_rsqrt_q28 cases=%lld worst relative error = %.4Le (%.2Lf LSB Q28 at the "
           "output) at s=%" PRId32 " -> %" PRId32 "; cases >= 2e-8: %lld\n",
           r.cases, r.worst_rel, r.worst_rel * (long double)r.worst_out, r.worst_in, r.worst_out,
           r.over);
    /* Inputs outside [2^26, 2^30) are clamped to it. */
    static const int32_t below[] = {INT32_MIN, -1, 0, 1, (1 << 26) - 1};
    static const int32_t above[] = {1 << 30, (1 << 30) + 1, INT32_MAX};
    for (size_t i = 0; i < sizeof below / sizeof below[0]; i++) {
        TEST_ASSERT_EQUAL_INT32(q_rsqrt_q28(1 << 26), q_rsqrt_q28(below[i]));
    }
    for (size_t i = 0; i < sizeof above / sizeof above[0]; i++) {
        TEST_ASSERT_EQUAL_INT32(q_rsqrt_q28((1 << 30) - 1), q_rsqrt_q28(above[i]));
    }
    TEST_ASSERT_INT32_WITHIN(1, 1 << 28, q_rsqrt_q28(1 << 28)); /* 1/sqrt(1) */
    TEST_ASSERT_INT32_WITHIN(1, 1 << 29, q_rsqrt_q28(1 << 26)); /* 1/sqrt(1/4) */
    TEST_ASSERT_EQUAL_INT64_MESSAGE(0, r.over, r.first);
}

/* ---- q_rsqrt_norm_q28 (any positive x, mantissa and power of two) ---------- */

/* q14.h: "relative error below 1e-8". */
#define RSQRT_NORM_REL_BOUND 1e-8L

static void rsqrt_norm_case(rel_stats_t *r, uint32_t x, int *bad_range)
{
    int exp2 = 99;
    int32_t y = q_rsqrt_norm_q28(x, &exp2);
    if (exp2 < -1 || exp2 > 14 || y < (1 << 27) || y > (1 << 28)) {
        (*bad_range)++;
    }
    /* 1/sqrt(x / 2^28) = y * 2^exp2 / 2^28 */
    long double exact = 16384.0L / sqrtl((long double)x);
    long double got = ldexpl((long double)y, exp2 - 28);
    long double rel = fabsl(got / exact - 1.0L);
    r->cases++;
    if (rel > r->worst_rel) {
        r->worst_rel = rel;
        r->worst_in = (int32_t)(x >> 1);
        r->worst_out = y;
    }
    if (!(rel < RSQRT_NORM_REL_BOUND) && r->over++ == 0) {
        snprintf(r->first, sizeof r->first,
                 "q_rsqrt_norm_q28(%" PRIu32 ") = %" PRId32
                 " * 2^%d, exact %.6Le, relative error %.3Le",
                 x, y, exp2, exact, rel);
    }
}

static void test_q_rsqrt_norm_q28_every_octave(void)
{
    rel_stats_t r;
    memset(&r, 0, sizeof r);
    int bad_range = 0;
    /* The normalized mantissas [2^28, 2^30): a stride-61 sweep (every table
     * cell many times; a Newton residual beyond its 2^15 bound would show as
     * a wrong result here) and every knot with its neighbours. */
    for (uint32_t x = 1u << 28; x < (1u << 30); x += 61u) {
        rsqrt_norm_case(&r, x, &bad_range);
    }
    for (uint32_t i = 0; i <= 64u; i++) {
        for (int d = -3; d <= 3; d++) {
            rsqrt_norm_case(&r, (uint32_t)((int64_t)(1u << 28) + (int64_t)i * (1 << 22) + d),
                            &bad_range);
            rsqrt_norm_case(&r, (uint32_t)((int64_t)(1u << 29) + (int64_t)i * (1 << 23) + d),
                            &bad_range);
        }
    }
    /* Every power of two and its neighbours, and 10^6 log-uniform x over the
     * whole uint32 range (exp2 from -1 to 14). */
    for (unsigned k = 0; k < 32u; k++) {
        const uint32_t p = 1u << k;
        rsqrt_norm_case(&r, p, &bad_range);
        rsqrt_norm_case(&r, p + 1u, &bad_range);
        if (k > 0u) {
            rsqrt_norm_case(&r, p - 1u, &bad_range);
        }
    }
    rsqrt_norm_case(&r, UINT32_MAX, &bad_range);
    uint64_t rng = 0x25C4ull;
    for (int i = 0; i < 1000000; i++) {
        const unsigned bits = 1u + q14t_below(&rng, 32u);
        const uint32_t x = (q14t_u32(&rng) >> (32u - bits)) | (1u << (bits - 1u));
        rsqrt_norm_case(&r, x, &bad_range);
    }
    printf("[q14] q_rsqrt_norm_q28 cases=%lld worst relative error = %.4Le; out of range: %d; "
           "cases >= 1e-8: %lld\n",
           r.cases, r.worst_rel, bad_range, r.over);
    /* exact at the powers of four, and x == 0 read as 1 */
    int e = 0;
    TEST_ASSERT_EQUAL_INT32(1 << 28, q_rsqrt_norm_q28(1u << 28, &e));
    TEST_ASSERT_EQUAL_INT(0, e);
    TEST_ASSERT_EQUAL_INT32(1 << 28, q_rsqrt_norm_q28(1u, &e));
    TEST_ASSERT_EQUAL_INT(14, e);
    TEST_ASSERT_EQUAL_INT32(1 << 28, q_rsqrt_norm_q28(0u, &e));
    TEST_ASSERT_EQUAL_INT(14, e);
    TEST_ASSERT_EQUAL_INT(0, bad_range);
    TEST_ASSERT_EQUAL_INT64_MESSAGE(0, r.over, r.first);
}

/* ---- q_recip_q30 -------------------------------------------------------------------- */

typedef struct {
    long long bad_exp; /* exponent != floor(log2(x)) */
    long long m_low;   /* m < 2^29 */
    long long m_high;  /* m > 2^30 */
    int32_t m_min;
    int32_t m_max;
    char first[200]; /* the first form failure */
} recip_form_t;

static void recip30_case(rel_stats_t *r, recip_form_t *f, int32_t x)
{
    unsigned e = 99u;
    int32_t m = q_recip_q30(x, &e);
    int32_t xe = (x > 0) ? x : 1; /* x <= 0 is treated as 1 */
    unsigned want_e = 0u;
    while (want_e < 31u && ((int64_t)1 << (want_e + 1u)) <= xe) {
        want_e++;
    }
    r->cases++;
    int bad = 0;
    if (e != want_e) {
        f->bad_exp++;
        bad = 1;
    }
    if (m < (1 << 29)) {
        f->m_low++;
        bad = 1;
    }
    if (m > (1 << 30)) {
        f->m_high++;
        bad = 1;
    }
    f->m_min = (m < f->m_min) ? m : f->m_min;
    f->m_max = (m > f->m_max) ? m : f->m_max;
    if (bad && f->first[0] == '\0') {
        snprintf(f->first, sizeof f->first,
                 "q_recip_q30(%" PRId32 ") = %" PRId32 ", exponent %u: expected exponent %u and "
                 "2^29 <= m <= 2^30",
                 x, m, e, want_e);
    }
    /* 1/x = m * 2^-(30 + e): relative error m * x / 2^(30 + e) - 1. */
    long double rel = fabsl(ldexpl((long double)m * (long double)xe, -(int)(30u + e)) - 1.0L);
    if (rel > r->worst_rel) {
        r->worst_rel = rel;
        r->worst_in = x;
        r->worst_out = m;
    }
    /* 2^-28: the third-order step's e^3 (1.5e-11) plus its three Q30
     * roundings (at most 2^-31 + 2^-31 + 2^-30 relative, m >= 2^29) is
     * 1.88e-9; the contract leaves a factor 2. */
    if (!(rel < 0x1p-28L) && r->over++ == 0) {
        snprintf(r->first, sizeof r->first,
                 "q_recip_q30(%" PRId32 ") = %" PRId32 " exp %u, relative error %.3Le", x, m, e,
                 rel);
    }
}

static void test_q_recip_q30(void)
{
    rel_stats_t r;
    memset(&r, 0, sizeof r);
    recip_form_t f;
    memset(&f, 0, sizeof f);
    f.m_min = INT32_MAX;
    f.m_max = INT32_MIN;
    for (int32_t x = -16; x <= (1 << 20); x++) {
        recip30_case(&r, &f, x);
    }
    for (int64_t x = 1 << 20; x <= INT32_MAX; x += 2039) {
        recip30_case(&r, &f, (int32_t)x);
    }
    for (unsigned k = 0; k <= 30u; k++) {
        /* Powers of two, their neighbours and every table knot of the octave. */
        for (int64_t i = 0; i <= 32; i++) {
            for (int64_t d = -2; d <= 2; d++) {
                int64_t x = (((int64_t)32 + i) << k) / 32 + d;
                if (x >= 1 && x <= INT32_MAX) {
                    recip30_case(&r, &f, (int32_t)x);
                }
            }
        }
    }
    recip30_case(&r, &f, INT32_MIN);
    recip30_case(&r, &f, INT32_MAX);
    uint64_t rng = 0x4EC1ull;
    for (int i = 0; i < 1000000; i++) {
        int32_t x = q14t_i32_mixed(&rng);
        recip30_case(&r, &f, x < 0 ? -(x + 1) : x);
    }
    printf("[q14] q_recip_q30 cases=%lld worst relative error = %.4Le at x=%" PRId32 " (m=%" PRId32
           "); relative >= 2^-28: %lld\n",
           r.cases, r.worst_rel, r.worst_in, r.worst_out, r.over);
    printf("[q14] q_recip_q30 form: m in [%" PRId32 ", %" PRId32 "] (contract [2^29, 2^30] = "
           "[536870912, 1073741824]); m < 2^29: %lld, m > 2^30: %lld, wrong exponent: %lld\n",
           f.m_min, f.m_max, f.m_low, f.m_high, f.bad_exp);
    if (f.first[0] != '\0') {
        printf("[q14] q_recip_q30 FIRST FORM FAILURE: %s\n", f.first);
    }
    if (r.over != 0) {
        printf("[q14] q_recip_q30 FIRST ACCURACY FAILURE: %s\n", r.first);
    }
    TEST_ASSERT_EQUAL_INT64_MESSAGE(0, r.over, r.first);
    TEST_ASSERT_EQUAL_INT64_MESSAGE(0, f.bad_exp + f.m_low + f.m_high, f.first);
}

int main(void)
{
    double t0 = q14t_seconds();
    UNITY_BEGIN();
    RUN_TEST(test_q14_sqrt_every_int16);
    RUN_TEST(test_q14_recip_every_int16);
    RUN_TEST(test_q14_div_rows_columns_random);
    RUN_TEST(test_q_isqrt32_exhaustive_2_24_squares_random);
    RUN_TEST(test_q_rsqrt_q28_whole_range);
    RUN_TEST(test_q_rsqrt_norm_q28_every_octave);
    RUN_TEST(test_q_recip_q30);
    int rc = UNITY_END();
    printf("[q14] test_q14_sqrt_div runtime %.2f s\n", q14t_seconds() - t0);
    return rc;
}
