/*
 * log_f32.c - binary32 from a ratio of integers, rounded to nearest, ties to
 * even: num / den is scaled into [2^24, 2^26) by a shift, divided once, and
 * the remainder kept as a sticky bit (the same rule as the link's
 * fw_f32_from_ratio; the log keeps its own so that it does not depend on the
 * link's layer). tests/test_fw_log_f32.c compares it with the host's float
 * division over every 16-bit value and a seeded sweep of 32-bit values at
 * each of the parameter table's scales.
 */
#include "log/log_f32.h"

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

uint32_t fw_log_f32_from_ratio(int64_t num, uint32_t den)
{
    if ((num == 0) || (den == 0u)) {
        return 0u;
    }
    const uint32_t sign = (num < 0) ? 0x80000000u : 0u;
    uint64_t a = (num < 0) ? (0u - (uint64_t)num) : (uint64_t)num;
    /* shift so that a / den lands in [2^24, 2^26): 24 significant bits, a
     * round bit, and what is lost goes into the sticky flag */
    int s = 25 + bit_length64((uint64_t)den) - bit_length64(a);
    uint32_t sticky = 0u;
    if (s >= 0) {
        a <<= (unsigned)s; /* a < 2^(25 + 32): fits */
    } else {
        if ((a & ((1ULL << (unsigned)(-s)) - 1u)) != 0u) {
            sticky = 1u;
        }
        a >>= (unsigned)(-s);
    }
    uint64_t q = a / den;
    if ((a % den) != 0u) {
        sticky = 1u;
    }
    if (q >= 0x2000000ULL) { /* 2^25: one bit too many */
        sticky |= (uint32_t)(q & 1u);
        q >>= 1u;
        --s;
    }
    uint32_t mant = (uint32_t)(q >> 1u); /* [2^23, 2^24) */
    const uint32_t round = (uint32_t)(q & 1u);
    int exponent = 24 - s; /* value = mant * 2^(exponent - 23) */
    if ((round != 0u) && ((sticky != 0u) || ((mant & 1u) != 0u))) {
        ++mant;
        if (mant == 0x1000000u) { /* the carry reached the exponent */
            mant = 0x800000u;
            ++exponent;
        }
    }
    /* |num| < 2^62 and den >= 1 keep the exponent well inside the normal
     * range (no subnormal, no infinity) */
    const int32_t biased_signed = exponent + 127;
    const uint32_t biased = (uint32_t)biased_signed;
    return sign | (biased << 23u) | (mant & 0x7FFFFFu);
}
