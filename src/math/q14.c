/*
 * q14.c - the portable fixed-point primitives (see q14.h for ranges and
 * rounding). Integer only; a division by a variable only in q14_div and
 * the unit-vector functions (one each).
 */
#include "helical/math/q14.h"

#include "math/q_inline.h"

/* The library's rounding shifts rely on arithmetic >> of negative values:
 * this is the check that the MISRA 10.1 suppressions on them point to. */
// cppcheck-suppress [misra-c2012-10.1, shiftNegativeLHS] ; the check itself
_Static_assert((-1 >> 1) == -1, "signed right shift must be arithmetic");
// cppcheck-suppress [misra-c2012-10.1, shiftNegativeLHS] ; the check itself
_Static_assert((-3L >> 1) == -2L, "signed right shift must be arithmetic");

/* Powers of two in the Q formats of this file (signed, without a signed shift). */
#define Q26_ONE_I32 ((int32_t)0x04000000) /* 2^26 */
#define Q30_ONE_I32 ((int32_t)0x40000000) /* 2^30 */

int16_t q_sat16(int32_t x)
{
    return qi_sat16(x);
}

int32_t q_clamp32(int32_t x, int32_t lo, int32_t hi)
{
    if (x < lo) {
        return lo;
    }
    if (x > hi) {
        return hi;
    }
    return x;
}

int16_t q14_add_sat(int16_t a, int16_t b)
{
    return qi_sat16((int32_t)a + (int32_t)b);
}

int16_t q14_sub_sat(int16_t a, int16_t b)
{
    return qi_sat16((int32_t)a - (int32_t)b);
}

int32_t q_add_sat32(int32_t a, int32_t b)
{
    return qi_add_sat32(a, b);
}

int32_t q_sub_sat32(int32_t a, int32_t b)
{
    return qi_sub_sat32(a, b);
}

int32_t q_rshift_round(int32_t x, unsigned shift)
{
    return qi_rshift_round(x, shift);
}

q14_t q14_mul(q14_t a, q14_t b)
{
    int32_t p = Q_TARGET_MUL16(a, b);
    // cppcheck-suppress misra-c2012-10.1 ; arithmetic >> by design (static assert above)
    return qi_sat16((p + 8192) >> 14);
}

/* ---- the wide multiply (see q_inline.h) ---------------------------------- */

int32_t q_mul32(int32_t a, int32_t b, unsigned shift)
{
    return qi_mul32(a, b, shift);
}

int32_t q_mul32_portable(int32_t a, int32_t b, unsigned shift)
{
    return qi_mul32_portable(a, b, shift);
}

int32_t q_mul32x16(int32_t a, int16_t b, unsigned shift)
{
    return qi_mul32x16(a, b, shift);
}

int32_t q_mul32x16_portable(int32_t a, int16_t b, unsigned shift)
{
    return qi_mul32x16_portable(a, b, shift);
}

/* ---- reciprocal square root and reciprocal, without division ------------- */

/* 1/sqrt over [1, 4] in Q15: round(2^15 / sqrt(1 + i/64)) for i = 0..64 (steps
 * of 1/64 on [1, 2]) and round(2^15 / sqrt(2 + (i - 64)/32)) for i = 65..128
 * (steps of 1/32 on [2, 4]): power-of-two steps, so the index is a shift, and
 * linear interpolation is within 3e-5 everywhere. */
const uint16_t q_rsqrt_table_q15[129] = {
    32768, 32515, 32268, 32026, 31790, 31558, 31332, 31111, 30894, 30682, 30474, 30270, 30070,
    29874, 29682, 29494, 29309, 29127, 28949, 28774, 28602, 28434, 28268, 28105, 27945, 27787,
    27632, 27480, 27330, 27183, 27038, 26895, 26755, 26617, 26481, 26346, 26214, 26084, 25956,
    25830, 25705, 25583, 25462, 25342, 25225, 25109, 24994, 24882, 24770, 24660, 24552, 24445,
    24339, 24235, 24132, 24031, 23930, 23831, 23733, 23637, 23541, 23447, 23354, 23262, 23170,
    22992, 22817, 22646, 22479, 22315, 22155, 21999, 21845, 21695, 21548, 21404, 21263, 21124,
    20988, 20855, 20724, 20596, 20470, 20346, 20225, 20106, 19988, 19873, 19760, 19649, 19539,
    19431, 19326, 19221, 19119, 19018, 18919, 18821, 18725, 18630, 18536, 18444, 18354, 18264,
    18176, 18090, 18004, 17920, 17837, 17755, 17674, 17594, 17515, 17438, 17361, 17285, 17211,
    17137, 17064, 16992, 16921, 16851, 16782, 16714, 16646, 16579, 16514, 16448, 16384};

/* round(2^15 / (1 + i/32)), i = 0..32: 1/m over [1, 2]. */
static const uint16_t recip_table_q15[33] = {
    32768, 31775, 30840, 29959, 29127, 28340, 27594, 26887, 26214, 25575, 24966,
    24385, 23831, 23302, 22795, 22310, 21845, 21400, 20972, 20560, 20165, 19784,
    19418, 19065, 18725, 18396, 18079, 17772, 17476, 17190, 16913, 16644, 16384};

/* Linear interpolation between table[i] and table[i + 1], frac in Q15. */
static QI_ALWAYS_INLINE int32_t table_interp_q15(const uint16_t *table, uint32_t i,
                                                 uint32_t frac_q15)
{
    int32_t t0 = table[i];
    int32_t t1 = table[i + 1u];
    // cppcheck-suppress misra-c2012-10.1 ; arithmetic >> by design (static assert above)
    return t0 + ((((t1 - t0) * (int32_t)frac_q15) + 16384) >> 15);
}

int32_t q_rsqrt_q28(int32_t s_q28)
{
    /* the normalized 1/sqrt on the clamped range: [1/4, 1) comes back with
     * exp2 = 1 (y doubles), [1, 4) with exp2 = 0 */
    const int32_t s_clamped = q_clamp32(s_q28, Q26_ONE_I32, Q30_ONE_I32 - 1);
    const qi_rsqrt_t r = qi_rsqrt_norm_q28((uint32_t)s_clamped);
    const uint32_t y_u = (uint32_t)r.y_q28 << (unsigned)r.exp2; /* <= 2^29 */
    return (int32_t)y_u;
}

int32_t q_rsqrt_norm_q28(uint32_t x, int *exp2)
{
    const qi_rsqrt_t r = qi_rsqrt_norm_q28(x);
    *exp2 = r.exp2;
    return r.y_q28;
}

/* The documented shift range [1, 46], enforced: a shift outside it is read
 * as the nearest end, never as an undefined shift. */
static unsigned fit_shift(unsigned shift)
{
    return (shift < 1u) ? 1u : ((shift > 46u) ? 46u : shift);
}

int32_t q_mul32_fit(int32_t a, int32_t b, unsigned shift)
{
    return qi_mul32_fit(a, b, fit_shift(shift));
}

int32_t q_mul32_fit_portable(int32_t a, int32_t b, unsigned shift)
{
    return qi_mul32_fit_portable(a, b, fit_shift(shift));
}

int32_t q_recip_q30(int32_t x, unsigned *exponent)
{
    uint32_t ux = (x > 0) ? (uint32_t)x : 1u;
    unsigned lz = qi_clz32(ux);
    *exponent = 31u - lz;      /* x in [2^e, 2^(e+1)) */
    uint32_t m_q31 = ux << lz; /* the mantissa in [1, 2), Q31 */
    /* Q15 -> Q30 */
    int32_t y_q30 =
        table_interp_q15(recip_table_q15, (m_q31 >> 26) & 31u, (m_q31 >> 11) & 0x7FFFu) * 32768;
    /* With e = 1 - m*y (the table's relative error, |e| <= 2.4e-4), the
     * exact 1/m is y / (1 - e) = y * (1 + e + e^2 + ...): the third-order
     * step y += y * (e + e^2) leaves e^3 (1.4e-11) and the Q30 roundings of
     * its three products (a few 2^-31), so callers need no step of their own
     * (the control step's 1/airspeed times a rate gain of 512). It costs one
     * product more than Newton's y += y * e (error e^2, 6e-8) and one fewer
     * than two Newton steps. m_q31 >> 1 is exact: x < 2^31 has a zero top bit,
     * so m_q31 has a zero low bit. */
    const int32_t e_q30 = Q30_ONE_I32 - qi_mul32_fit((int32_t)(m_q31 >> 1), y_q30, 30u);
    const int32_t e2_q30 = qi_mul32_fit(e_q30, e_q30, 30u); /* |.| < 2^18: e + e^2 fits */
    return y_q30 + qi_mul32_fit(y_q30, e_q30 + e2_q30, 30u);
}

/* ---- division and square roots ------------------------------------------ */

q14_t q14_div(q14_t num, q14_t den)
{
    if (den == 0) {
        return (num >= 0) ? INT16_MAX : INT16_MIN;
    }
    int32_t n = (int32_t)num * 16384;
    int32_t d = den;
    int32_t an = (n < 0) ? -n : n;
    int32_t ad = (d < 0) ? -d : d;
    // cppcheck-suppress zerodivcond ; den == 0 returned above, so ad >= 1
    int32_t q = (an + (ad / 2)) / ad; /* ties away from zero */
    return qi_sat16(((n < 0) != (d < 0)) ? -q : q);
}

q14_t q14_recip(q14_t x)
{
    return q14_div(Q14_ONE, x);
}

uint16_t q_isqrt32(uint32_t x)
{
    /* Digit-by-digit (base 4) square root: 16 iterations, no division. */
    uint32_t rem = x;
    uint32_t root = 0u;
    uint32_t bit = (uint32_t)1u << 30;
    while (bit > rem) {
        bit >>= 2;
    }
    while (bit != 0u) {
        if (rem >= (root + bit)) {
            rem -= root + bit;
            root = (root >> 1) + bit;
        } else {
            root >>= 1;
        }
        bit >>= 2;
    }
    return (uint16_t)root;
}

uint32_t q_isqrt32_round(uint32_t x)
{
    uint32_t s = q_isqrt32(x);
    /* round up when x >= s^2 + s + 1, i.e. x - s^2 > s: (s + 1/2)^2 = s^2 + s + 1/4 */
    return ((x - (s * s)) > s) ? (s + 1u) : s;
}

q14_t q14_sqrt(q14_t x)
{
    if (x <= 0) {
        return 0;
    }
    return (q14_t)q_isqrt32_round((uint32_t)x << 14);
}

/* ---- vectors -------------------------------------------------------------- */

q14_t q14_dot3(const q14_t a[3], const q14_t b[3])
{
    /* Each product is at most 2^30 in magnitude; three fit only as a
     * saturating sum. */
    int32_t s = (int32_t)a[0] * b[0];
    s = qi_add_sat32(s, (int32_t)a[1] * b[1]);
    s = qi_add_sat32(s, (int32_t)a[2] * b[2]);
    return qi_sat16(qi_rshift_round(s, 14));
}

static q14_t cross_term(q14_t a, q14_t b, q14_t c, q14_t d)
{
    /* a*b - c*d: each product is in [-2^30, 2^30], so the difference fits. */
    int32_t s = ((int32_t)a * b) - ((int32_t)c * d);
    return qi_sat16(qi_rshift_round(s, 14));
}

void q14_cross3(const q14_t a[3], const q14_t b[3], q14_t out[3])
{
    q14_t r0 = cross_term(a[1], b[2], a[2], b[1]);
    q14_t r1 = cross_term(a[2], b[0], a[0], b[2]);
    q14_t r2 = cross_term(a[0], b[1], a[1], b[0]);
    out[0] = r0;
    out[1] = r1;
    out[2] = r2;
}

/*
 * Unit vector of n int32 components (n = 2 or 3), in Q28.
 * The components are block-scaled so that the largest magnitude c lies in
 * [1/2, 1] as Q30 (no bits are lost unless an input exceeds 2^30); the sum of
 * squares S in [1/4, 3] is formed in Q28 with the exact wide multiply; each
 * component is then c_i / sqrt(S) with q_rsqrt_q28. No division.
 */
int q_unit_q28(const int32_t *v, unsigned n, int32_t *out)
{
    uint32_t big = 0u;
    for (unsigned i = 0; i < n; i++) {
        uint32_t m = (v[i] < 0) ? (0u - (uint32_t)v[i]) : (uint32_t)v[i];
        big = (m > big) ? m : big;
    }
    if (big == 0u) {
        for (unsigned i = 0; i < n; i++) {
            out[i] = 0;
        }
        return 0;
    }
    /* bring the top bit of big to bit 29; out holds the scaled components
     * (no scratch array: the control tick's stack is counted in bytes) */
    unsigned lz = qi_clz32(big);
    unsigned down = (lz < 2u) ? (2u - lz) : 0u;
    unsigned up = (lz > 2u) ? (lz - 2u) : 0u;
    int32_t sum_q28 = 0;
    for (unsigned i = 0; i < n; i++) {
        uint32_t m = (v[i] < 0) ? (0u - (uint32_t)v[i]) : (uint32_t)v[i];
        if (down > 0u) {
            m = (m >> down) + ((m >> (down - 1u)) & 1u);
        }
        const uint32_t c_u = m << up;
        int32_t c = (int32_t)c_u; /* |c| <= 2^30 */
        out[i] = (v[i] < 0) ? -c : c;
        sum_q28 += qi_mul32_fit(c, c, 32u); /* <= 3 * 2^28 */
    }
    int32_t y_q28 = q_rsqrt_q28(sum_q28);
    for (unsigned i = 0; i < n; i++) {
        out[i] = qi_mul32_fit(out[i], y_q28, 30u);
    }
    return 1;
}

int q_unit2_q28(int32_t a, int32_t b, int32_t *ua, int32_t *ub)
{
    int32_t v[2] = {a, b};
    int32_t u[2];
    int ok = q_unit_q28(v, 2u, u);
    *ua = u[0];
    *ub = u[1];
    return ok;
}

int q_unit3_q28(const int32_t v[3], int32_t out[3])
{
    return q_unit_q28(v, 3u, out);
}

int q_unit2_q16(int32_t a, int32_t b, q16_t *ua, q16_t *ub)
{
    int32_t u[2];
    int ok = q_unit2_q28(a, b, &u[0], &u[1]);
    *ua = qi_rshift_round(u[0], 12u);
    *ub = qi_rshift_round(u[1], 12u);
    return ok;
}

int q_unit3_q16(const int32_t v[3], q16_t out[3])
{
    int ok = q_unit_q28(v, 3u, out);
    for (unsigned i = 0; i < 3u; i++) {
        out[i] = qi_rshift_round(out[i], 12u);
    }
    return ok;
}

q16_t q14_norm2_q16(q14_t a, q14_t b)
{
    /* a^2 + b^2 <= 2^31 in Q28; scaled by 4^k to Q(28+2k) while it fits, the
     * root is Q(14+k), shifted up to Q16. */
    const int32_t a2 = (int32_t)a * a;
    const int32_t b2 = (int32_t)b * b;
    uint32_t s = (uint32_t)a2 + (uint32_t)b2;
    unsigned k = 0u;
    while ((k < 2u) && (s < 0x40000000u)) {
        s <<= 2;
        k++;
    }
    const uint32_t r = q_isqrt32_round(s) << (2u - k);
    return (q16_t)r;
}

static int normalize_q14(q14_t *v, unsigned n)
{
    int32_t w[3];
    int32_t u[3];
    for (unsigned i = 0; i < n; i++) {
        w[i] = v[i];
    }
    int ok = q_unit_q28(w, n, u);
    for (unsigned i = 0; i < n; i++) {
        v[i] = qi_sat16(qi_rshift_round(u[i], 14u));
    }
    return ok;
}

int q14_normalize2(q14_t v[2])
{
    return normalize_q14(v, 2u);
}

int q14_normalize3(q14_t v[3])
{
    return normalize_q14(v, 3u);
}
