/*
 * test_sim_flash.c - the simulated NOR flash the parameter store's tests
 * stand on: erase to 0xFF, program clears bits only (0 -> 1 reported),
 * alignment, and each power-cut model doing what sim_flash.h says.
 */
#include "unity.h"

#include "sim_flash.h"

#include <string.h>

#define SLOT 64u

static uint8_t mem[2u * SLOT];
static sim_flash_t sim;

void setUp(void)
{
    sim_flash_init(&sim, mem, SLOT, 2u, 4u);
}

void tearDown(void) {}

static void test_starts_erased(void)
{
    for (uint32_t i = 0u; i < sizeof mem; ++i) {
        TEST_ASSERT_EQUAL_HEX8(0xFFu, mem[i]);
    }
    TEST_ASSERT_EQUAL_UINT8(1u, sim.powered);
}

static void test_program_clears_bits_only(void)
{
    const uint8_t a[4] = {0xF0u, 0x0Fu, 0x00u, 0xFFu};
    const uint8_t b[4] = {0xF0u, 0x0Fu, 0x00u, 0x7Fu}; /* only clears more */
    const uint8_t c[4] = {0xFFu, 0x0Fu, 0x00u, 0x7Fu}; /* byte 0 needs 0 -> 1 */
    TEST_ASSERT_EQUAL_INT(0, sim_flash_program(&sim, 1u, 8u, a, 4u));
    TEST_ASSERT_EQUAL_MEMORY(a, &mem[SLOT + 8u], 4u);
    TEST_ASSERT_EQUAL_INT(0, sim_flash_program(&sim, 1u, 8u, b, 4u));
    TEST_ASSERT_EQUAL_HEX8(0x7Fu, mem[SLOT + 11u]);
    TEST_ASSERT_EQUAL_INT(SIM_FLASH_ERR_NOR, sim_flash_program(&sim, 1u, 8u, c, 4u));
    TEST_ASSERT_EQUAL_UINT32(1u, sim.nor_violations);
    TEST_ASSERT_EQUAL_HEX8(0xF0u, mem[SLOT + 8u]); /* the cells keep old & new */
    TEST_ASSERT_EQUAL_HEX8(0xFFu, mem[7u]);        /* slot 0 untouched */
    TEST_ASSERT_EQUAL_INT(0, sim_flash_erase(&sim, 1u));
    TEST_ASSERT_EQUAL_HEX8(0xFFu, mem[SLOT + 8u]);
}

static void test_alignment_and_range(void)
{
    const uint8_t a[8] = {0};
    TEST_ASSERT_EQUAL_INT(SIM_FLASH_ERR_ALIGN, sim_flash_program(&sim, 0u, 2u, a, 4u));
    TEST_ASSERT_EQUAL_INT(SIM_FLASH_ERR_ALIGN, sim_flash_program(&sim, 0u, 0u, a, 3u));
    TEST_ASSERT_EQUAL_UINT32(2u, sim.align_violations);
    TEST_ASSERT_EQUAL_INT(SIM_FLASH_ERR_RANGE, sim_flash_program(&sim, 2u, 0u, a, 4u));
    TEST_ASSERT_EQUAL_INT(SIM_FLASH_ERR_RANGE, sim_flash_program(&sim, 0u, SLOT - 4u, a, 8u));
    TEST_ASSERT_EQUAL_INT(SIM_FLASH_ERR_RANGE, sim_flash_erase(&sim, 2u));
    uint8_t r[4];
    TEST_ASSERT_EQUAL_INT(SIM_FLASH_ERR_RANGE, sim_flash_read(&sim, 1u, SLOT - 2u, r, 4u));
    TEST_ASSERT_EQUAL_INT(0, sim_flash_read(&sim, 1u, SLOT - 4u, r, 4u));
    for (uint32_t i = 0u; i < sizeof mem; ++i) {
        TEST_ASSERT_EQUAL_HEX8(0xFFu, mem[i]); /* nothing was written */
    }
}

static void test_program_cut_and_torn_byte(void)
{
    const uint8_t a[8] = {0x00u, 0x11u, 0x22u, 0x33u, 0x44u, 0x55u, 0x66u, 0x77u};
    sim_flash_cut_program(&sim, 5u, 0x0Fu); /* 5 bytes, then byte 5 torn */
    TEST_ASSERT_EQUAL_INT(0, sim_flash_program(&sim, 0u, 0u, a, 4u));
    TEST_ASSERT_EQUAL_INT(SIM_FLASH_ERR_POWER, sim_flash_program(&sim, 0u, 4u, &a[4], 4u));
    TEST_ASSERT_EQUAL_MEMORY(a, mem, 5u);
    /* byte 5: 0xFF -> 0x55 needs bits 7,5,3,1 cleared; only 3 and 1 (mask 0x0F) are */
    TEST_ASSERT_EQUAL_HEX8(0xF5u, mem[5]);
    TEST_ASSERT_EQUAL_HEX8(0xFFu, mem[6]);
    TEST_ASSERT_EQUAL_UINT8(0u, sim.powered);
    uint8_t r[4];
    TEST_ASSERT_EQUAL_INT(SIM_FLASH_ERR_POWER, sim_flash_read(&sim, 0u, 0u, r, 4u));
    TEST_ASSERT_EQUAL_INT(SIM_FLASH_ERR_POWER, sim_flash_erase(&sim, 0u));
    TEST_ASSERT_EQUAL_HEX8(0x00u, mem[0]); /* the erase did nothing */
    sim_flash_power_on(&sim);
    TEST_ASSERT_EQUAL_INT(0, sim_flash_read(&sim, 0u, 4u, r, 4u));
    TEST_ASSERT_EQUAL_HEX8(0xF5u, r[1]);
}

static void test_program_cut_at_zero(void)
{
    const uint8_t a[4] = {0x12u, 0x34u, 0x56u, 0x78u};
    sim_flash_cut_program(&sim, 0u, 0x00u);
    TEST_ASSERT_EQUAL_INT(SIM_FLASH_ERR_POWER, sim_flash_program(&sim, 0u, 0u, a, 4u));
    TEST_ASSERT_EQUAL_HEX8(0xFFu, mem[0]);
}

static void fill_slot0(uint8_t v)
{
    memset(mem, v, SLOT);
}

static void test_erase_cut_prefix_suffix(void)
{
    fill_slot0(0x00u);
    sim_flash_cut_erase(&sim, SIM_ERASE_PREFIX, 10u);
    TEST_ASSERT_EQUAL_INT(SIM_FLASH_ERR_POWER, sim_flash_erase(&sim, 0u));
    TEST_ASSERT_EQUAL_HEX8(0xFFu, mem[9]);
    TEST_ASSERT_EQUAL_HEX8(0x00u, mem[10]);
    TEST_ASSERT_EQUAL_HEX8(0x00u, mem[SLOT - 1u]);
    TEST_ASSERT_EQUAL_HEX8(0xFFu, mem[SLOT]); /* slot 1 untouched */
    sim_flash_power_on(&sim);
    fill_slot0(0x00u);
    sim_flash_cut_erase(&sim, SIM_ERASE_SUFFIX, 10u);
    TEST_ASSERT_EQUAL_INT(SIM_FLASH_ERR_POWER, sim_flash_erase(&sim, 0u));
    TEST_ASSERT_EQUAL_HEX8(0x00u, mem[SLOT - 11u]);
    TEST_ASSERT_EQUAL_HEX8(0xFFu, mem[SLOT - 10u]);
    sim_flash_power_on(&sim);
    sim_flash_cut_erase(&sim, SIM_ERASE_PREFIX, 1000u); /* past the end: all erased */
    TEST_ASSERT_EQUAL_INT(SIM_FLASH_ERR_POWER, sim_flash_erase(&sim, 0u));
    TEST_ASSERT_EQUAL_HEX8(0xFFu, mem[SLOT - 1u]);
}

static void test_erase_cut_noise_only_sets_bits(void)
{
    for (uint32_t i = 0u; i < SLOT; ++i) {
        mem[i] = (uint8_t)(i * 37u);
    }
    uint8_t before[SLOT];
    memcpy(before, mem, SLOT);
    sim_flash_cut_erase(&sim, SIM_ERASE_NOISE, 7u);
    TEST_ASSERT_EQUAL_INT(SIM_FLASH_ERR_POWER, sim_flash_erase(&sim, 0u));
    uint32_t changed = 0u;
    uint32_t erased = 0u;
    for (uint32_t i = 0u; i < SLOT; ++i) {
        TEST_ASSERT_EQUAL_HEX8(before[i], (uint8_t)(mem[i] & before[i])); /* no bit cleared */
        changed += (mem[i] != before[i]) ? 1u : 0u;
        erased += (mem[i] == 0xFFu) ? 1u : 0u;
    }
    TEST_ASSERT_TRUE(changed > SLOT / 2u); /* a real mix: neither untouched ... */
    TEST_ASSERT_TRUE(erased < SLOT);       /* ... nor erased */
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_starts_erased);
    RUN_TEST(test_program_clears_bits_only);
    RUN_TEST(test_alignment_and_range);
    RUN_TEST(test_program_cut_and_torn_byte);
    RUN_TEST(test_program_cut_at_zero);
    RUN_TEST(test_erase_cut_prefix_suffix);
    RUN_TEST(test_erase_cut_noise_only_sets_bits);
    return UNITY_END();
}
