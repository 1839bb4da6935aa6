/*
 * test_crc32.c - CRC-32/ISO-HDLC against published check values.
 *
 * Expected values (the catalogue of parametrised CRCs, "CRC-32/ISO-HDLC":
 * width 32, poly 0x04C11DB7, init 0xFFFFFFFF, refin/refout true, xorout
 * 0xFFFFFFFF, check 0xCBF43926; the other values agree with zlib's crc32):
 *   "123456789"                                   -> 0xCBF43926
 *   ""                                            -> 0x00000000
 *   "a"                                           -> 0xE8B7BE43
 *   "The quick brown fox jumps over the lazy dog" -> 0x414FA339
 *   32 bytes 0x00                                 -> 0x190A55AD
 *   32 bytes 0xFF                                 -> 0xFF6CAB0B
 */
#include "unity.h"

#include "crc32.h"

#include <string.h>

void setUp(void) {}
void tearDown(void) {}

static uint32_t crc_str(const char *s)
{
    return crc32_iso_hdlc(0u, (const uint8_t *)s, strlen(s));
}

static void test_check_values(void)
{
    TEST_ASSERT_EQUAL_HEX32(0xCBF43926u, crc_str("123456789"));
    TEST_ASSERT_EQUAL_HEX32(0x00000000u, crc_str(""));
    TEST_ASSERT_EQUAL_HEX32(0xE8B7BE43u, crc_str("a"));
    TEST_ASSERT_EQUAL_HEX32(0x414FA339u, crc_str("The quick brown fox jumps over the lazy dog"));
}

static void test_blocks_of_zeros_and_ones(void)
{
    uint8_t b[32];
    memset(b, 0x00, sizeof b);
    TEST_ASSERT_EQUAL_HEX32(0x190A55ADu, crc32_iso_hdlc(0u, b, sizeof b));
    memset(b, 0xFF, sizeof b);
    TEST_ASSERT_EQUAL_HEX32(0xFF6CAB0Bu, crc32_iso_hdlc(0u, b, sizeof b));
}

static void test_pieces_chain(void)
{
    const uint8_t *s = (const uint8_t *)"123456789";
    for (size_t cut = 0u; cut <= 9u; ++cut) {
        const uint32_t first = crc32_iso_hdlc(0u, s, cut);
        TEST_ASSERT_EQUAL_HEX32(0xCBF43926u, crc32_iso_hdlc(first, &s[cut], 9u - cut));
    }
}

static void test_null_leaves_crc(void)
{
    TEST_ASSERT_EQUAL_HEX32(0x12345678u, crc32_iso_hdlc(0x12345678u, NULL, 5u));
}

static void test_one_bit_changes_it(void)
{
    uint8_t b[9];
    memcpy(b, "123456789", 9u);
    b[4] ^= 0x01u;
    TEST_ASSERT_NOT_EQUAL(0xCBF43926u, crc32_iso_hdlc(0u, b, sizeof b));
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_check_values);
    RUN_TEST(test_blocks_of_zeros_and_ones);
    RUN_TEST(test_pieces_chain);
    RUN_TEST(test_null_leaves_crc);
    RUN_TEST(test_one_bit_changes_it);
    return UNITY_END();
}
