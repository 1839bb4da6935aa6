/*
 * crc32.c - CRC-32/ISO-HDLC, bit at a time (see crc32.h). A flash record is
 * checked once at boot and once per save, so speed does not matter and the
 * 1 KiB table is not worth its flash.
 */
#include "crc32.h"

#define CRC32_POLY_REFLECTED 0xEDB88320u

uint32_t crc32_iso_hdlc(uint32_t crc, const uint8_t *data, size_t n)
{
    uint32_t c = ~crc;
    if (data == NULL) {
        return crc;
    }
    for (size_t i = 0u; i < n; ++i) {
        c ^= data[i];
        for (uint32_t bit = 0u; bit < 8u; ++bit) {
            const uint32_t lsb = c & 1u;
            c >>= 1;
            if (lsb != 0u) {
                c ^= CRC32_POLY_REFLECTED;
            }
        }
    }
    return ~c;
}
