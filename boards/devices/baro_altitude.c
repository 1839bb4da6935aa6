/*
 * baro_altitude.c - the table lookup of baro_altitude.h.
 */
#include "baro_altitude.h"

#include <stddef.h>

int32_t baro_altitude_cm(uint32_t p_q24_8, uint8_t *clamped)
{
    uint8_t out_of_range = 0u;
    uint32_t p = p_q24_8;
    if (p < BARO_ALT_P_MIN_Q8) {
        p = BARO_ALT_P_MIN_Q8;
        out_of_range = 1u;
    } else if (p > BARO_ALT_P_MAX_Q8) {
        p = BARO_ALT_P_MAX_Q8;
        out_of_range = 1u;
    } else {
        /* inside */
    }
    if (clamped != NULL) {
        *clamped = out_of_range;
    }
    /* 256 Pa per node is 2^16 in Q24.8: the high half indexes, the low
     * half is the fraction of the step. */
    const uint32_t offset = p - BARO_ALT_P_MIN_Q8;
    const uint32_t idx = offset >> 16;
    const uint32_t frac_u = offset & 0xFFFFu;
    const int32_t frac = (int32_t)frac_u;
    if (idx >= BARO_ALT_TABLE_NODES - 1u) {
        return baro_alt_table_cm[BARO_ALT_TABLE_NODES - 1u]; /* exactly the top node */
    }
    const int32_t h0 = baro_alt_table_cm[idx];
    const int32_t dh = baro_alt_table_cm[idx + 1u] - h0; /* |dh| < 5700 cm: the product fits */
    const int32_t step = dh * frac + 32768;
    // cppcheck-suppress misra-c2012-10.1 ; ASR: rounded floor of a signed altitude step
    return h0 + (step >> 16);
}
