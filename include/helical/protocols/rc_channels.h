/*
 * rc_channels.h - the 11-bit channel packing that CRSF (RC_CHANNELS_PACKED)
 * and SBUS share, and its mapping to a servo pulse width in microseconds.
 *
 * Packing: 16 channels of 11 bits in 22 bytes, least significant bit first:
 * channel k occupies bits 11k .. 11k + 10 of the 176-bit little-endian
 * number formed by the bytes (byte 0 holds bits 0..7).
 *
 * Mapping (the one CRSF documents and FrSky SBUS receivers use, so that a
 * radio at 100 % travel gives 988..2012 us on both links):
 *
 *   pulse_us = 1500 + (ticks - 992) * 5 / 8       exactly, in real numbers
 *
 * so 172 -> 987.5, 992 -> 1500, 1811 -> 2011.875. It is rounded to the
 * nearest microsecond, halves upwards, in integers as
 *
 *   pulse_us = (5 * ticks + 7044) >> 3            (ticks 0..2047)
 *
 * (7044 = 8 * 1500 - 5 * 992 + 4: the + 4 is the half for rounding). Hence
 * 172 -> 988, 992 -> 1500, 1811 -> 2012, and 0..2047 -> 880..2159 us.
 * test_rc_channels checks all 2048 values against a double-precision
 * evaluation of the first line.
 */
#ifndef HELICAL_RC_CHANNELS_H
#define HELICAL_RC_CHANNELS_H

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#define RC_CHANNELS           16u
#define RC_PACKED_BYTES       22u   /* 16 x 11 bits */
#define RC_TICKS_MAX          2047u /* 11 bits */
#define RC_PULSE_US_AT_TICKS0 880u  /* the formula at ticks 0 */
#define RC_PULSE_US_AT_MAX    2159u /* the formula at ticks 2047 */

/* Unpack 16 channels from RC_PACKED_BYTES bytes (ticks_out[k] <= 2047). */
void rc_unpack_11bit(const uint8_t *packed, uint16_t ticks_out[RC_CHANNELS]);

/* Pack 16 channels (each masked to 11 bits) into RC_PACKED_BYTES bytes. */
void rc_pack_11bit(const uint16_t ticks[RC_CHANNELS], uint8_t *packed);

/* The pulse width in microseconds of an 11-bit value (the formula above;
 * bits above the 11th are ignored). */
uint16_t rc_ticks_to_pulse_us(uint16_t ticks);

#ifdef __cplusplus
}
#endif

#endif /* HELICAL_RC_CHANNELS_H */
