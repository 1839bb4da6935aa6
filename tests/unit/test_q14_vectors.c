/*
 * Unit tests of the vector functions of q14.h: q14_dot3, q14_cross3 (exact
 * integer reference plus the error against double), q_unit2_q16,
 * q_unit3_q16, q14_norm2_q16, q14_normalize2 and q14_normalize3 (error
 * against long double over vectors of every magnitude, the worst one printed
 * with its input).
 *
 * Bounds asserted (from the contract in q14.h):
 *   dot3, cross3      bit-exact: round(sum / 2^14), ties toward +inf, saturated
 *                     once (so <= 0.5 LSB of Q14 where not saturated)
 *   unit2/3_q16       "an error below 1 LSB of Q16 per component": < 1.0 LSB
 *   unit2/3_q28       "within 6 LSB of Q28 (2.3e-8) ... per component": < 6 LSB
 *   norm2_q16         per range, see test_q14_norm2_q16
 *   normalize2/3      rounded to Q14 from the Q28 unit vector: <= 1/2 LSB of Q14
 *                     plus 6 LSB of Q28; the count of results that are not
 *                     the nearest Q14 value is printed
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

static const int16_t edges16[] = {INT16_MIN, INT16_MIN + 1, -16384, -1, 0, 1, 16384, INT16_MAX};
#define N_EDGES16 8

/* ---- q14_dot3 / q14_cross3 ------------------------------------------------------ */

static int16_t ref_round14(int64_t s)
{
    return q14t_sat16(q14t_floordiv64(s + 8192, 16384));
}

typedef struct {
    q14t_check_t dot;
    q14t_check_t cross;
    double worst_dot;   /* LSB of Q14 vs double, unsaturated results */
    double worst_cross; /* LSB of Q14 vs double, unsaturated components */
    long long sat_dot;
    long long sat_cross;
} dc_checks_t;

static void check_dot_cross(dc_checks_t *k, const int16_t a[3], const int16_t b[3])
{
    int64_t s = (int64_t)a[0] * b[0] + (int64_t)a[1] * b[1] + (int64_t)a[2] * b[2];
    int16_t want = ref_round14(s);
    int16_t got = q14_dot3(a, b);
    k->dot.cases++;
    if (got != want && k->dot.failures++ == 0) {
        snprintf(k->dot.first, sizeof k->dot.first,
                 "q14_dot3((%d,%d,%d),(%d,%d,%d)) = %d, expected %d", a[0], a[1], a[2], b[0], b[1],
                 b[2], got, want);
    }
    double exact = ((double)a[0] * b[0] + (double)a[1] * b[1] + (double)a[2] * b[2]) / 16384.0;
    if (exact > -32768.5 && exact < 32767.5) {
        double e = fabs((double)got - exact);
        if (e > k->worst_dot) {
            k->worst_dot = e;
        }
    } else {
        k->sat_dot++;
    }

    int16_t out[3];
    q14_cross3(a, b, out);
    int64_t cs[3] = {(int64_t)a[1] * b[2] - (int64_t)a[2] * b[1],
                     (int64_t)a[2] * b[0] - (int64_t)a[0] * b[2],
                     (int64_t)a[0] * b[1] - (int64_t)a[1] * b[0]};
    for (int i = 0; i < 3; i++) {
        int16_t w = ref_round14(cs[i]);
        k->cross.cases++;
        if (out[i] != w && k->cross.failures++ == 0) {
            snprintf(k->cross.first, sizeof k->cross.first,
                     "q14_cross3((%d,%d,%d),(%d,%d,%d))[%d] = %d, expected %d", a[0], a[1], a[2],
                     b[0], b[1], b[2], i, out[i], w);
        }
        double ex = (double)cs[i] / 16384.0;
        if (ex > -32768.5 && ex < 32767.5) {
            double e = fabs((double)out[i] - ex);
            if (e > k->worst_cross) {
                k->worst_cross = e;
            }
        } else {
            k->sat_cross++;
        }
    }
}

static void test_q14_dot3_cross3_edges_and_random(void)
{
    dc_checks_t k;
    memset(&k, 0, sizeof k);
    q14t_check_init(&k.dot, "q14_dot3");
    q14t_check_init(&k.cross, "q14_cross3");
    /* Every combination of 8 edge values in all 6 components (262144 pairs). */
    for (int m = 0; m < (1 << 18); m++) {
        int16_t a[3];
        int16_t b[3];
        for (int i = 0; i < 3; i++) {
            a[i] = edges16[(m >> (3 * i)) & 7];
            b[i] = edges16[(m >> (9 + 3 * i)) & 7];
        }
        check_dot_cross(&k, a, b);
    }
    uint64_t rng = 0xD07ull;
    for (int n = 0; n < 1000000; n++) {
        int16_t a[3];
        int16_t b[3];
        for (int i = 0; i < 3; i++) {
            a[i] = q14t_i16_mixed(&rng);
            b[i] = q14t_i16_mixed(&rng);
        }
        check_dot_cross(&k, a, b);
    }
    /* Unit-range vectors (|v| <= 1), the library's real use. */
    for (int n = 0; n < 200000; n++) {
        int16_t a[3];
        int16_t b[3];
        for (int i = 0; i < 3; i++) {
            a[i] = (int16_t)((int32_t)q14t_below(&rng, 18919u) - 9459); /* |v| <= 1 */
            b[i] = (int16_t)((int32_t)q14t_below(&rng, 18919u) - 9459);
        }
        check_dot_cross(&k, a, b);
    }
    printf("[q14] q14_dot3 worst |err| (unsaturated) = %.6f LSB Q14, saturated=%lld\n", k.worst_dot,
           k.sat_dot);
    printf("[q14] q14_cross3 worst |err| (unsaturated) = %.6f LSB Q14, saturated comps=%lld\n",
           k.worst_cross, k.sat_cross);
    TEST_ASSERT_TRUE(k.worst_dot <= 0.5);
    TEST_ASSERT_TRUE(k.worst_cross <= 0.5);
    /* INT16_MIN everywhere: 3 * 4.0 saturates; cross of equal vectors is 0. */
    {
        const int16_t m[3] = {INT16_MIN, INT16_MIN, INT16_MIN};
        const int16_t p[3] = {INT16_MAX, INT16_MAX, INT16_MAX};
        int16_t o[3];
        TEST_ASSERT_EQUAL_INT16(INT16_MAX, q14_dot3(m, m));
        TEST_ASSERT_EQUAL_INT16(INT16_MIN, q14_dot3(m, p));
        q14_cross3(m, m, o);
        TEST_ASSERT_EQUAL_INT16(0, o[0]);
        TEST_ASSERT_EQUAL_INT16(0, o[1]);
        TEST_ASSERT_EQUAL_INT16(0, o[2]);
        /* The first two products saturate the int32 sum, the third takes it back
         * below: 4 + 4 - 3.9999 = 4.0001 still saturates to INT16_MAX. */
        const int16_t x[3] = {INT16_MIN, INT16_MIN, INT16_MIN};
        const int16_t y[3] = {INT16_MIN, INT16_MIN, INT16_MAX};
        TEST_ASSERT_EQUAL_INT16(INT16_MAX, q14_dot3(x, y));
        const int16_t e1[3] = {16384, 0, 0};
        const int16_t e2[3] = {0, 16384, 0};
        q14_cross3(e1, e2, o);
        TEST_ASSERT_EQUAL_INT16(0, o[0]);
        TEST_ASSERT_EQUAL_INT16(0, o[1]);
        TEST_ASSERT_EQUAL_INT16(16384, o[2]);
    }
    q14t_check_report(&k.dot);
    q14t_check_report(&k.cross);
}

/* ---- unit vectors ----------------------------------------------------------------- */

typedef struct {
    const char *name;
    long long cases;
    long double worst; /* LSB */
    int32_t worst_in[3];
    int32_t worst_out[3];
    long long over_bound;
    int32_t first_over_in[3];
    int32_t first_over_out[3];
    long double first_over_err;
    long long bad_zero;
    uint64_t hash; /* FNV-1a of every output: the portable build must print the same */
} unit_stats_t;

static void unit_stats_init(unit_stats_t *u, const char *name)
{
    memset(u, 0, sizeof *u);
    u->name = name;
    u->hash = UINT64_C(0xCBF29CE484222325);
}

/* err: the worst component error of one case (LSB); n: 2 or 3. */
static void unit_stats_add(unit_stats_t *u, unsigned n, const int32_t *in, const int32_t *out,
                           long double err, long double bound)
{
    u->cases++;
    for (unsigned i = 0; i < n; i++) {
        u->hash = (u->hash ^ (uint32_t)out[i]) * UINT64_C(0x100000001B3);
    }
    if (err > u->worst) {
        u->worst = err;
        for (unsigned i = 0; i < 3; i++) {
            u->worst_in[i] = (i < n) ? in[i] : 0;
            u->worst_out[i] = (i < n) ? out[i] : 0;
        }
    }
    if (!(err < bound)) {
        if (u->over_bound++ == 0) {
            u->first_over_err = err;
            for (unsigned i = 0; i < 3; i++) {
                u->first_over_in[i] = (i < n) ? in[i] : 0;
                u->first_over_out[i] = (i < n) ? out[i] : 0;
            }
        }
    }
}

static void unit_stats_report(const unit_stats_t *u, unsigned n, const char *unit,
                              long double bound)
{
    printf("[q14] %-16s cases=%lld worst |err| = %.4Lf LSB %s  at in=(%" PRId32 ", %" PRId32,
           u->name, u->cases, u->worst, unit, u->worst_in[0], u->worst_in[1]);
    if (n == 3u) {
        printf(", %" PRId32, u->worst_in[2]);
    }
    printf(") out=(%" PRId32 ", %" PRId32, u->worst_out[0], u->worst_out[1]);
    if (n == 3u) {
        printf(", %" PRId32, u->worst_out[2]);
    }
    printf(")\n[q14] %-16s cases with |err| >= %.6Lf LSB: %lld", u->name, bound, u->over_bound);
    if (u->over_bound != 0) {
        printf("; first: in=(%" PRId32 ", %" PRId32 ", %" PRId32 ") out=(%" PRId32 ", %" PRId32
               ", %" PRId32 ") err=%.4Lf",
               u->first_over_in[0], u->first_over_in[1], u->first_over_in[2], u->first_over_out[0],
               u->first_over_out[1], u->first_over_out[2], u->first_over_err);
    }
    printf("\n[q14] %-16s output hash %016" PRIx64
           " (test_q14_vectors_portable must print the same)\n",
           u->name, u->hash);
    fflush(stdout);
}

/* A random int32 component at a random scale: |v| < 2^bits, bits in [0, 32]. */
static int32_t rand_scaled32(uint64_t *rng, unsigned bits)
{
    if (bits == 0u) {
        return 0;
    }
    int64_t mag = (bits >= 32u) ? (int64_t)q14t_u32(rng) : (int64_t)(q14t_u32(rng) >> (32u - bits));
    int64_t v = q14t_below(rng, 2u) ? -mag : mag;
    return q14t_sat32(v);
}

/* Worst component error (LSB of the output format) of one vector through
 * q_unit2/3_q16 (frac = 16) or q_unit2/3_q28 (frac = 28); checks the return
 * value and the zero-vector contract too. */
static long double unit_case(unit_stats_t *u, unsigned n, unsigned frac, const int32_t *v,
                             int32_t *out)
{
    int32_t o[3] = {0x5A5A5A5A, 0x5A5A5A5A, 0x5A5A5A5A};
    int ret;
    if (frac == 16u) {
        ret = (n == 2u) ? q_unit2_q16(v[0], v[1], &o[0], &o[1]) : q_unit3_q16(v, o);
    } else {
        ret = (n == 2u) ? q_unit2_q28(v[0], v[1], &o[0], &o[1]) : q_unit3_q28(v, o);
    }
    long double one = (frac == 16u) ? 65536.0L : 268435456.0L;
    long double ss = 0.0L;
    for (unsigned i = 0; i < n; i++) {
        ss += (long double)v[i] * (long double)v[i];
    }
    long double worst = 0.0L;
    if (ss == 0.0L) {
        if (ret != 0 || o[0] != 0 || o[1] != 0 || (n == 3u && o[2] != 0)) {
            u->bad_zero++;
        }
    } else {
        if (ret != 1) {
            u->bad_zero++;
        }
        long double norm = sqrtl(ss);
        for (unsigned i = 0; i < n; i++) {
            long double e = fabsl((long double)o[i] - one * (long double)v[i] / norm);
            if (e > worst) {
                worst = e;
            }
        }
    }
    for (unsigned i = 0; i < n; i++) {
        out[i] = o[i];
    }
    return worst;
}

static void unit_sweep(unit_stats_t *u, unsigned n, unsigned frac, long double bound, uint64_t seed,
                       long random_cases)
{
    uint64_t rng = seed;
    int32_t v[3] = {0, 0, 0};
    int32_t o[3];
    /* Fixed cases: tiny, huge, mixed scales. */
    static const int32_t fixed[][3] = {{0, 0, 0},
                                       {1, 0, 0},
                                       {0, -1, 0},
                                       {1, 1, 1},
                                       {-1, 1, -1},
                                       {INT32_MIN, 0, 0},
                                       {INT32_MIN, INT32_MIN, INT32_MIN},
                                       {INT32_MIN, INT32_MAX, INT32_MIN},
                                       {INT32_MAX, INT32_MAX, INT32_MAX},
                                       {1, 1 << 30, 0},
                                       {1 << 30, 1, 1},
                                       {INT32_MIN, 1, -1},
                                       {32768, 1, 0},
                                       {32768, 1, 1},
                                       {32767, 1, 0},
                                       {65535, 1, 0},
                                       {65536, 1, 1},
                                       {3, 4, 0},
                                       {-3, 4, 12},
                                       {16384, 16384, 0},
                                       {46341, 46341, 46341},
                                       /* the worst cases found by long searches (q_unit*_q28) */
                                       {11586, 135227512, -12058897},
                                       {2922, 751, 66801},
                                       {-33227, -867, -3347},
                                       {-18109856, -6637, 0},
                                       {209340, 2991618, 0},
                                       {263117, 60, 0},
                                       {4306686, -15441, 631}};
    for (size_t f = 0; f < sizeof fixed / sizeof fixed[0]; f++) {
        long double e = unit_case(u, n, frac, fixed[f], o);
        unit_stats_add(u, n, fixed[f], o, e, bound);
    }
    /* Every small integer vector in [-40, 40]^n (n = 2) or [-12, 12]^3. */
    int lim = (n == 2u) ? 40 : 12;
    for (int x = -lim; x <= lim; x++) {
        for (int y = -lim; y <= lim; y++) {
            for (int z = (n == 3u ? -lim : 0); z <= (n == 3u ? lim : 0); z++) {
                v[0] = x;
                v[1] = y;
                v[2] = z;
                long double e = unit_case(u, n, frac, v, o);
                unit_stats_add(u, n, v, o, e, bound);
            }
        }
    }
    /* One component 2^k (or 2^k +- 1), the others small: the block-scaling boundary. */
    for (unsigned k = 0; k <= 31u; k++) {
        for (int d = -1; d <= 1; d++) {
            for (int s = 0; s < 64; s++) {
                int64_t big = ((int64_t)1 << k) + d;
                v[0] = q14t_sat32((s & 1) ? -big : big);
                v[1] = (int32_t)(s >> 1) - 16;
                v[2] = (n == 3u) ? (int32_t)(s % 7) - 3 : 0;
                long double e = unit_case(u, n, frac, v, o);
                unit_stats_add(u, n, v, o, e, bound);
            }
        }
    }
    /* Random vectors: each component at its own random scale, or all at one scale. */
    for (long c = 0; c < random_cases; c++) {
        unsigned common = q14t_below(&rng, 33u);
        int mixed = (int)(q14t_below(&rng, 2u));
        for (unsigned i = 0; i < n; i++) {
            v[i] = rand_scaled32(&rng, mixed ? q14t_below(&rng, 33u) : common);
        }
        long double e = unit_case(u, n, frac, v, o);
        unit_stats_add(u, n, v, o, e, bound);
    }
}

/* The documented bounds: Q16 "an error below 1 LSB of Q16 per component";
 * Q28 "within 6 LSB of Q28 (2.3e-8) of the exact unit vector per component". */
#define UNIT_Q16_BOUND 1.0L
#define UNIT_Q28_BOUND 6.0L

static void run_unit(const char *name, unsigned n, unsigned frac, long double bound, uint64_t seed)
{
    unit_stats_t u;
    unit_stats_init(&u, name);
    unit_sweep(&u, n, frac, bound, seed, 1000000L);
    unit_stats_report(&u, n, (frac == 16u) ? "Q16" : "Q28", bound);
    TEST_ASSERT_EQUAL_INT64_MESSAGE(0, u.bad_zero, "return value / zero-vector contract");
    TEST_ASSERT_EQUAL_INT64_MESSAGE(0, u.over_bound,
                                    "unit vector error above the documented bound");
}

static void test_q_unit2_q16_error(void)
{
    run_unit("q_unit2_q16", 2u, 16u, UNIT_Q16_BOUND, 0x0217ull);
}

static void test_q_unit3_q16_error(void)
{
    run_unit("q_unit3_q16", 3u, 16u, UNIT_Q16_BOUND, 0x0317ull);
}

static void test_q_unit2_q28_error(void)
{
    run_unit("q_unit2_q28", 2u, 28u, UNIT_Q28_BOUND, 0x0228ull);
}

static void test_q_unit3_q28_error(void)
{
    run_unit("q_unit3_q28", 3u, 28u, UNIT_Q28_BOUND, 0x0328ull);
}

/* q_unit_q28 (array form): the same bits as q_unit2_q28 / q_unit3_q28, and in
 * place (out == v) too. */
static void test_q_unit_q28_array_form_and_in_place(void)
{
    q14t_check_t c;
    q14t_check_init(&c, "q_unit_q28 == q_unit2/3_q28");
    uint64_t rng = 0xA77ull;
    for (long k = 0; k < 300000L; k++) {
        unsigned n = 2u + (unsigned)(k & 1);
        int32_t v[3];
        unsigned common = q14t_below(&rng, 33u);
        for (unsigned i = 0; i < 3u; i++) {
            v[i] = rand_scaled32(&rng, (k & 2) ? q14t_below(&rng, 33u) : common);
        }
        if (n == 2u) {
            v[2] = 0x13579BDF; /* must be left alone */
        }
        int32_t ref[3] = {0, 0, 0};
        int ref_ok = (n == 2u) ? q_unit2_q28(v[0], v[1], &ref[0], &ref[1]) : q_unit3_q28(v, ref);
        int32_t out[3] = {0x5A5A5A5A, 0x5A5A5A5A, 0x5A5A5A5A};
        int ok = q_unit_q28(v, n, out);
        int32_t inplace[3] = {v[0], v[1], v[2]};
        int ok2 = q_unit_q28(inplace, n, inplace);
        int bad = (ok != ref_ok) || (ok2 != ref_ok);
        for (unsigned i = 0; i < n; i++) {
            bad |= (out[i] != ref[i]) || (inplace[i] != ref[i]);
        }
        if (n == 2u) {
            bad |= (out[2] != 0x5A5A5A5A) || (inplace[2] != 0x13579BDF);
        }
        c.cases++;
        if (bad && c.failures++ == 0) {
            snprintf(c.first, sizeof c.first,
                     "q_unit_q28((%" PRId32 ", %" PRId32 ", %" PRId32 "), %u): out=(%" PRId32
                     ", %" PRId32 ", %" PRId32 ") in place=(%" PRId32 ", %" PRId32 ", %" PRId32
                     ") expected (%" PRId32 ", %" PRId32 ", %" PRId32 ")",
                     v[0], v[1], v[2], n, out[0], out[1], out[2], inplace[0], inplace[1],
                     inplace[2], ref[0], ref[1], ref[2]);
        }
    }
    int32_t z[3] = {0, 0, 0};
    int32_t o[3] = {1, 2, 3};
    TEST_ASSERT_EQUAL_INT(0, q_unit_q28(z, 3u, o));
    TEST_ASSERT_EQUAL_INT32(0, o[0]);
    TEST_ASSERT_EQUAL_INT32(0, o[1]);
    TEST_ASSERT_EQUAL_INT32(0, o[2]);
    q14t_check_report(&c);
}

static void test_q_unit_zero_vector(void)
{
    q16_t a = 77;
    q16_t b = 77;
    TEST_ASSERT_EQUAL_INT(0, q_unit2_q16(0, 0, &a, &b));
    TEST_ASSERT_EQUAL_INT32(0, a);
    TEST_ASSERT_EQUAL_INT32(0, b);
    const int32_t z[3] = {0, 0, 0};
    q16_t o[3] = {5, 6, 7};
    TEST_ASSERT_EQUAL_INT(0, q_unit3_q16(z, o));
    TEST_ASSERT_EQUAL_INT32(0, o[0]);
    TEST_ASSERT_EQUAL_INT32(0, o[1]);
    TEST_ASSERT_EQUAL_INT32(0, o[2]);
    TEST_ASSERT_EQUAL_INT(1, q_unit2_q16(0, -1, &a, &b));
    TEST_ASSERT_EQUAL_INT32(0, a);
    TEST_ASSERT_EQUAL_INT32(-65536, b);
    TEST_ASSERT_EQUAL_INT(1, q_unit2_q16(INT32_MIN, 0, &a, &b));
    TEST_ASSERT_EQUAL_INT32(-65536, a);
    TEST_ASSERT_EQUAL_INT32(0, b);
}

/* ---- q14_norm2_q16 ---------------------------------------------------------------- */

/*
 * The contract (q14.h): the correctly rounded root on the Q16 grid when
 * a^2 + b^2 < 1/4, on the Q15 grid below 1 and on the Q14 grid above (so
 * within 2 LSB of Q16). Checked per range: below 1/4 the result must be
 * exactly round(4 sqrt(a^2 + b^2)) (Q16 LSB units, no ties exist); in
 * [1/4, 1) the error must be at most 1/2 LSB of Q15 (= 1 LSB of Q16); from 1
 * up at most 1/2 LSB of Q14 (= 2 LSB of Q16). The worst error of each range is
 * printed, and so is the range the implementation actually rounds on.
 */
typedef struct {
    long long cases;
    long double worst;
    int32_t wa, wb;
    long long on_q16_grid; /* results equal to the correctly rounded Q16 value */
} norm_range_t;

static void test_q14_norm2_q16(void)
{
    q14t_check_t c;
    q14t_check_init(&c, "q14_norm2_q16 (contract)");
    norm_range_t r[3];
    memset(r, 0, sizeof r);
    static const long double bound[3] = {0.5L, 1.0L, 2.0L};
    static const char *const range_name[3] = {"|v|^2 < 1/4", "1/4 <= |v|^2 < 1", "|v|^2 >= 1"};
    uint64_t rng = 0x0F2ull;
    for (long n = 0; n < 3000000L; n++) {
        int32_t a;
        int32_t b;
        if (n < 65536L * 8) {
            a = (int32_t)(n >> 3) + INT16_MIN; /* every a against 8 edge values of b */
            b = edges16[n & 7];
        } else if (n < 65536L * 10) {
            a = (int32_t)((n - 65536L * 8) >> 1) + INT16_MIN; /* the diagonals */
            b = (n & 1) ? a : -a;
            b = (b > INT16_MAX) ? INT16_MAX : b;
        } else if (n < 65536L * 10 + 1000000L) {
            /* Small vectors (every magnitude, mostly under 1). */
            unsigned bits = q14t_below(&rng, 16u);
            a = (int32_t)(q14t_u32(&rng) & ((1u << bits) - 1u)) * (q14t_below(&rng, 2u) ? -1 : 1);
            b = (int32_t)(q14t_u32(&rng) & ((1u << bits) - 1u)) * (q14t_below(&rng, 2u) ? -1 : 1);
        } else {
            a = q14t_i16_mixed(&rng);
            b = q14t_i16_mixed(&rng);
        }
        q16_t got = q14_norm2_q16((int16_t)a, (int16_t)b);
        int64_t ss = (int64_t)a * a + (int64_t)b * b; /* Q28 */
        int64_t nearest16 = (int64_t)q14t_isqrt64_round(16u * (uint64_t)ss);
        long double exact = 4.0L * sqrtl((long double)ss);
        long double e = fabsl((long double)got - exact);
        int k = (ss < (1 << 26)) ? 0 : ((ss < (1 << 28)) ? 1 : 2);
        r[k].cases++;
        if ((int64_t)got == nearest16) {
            r[k].on_q16_grid++;
        }
        if (e > r[k].worst) {
            r[k].worst = e;
            r[k].wa = a;
            r[k].wb = b;
        }
        int ok = (k == 0) ? ((int64_t)got == nearest16) : (e <= bound[k]);
        c.cases++;
        if (!ok && c.failures++ == 0) {
            snprintf(c.first, sizeof c.first,
                     "q14_norm2_q16(%" PRId32 ", %" PRId32 ") = %" PRId32 ", exact %.4Lf (%s: "
                     "allowed %.1Lf LSB)",
                     a, b, got, exact, range_name[k], bound[k]);
        }
    }
    for (int k = 0; k < 3; k++) {
        printf("[q14] q14_norm2_q16 %-17s cases=%lld worst |err| = %.4Lf LSB Q16 at (%" PRId32
               ", %" PRId32 "), correctly rounded on Q16: %lld\n",
               range_name[k], r[k].cases, r[k].worst, r[k].wa, r[k].wb, r[k].on_q16_grid);
    }
    TEST_ASSERT_EQUAL_INT32(0, q14_norm2_q16(0, 0));
    TEST_ASSERT_EQUAL_INT32(65536, q14_norm2_q16(16384, 0));
    TEST_ASSERT_EQUAL_INT32(65536, q14_norm2_q16(0, -16384));
    TEST_ASSERT_EQUAL_INT32(4, q14_norm2_q16(1, 0));
    TEST_ASSERT_EQUAL_INT32(6, q14_norm2_q16(1, -1));                         /* 5.657 */
    TEST_ASSERT_INT32_WITHIN(2, 185364, q14_norm2_q16(INT16_MIN, INT16_MIN)); /* 2 sqrt 2 */
    TEST_ASSERT_TRUE(q14_norm2_q16(INT16_MIN, INT16_MIN) <= Q16_FROM_REAL(2.8284271247461903) + 2);
    q14t_check_report(&c);
}

/* ---- q14_normalize2 / q14_normalize3 ------------------------------------------------ */

/*
 * "Normalize ... to unit length (Q14, rounded)": the Q28 unit vector (within
 * UNIT_Q28_BOUND LSB of Q28) rounded once to Q14, so at most 1/2 LSB of Q14
 * plus UNIT_Q28_BOUND / 2^14. The count of results that are not the nearest
 * Q14 value is printed.
 */
#define NORMALIZE_BOUND (0.5L + UNIT_Q28_BOUND / 16384.0L)

static void normalize_sweep(unsigned n)
{
    unit_stats_t u;
    unit_stats_init(&u, (n == 2u) ? "q14_normalize2" : "q14_normalize3");
    const long double bound = NORMALIZE_BOUND;
    long long not_nearest = 0;
    uint64_t rng = (n == 2u) ? 0x2A2ull : 0x3A3ull;
    long total = 1500000L;
    for (long c = 0; c < total; c++) {
        int16_t v[3] = {0, 0, 0};
        if (c < 6561) {
            /* Every vector of 9 edge values in each component (n = 3: 729, n = 2: 81). */
            static const int16_t e9[9] = {INT16_MIN, INT16_MIN + 1, -16384, -1,       0,
                                          1,         16384,         32766,  INT16_MAX};
            v[0] = e9[c % 9];
            v[1] = e9[(c / 9) % 9];
            v[2] = (n == 3u) ? e9[(c / 81) % 9] : 0;
        } else if (c < 6561 + 200000) {
            /* Small vectors: every magnitude from 1 LSB up. */
            unsigned bits = q14t_below(&rng, 17u);
            for (unsigned i = 0; i < n; i++) {
                int32_t m = (int32_t)(q14t_u32(&rng) & ((1u << bits) - 1u));
                v[i] = q14t_sat16(q14t_below(&rng, 2u) ? -(int64_t)m : m);
            }
        } else {
            for (unsigned i = 0; i < n; i++) {
                v[i] = q14t_i16_mixed(&rng);
            }
        }
        int16_t w[3] = {v[0], v[1], v[2]};
        int ret = (n == 2u) ? q14_normalize2(w) : q14_normalize3(w);
        long double ss = 0.0L;
        for (unsigned i = 0; i < n; i++) {
            ss += (long double)v[i] * v[i];
        }
        int32_t in32[3] = {v[0], v[1], v[2]};
        int32_t out32[3] = {w[0], w[1], w[2]};
        long double worst = 0.0L;
        if (ss == 0.0L) {
            if (ret != 0 || w[0] != 0 || w[1] != 0 || w[2] != 0) {
                u.bad_zero++;
            }
        } else {
            if (ret != 1) {
                u.bad_zero++;
            }
            long double norm = sqrtl(ss);
            int nearest = 1;
            for (unsigned i = 0; i < n; i++) {
                long double exact = 16384.0L * (long double)v[i] / norm;
                long double e = fabsl((long double)w[i] - exact);
                if (e > worst) {
                    worst = e;
                }
                if (e > 0.5L) {
                    nearest = 0;
                }
            }
            if (!nearest) {
                not_nearest++;
            }
        }
        unit_stats_add(&u, n, in32, out32, worst, bound);
    }
    unit_stats_report(&u, n, "Q14", bound);
    printf("[q14] %-16s results not the nearest Q14 value (|err| > 0.5 LSB): %lld of %lld\n",
           u.name, not_nearest, u.cases);
    TEST_ASSERT_EQUAL_INT64_MESSAGE(0, u.bad_zero, "return value / zero-vector contract");
    TEST_ASSERT_EQUAL_INT64_MESSAGE(0, u.over_bound,
                                    "normalize: error above 1/2 LSB of Q14 + Q28 error");
}

static void test_q14_normalize2_error(void)
{
    normalize_sweep(2u);
}

static void test_q14_normalize3_error(void)
{
    normalize_sweep(3u);
}

static void test_q14_normalize_zero_and_axes(void)
{
    int16_t z2[2] = {0, 0};
    int16_t z3[3] = {0, 0, 0};
    TEST_ASSERT_EQUAL_INT(0, q14_normalize2(z2));
    TEST_ASSERT_EQUAL_INT16(0, z2[0]);
    TEST_ASSERT_EQUAL_INT16(0, z2[1]);
    TEST_ASSERT_EQUAL_INT(0, q14_normalize3(z3));
    TEST_ASSERT_EQUAL_INT16(0, z3[0]);
    TEST_ASSERT_EQUAL_INT16(0, z3[1]);
    TEST_ASSERT_EQUAL_INT16(0, z3[2]);
    int16_t a[2] = {INT16_MIN, 0};
    TEST_ASSERT_EQUAL_INT(1, q14_normalize2(a));
    TEST_ASSERT_EQUAL_INT16(-16384, a[0]);
    TEST_ASSERT_EQUAL_INT16(0, a[1]);
    int16_t b[3] = {0, 0, 1};
    TEST_ASSERT_EQUAL_INT(1, q14_normalize3(b));
    TEST_ASSERT_EQUAL_INT16(0, b[0]);
    TEST_ASSERT_EQUAL_INT16(0, b[1]);
    TEST_ASSERT_EQUAL_INT16(16384, b[2]);
}

int main(void)
{
    double t0 = q14t_seconds();
    UNITY_BEGIN();
    RUN_TEST(test_q14_dot3_cross3_edges_and_random);
    RUN_TEST(test_q_unit_zero_vector);
    RUN_TEST(test_q_unit2_q16_error);
    RUN_TEST(test_q_unit3_q16_error);
    RUN_TEST(test_q_unit2_q28_error);
    RUN_TEST(test_q_unit3_q28_error);
    RUN_TEST(test_q_unit_q28_array_form_and_in_place);
    RUN_TEST(test_q14_norm2_q16);
    RUN_TEST(test_q14_normalize_zero_and_axes);
    RUN_TEST(test_q14_normalize2_error);
    RUN_TEST(test_q14_normalize3_error);
    int rc = UNITY_END();
    printf("[q14] test_q14_vectors runtime %.2f s\n", q14t_seconds() - t0);
    return rc;
}
