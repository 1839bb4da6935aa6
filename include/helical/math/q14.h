/*
 * q14.h - the fixed-point arithmetic of the helical-turn library.
 *
 * Formats (the number after Q is the count of fractional bits):
 *   q14_t  int16_t  16384 = 1.0, range [-2.0, +2.0 - 2^-14]   unit vectors, surfaces
 *   q11_t  int16_t   2048 = 1.0, range [-16.0, +16.0 - 2^-11] body rates in rad/s
 *   q16_t  int32_t  65536 = 1.0, range about +/-32768          gains, ratios
 *   (Q28)  int32_t  2^28 = 1.0, range [-8, 8)                  the control law's internal
 *                                                               unit quantities
 *
 * Rounding: every narrowing step rounds to nearest with ties toward +infinity
 * (add half an LSB, then shift right arithmetically), so rounding is symmetric
 * in magnitude except on exact ties. Saturation: every function that can
 * overflow its result type clamps to the type's limits instead of wrapping.
 *
 * Only int16/int32 (and their unsigned forms) are used by the portable code.
 * Where a core has a faster primitive the alternative is chosen at compile time
 * (see q14_target.h) and the host tests prove it gives the same bits.
 *
 * The library requires that >> on a negative signed integer is an arithmetic
 * shift (gcc, clang and XC16 all guarantee it); q14.c checks this at compile
 * time.
 */
#ifndef HELICAL_Q14_H
#define HELICAL_Q14_H

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef int16_t q14_t;
typedef int16_t q11_t;
typedef int32_t q16_t;

#define Q14_ONE ((q14_t)16384)
#define Q11_ONE ((q11_t)2048)
#define Q16_ONE ((q16_t)65536)

/*
 * Compile-time conversions from a real constant. Use them only with constant
 * expressions (a gain table, a test vector): they are the one place where a
 * floating-point literal meets the library, and the compiler folds them.
 * Out-of-range constants are the caller's bug; the parameter checker refuses
 * the values that matter.
 */
#define Q14_FROM_REAL(x) ((q14_t)((x)*16384.0 + ((x) >= 0 ? 0.5 : -0.5)))
#define Q11_FROM_REAL(x) ((q11_t)((x)*2048.0 + ((x) >= 0 ? 0.5 : -0.5)))
#define Q16_FROM_REAL(x) ((q16_t)((x)*65536.0 + ((x) >= 0 ? 0.5 : -0.5)))

/* --- saturation -------------------------------------------------------- */

/* Clamp an int32 to [INT16_MIN, INT16_MAX]. */
int16_t q_sat16(int32_t x);

/* Clamp x to [lo, hi]; requires lo <= hi. */
int32_t q_clamp32(int32_t x, int32_t lo, int32_t hi);

/* a + b and a - b saturated to int16 (q14, q11 or any 16-bit format). */
int16_t q14_add_sat(int16_t a, int16_t b);
int16_t q14_sub_sat(int16_t a, int16_t b);

/* a + b and a - b saturated to int32. */
int32_t q_add_sat32(int32_t a, int32_t b);
int32_t q_sub_sat32(int32_t a, int32_t b);

/*
 * Rounding right shift of an int32: round(x / 2^shift), ties toward +inf,
 * for shift in [1, 31]. Never overflows (the carry is added after shifting).
 */
int32_t q_rshift_round(int32_t x, unsigned shift);

/* --- multiplication ---------------------------------------------------- */

/*
 * a * b in Q14: round(a*b / 2^14), saturated. Exact to 1/2 LSB.
 * Products of magnitude >= 2.0 clamp (for example (-2.0) * (-2.0) = +4.0 and
 * (-2.0) * (-1.99994) both give INT16_MAX).
 */
q14_t q14_mul(q14_t a, q14_t b);

/*
 * The wide multiply of the core: round(a*b / 2^shift) of two int32 values,
 * ties toward +inf, saturated to int32, for shift in [1, 62]. The product is
 * formed exactly (up to 64 bits) from four 16x16 partial products, so the
 * result is the correctly rounded value of the exact product.
 */
int32_t q_mul32(int32_t a, int32_t b, unsigned shift);

/* The portable, int32-only form of q_mul32 (four 16x16 partial products).
 * q_mul32 uses a hardware 32x32->64 multiply where the core has one; this
 * function is the reference both are tested against. */
int32_t q_mul32_portable(int32_t a, int32_t b, unsigned shift);

/*
 * q_mul32 for an int16 second factor (a row element, a gyro rate): the same
 * bits, from two 16x16 partial products; shift in [1, 46].
 */
int32_t q_mul32x16(int32_t a, int16_t b, unsigned shift);
int32_t q_mul32x16_portable(int32_t a, int16_t b, unsigned shift);

/*
 * q_mul32 where the caller has shown that the rounded result fits an int32
 * (the control step's products): no saturation test. Where it does not fit,
 * the result is the low 32 bits of the rounded product (defined, not UB).
 * shift in [1, 46]; a shift outside is read as the nearest end.
 */
int32_t q_mul32_fit(int32_t a, int32_t b, unsigned shift);
int32_t q_mul32_fit_portable(int32_t a, int32_t b, unsigned shift);

/* --- division, reciprocal and square root -------------------------------- */

/*
 * num / den in Q14: round(num * 2^14 / den) (ties away from zero), saturated.
 * den == 0 returns INT16_MAX for num >= 0 and INT16_MIN for num < 0.
 */
q14_t q14_div(q14_t num, q14_t den);

/*
 * 1 / x in Q14, saturated: |x| <= 0.5 (8192) gives +/-2.0 clamped to
 * INT16_MAX / INT16_MIN; x == 0 gives INT16_MAX.
 */
q14_t q14_recip(q14_t x);

/*
 * 1/sqrt(s) in Q28 for s in Q28 within [1/4, 4) (2^26 <= s < 2^30), without
 * division: q_rsqrt_norm_q28 on that range (a 129-entry table over [1, 4) with
 * linear interpolation and one Newton step), relative error below 2e-8 (the
 * tests measure it over the whole range). Inputs outside the range are
 * clamped to it.
 */
int32_t q_rsqrt_q28(int32_t s_q28);

/*
 * 1/sqrt of any positive x read as Q28, without division, as a mantissa and a
 * power of two: 1/sqrt(x / 2^28) = y * 2^*exp2 / 2^28, with y in Q28 within
 * [2^27, 2^28] and *exp2 in [-1, 14]; relative error below 1e-8. One wide
 * product (the Newton residual). x == 0 is read as 1.
 */
int32_t q_rsqrt_norm_q28(uint32_t x, int *exp2);

/*
 * Reciprocal of a positive integer x (1 <= x < 2^31), without division:
 * returns the mantissa m in Q30, 2^29 <= m <= 2^30, and writes the exponent e
 * so that 1/x = m * 2^-(30 + e), within a relative error of 2^-28 (3.7e-9:
 * a table, then one third-order step). x <= 0 is treated as 1.
 */
int32_t q_recip_q30(int32_t x, unsigned *exponent);

/* floor(sqrt(x)) for every uint32 x; exact. */
uint16_t q_isqrt32(uint32_t x);

/* sqrt(x) rounded to nearest for every uint32 x (0xFFFFFFFF -> 65536). */
uint32_t q_isqrt32_round(uint32_t x);

/* sqrt(x) in Q14, rounded to nearest; x < 0 returns 0 (documented clamp). */
q14_t q14_sqrt(q14_t x);

/* --- vectors ------------------------------------------------------------ */

/*
 * Dot product of two Q14 3-vectors: round(sum a_i*b_i / 2^14), saturated:
 * the same result as the exact sum saturated at the end (the int32
 * accumulator saturates on the way only when the final value would too).
 */
q14_t q14_dot3(const q14_t a[3], const q14_t b[3]);

/* Cross product a x b of two Q14 3-vectors, each component rounded once and
 * saturated. */
void q14_cross3(const q14_t a[3], const q14_t b[3], q14_t out[3]);

/*
 * Unit vector of (a, b), components given in any common fixed-point format
 * as int32 (the format cancels). Result in Q16 with an error below 1 LSB of
 * Q16 per component. Returns 0 and writes (0, 0) when a == b == 0; returns 1
 * otherwise.
 */
int q_unit2_q16(int32_t a, int32_t b, q16_t *ua, q16_t *ub);

/* The same for a 3-vector. */
int q_unit3_q16(const int32_t v[3], q16_t out[3]);

/*
 * The same in Q28 (2^28 = 1.0), the format the control law carries its unit
 * quantities in: within 6 LSB of Q28 (2.3e-8) of the exact unit vector per
 * component (the reciprocal square root contributes up to 3, the roundings the rest).
 */
int q_unit2_q28(int32_t a, int32_t b, int32_t *ua, int32_t *ub);
int q_unit3_q28(const int32_t v[3], int32_t out[3]);

/* The same for n = 2 or 3 components in arrays; out may be v itself. */
int q_unit_q28(const int32_t *v, unsigned n, int32_t *out);

/*
 * Euclidean length of (a, b) with a and b in Q14, as Q16 (two guard bits):
 * the correctly rounded root on the Q16 grid when a^2 + b^2 < 1, on the Q15
 * grid below 4 and on the Q14 grid above (so within 2 LSB of Q16); at most
 * 2*sqrt(2) for any inputs.
 */
q16_t q14_norm2_q16(q14_t a, q14_t b);

/*
 * Normalize a Q14 2-vector or 3-vector in place to unit length, in Q14:
 * the Q28 unit vector rounded once, so within 0.5 LSB + 6 LSB of Q28 of the
 * exact value (0.50037 LSB of Q14). A zero vector is left zero and the
 * function returns 0.
 */
int q14_normalize2(q14_t v[2]);
int q14_normalize3(q14_t v[3]);

#ifdef __cplusplus
}
#endif

#endif /* HELICAL_Q14_H */
