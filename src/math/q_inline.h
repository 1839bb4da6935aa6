/*
 * q_inline.h - the library's hot primitives as static inline functions, so
 * that the control step gets them without a call and with its constant shifts
 * folded. The public functions of q14.h are thin wrappers around these, and
 * the tests of q14.h therefore test these.
 */
#ifndef HELICAL_Q_INLINE_H
#define HELICAL_Q_INLINE_H

#include <stdint.h>

#include "math/q14_target.h"

/* Where a call's frame would count against the control tick's stack. */
#if defined(__GNUC__) || defined(__clang__)
#define QI_ALWAYS_INLINE inline __attribute__((always_inline))
#else
#define QI_ALWAYS_INLINE inline
#endif

static inline int16_t qi_sat16(int32_t x)
{
    return Q_TARGET_SAT16(x);
}

/* round(x / 2^shift), ties toward +inf, shift in [1, 31]: floor plus the
 * first dropped bit, so it cannot overflow. */
static inline int32_t qi_rshift_round(int32_t x, unsigned shift)
{
    /* arithmetic >> of a negative x by design: floor(x / 2^shift), see q14.h */
    // cppcheck-suppress misra-c2012-10.1 ; arithmetic >> by design (q14.c static assert)
    return (x >> shift) + ((x >> (shift - 1u)) & 1);
}

/* Count of leading zero bits of a nonzero x (CLZ on ARMv7-M, a libgcc helper
 * on ARMv6-M, a loop where the compiler has no builtin). */
static inline unsigned qi_clz32(uint32_t x)
{
#if defined(__GNUC__) || defined(__clang__)
    return (unsigned)__builtin_clz(x);
#else
    unsigned n = 0u;
    uint32_t v = x;
    while ((v & 0x80000000u) == 0u) {
        v <<= 1;
        n++;
    }
    return n;
#endif
}

#if Q_TARGET_HAS_QADD
static inline int32_t qi_add_sat32(int32_t a, int32_t b)
{
    return __qadd(a, b);
}

static inline int32_t qi_sub_sat32(int32_t a, int32_t b)
{
    return __qsub(a, b);
}
#else
static inline int32_t qi_add_sat32(int32_t a, int32_t b)
{
    if ((b > 0) && (a > (INT32_MAX - b))) {
        return INT32_MAX;
    }
    if ((b < 0) && (a < (INT32_MIN - b))) {
        return INT32_MIN;
    }
    return a + b;
}

static inline int32_t qi_sub_sat32(int32_t a, int32_t b)
{
    if ((b < 0) && (a > (INT32_MAX + b))) {
        return INT32_MAX;
    }
    if ((b > 0) && (a < (INT32_MIN + b))) {
        return INT32_MIN;
    }
    return a - b;
}
#endif

/* 64-bit unsigned value as two 32-bit halves. */
typedef struct {
    uint32_t hi, lo;
} u64pair_t;

static inline u64pair_t umul32(uint32_t a, uint32_t b)
{
    uint32_t a0 = a & 0xFFFFu, a1 = a >> 16;
    uint32_t b0 = b & 0xFFFFu, b1 = b >> 16;
    uint32_t p00 = a0 * b0, p01 = a0 * b1, p10 = a1 * b0, p11 = a1 * b1;
    uint32_t mid = p01 + p10;
    uint32_t mid_carry = (mid < p01) ? 0x10000u : 0u;
    u64pair_t r;
    r.lo = p00 + (mid << 16);
    r.hi = p11 + (mid >> 16) + mid_carry + ((r.lo < p00) ? 1u : 0u);
    return r;
}

static inline u64pair_t u64_add(u64pair_t x, uint32_t hi, uint32_t lo)
{
    u64pair_t r;
    r.lo = x.lo + lo;
    r.hi = x.hi + hi + ((r.lo < x.lo) ? 1u : 0u);
    return r;
}

/* 2^k as a 64-bit pair, k in [0, 62]. */
static inline u64pair_t u64_pow2(unsigned k)
{
    u64pair_t r;
    if (k >= 32u) {
        r.hi = (uint32_t)1u << (k - 32u);
        r.lo = 0u;
    } else {
        r.hi = 0u;
        r.lo = (uint32_t)1u << k;
    }
    return r;
}

/*
 * The 64-bit two's-complement product a*b + 2^(shift-1), shifted right
 * arithmetically by shift, as (hi, lo) halves. The unsigned product of the
 * bit patterns differs from the signed one only in the high half, by b when
 * a < 0 and by a when b < 0 (mod 2^32), so no sign-magnitude detour is needed.
 */
static inline u64pair_t smul32_round_shift(int32_t a, int32_t b, unsigned shift)
{
    uint32_t ua = (uint32_t)a, ub = (uint32_t)b;
    u64pair_t p = umul32(ua, ub);
    p.hi -= (a < 0) ? ub : 0u;
    p.hi -= (b < 0) ? ua : 0u;
    u64pair_t half = u64_pow2(shift - 1u);
    p = u64_add(p, half.hi, half.lo);
    u64pair_t r;
    int32_t shi = (int32_t)p.hi; /* the conversion keeps the bits (gcc, clang, XC16) */
    if (shift < 32u) {
        r.lo = (p.lo >> shift) | (p.hi << (32u - shift));
        // cppcheck-suppress [misra-c2012-10.1, shiftTooManyBitsSigned] ; arithmetic >> by design
        const int32_t hi = shi >> shift;
        r.hi = (uint32_t)hi;
    } else {
        // cppcheck-suppress misra-c2012-10.1 ; arithmetic >> by design (q14.c static assert)
        const int32_t lo = shi >> (shift - 32u);
        // cppcheck-suppress [misra-c2012-10.1, shiftTooManyBitsSigned] ; arithmetic >> by design
        const int32_t sign = shi >> 31;
        r.lo = (uint32_t)lo;
        r.hi = (uint32_t)sign;
    }
    return r;
}

/*
 * The signed product a*b as hi * 2^32 + mid * 2^16 + (low 16 bits), from four
 * 16x16 partial products with signed high halves: a = ah * 2^16 + al with
 * 0 <= al < 2^16, so ah*bl and al*bh fit an int32 and no sign correction is
 * needed. mid carries up to 2 bits above its 16 (it is < 3 * 2^16), and the
 * low 16 bits of al*bl are left out: a shift of 16 or more cannot see them.
 * This is what a core without a 32x32->64 multiplier (Cortex-M0) wants: about
 * half the instructions of the unsigned 64-bit form above.
 */
typedef struct {
    int32_t hi;
    uint32_t mid;
} smul_parts_t;

static QI_ALWAYS_INLINE smul_parts_t smul32_parts(int32_t a, int32_t b, uint32_t mid_add)
{
    // cppcheck-suppress misra-c2012-10.1 ; arithmetic >> by design (q14.c static assert)
    const int32_t ah = a >> 16;
    // cppcheck-suppress misra-c2012-10.1 ; arithmetic >> by design (q14.c static assert)
    const int32_t bh = b >> 16;
    const uint32_t al = (uint32_t)a & 0xFFFFu;
    const uint32_t bl = (uint32_t)b & 0xFFFFu;
    const uint32_t ll = al * bl;
    const int32_t m1 = ah * (int32_t)bl; /* |.| < 2^31 */
    const int32_t m2 = (int32_t)al * bh;
    smul_parts_t p;
    p.mid = (ll >> 16) + ((uint32_t)m1 & 0xFFFFu) + ((uint32_t)m2 & 0xFFFFu) + mid_add;
    // cppcheck-suppress misra-c2012-10.1 ; arithmetic >> by design (q14.c static assert)
    p.hi = (ah * bh) + (m1 >> 16) + (m2 >> 16); /* |.| <= 2^30 + 2^16 */
    return p;
}

/* 2^(shift-17) for shift in [17, 32]: the rounding half in units of 2^16. */
static QI_ALWAYS_INLINE uint32_t mid_half(unsigned shift)
{
    return (uint32_t)1u << (shift - 17u);
}

/* Shift >= 33: the result is the high word shifted, rounded on its own. */
static QI_ALWAYS_INLINE int32_t parts_shift_above_32(smul_parts_t p, unsigned shift)
{
    const uint32_t carry = p.mid >> 16;
    const int32_t hi = p.hi + (int32_t)carry; /* floor(a*b / 2^32) */
    const uint32_t half_u = (uint32_t)1u << (shift - 33u);
    const int32_t half = (int32_t)half_u;
    // cppcheck-suppress misra-c2012-10.1 ; arithmetic >> by design (q14.c static assert)
    return (hi + half) >> (shift - 32u);
}

static inline int32_t qi_mul32_portable(int32_t a, int32_t b, unsigned shift)
{
    if (shift >= 17u && shift <= 32u) {
        /* (a*b + 2^(shift-1)) = hr * 2^32 + (mid16 * 2^16 + low16): the
         * result is hr * 2^(32-shift) + mid16 >> (shift-16), which fits an
         * int32 exactly when -2^(shift-1) <= hr < 2^(shift-1). */
        const smul_parts_t p = smul32_parts(a, b, mid_half(shift));
        const uint32_t carry = p.mid >> 16;
        const int32_t hr = p.hi + (int32_t)carry;
        if (shift < 32u) {
            const uint32_t lim_u = (uint32_t)1u << (shift - 1u);
            const int32_t lim = (int32_t)lim_u;
            if (hr >= lim) {
                return INT32_MAX;
            }
            if (hr < -lim) {
                return INT32_MIN;
            }
        }
        const uint32_t r_u = ((uint32_t)hr << (32u - shift)) + ((p.mid & 0xFFFFu) >> (shift - 16u));
        return (int32_t)r_u;
    }
    if (shift > 32u) {
        return parts_shift_above_32(smul32_parts(a, b, 0u), shift); /* |.| <= 2^30: fits */
    }
    /* shifts 1..16 (0 is read as 1: never an undefined shift) */
    u64pair_t r = smul32_round_shift(a, b, (shift < 1u) ? 1u : shift);
    int32_t lo = (int32_t)r.lo;
    /* it fits iff the high half is the sign extension of the low half */
    // cppcheck-suppress [misra-c2012-10.1, shiftTooManyBitsSigned] ; arithmetic >> by design
    if ((int32_t)r.hi != (lo >> 31)) {
        return ((int32_t)r.hi < 0) ? INT32_MIN : INT32_MAX;
    }
    return lo;
}

/* qi_mul32_portable where the caller has shown that the result fits. */
static inline int32_t qi_mul32_fit_portable(int32_t a, int32_t b, unsigned shift)
{
    if (shift >= 17u && shift <= 32u) {
        const smul_parts_t p = smul32_parts(a, b, mid_half(shift));
        /* mid's carries are added at their weight by the shift of mid */
        const uint32_t r_u = ((uint32_t)p.hi << (32u - shift)) + (p.mid >> (shift - 16u));
        return (int32_t)r_u;
    }
    if (shift > 32u) {
        return parts_shift_above_32(smul32_parts(a, b, 0u), shift);
    }
    return (int32_t)smul32_round_shift(a, b, (shift < 1u) ? 1u : shift).lo; /* shifts 1..16 */
}

#if Q_TARGET_HAS_MUL64
/* p (an exact 64-bit sum of products, |p| <= 2^62) rounded by shift in
 * [1, 62], ties toward +inf, saturated to int32: the one rounding of
 * qi_mul32 and qi_dot3 on a core with a 32x32->64 multiplier. */
static inline int32_t qi_round_sat64(int64_t p, unsigned shift)
{
    const unsigned half_shift = shift - 1u;
    const uint64_t half = (uint64_t)1u << half_shift;
    int64_t r = p + (int64_t)half;
    // cppcheck-suppress misra-c2012-10.1 ; arithmetic >> by design (q14.c static assert)
    r >>= shift;
    if (r > INT32_MAX) {
        return INT32_MAX;
    }
    if (r < INT32_MIN) {
        return INT32_MIN;
    }
    return (int32_t)r;
}

static inline int32_t qi_mul32(int32_t a, int32_t b, unsigned shift)
{
    /* Cores with a 32x32->64 multiplier (SMULL, x86-64 IMUL): same bits as
     * the portable version below, proven by test_q14_wide. */
    return qi_round_sat64((int64_t)a * (int64_t)b, shift);
}
#else
static inline int32_t qi_mul32(int32_t a, int32_t b, unsigned shift)
{
    return qi_mul32_portable(a, b, shift);
}
#endif

/*
 * round(a*b / 2^shift) for an int32 a and an int16 b, ties toward +inf,
 * saturated, shift in [1, 46]: the same bits as qi_mul32 (the product is
 * exact before the one rounding), but from two 16x16 partial products, which
 * is what a core without a wide multiplier wants.
 */
static inline int32_t qi_mul32x16_portable(int32_t a, int16_t b, unsigned shift)
{
    // cppcheck-suppress misra-c2012-10.1 ; arithmetic >> by design (q14.c static assert)
    int32_t a_hi = a >> 16;
    const uint32_t a_lo_u = (uint32_t)a & 0xFFFFu;
    int32_t a_lo = (int32_t)a_lo_u;
    int32_t p_lo = a_lo * b; /* |.| < 2^31: 65535 * 32768 = 2^31 - 2^15 */
    /* a*b = hi * 2^16 + lo exactly, 0 <= lo < 2^16 */
    // cppcheck-suppress misra-c2012-10.1 ; arithmetic >> by design (q14.c static assert)
    int32_t hi = (a_hi * b) + (p_lo >> 16);
    uint32_t lo = (uint32_t)p_lo & 0xFFFFu;
    if (shift >= 16u) {
        if (shift == 16u) {
            return hi + (int32_t)(lo >> 15);
        }
        /* lo / 2^16 < 1 cannot carry past the rounding bit: drop it. */
        const uint32_t half = (uint32_t)1u << (shift - 17u);
        // cppcheck-suppress misra-c2012-10.1 ; arithmetic >> by design (q14.c static assert)
        return (hi + (int32_t)half) >> (shift - 16u);
    }
    unsigned up = 16u - shift;
    // cppcheck-suppress misra-c2012-10.1 ; >> of a signed constant, as the test below
    if (hi > (INT32_MAX >> up)) {
        return INT32_MAX;
    }
    // cppcheck-suppress [misra-c2012-10.1, shiftNegativeLHS] ; arithmetic >> by design
    if (hi < (INT32_MIN >> up)) {
        return INT32_MIN;
    }
    const uint32_t r_u = (lo + ((uint32_t)1u << (shift - 1u))) >> shift;
    const uint32_t hi_up = (uint32_t)hi << up; /* |hi| fits: tested above */
    return qi_add_sat32((int32_t)hi_up, (int32_t)r_u);
}

#if Q_TARGET_HAS_MUL64
static inline int32_t qi_mul32x16(int32_t a, int16_t b, unsigned shift)
{
    return qi_mul32(a, b, shift);
}
#else
static inline int32_t qi_mul32x16(int32_t a, int16_t b, unsigned shift)
{
    return qi_mul32x16_portable(a, b, shift);
}
#endif

/*
 * The same products where the caller has shown that the result fits in int32
 * (each use says why): on a core with a wide multiplier the saturation test is
 * dropped (SMULL, add, shift); the portable forms keep theirs, which cost
 * little next to the partial products. The rounding is identical.
 */
#if Q_TARGET_HAS_MUL64
static inline int32_t qi_mul32_fit(int32_t a, int32_t b, unsigned shift)
{
    const unsigned half_shift = shift - 1u;
    const uint64_t half = (uint64_t)1u << half_shift;
    const int64_t p = ((int64_t)a * (int64_t)b) + (int64_t)half;
    // cppcheck-suppress misra-c2012-10.1 ; arithmetic >> by design (q14.c static assert)
    const int64_t r = p >> shift;
    return (int32_t)r; /* fits: the caller's proof */
}
static inline int32_t qi_mul32x16_fit(int32_t a, int16_t b, unsigned shift)
{
    return qi_mul32_fit(a, b, shift);
}
#else
static inline int32_t qi_mul32_fit(int32_t a, int32_t b, unsigned shift)
{
    return qi_mul32_fit_portable(a, b, shift);
}
static inline int32_t qi_mul32x16_fit(int32_t a, int16_t b, unsigned shift)
{
    /* the two-partial-product form of qi_mul32x16_portable, without its
     * saturation test */
    // cppcheck-suppress misra-c2012-10.1 ; arithmetic >> by design (q14.c static assert)
    int32_t a_hi = a >> 16;
    const uint32_t a_lo_u = (uint32_t)a & 0xFFFFu;
    int32_t p_lo = (int32_t)a_lo_u * b;
    // cppcheck-suppress misra-c2012-10.1 ; arithmetic >> by design (q14.c static assert)
    int32_t hi = (a_hi * b) + (p_lo >> 16);
    uint32_t lo = (uint32_t)p_lo & 0xFFFFu;
    if (shift == 16u) {
        return hi + (int32_t)(lo >> 15);
    }
    if (shift > 16u) {
        const uint32_t half = (uint32_t)1u << (shift - 17u);
        // cppcheck-suppress misra-c2012-10.1 ; arithmetic >> by design (q14.c static assert)
        return (hi + (int32_t)half) >> (shift - 16u);
    }
    /* the int32 result is known to fit (the caller's proof): the sum of the
     * bit patterns is its two's-complement representation */
    const uint32_t r_u =
        ((uint32_t)hi << (16u - shift)) + ((lo + ((uint32_t)1u << (shift - 1u))) >> shift);
    return (int32_t)r_u;
}
#endif

/*
 * 1/sqrt of a positive x read as Q28, as a mantissa and a power of two:
 * 1/sqrt(x * 2^-28) = y * 2^*exp2 * 2^-28 with y in Q28, 2^27 <= y <= 2^28
 * and *exp2 in [-1, 14]. x is first scaled by an even power of two into
 * [2^28, 2^30) (bits are lost only when x >= 2^30: at most 2 of 31);
 * a 129-entry table over [1, 4) with linear interpolation gives a 16-bit y0
 * within 6.2e-5 (q14.c), and one Newton step y = y0 + y0 * (1 - x*y0^2) / 2
 * leaves a relative error below 1e-8 (test_q14_sqrt_div). The residual is
 * below 2^15 in Q28, so the correction is a 16x16-wide product, and y0^2 is
 * exact: one wide product in all. Needs x != 0 (x == 0 is read as 1).
 */
extern const uint16_t q_rsqrt_table_q15[129];

/* The result, and the scaled argument x_n = x * 2^(2 * exp2) in [2^28, 2^30)
 * (Q28 in [1, 4)), which callers use for sqrt(x) = x_n * y * 2^-exp2. */
typedef struct {
    int32_t y_q28;
    int exp2;
    int32_t xn_q28;
} qi_rsqrt_t;

/* The normalization and the table's first guess that both 1/sqrt forms start
 * from: x_n = x * 2^(2 * exp2) in [2^28, 2^30) and y0 (Q15) within 6.2e-5. */
typedef struct {
    int32_t y0_q15;
    int exp2;
    uint32_t xn_q28;
} qi_rsqrt_seed_t;

static QI_ALWAYS_INLINE qi_rsqrt_seed_t qi_rsqrt_seed(uint32_t x)
{
    const uint32_t xs = (x != 0u) ? x : 1u;
    const unsigned lz = qi_clz32(xs);
    /* the even shift that puts the top bit at 28 or 29 */
    const unsigned even = lz & ~1u;
    uint32_t xn;
    if (even >= 2u) {
        xn = xs << (even - 2u);
    } else {
        xn = xs >> 2;
    }
    qi_rsqrt_seed_t s;
    s.exp2 = ((int)even / 2) - 1;
    s.xn_q28 = xn;
    uint32_t idx;
    uint32_t frac_q15;
    /* the masks keep the index inside the table by construction */
    if (xn < ((uint32_t)1u << 29)) { /* [1, 2): steps of 2^22, cells 0..63 */
        idx = (xn >> 22) & 63u;
        frac_q15 = (xn >> 7) & 0x7FFFu;
    } else { /* [2, 4): steps of 2^23, cells 64..127 */
        idx = (xn >> 23) & 127u;
        frac_q15 = (xn >> 8) & 0x7FFFu;
    }
    const int32_t t0 = (int32_t)q_rsqrt_table_q15[idx];
    const int32_t t1 = (int32_t)q_rsqrt_table_q15[idx + 1u];
    // cppcheck-suppress misra-c2012-10.1 ; arithmetic >> by design (q14.c static assert)
    s.y0_q15 = t0 + ((((t1 - t0) * (int32_t)frac_q15) + 16384) >> 15);
    return s;
}

static QI_ALWAYS_INLINE qi_rsqrt_t qi_rsqrt_norm_q28(uint32_t x)
{
    const qi_rsqrt_seed_t s = qi_rsqrt_seed(x);
    qi_rsqrt_t r;
    r.exp2 = s.exp2;
    r.xn_q28 = (int32_t)s.xn_q28;
    const int32_t y0 = s.y0_q15;
    const uint32_t y0sq_q30 = (uint32_t)y0 * (uint32_t)y0; /* <= 2^30 */
    /* x * y0^2 ~ 1: Q28 * Q30 -> Q28 */
    const int32_t xy2_q28 = qi_mul32_fit(r.xn_q28, (int32_t)y0sq_q30, 30u);
    const int32_t resid_q28 = (int32_t)0x10000000 - xy2_q28; /* |.| < 2^15 */
    /* y0 * resid / 2: Q15 * Q28 -> Q28 needs >> 15, the halving one more */
    // cppcheck-suppress misra-c2012-10.1 ; arithmetic >> by design (q14.c static assert)
    const int32_t corr_q28 = ((y0 * resid_q28) + 32768) >> 16;
    r.y_q28 = (y0 * 8192) + corr_q28;
    return r;
}

/*
 * The same 1/sqrt to 1.5e-9 relative, for the control law (whose target
 * tilt, times a unit row of up to 2 and a gain of 2048, must be exact to a few
 * 2^-28): y in Q30, 2^29 <= y <= 2^30, 1/sqrt(x * 2^-28) = y * 2^exp2 * 2^-30.
 * With r = 1 - x*y0^2 (|r| < 1.3e-4, the table's error), the exact root is
 * y0 / sqrt(1 - r) = y0 * (1 + r/2 + 3r^2/8 + ...): the second-order step
 * leaves 5r^3/16 (1e-12) and its roundings (r in Q30, from every bit of x;
 * r/2 + 3r^2/8 in Q31; the product in Q30): below 1.5e-9 relative
 * (test_ht_arith). Int32 only: r^2 from r / 4 (a 16x16 product), and y0 * t
 * split at bit 16.
 */
typedef struct {
    int32_t y_q30;
    int exp2;
    int32_t xn_q28;
} qi_rsqrt30_t;

static inline qi_rsqrt30_t qi_rsqrt_norm_q30(uint32_t x)
{
    const qi_rsqrt_seed_t s = qi_rsqrt_seed(x);
    qi_rsqrt30_t r;
    r.exp2 = s.exp2;
    r.xn_q28 = (int32_t)s.xn_q28;
    const int32_t y0 = s.y0_q15;                           /* [2^14, 2^15] */
    const uint32_t y0sq_q30 = (uint32_t)y0 * (uint32_t)y0; /* <= 2^30 */
    /* x * y0^2 ~ 1: Q28 * Q30 -> Q30, below 2^30 * (1 + 1.3e-4); for x >= 2^30
     * the two bits the normalization dropped are added back (below 3 in Q30) */
    int32_t xy2_q30 = qi_mul32_fit(r.xn_q28, (int32_t)y0sq_q30, 28u);
    if (s.exp2 < 0) {
        xy2_q30 += (int32_t)((((x & 3u) * y0sq_q30) + 0x20000000u) >> 30);
    }
    const int32_t resid_q30 = (int32_t)0x40000000 - xy2_q30; /* r, |.| < 2^17.1 */
    /* 3r^2/8 in Q31 = 3 * resid^2 / 2^32 = 3 * (resid / 4)^2 / 2^28 (at most 12) */
    // cppcheck-suppress misra-c2012-10.1 ; arithmetic >> by design (q14.c static assert)
    const int32_t quarter = resid_q30 >> 2; /* |.| < 2^15.1: the square is below 2^30.2 */
    const int32_t quarter_sq_s = quarter * quarter;
    const uint32_t quarter_sq = (uint32_t)quarter_sq_s;
    const uint32_t r2_term = ((3u * quarter_sq) + 0x08000000u) >> 28;
    const int32_t t_q31 = resid_q30 + (int32_t)r2_term; /* r/2 + 3r^2/8 */
    /* y0 * t / 2^16, rounded once: t = th * 2^16 + tl, 0 <= tl < 2^16 */
    // cppcheck-suppress misra-c2012-10.1 ; arithmetic >> by design (q14.c static assert)
    const int32_t th = t_q31 >> 16;
    const uint32_t tl = (uint32_t)t_q31 & 0xFFFFu;
    const uint32_t low = (((uint32_t)y0 * tl) + 0x8000u) >> 16; /* y0 * tl < 2^31 */
    r.y_q30 = (y0 * 32768) + (y0 * th) + (int32_t)low;
    return r;
}

/*
 * round((a0*b0 + a1*b1 + a2*b2) / 2^shift), ties toward +inf, saturated to
 * int32, shift in [1, 62]: the three products summed exactly before the one
 * rounding (the control law's surface demand). The caller shows that the
 * exact sum is below 2^62 in magnitude. The portable form adds the three
 * 64-bit two's-complement products as 32-bit halves (int32 only, what the
 * dsPIC and the Cortex-M0 run); a core with a 32x32->64 multiplier uses it.
 */
static inline u64pair_t smul64_pair(int32_t a, int32_t b)
{
    const uint32_t ua = (uint32_t)a, ub = (uint32_t)b;
    u64pair_t p = umul32(ua, ub);
    p.hi -= (a < 0) ? ub : 0u;
    p.hi -= (b < 0) ? ua : 0u;
    return p;
}

static inline int32_t qi_dot3_portable(int32_t a0, int32_t b0, int32_t a1, int32_t b1, int32_t a2,
                                       int32_t b2, unsigned shift)
{
    const unsigned sh = (shift < 1u) ? 1u : shift; /* 0 is read as 1: never an undefined shift */
    u64pair_t acc = smul64_pair(a0, b0);
    const u64pair_t p1 = smul64_pair(a1, b1);
    acc = u64_add(acc, p1.hi, p1.lo);
    const u64pair_t p2 = smul64_pair(a2, b2);
    acc = u64_add(acc, p2.hi, p2.lo);
    const u64pair_t half = u64_pow2(sh - 1u);
    acc = u64_add(acc, half.hi, half.lo);
    const int32_t shi = (int32_t)acc.hi; /* the conversion keeps the bits (gcc, clang, XC16) */
    int32_t hi;
    int32_t lo;
    if (sh < 32u) {
        const uint32_t lo_u = (acc.lo >> sh) | (acc.hi << (32u - sh));
        lo = (int32_t)lo_u;
        // cppcheck-suppress [misra-c2012-10.1, shiftTooManyBitsSigned] ; arithmetic >> by design
        hi = shi >> sh;
    } else {
        // cppcheck-suppress misra-c2012-10.1 ; arithmetic >> by design (q14.c static assert)
        lo = shi >> (sh - 32u);
        // cppcheck-suppress [misra-c2012-10.1, shiftTooManyBitsSigned] ; arithmetic >> by design
        hi = shi >> 31;
    }
    /* it fits iff the high half is the sign extension of the low half */
    // cppcheck-suppress [misra-c2012-10.1, shiftTooManyBitsSigned] ; arithmetic >> by design
    if (hi != (lo >> 31)) {
        return (hi < 0) ? INT32_MIN : INT32_MAX;
    }
    return lo;
}

#if Q_TARGET_HAS_MUL64
static inline int32_t qi_dot3(int32_t a0, int32_t b0, int32_t a1, int32_t b1, int32_t a2,
                              int32_t b2, unsigned shift)
{
    return qi_round_sat64(((int64_t)a0 * (int64_t)b0) + ((int64_t)a1 * (int64_t)b1) +
                              ((int64_t)a2 * (int64_t)b2),
                          shift);
}
#else
static inline int32_t qi_dot3(int32_t a0, int32_t b0, int32_t a1, int32_t b1, int32_t a2,
                              int32_t b2, unsigned shift)
{
    return qi_dot3_portable(a0, b0, a1, b1, a2, b2, shift);
}
#endif

/* a / b rounded to nearest, ties away from zero, for b in [1, 2^30) (the
 * remainder test cannot overflow): the holds' integrators and the turn-rate
 * trim's step. */
static inline int32_t qi_div_round(int32_t a, int32_t b)
{
    int32_t q = a / b;
    const int32_t r = a % b;
    const int32_t r_abs = (r < 0) ? -r : r;
    if ((2 * r_abs) >= b) {
        q += (a < 0) ? -1 : 1;
    }
    return q;
}

#endif /* HELICAL_Q_INLINE_H */
