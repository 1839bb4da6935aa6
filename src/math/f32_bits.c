/*
 * f32_bits.c - IEEE-754 binary32 bit patterns from and to the library's
 * fixed-point values, in integers: MAVLink carries attitudes, speeds and
 * parameter values as float, the per-step path has no float (the
 * soft-float runtime must not reach the image: tools/image/check_no_float.sh).
 *
 * Both directions are exact to the rounding rule (tests/test_fw_link_f32.c
 * compares them with the host's float conversion, exhaustively over the
 * 16-bit formats and at every edge): binary32 from a ratio rounds to nearest,
 * ties to even (as a float division would); a binary32 to fixed point rounds
 * to nearest, ties away from zero (as the parameter table's defaults do),
 * and saturates.
 */
#include "helical/math/f32_bits.h"

#include <stddef.h>

/* Bits needed for x (0 for 0). */
static int bit_length64(uint64_t x)
{
    uint64_t v = x;
    int n = 0;
    while (v != 0u) {
        v >>= 1u;
        ++n;
    }
    return n;
}

uint32_t ht_f32_from_ratio(int64_t num, uint32_t den)
{
    if ((num == 0) || (den == 0u)) {
        return 0u;
    }
    const uint32_t sign = (num < 0) ? 0x80000000u : 0u;
    uint64_t a = (num < 0) ? (0u - (uint64_t)num) : (uint64_t)num;
    /* q = a * 2^s / den in [2^24, 2^26): 24 significant bits, a round bit,
     * and whatever was lost in the sticky flag */
    int s = 25 + bit_length64((uint64_t)den) - bit_length64(a);
    uint32_t sticky = 0u;
    if (s >= 0) {
        a <<= (unsigned)s; /* < 2^(25 + 31): no overflow */
    } else {
        const uint64_t lost = a & ((1ULL << (unsigned)(-s)) - 1U);
        if (lost != 0U) {
            sticky = 1U;
        }
        a >>= (unsigned)(-s);
    }
    uint64_t q = a / den;
    if ((a % den) != 0u) {
        sticky = 1u;
    }
    if (q >= 0x2000000ULL) { /* 2^25 */
        sticky |= (uint32_t)(q & 1u);
        q >>= 1u;
        --s;
    }
    uint32_t mant = (uint32_t)(q >> 1u); /* [2^23, 2^24) */
    const uint32_t round = (uint32_t)(q & 1u);
    int exponent = 24 - s; /* value = mant * 2^(exponent - 23) */
    if ((round != 0u) && ((sticky != 0u) || ((mant & 1u) != 0u))) {
        ++mant;
        if (mant == 0x1000000U) { /* 2^24: the carry reached the exponent */
            mant = 0x800000U;
            ++exponent;
        }
    }
    const int32_t biased_s = exponent + 127;
    const uint32_t biased = (uint32_t)biased_s;
    return sign | (biased << 23u) | (mant & 0x7FFFFFu);
}

int ht_f32_to_fixed(uint32_t f, int32_t scale, int32_t *out)
{
    const uint32_t exp_field = (f >> 23u) & 0xFFu;
    const uint32_t frac = f & 0x7FFFFFu;
    if ((exp_field == 0xFFu) || (out == NULL) || (scale < 1) || (scale > 16777216)) {
        return -1; /* NaN or infinity (or a bad call) */
    }
    const uint32_t neg = f >> 31u;
    uint64_t m;
    int e;
    if (exp_field == 0u) {
        m = frac; /* zero or subnormal: frac * 2^-149 */
        e = -149;
    } else {
        m = (uint64_t)frac | 0x800000u;
        e = (int)exp_field - 150;
    }
    const uint64_t p = m * (uint64_t)(uint32_t)scale; /* < 2^48 */
    const uint64_t limit = (neg != 0u) ? 0x80000000ULL : 0x7FFFFFFFULL;
    uint64_t mag = 0u; /* p == 0: zero */
    int status = 0;
    if ((p == 0u) || (e < -62)) {
        /* +-0, or below 2^48 * 2^-63: less than half a step: zero */
    } else if (e >= 0) {
        if ((e >= 32) || (p > (limit >> (unsigned)e))) { /* p * 2^e > limit */
            mag = limit;
            status = 1;
        } else {
            mag = p << (unsigned)e;
        }
    } else {
        const unsigned sh = (unsigned)(-e);
        mag = p >> sh;
        const uint64_t rem = p & ((1ULL << sh) - 1U);
        const unsigned half_sh = sh - 1U;
        const uint64_t half = 1ULL << half_sh;
        if (rem >= half) {
            ++mag; /* half away from zero */
        }
        if (mag > limit) {
            mag = limit;
            status = 1;
        }
    }
    const int64_t value = (int64_t)mag;
    *out = (int32_t)((neg != 0u) ? -value : value);
    return status;
}
