/*
 * dcm_trig.h - the estimator's integer trigonometry (internal to the library;
 * the unit tests include it to compare it with libm).
 *
 * Angles are binary angles ("bam"): an int32 where 2^31 is 180 degrees, so a
 * full turn is the int32 wrap-around and no angle ever needs a range check.
 * Both functions are CORDIC (shift-and-add, 30 iterations, no multiply in the
 * loop), which is what a Cortex-M0 or a dsPIC wants.
 */
#ifndef HELICAL_DCM_TRIG_H
#define HELICAL_DCM_TRIG_H

#include <stdint.h>

/* 1.0 in Q30, the estimator's matrix format. */
#define HT_DCM_Q30_ONE ((int32_t)0x40000000)

/* 90 degrees as a binary angle. */
#define HT_BAM_90 ((int32_t)0x40000000)

/* The CORDIC gain prod sqrt(1 + 2^-2i), i = 0..30, in Q30 (1.6467602581). */
#define HT_CORDIC_GAIN_Q30 ((int32_t)1768195363)

/*
 * atan2(y, x) as a binary angle, for any int32 pair (the format cancels);
 * (0, 0) gives 0. Within 4e-8 rad of the exact angle (test_dcm_api sweeps it).
 * If mag_k is not NULL it receives HT_CORDIC_GAIN * sqrt(x^2 + y^2) in the
 * inputs' format within 1e-6 relative, saturated to INT32_MAX (the caller scales the other
 * operand by the gain instead of dividing this one).
 */
int32_t ht_dcm_atan2_bam(int32_t y, int32_t x, int32_t *mag_k);

/* cos and sin of a binary angle in Q30, within 3e-8 of the exact values. */
void ht_dcm_sincos_q30(int32_t angle_bam, int32_t *cos_q30, int32_t *sin_q30);

/* A binary angle in centidegrees rounded to nearest, (-18000, 18000]. */
int32_t ht_dcm_bam_to_cdeg(int32_t angle_bam);

/* Centidegrees (any int32 within +/-2^31 / 119305) to a binary angle. */
int32_t ht_dcm_cdeg_to_bam(int32_t cdeg);

#endif /* HELICAL_DCM_TRIG_H */
