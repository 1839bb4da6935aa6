/*
 * test_stm32f4_param_flash.c - the parameter store on the STM32F405 slots:
 * param_store over stm32_param_flash over the flash driver (built with the
 * access hooks) over the controller model of fake_flash_ctrl.c.
 *
 * Expected placement (RM0090 table 5; stm32f4_flash_regs.h): slot 0 =
 * sector 1 = offset 0x4000 (word 0x1000), slot 1 = sector 2 = offset 0x8000
 * (word 0x2000), 16 KiB each. The first record's first word is the magic
 * "HTPS" read as a little-endian word: 0x53505448. Sectors 0 and 3 (the
 * image) are never written.
 */
#include "unity.h"

#include "fake_flash_ctrl.h"
#include "param_store.h"
#include "stm32f4_param_flash.h"

#include <string.h>

static stm32_flash_t fl;
static param_flash_t pf;
static param_store_t store;

#define IMAGE_FILL 0x0BADC0DEu

void setUp(void)
{
    fake_reset(IMAGE_FILL, 2u);
    memset(&fl, 0, sizeof fl);
    TEST_ASSERT_EQUAL(STM32_FLASH_OK, stm32_flash_init(&fl, &fake.regs, fake.mem, 100u, 100u));
    stm32_param_flash_bind(&fl, &pf);
    store.flash = &pf;
    store.schema_id = 0x0001u;
    store.schema_version = 1u;
    store.length = 10u;
}

void tearDown(void)
{
    TEST_ASSERT_EQUAL_UINT32(0u, fake.cr_writes_while_busy);
    TEST_ASSERT_EQUAL_UINT32(0u, fake.bus_errors);
}

static void image_untouched(void)
{
    TEST_ASSERT_EQUAL_HEX32(IMAGE_FILL, fake.mem[0]);
    TEST_ASSERT_EQUAL_HEX32(IMAGE_FILL, fake.mem[0x0FFFu]);  /* sector 0's last word */
    TEST_ASSERT_EQUAL_HEX32(IMAGE_FILL, fake.mem[0x3000u]);  /* sector 3's first */
    TEST_ASSERT_EQUAL_HEX32(IMAGE_FILL, fake.mem[0x3FFFFu]); /* sector 11's last */
}

static void test_bind(void)
{
    TEST_ASSERT_EQUAL_UINT32(0x4000u, pf.slot_size);
    TEST_ASSERT_EQUAL_PTR(&fl, pf.ctx);
    TEST_ASSERT_EQUAL_UINT32(16356u, param_store_max_payload(pf.slot_size));
}

static void test_store_on_sectors_1_and_2(void)
{
    /* the factory image leaves the parameter sectors as whatever was there:
     * here not erased, so the first load reports CORRUPT and defaults */
    uint8_t out[10];
    param_store_load_t r;
    TEST_ASSERT_EQUAL(PARAM_STORE_CORRUPT, param_store_load(&store, out, &r));
    TEST_ASSERT_EQUAL_UINT8(0u, r.loaded);
    const uint8_t a[10] = {1u, 2u, 3u, 4u, 5u, 6u, 7u, 8u, 9u, 10u};
    const uint8_t b[10] = {10u, 9u, 8u, 7u, 6u, 5u, 4u, 3u, 2u, 1u};
    uint8_t slot = 9u;
    TEST_ASSERT_EQUAL(PARAM_STORE_OK, param_store_save(&store, a, &slot, NULL));
    TEST_ASSERT_EQUAL_UINT8(0u, slot);
    TEST_ASSERT_EQUAL_HEX32(1u << 1, fake.erased_sectors);
    TEST_ASSERT_EQUAL_HEX32(0x53505448u, fake.mem[0x1000u]);
    TEST_ASSERT_EQUAL_HEX32(0x04030201u, fake.mem[0x1005u]); /* payload at byte 20 */
    TEST_ASSERT_EQUAL_HEX32(FLASH_CR_LOCK, fake.regs.CR);    /* locked between calls */
    /* slot 1 (sector 2) still holds old data: CORRUPT beside a good slot 0 */
    TEST_ASSERT_EQUAL(PARAM_STORE_CORRUPT, param_store_load(&store, out, &r));
    TEST_ASSERT_EQUAL_UINT8(1u, r.loaded);
    TEST_ASSERT_EQUAL_HEX8_ARRAY(a, out, 10u);
    TEST_ASSERT_EQUAL(PARAM_STORE_OK, param_store_save(&store, b, &slot, NULL));
    TEST_ASSERT_EQUAL_UINT8(1u, slot);
    TEST_ASSERT_EQUAL_HEX32(0x53505448u, fake.mem[0x2000u]);
    TEST_ASSERT_EQUAL(PARAM_STORE_OK, param_store_load(&store, out, &r));
    TEST_ASSERT_EQUAL_UINT8(1u, r.slot);
    TEST_ASSERT_EQUAL_UINT32(2u, r.sequence);
    TEST_ASSERT_EQUAL_HEX8_ARRAY(b, out, 10u);
    image_untouched();
    TEST_ASSERT_EQUAL_HEX32((1u << 1) | (1u << 2), fake.erased_sectors);
}

static void test_write_protected_slot_fails_and_keeps_the_other(void)
{
    const uint8_t a[10] = {1u, 2u, 3u, 4u, 5u, 6u, 7u, 8u, 9u, 10u};
    TEST_ASSERT_EQUAL(PARAM_STORE_OK, param_store_save(&store, a, NULL, NULL));
    fake.wrp_sectors = 1u << 2;
    TEST_ASSERT_EQUAL(PARAM_STORE_ERR_FLASH, param_store_save(&store, a, NULL, NULL));
    uint8_t out[10];
    param_store_load_t r;
    TEST_ASSERT_EQUAL(PARAM_STORE_CORRUPT, param_store_load(&store, out, &r));
    TEST_ASSERT_EQUAL_UINT8(1u, r.loaded);
    TEST_ASSERT_EQUAL_UINT8(0u, r.slot);
    image_untouched();
}

static void test_adapter_refuses_bad_spans(void)
{
    uint8_t b[8] = {0};
    TEST_ASSERT_EQUAL_INT(-(int)STM32_FLASH_ERR_RANGE, stm32_param_flash_erase(&fl, 2u));
    TEST_ASSERT_EQUAL_INT(-(int)STM32_FLASH_ERR_RANGE,
                          stm32_param_flash_program(&fl, 0u, 0x3FFCu, b, 8u));
    TEST_ASSERT_EQUAL_INT(-(int)STM32_FLASH_ERR_RANGE,
                          stm32_param_flash_read(&fl, 1u, 0x4000u, b, 1u));
    TEST_ASSERT_EQUAL_INT(-(int)STM32_FLASH_ERR_RANGE, stm32_param_flash_read(&fl, 2u, 0u, b, 1u));
    TEST_ASSERT_EQUAL_INT(0, stm32_param_flash_read(&fl, 1u, 0x3FF8u, b, 8u));
    TEST_ASSERT_EQUAL_HEX8(0xDEu, b[0]); /* sector 2's last words: IMAGE_FILL, LE */
    TEST_ASSERT_EQUAL_UINT32(0u, fake.writes);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_bind);
    RUN_TEST(test_store_on_sectors_1_and_2);
    RUN_TEST(test_write_protected_slot_fails_and_keeps_the_other);
    RUN_TEST(test_adapter_refuses_bad_spans);
    return UNITY_END();
}
