/*
 * q14_target.h - compile-time choice of the fastest primitive each core has.
 *
 * The portable C expression is the reference; an alternative is used only
 * where it gives the same bits by definition (a 16x16->32 multiply, a
 * saturation to 16 bits, a 32x32->64 multiply). Build with
 * -DHT_PORTABLE_ONLY=1 to force the portable code everywhere (the host tests
 * compare both).
 */
#ifndef HELICAL_Q14_TARGET_H
#define HELICAL_Q14_TARGET_H

#include <stdint.h>

#ifndef HT_PORTABLE_ONLY
#define HT_PORTABLE_ONLY 0
#endif

#if !HT_PORTABLE_ONLY && defined(__XC16__)
/* dsPIC30/33: the DSP engine's signed 16x16 multiply (MUL.SS). */
#define Q_TARGET_MUL16(a, b) ((int32_t)__builtin_mulss((a), (b)))
#elif !HT_PORTABLE_ONLY && defined(__ARM_FEATURE_DSP)
/* Cortex-M4/M7: SMLABB (bottom halfwords, accumulator 0) is the one-cycle 16x16 multiply. */
#include <arm_acle.h>
#define Q_TARGET_MUL16(a, b) ((int32_t)__smlabb((int32_t)(a), (int32_t)(b), 0))
#else
#define Q_TARGET_MUL16(a, b) ((int32_t)(a) * (int32_t)(b))
#endif

#if !HT_PORTABLE_ONLY && defined(__ARM_FEATURE_SAT)
/* Cortex-M3/M4: SSAT #16 (the builtin: arm_acle.h's __ssat trips -Wsign-conversion). */
#define Q_TARGET_SAT16(x) ((int16_t)(int32_t)__builtin_arm_ssat((int32_t)(x), 16))
#else
#define Q_TARGET_SAT16(x)                                                                          \
    ((int16_t)((x) > INT16_MAX ? INT16_MAX : ((x) < INT16_MIN ? INT16_MIN : (x))))
#endif

#if !HT_PORTABLE_ONLY && defined(__ARM_FEATURE_QBIT) && defined(__ARM_FEATURE_DSP)
/* Cortex-M4/M7: QADD, QSUB: the saturating 32-bit add and subtract in one
 * instruction, the same bits as the portable tests. */
#define Q_TARGET_HAS_QADD 1
#else
#define Q_TARGET_HAS_QADD 0
#endif

/* A 32x32->64 multiply in hardware: x86-64, AArch64, ARMv7-M (SMULL). */
#if !HT_PORTABLE_ONLY && (defined(__x86_64__) || defined(__aarch64__) ||                           \
                          defined(__ARM_ARCH_7M__) || defined(__ARM_ARCH_7EM__))
#define Q_TARGET_HAS_MUL64 1
#else
#define Q_TARGET_HAS_MUL64 0
#endif

#endif /* HELICAL_Q14_TARGET_H */
