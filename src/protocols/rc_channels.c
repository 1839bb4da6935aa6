/*
 * rc_channels.c - 11-bit channel unpacking and the ticks-to-microseconds
 * mapping of CRSF and SBUS. See rc_channels.h.
 */
#include "helical/protocols/rc_channels.h"

void rc_unpack_11bit(const uint8_t *packed, uint16_t ticks_out[RC_CHANNELS])
{
    /* A bit accumulator rather than per-channel shift tables: 11 bits never
     * straddle more than three bytes, and the loop is the definition. */
    uint32_t acc = 0u;
    unsigned bits = 0u;
    unsigned byte = 0u;
    for (unsigned ch = 0u; ch < RC_CHANNELS; ch++) {
        while (bits < 11u) {
            acc |= (uint32_t)packed[byte] << bits;
            byte++;
            bits += 8u;
        }
        ticks_out[ch] = (uint16_t)(acc & RC_TICKS_MAX);
        acc >>= 11u;
        bits -= 11u;
    }
}

void rc_pack_11bit(const uint16_t ticks[RC_CHANNELS], uint8_t *packed)
{
    uint32_t acc = 0u;
    unsigned bits = 0u;
    unsigned byte = 0u;
    for (unsigned ch = 0u; ch < RC_CHANNELS; ch++) {
        acc |= ((uint32_t)ticks[ch] & RC_TICKS_MAX) << bits;
        bits += 11u;
        while (bits >= 8u) {
            packed[byte] = (uint8_t)(acc & 0xFFu);
            byte++;
            acc >>= 8u;
            bits -= 8u;
        }
    }
}

uint16_t rc_ticks_to_pulse_us(uint16_t ticks)
{
    /* 5 * 2047 + 7044 = 17279: no overflow even in 16-bit int arithmetic
     * (done in uint32_t for the dsPIC all the same). */
    uint32_t t = (uint32_t)ticks & RC_TICKS_MAX;
    return (uint16_t)(((5u * t) + 7044u) >> 3u);
}
