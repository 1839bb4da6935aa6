/*
 * crc32.h - CRC-32/ISO-HDLC (the zlib, Ethernet and PNG CRC): polynomial
 * 0x04C11DB7 processed reflected (0xEDB88320), initial value 0xFFFFFFFF,
 * reflected input and output, final XOR 0xFFFFFFFF. Check value of the nine
 * ASCII bytes "123456789": 0xCBF43926.
 */
#ifndef HT_CRC32_H
#define HT_CRC32_H

#include <stddef.h>
#include <stdint.h>

/* CRC-32 of n bytes, continuing from crc: start with 0, and pass the result
 * of one call as crc of the next to cover data given in pieces (the initial
 * value and the final XOR are applied inside, so crc32(crc32(0, a), b) is the
 * CRC of a followed by b). Bitwise: no table, no state. */
uint32_t crc32_iso_hdlc(uint32_t crc, const uint8_t *data, size_t n);

#endif /* HT_CRC32_H */
