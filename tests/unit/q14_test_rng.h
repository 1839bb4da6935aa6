/*
 * q14_test_rng.h - what the q14 unit tests share: a seeded RNG (splitmix64,
 * the same sequence on every platform), generators of "interesting" int32 and
 * int16 values (edges, powers of two and their neighbours, every magnitude),
 * exact floor division, and a small failure recorder that keeps the first
 * failing input so a test prints it before it fails.
 *
 * Header-only on purpose (static inline): it does not depend on the shared
 * test-support library.
 */
#ifndef Q14_TEST_RNG_H
#define Q14_TEST_RNG_H

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <time.h>

#include "unity.h"

/* ---- RNG ------------------------------------------------------------------ */

static inline uint64_t q14t_next(uint64_t *s)
{
    uint64_t z = (*s += UINT64_C(0x9E3779B97F4A7C15));
    z = (z ^ (z >> 30)) * UINT64_C(0xBF58476D1CE4E5B9);
    z = (z ^ (z >> 27)) * UINT64_C(0x94D049BB133111EB);
    return z ^ (z >> 31);
}

static inline uint32_t q14t_u32(uint64_t *s)
{
    return (uint32_t)(q14t_next(s) >> 32);
}

/* Uniform in [0, n), n >= 1 (the tiny modulo bias does not matter here). */
static inline uint32_t q14t_below(uint64_t *s, uint32_t n)
{
    return (uint32_t)(q14t_next(s) % n);
}

/* Two's-complement reinterpretation without implementation-defined casts. */
static inline int32_t q14t_as_i32(uint32_t u)
{
    return (u <= (uint32_t)INT32_MAX) ? (int32_t)u : (int32_t)(int64_t)((int64_t)u - 4294967296LL);
}

static inline int16_t q14t_as_i16(uint32_t u)
{
    u &= 0xFFFFu;
    return (u <= 0x7FFFu) ? (int16_t)u : (int16_t)((int32_t)u - 65536);
}

/*
 * An int32 drawn from a mixture: uniform; a random bit length (every
 * magnitude from 0 to 2^31); a power of two or its neighbours; the edges.
 */
static inline int32_t q14t_i32_mixed(uint64_t *s)
{
    uint32_t kind = q14t_below(s, 8u);
    uint32_t r = q14t_u32(s);
    int neg = (int)(q14t_below(s, 2u));
    int64_t v;
    switch (kind) {
    case 0:
    case 1:
        return q14t_as_i32(r);
    case 2:
    case 3: {
        unsigned bits = q14t_below(s, 32u); /* magnitude < 2^bits */
        v = (bits == 0u) ? 0 : (int64_t)(r & ((bits >= 32u) ? 0xFFFFFFFFu : ((1u << bits) - 1u)));
        break;
    }
    case 4:
    case 5: {
        unsigned k = q14t_below(s, 32u);
        v = ((int64_t)1 << k) + (int64_t)q14t_below(s, 3u) - 1; /* 2^k - 1, 2^k, 2^k + 1 */
        break;
    }
    case 6: {
        static const int64_t edge[] = {0,
                                       1,
                                       2,
                                       3,
                                       32767,
                                       32768,
                                       32769,
                                       65535,
                                       65536,
                                       65537,
                                       INT32_MAX - 1,
                                       INT32_MAX,
                                       (int64_t)INT32_MAX + 1};
        v = edge[q14t_below(s, (uint32_t)(sizeof edge / sizeof edge[0]))];
        break;
    }
    default:
        v = (int64_t)q14t_below(s, 256u);
        break;
    }
    if (neg) {
        v = -v;
    }
    if (v > INT32_MAX) {
        v = INT32_MAX;
    }
    if (v < INT32_MIN) {
        v = INT32_MIN;
    }
    return (int32_t)v;
}

/* An int16 from the same kind of mixture (uniform half of the time). */
static inline int16_t q14t_i16_mixed(uint64_t *s)
{
    uint32_t kind = q14t_below(s, 4u);
    if (kind <= 1u) {
        return q14t_as_i16(q14t_u32(s));
    }
    if (kind == 2u) {
        static const int16_t edge[] = {
            INT16_MIN, INT16_MIN + 1, -16385, -16384, -16383, -8192,         -2,       -1, 0, 1,
            2,         8192,          16383,  16384,  16385,  INT16_MAX - 1, INT16_MAX};
        return edge[q14t_below(s, (uint32_t)(sizeof edge / sizeof edge[0]))];
    }
    unsigned bits = q14t_below(s, 16u);
    int32_t v = (int32_t)(q14t_u32(s) & ((1u << bits) - 1u));
    return (int16_t)(q14t_below(s, 2u) ? -v : v);
}

/* ---- exact arithmetic ----------------------------------------------------- */

/* floor(n / d) for d > 0, by C division plus a correction (no shifts). */
static inline int64_t q14t_floordiv64(int64_t n, int64_t d)
{
    int64_t q = n / d;
    if ((n % d) != 0 && n < 0) {
        q -= 1;
    }
    return q;
}

static inline int32_t q14t_sat32(int64_t v)
{
    return (v > INT32_MAX) ? INT32_MAX : ((v < INT32_MIN) ? INT32_MIN : (int32_t)v);
}

static inline int16_t q14t_sat16(int64_t v)
{
    return (v > INT16_MAX) ? INT16_MAX : ((v < INT16_MIN) ? INT16_MIN : (int16_t)v);
}

/* floor(sqrt(x)) of a uint64, exact (double estimate then integer fix-up). */
static inline uint64_t q14t_isqrt64(uint64_t x)
{
    uint64_t r = (uint64_t)sqrt((double)x);
    while (r > 0u && (r > UINT64_C(0xFFFFFFFF) || r * r > x)) {
        r--;
    }
    while ((r + 1u) <= UINT64_C(0xFFFFFFFF) && (r + 1u) * (r + 1u) <= x) {
        r++;
    }
    return r;
}

/* sqrt(x) rounded to nearest (no ties exist for an integer x). */
static inline uint64_t q14t_isqrt64_round(uint64_t x)
{
    uint64_t s = q14t_isqrt64(x);
    return (x - s * s > s) ? s + 1u : s; /* x >= s^2 + s + 1 <=> x >= (s + 1/2)^2 */
}

/* ---- failure recorder ----------------------------------------------------- */

typedef struct {
    const char *name;
    long long cases;
    long long failures;
    char first[256]; /* the first failing input, expected and actual */
} q14t_check_t;

static inline void q14t_check_init(q14t_check_t *c, const char *name)
{
    c->name = name;
    c->cases = 0;
    c->failures = 0;
    c->first[0] = '\0';
}

/* Print the figures, then fail (with the first failing case) if any failed. */
static inline void q14t_check_report(const q14t_check_t *c)
{
    printf("[q14] %-34s cases=%lld failures=%lld\n", c->name, c->cases, c->failures);
    if (c->failures != 0) {
        printf("[q14] %-34s FIRST FAILURE: %s\n", c->name, c->first);
    }
    fflush(stdout);
    if (c->failures != 0) {
        TEST_FAIL_MESSAGE(c->first);
    }
}

/* Wall-clock seconds (for the runtime figures). */
static inline double q14t_seconds(void)
{
    struct timespec ts;
    timespec_get(&ts, TIME_UTC);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

#endif /* Q14_TEST_RNG_H */
