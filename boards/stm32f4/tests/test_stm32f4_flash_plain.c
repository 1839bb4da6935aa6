/*
 * test_stm32f4_flash_plain.c - the flash driver as the firmware builds it
 * (plain volatile accesses, no hooks) on a fake register block that keeps
 * what is written and never changes by itself: final register values, the
 * bounded waits and the lock check. The exact sequences are in
 * test_stm32f4_flash.c (the same source built with the access hooks).
 *
 * Expected values (RM0090 sections 3.6 and 3.9): KEYR ends holding KEY2
 * 0xCDEF89AB; BSY is SR bit 16; CR.LOCK is bit 31 (reset value 0x80000000);
 * the SR clear writes 0xF3; the program CR is 0x201; the last CR write is
 * 0x80000000.
 */
#include "unity.h"

#include "stm32f4_flash.h"

#include <string.h>

static stm32_flash_regs_t regs;
static uint32_t mem[0x4000u / 4u]; /* sector 0 is all these tests touch */
static stm32_flash_t fl;

void setUp(void)
{
    memset((void *)&regs, 0, sizeof regs);
    memset(mem, 0xFF, sizeof mem);
    memset(&fl, 0, sizeof fl);
    TEST_ASSERT_EQUAL(STM32_FLASH_OK, stm32_flash_init(&fl, &regs, mem, 50u, 50u));
}

void tearDown(void) {}

static void test_busy_forever_times_out_untouched(void)
{
    regs.SR = FLASH_SR_BSY;
    regs.CR = FLASH_CR_LOCK;
    TEST_ASSERT_EQUAL(STM32_FLASH_ERR_TIMEOUT, stm32_flash_erase_sector(&fl, 0u));
    const uint8_t d[4] = {0u, 0u, 0u, 0u};
    TEST_ASSERT_EQUAL(STM32_FLASH_ERR_TIMEOUT, stm32_flash_program(&fl, 0u, d, 4u));
    TEST_ASSERT_EQUAL(STM32_FLASH_ERR_TIMEOUT, stm32_flash_lock(&fl));
    TEST_ASSERT_EQUAL_HEX32(0u, regs.KEYR);
    TEST_ASSERT_EQUAL_HEX32(FLASH_CR_LOCK, regs.CR);
    TEST_ASSERT_EQUAL_UINT16(3u, fl.timeouts);
    TEST_ASSERT_EQUAL_HEX32(0xFFFFFFFFu, mem[0]);
}

static void test_lock_that_stays_is_reported(void)
{
    regs.CR = FLASH_CR_LOCK; /* this fake never clears it: as after a bad key */
    TEST_ASSERT_EQUAL(STM32_FLASH_ERR_LOCKED, stm32_flash_erase_sector(&fl, 0u));
    TEST_ASSERT_EQUAL_HEX32(0xCDEF89ABu, regs.KEYR);
    TEST_ASSERT_EQUAL_HEX32(FLASH_CR_LOCK, regs.CR);
}

static void test_program_final_values(void)
{
    regs.CR = 0u; /* unlocked; SR = 0: idle, no errors */
    const uint8_t d[4] = {0x78u, 0x56u, 0x34u, 0x12u};
    /* the fake SR keeps the 0xF3 the driver writes to clear it, so the
     * flags read back set: a plain fake cannot clear write-1 bits */
    TEST_ASSERT_EQUAL(STM32_FLASH_ERR_PROGRAM, stm32_flash_program(&fl, 8u, d, 4u));
    TEST_ASSERT_EQUAL_HEX32(0xF2u, fl.last_errors); /* 0xF3 without EOP */
    TEST_ASSERT_EQUAL_HEX32(0x12345678u, mem[2]);   /* the word went to offset 8 */
    TEST_ASSERT_EQUAL_HEX32(FLASH_CR_LOCK, regs.CR);
    TEST_ASSERT_EQUAL_HEX32(0u, regs.KEYR); /* was unlocked: no keys */
}

static void test_read(void)
{
    mem[1] = 0xA1B2C3D4u;
    uint8_t b[3];
    TEST_ASSERT_EQUAL(STM32_FLASH_OK, stm32_flash_read(&fl, 5u, b, 3u));
    TEST_ASSERT_EQUAL_HEX8(0xC3u, b[0]);
    TEST_ASSERT_EQUAL_HEX8(0xB2u, b[1]);
    TEST_ASSERT_EQUAL_HEX8(0xA1u, b[2]);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_busy_forever_times_out_untouched);
    RUN_TEST(test_lock_that_stays_is_reported);
    RUN_TEST(test_program_final_values);
    RUN_TEST(test_read);
    return UNITY_END();
}
