/*
 * dcm_trig.c - CORDIC atan2 and sin/cos for the attitude estimator
 * (dcm_trig.h). Integer only; one 31-entry table.
 */
#include <stddef.h>

#include "estimator/dcm_trig.h"
#include "math/q_inline.h"

/* round(atan(2^-i) / pi * 2^31), i = 0..30: the rotation of each step as a
 * binary angle. */
static const int32_t cordic_atan_bam[31] = {
    536870912, 316933406, 167458907, 85004756, 42667331, 21354465, 10679838, 5340245,
    2670163,   1335087,   667544,    333772,   166886,   83443,    41722,    20861,
    10430,     5215,      2608,      1304,     652,      326,      163,      81,
    41,        20,        10,        5,        3,        1,        1};

#define CORDIC_STEPS 31u

/* 2^32 / 36000 in Q14: centidegrees to binary angle. */
#define CDEG_TO_BAM_Q14 1954687338L

int32_t ht_dcm_atan2_bam(int32_t y, int32_t x, int32_t *mag_k)
{
    /* Work on |x|, |y| scaled so the larger sits in [2^28, 2^29): room for
     * the gain (1.65) and the pre-rotation (sqrt 2) below 2^31, and 29 bits
     * of precision whatever the inputs' format. uint32 avoids -INT32_MIN. */
    const uint32_t ax = (x < 0) ? (0u - (uint32_t)x) : (uint32_t)x;
    const uint32_t ay = (y < 0) ? (0u - (uint32_t)y) : (uint32_t)y;
    const uint32_t big = (ax > ay) ? ax : ay;
    if (big == 0u) {
        if (mag_k != NULL) {
            *mag_k = 0;
        }
        return 0;
    }
    const unsigned lz = qi_clz32(big);
    /* top bit to bit 28: lz == 3 */
    const unsigned down = (lz < 3u) ? (3u - lz) : 0u;
    const unsigned up = (lz > 3u) ? (lz - 3u) : 0u;
    const uint32_t sxu = (ax >> down) << up;
    const uint32_t syu = (ay >> down) << up;
    const int32_t sx = (int32_t)sxu;
    const int32_t sy = (int32_t)syu;
    int32_t xs = (x < 0) ? -sx : sx;
    int32_t ys = (y < 0) ? -sy : sy;
    int32_t z = 0;
    /* into the right half plane: rotate by -90 or +90 degrees */
    if (xs < 0) {
        const int32_t t = xs;
        if (ys >= 0) {
            xs = ys;
            ys = -t;
            z = HT_BAM_90;
        } else {
            xs = -ys;
            ys = t;
            z = -HT_BAM_90;
        }
    }
    for (unsigned i = 0u; i < CORDIC_STEPS; i++) {
        // cppcheck-suppress misra-c2012-10.1 ; arithmetic >> by design (q14.c static assert)
        const int32_t dx = xs >> i;
        // cppcheck-suppress misra-c2012-10.1 ; arithmetic >> by design (q14.c static assert)
        const int32_t dy = ys >> i;
        /* z wraps only at +/-180 degrees, where int32 wrap is the angle's */
        if (ys > 0) {
            xs += dy;
            ys -= dx;
            const uint32_t zu = (uint32_t)z + (uint32_t)cordic_atan_bam[i];
            z = (int32_t)zu;
        } else {
            xs -= dy;
            ys += dx;
            const uint32_t zu = (uint32_t)z - (uint32_t)cordic_atan_bam[i];
            z = (int32_t)zu;
        }
    }
    if (mag_k != NULL) {
        /* undo the scaling; xs > 0 and < 2^31 */
        const uint32_t m = (uint32_t)xs;
        uint32_t r;
        if (down > 0u) {
            r = (m > (0x7FFFFFFFu >> down)) ? 0x7FFFFFFFu : (m << down);
        } else if (up > 0u) {
            r = (m + ((uint32_t)1u << (up - 1u))) >> up;
        } else {
            r = m;
        }
        *mag_k = (int32_t)r;
    }
    return z;
}

void ht_dcm_sincos_q30(int32_t angle_bam, int32_t *cos_q30, int32_t *sin_q30)
{
    /* into [-90, 90] degrees: beyond, turn by 180 and negate the result */
    int32_t z = angle_bam;
    int neg = 0;
    if (z > HT_BAM_90 || z < -HT_BAM_90) {
        const uint32_t zu = (uint32_t)z + 0x80000000u;
        z = (int32_t)zu;
        neg = 1;
    }
    /* start at 1/gain so that the result has unit length */
    int32_t xs = 652032874; /* round(2^30 / 1.6467602581) */
    int32_t ys = 0;
    for (unsigned i = 0u; i < CORDIC_STEPS; i++) {
        // cppcheck-suppress misra-c2012-10.1 ; arithmetic >> by design (q14.c static assert)
        const int32_t dx = xs >> i;
        // cppcheck-suppress misra-c2012-10.1 ; arithmetic >> by design (q14.c static assert)
        const int32_t dy = ys >> i;
        if (z >= 0) {
            xs -= dy;
            ys += dx;
            z -= cordic_atan_bam[i];
        } else {
            xs += dy;
            ys -= dx;
            z += cordic_atan_bam[i];
        }
    }
    *cos_q30 = neg ? -xs : xs;
    *sin_q30 = neg ? -ys : ys;
}

int32_t ht_dcm_bam_to_cdeg(int32_t angle_bam)
{
    /* 36000 / 2^32 per unit; the result is within [-18000, 18000] */
    const int32_t c = qi_mul32(angle_bam, 36000, 32u);
    return (c == -18000) ? 18000 : c;
}

int32_t ht_dcm_cdeg_to_bam(int32_t cdeg)
{
    return qi_mul32(cdeg, (int32_t)CDEG_TO_BAM_Q14, 14u);
}
