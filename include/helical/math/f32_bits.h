/*
 * f32_bits.h - IEEE-754 binary32 bit patterns without float
 * (src/math/f32_bits.c): how the link makes and reads MAVLink's float
 * fields, and the flight log its PARM values.
 */
#ifndef HELICAL_MATH_F32_BITS_H
#define HELICAL_MATH_F32_BITS_H

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* num / den (den > 0), rounded to nearest, ties to even. |num| < 2^62,
 * den < 2^31. */
uint32_t ht_f32_from_ratio(int64_t num, uint32_t den);
/* The binary32 value f times scale (1 .. 2^24), rounded to nearest (ties
 * away from zero), into *out. 0 = exact or rounded; 1 = saturated to
 * INT32_MIN / INT32_MAX; -1 = NaN or infinity (*out untouched). */
int ht_f32_to_fixed(uint32_t f, int32_t scale, int32_t *out);

#ifdef __cplusplus
}
#endif

#endif /* HELICAL_MATH_F32_BITS_H */
