/*
 * log_f32.h - IEEE-754 binary32 bit patterns from integers, without float
 * (log_f32.c): the DataFlash PARM record carries a parameter's value as a
 * float ('f'), the log writer runs on the per-step path, which has none.
 */
#ifndef HT_LOG_F32_H
#define HT_LOG_F32_H

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* The binary32 nearest num / den (ties to even, as a float division of the
 * exact values would give), for den > 0 and |num| < 2^62. den == 0: 0. */
uint32_t fw_log_f32_from_ratio(int64_t num, uint32_t den);

#ifdef __cplusplus
}
#endif

#endif /* HT_LOG_F32_H */
