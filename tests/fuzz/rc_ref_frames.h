/*
 * rc_ref_frames.h - an independent encoder of SBUS and CRSF channel frames
 * for the receiver fuzz targets (fuzz_sbus.c, fuzz_crsf.c), written from the
 * wire formats (rx_sbus.h, rx_crsf.h), not from the decoders: 11-bit channels
 * packed one bit at a time, least significant bit first, and CRC-8/DVB-S2
 * computed bit by bit (polynomial 0xD5). Each target builds a valid frame
 * from its input's bytes and checks that a fresh decoder gives back exactly
 * those channels at the frame's last byte: a decoder that rejected valid
 * frames, or decoded them wrong, now fails the target (the raw-bytes checks
 * of frame_fuzz.h alone would pass it).
 */
#ifndef RC_REF_FRAMES_H
#define RC_REF_FRAMES_H

#include <stddef.h>
#include <stdint.h>
#include <string.h>

/* Sixteen 11-bit channel values from the input (two bytes each, missing
 * bytes 0), and one more byte (flags or a choice) after them. */
static inline void ref_channels_from(const uint8_t *data, size_t size, uint16_t ticks[16],
                                     uint8_t *extra)
{
    uint8_t b[33] = {0};
    memcpy(b, data, (size < sizeof b) ? size : sizeof b);
    for (unsigned k = 0u; k < 16u; ++k) {
        ticks[k] = (uint16_t)((b[2u * k] | ((unsigned)b[2u * k + 1u] << 8)) & 0x7FFu);
    }
    *extra = b[32];
}

/* channel k's bit j is bit (11 k + j) of the 176-bit little-endian field */
static inline void ref_pack11(const uint16_t ticks[16], uint8_t out[22])
{
    memset(out, 0, 22u);
    for (unsigned k = 0u; k < 16u; ++k) {
        for (unsigned j = 0u; j < 11u; ++j) {
            if (((unsigned)ticks[k] >> j) & 1u) {
                const unsigned bit = 11u * k + j;
                out[bit / 8u] = (uint8_t)(out[bit / 8u] | (1u << (bit % 8u)));
            }
        }
    }
}

/* CRC-8/DVB-S2: polynomial x^8 + x^7 + x^6 + x^4 + x^2 + 1 (0xD5), initial 0,
 * no reflection, no final xor */
static inline uint8_t ref_crc8_dvb_s2(const uint8_t *p, size_t n)
{
    unsigned crc = 0u;
    for (size_t i = 0u; i < n; ++i) {
        crc ^= p[i];
        for (unsigned b = 0u; b < 8u; ++b) {
            crc = (crc & 0x80u) ? (((crc << 1) ^ 0xD5u) & 0xFFu) : ((crc << 1) & 0xFFu);
        }
    }
    return (uint8_t)crc;
}

/* SBUS: 0x0F | 22 bytes | flags | end */
static inline void ref_sbus_frame(const uint16_t ticks[16], uint8_t flags, uint8_t end,
                                  uint8_t f[25])
{
    f[0] = 0x0Fu;
    ref_pack11(ticks, &f[1]);
    f[23] = flags;
    f[24] = end;
}

/* CRSF RC_CHANNELS_PACKED: sync | 24 | 0x16 | 22 bytes | crc(type, payload) */
static inline void ref_crsf_rc_frame(const uint16_t ticks[16], uint8_t sync, uint8_t f[26])
{
    f[0] = sync;
    f[1] = 24u;
    f[2] = 0x16u;
    ref_pack11(ticks, &f[3]);
    f[25] = ref_crc8_dvb_s2(&f[2], 23u);
}

/* The pulse of a tick count from the formula of rc_channels.h, in wide
 * integers: 880 + ticks x 5 / 8 rounded (172 -> 988, 992 -> 1500). */
static inline unsigned ref_pulse_us(unsigned ticks)
{
    return 880u + (ticks * 5u + 4u) / 8u;
}

#endif /* RC_REF_FRAMES_H */
