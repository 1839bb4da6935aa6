/*
 * fw_link_f32.h - IEEE-754 binary32 bit patterns without float
 * (fw_link_f32.c): how the link produces and reads MAVLink's float fields.
 */
#ifndef HT_FW_LINK_F32_H
#define HT_FW_LINK_F32_H

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* num / den (den > 0), rounded to nearest, ties to even. |num| < 2^62,
 * den < 2^31. */
uint32_t fw_f32_from_ratio(int64_t num, uint32_t den);
/* The binary32 value f times scale (1 .. 2^24), rounded to nearest (ties
 * away from zero), into *out. 0 = exact or rounded; 1 = saturated to
 * INT32_MIN / INT32_MAX; -1 = NaN or infinity (*out untouched). */
int fw_f32_to_fixed(uint32_t f, int32_t scale, int32_t *out);

#ifdef __cplusplus
}
#endif

#endif /* HT_FW_LINK_F32_H */
