/*
 * frame_test_util.h - what the UBX, CRSF and SBUS decoder tests share: a
 * seeded RNG (splitmix64: the same sequence on every platform), an 11-bit
 * channel packer written bit by bit (independent of src/protocols/rc_channels.c), and
 * the byte-accounting identity of frame_counts.h. Header-only (static
 * inline), like q14_test_rng.h.
 */
#ifndef FRAME_TEST_UTIL_H
#define FRAME_TEST_UTIL_H

#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include "helical/protocols/frame_counts.h"
#include "unity.h"

static inline uint64_t ft_next(uint64_t *s)
{
    uint64_t z = (*s += UINT64_C(0x9E3779B97F4A7C15));
    z = (z ^ (z >> 30)) * UINT64_C(0xBF58476D1CE4E5B9);
    z = (z ^ (z >> 27)) * UINT64_C(0x94D049BB133111EB);
    return z ^ (z >> 31);
}

static inline unsigned ft_below(uint64_t *s, unsigned n)
{
    return (unsigned)(ft_next(s) % n);
}

static inline uint8_t ft_byte(uint64_t *s)
{
    return (uint8_t)(ft_next(s) & 0xFFu);
}

/* Channel k's bit b is bit 11k + b of the little-endian byte string. */
static inline void ft_pack11(const uint16_t ticks[16], uint8_t out[22])
{
    memset(out, 0, 22);
    for (unsigned k = 0; k < 16u; k++) {
        for (unsigned b = 0; b < 11u; b++) {
            if ((ticks[k] >> b) & 1u) {
                unsigned bit = 11u * k + b;
                out[bit / 8u] = (uint8_t)(out[bit / 8u] | (1u << (bit % 8u)));
            }
        }
    }
}

/* The exact mapping of rc_channels.h in real numbers, rounded half up. */
static inline long ft_pulse_ref(unsigned ticks)
{
    double exact = 1500.0 + ((double)ticks - 992.0) * 5.0 / 8.0;
    double r = exact + 0.5;
    long f = (long)r;
    return ((double)f > r) ? f - 1 : f; /* floor (r > 0 here anyway) */
}

/* Every byte fed is in exactly one place (frame_counts.h). */
static inline uint64_t ft_accounted(const ht_frame_counts_t *c, unsigned held)
{
    return (uint64_t)c->frame_bytes + c->bad_length + c->bad_checksum + c->bad_end + c->truncated +
           c->discarded_bytes + held;
}

static inline void ft_assert_counts_equal(const ht_frame_counts_t *a, const ht_frame_counts_t *b)
{
    TEST_ASSERT_EQUAL_UINT32(a->frames_ok, b->frames_ok);
    TEST_ASSERT_EQUAL_UINT32(a->unknown_type, b->unknown_type);
    TEST_ASSERT_EQUAL_UINT32(a->wrong_length, b->wrong_length);
    TEST_ASSERT_EQUAL_UINT32(a->frame_bytes, b->frame_bytes);
    TEST_ASSERT_EQUAL_UINT32(a->bad_length, b->bad_length);
    TEST_ASSERT_EQUAL_UINT32(a->bad_checksum, b->bad_checksum);
    TEST_ASSERT_EQUAL_UINT32(a->bad_end, b->bad_end);
    TEST_ASSERT_EQUAL_UINT32(a->truncated, b->truncated);
    TEST_ASSERT_EQUAL_UINT32(a->discarded_bytes, b->discarded_bytes);
}

#endif /* FRAME_TEST_UTIL_H */
