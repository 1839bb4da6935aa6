/*
 * test_stm32f4_flash.c - the flash driver's exact register sequences, on
 * the controller model of fake_flash_ctrl.c (the driver built with
 * STM32_FLASH_ACCESS_HOOKS, so every access is logged in order).
 *
 * Expected values, worked from RM0090 (sections 3.6 and 3.9):
 *   KEYR: 0x45670123 then 0xCDEF89AB (section 3.6.1)
 *   SR clear before an operation: EOP|OPERR|WRPERR|PGAERR|PGPERR|PGSERR
 *         = bits 0,1,4,5,6,7 = 0x000000F3 (write 1 to clear)
 *   CR, sector erase at x32: PSIZE=10b (0x200) | SER (bit 1) | SNB<<3:
 *         sector 0 -> 0x202, 1 -> 0x20A, 2 -> 0x212, 11 -> 0x25A;
 *         then the same | STRT (bit 16): 0x1020A for sector 1
 *   CR, programming at x32: PSIZE (0x200) | PG (bit 0) = 0x201
 *   CR after either: LOCK (bit 31) = 0x80000000, which clears the rest
 *   Sector map (table 5): sector 1 at offset 0x4000 (word 0x1000), 16 KiB;
 *         4 at 0x10000, 64 KiB; 5 at 0x20000, 11 at 0xE0000, 128 KiB.
 *   Data words little-endian: bytes 01 02 03 04 -> 0x04030201.
 *   ACR with the data cache on, 0x705 (LATENCY 5, PRFTEN, ICEN, DCEN): the
 *         flush writes 0x305 (DCEN off), 0x1305 (DCRST, bit 12), 0x305, 0x705.
 */
#include "unity.h"

#include "fake_flash_ctrl.h"
#include "stm32f4_flash.h"

#include <string.h>

static stm32_flash_t fl;

#define SECTOR1_WORD 0x1000u
#define SECTOR2_WORD 0x2000u

void setUp(void)
{
    fake_reset(0x12345678u, 3u);
    memset(&fl, 0, sizeof fl);
    TEST_ASSERT_EQUAL(STM32_FLASH_OK, stm32_flash_init(&fl, &fake.regs, fake.mem, 100u, 100u));
}

void tearDown(void)
{
    TEST_ASSERT_EQUAL_UINT32(0u, fake.cr_writes_while_busy);
    TEST_ASSERT_EQUAL_UINT32(0u, fake.dcrst_misuse);
}

static void expect_log(uint32_t i, fake_target_t t, uint32_t value)
{
    TEST_ASSERT_TRUE_MESSAGE(i < fake.log_len, "log too short");
    TEST_ASSERT_EQUAL_INT_MESSAGE((int)t, (int)fake.log[i].target, "register");
    TEST_ASSERT_EQUAL_HEX32(value, fake.log[i].value);
}

static void test_sector_map(void)
{
    static const uint32_t off[12] = {0x0u,     0x4000u,  0x8000u,  0xC000u,  0x10000u, 0x20000u,
                                     0x40000u, 0x60000u, 0x80000u, 0xA0000u, 0xC0000u, 0xE0000u};
    static const uint32_t size[12] = {0x4000u,  0x4000u,  0x4000u,  0x4000u,  0x10000u, 0x20000u,
                                      0x20000u, 0x20000u, 0x20000u, 0x20000u, 0x20000u, 0x20000u};
    uint32_t total = 0u;
    for (uint32_t s = 0u; s < 12u; ++s) {
        TEST_ASSERT_EQUAL_HEX32(off[s], stm32_flash_sector_offset(s));
        TEST_ASSERT_EQUAL_HEX32(size[s], stm32_flash_sector_bytes(s));
        total += size[s];
    }
    TEST_ASSERT_EQUAL_HEX32(STM32_FLASH_MEM_BYTES, total);
    TEST_ASSERT_EQUAL_HEX32(0u, stm32_flash_sector_offset(12u));
    TEST_ASSERT_EQUAL_HEX32(0u, stm32_flash_sector_bytes(12u));
    TEST_ASSERT_EQUAL_HEX32(STM32_PARAM_A_ADDR,
                            STM32_FLASH_MEM_BASE + stm32_flash_sector_offset(STM32_PARAM_SECTOR_A));
    TEST_ASSERT_EQUAL_HEX32(STM32_PARAM_B_ADDR,
                            STM32_FLASH_MEM_BASE + stm32_flash_sector_offset(STM32_PARAM_SECTOR_B));
}

static void test_init_refuses(void)
{
    stm32_flash_t f2;
    memset(&f2, 0, sizeof f2);
    TEST_ASSERT_EQUAL(STM32_FLASH_ERR_NULL, stm32_flash_init(NULL, &fake.regs, fake.mem, 1u, 1u));
    TEST_ASSERT_EQUAL(STM32_FLASH_ERR_NULL, stm32_flash_init(&f2, NULL, fake.mem, 1u, 1u));
    TEST_ASSERT_EQUAL(STM32_FLASH_ERR_NULL, stm32_flash_init(&f2, &fake.regs, NULL, 1u, 1u));
    TEST_ASSERT_EQUAL(STM32_FLASH_ERR_RANGE, stm32_flash_init(&f2, &fake.regs, fake.mem, 0u, 1u));
    TEST_ASSERT_EQUAL(STM32_FLASH_ERR_RANGE, stm32_flash_init(&f2, &fake.regs, fake.mem, 1u, 0u));
    TEST_ASSERT_EQUAL_UINT8(0u, f2.ready);
    TEST_ASSERT_EQUAL(STM32_FLASH_ERR_NULL, stm32_flash_erase_sector(&f2, 1u));
    TEST_ASSERT_EQUAL_UINT32(0u, fake.writes);
}

static void test_erase_sector1_sequence(void)
{
    fake.regs.SR = FLASH_SR_PGSERR | FLASH_SR_PGPERR; /* left by a stray write */
    TEST_ASSERT_EQUAL(STM32_FLASH_OK, stm32_flash_erase_sector(&fl, 1u));
    TEST_ASSERT_EQUAL_UINT32(6u, fake.log_len);
    expect_log(0u, FAKE_KEYR, 0x45670123u);
    expect_log(1u, FAKE_KEYR, 0xCDEF89ABu);
    expect_log(2u, FAKE_SR, 0x000000F3u);
    expect_log(3u, FAKE_CR, 0x0000020Au);
    expect_log(4u, FAKE_CR, 0x0001020Au);
    expect_log(5u, FAKE_CR, 0x80000000u);
    TEST_ASSERT_EQUAL_HEX32(FLASH_CR_LOCK, fake.regs.CR);
    TEST_ASSERT_EQUAL_HEX32(0u, fake.regs.SR);
    /* SR reads: 1 idle check, 3 busy + 1 idle after STRT, 1 for the flags */
    TEST_ASSERT_EQUAL_UINT32(6u, fake.sr_reads);
    TEST_ASSERT_EQUAL_HEX32(0xFFFFFFFFu, fake.mem[SECTOR1_WORD]);
    TEST_ASSERT_EQUAL_HEX32(0xFFFFFFFFu, fake.mem[SECTOR2_WORD - 1u]);
    TEST_ASSERT_EQUAL_HEX32(0x12345678u, fake.mem[SECTOR1_WORD - 1u]); /* sector 0 */
    TEST_ASSERT_EQUAL_HEX32(0x12345678u, fake.mem[SECTOR2_WORD]);      /* sector 2 */
    TEST_ASSERT_EQUAL_HEX32(1u << 1, fake.erased_sectors);
}

static void test_erase_other_sectors_snb(void)
{
    static const uint32_t sector[4] = {0u, 2u, 4u, 11u};
    static const uint32_t cr[4] = {0x202u, 0x212u, 0x222u, 0x25Au};
    for (uint32_t i = 0u; i < 4u; ++i) {
        fake_reset(0u, 0u);
        TEST_ASSERT_EQUAL(STM32_FLASH_OK, stm32_flash_erase_sector(&fl, sector[i]));
        expect_log(3u, FAKE_CR, cr[i]);
        expect_log(4u, FAKE_CR, cr[i] | 0x10000u);
        TEST_ASSERT_EQUAL_HEX32(1u << sector[i], fake.erased_sectors);
    }
    fake_reset(0u, 0u);
    TEST_ASSERT_EQUAL(STM32_FLASH_ERR_RANGE, stm32_flash_erase_sector(&fl, 12u));
    TEST_ASSERT_EQUAL_UINT32(0u, fake.writes);
}

static void test_erase_flushes_data_cache(void)
{
    fake.regs.ACR = 0x705u;
    TEST_ASSERT_EQUAL(STM32_FLASH_OK, stm32_flash_erase_sector(&fl, 2u));
    TEST_ASSERT_EQUAL_UINT32(10u, fake.log_len);
    expect_log(5u, FAKE_CR, 0x80000000u);
    expect_log(6u, FAKE_ACR, 0x305u);
    expect_log(7u, FAKE_ACR, 0x1305u);
    expect_log(8u, FAKE_ACR, 0x305u);
    expect_log(9u, FAKE_ACR, 0x705u);
    TEST_ASSERT_EQUAL_UINT32(1u, fake.dcache_resets);
    TEST_ASSERT_EQUAL_HEX32(0x705u, fake.regs.ACR);
}

static void test_already_unlocked_writes_no_keys(void)
{
    fake.regs.CR = 0u;
    TEST_ASSERT_EQUAL(STM32_FLASH_OK, stm32_flash_erase_sector(&fl, 1u));
    expect_log(0u, FAKE_SR, 0xF3u);
    TEST_ASSERT_EQUAL_UINT32(0u, fake.bus_errors);
}

static void test_locked_until_reset(void)
{
    fake.hard_locked = 1u; /* an earlier wrong key sequence */
    TEST_ASSERT_EQUAL(STM32_FLASH_ERR_LOCKED, stm32_flash_erase_sector(&fl, 1u));
    TEST_ASSERT_EQUAL_UINT32(2u, fake.log_len); /* the two keys, then nothing */
    TEST_ASSERT_EQUAL_HEX32(0x12345678u, fake.mem[SECTOR1_WORD]);
    const uint8_t w[4] = {0u, 0u, 0u, 0u};
    TEST_ASSERT_EQUAL(STM32_FLASH_ERR_LOCKED, stm32_flash_program(&fl, 0x4000u, w, 4u));
}

static void test_erase_busy_before_start_times_out(void)
{
    fake.stuck_busy = 1u;
    TEST_ASSERT_EQUAL(STM32_FLASH_ERR_TIMEOUT, stm32_flash_erase_sector(&fl, 1u));
    TEST_ASSERT_EQUAL_UINT32(0u, fake.writes);
    TEST_ASSERT_EQUAL_UINT32(100u, fake.sr_reads); /* exactly the spin limit */
    TEST_ASSERT_EQUAL_UINT16(1u, fl.timeouts);
}

static void test_erase_never_ends_times_out_without_cr_write(void)
{
    fake.busy_reads = 1000u; /* longer than the spin limit of 100 */
    TEST_ASSERT_EQUAL(STM32_FLASH_ERR_TIMEOUT, stm32_flash_erase_sector(&fl, 1u));
    TEST_ASSERT_EQUAL_UINT32(5u, fake.log_len); /* keys, SR, CR, CR|STRT: no lock while busy */
    expect_log(4u, FAKE_CR, 0x1020Au);
    TEST_ASSERT_EQUAL_UINT32(101u, fake.sr_reads);
    /* once BSY falls, the lock goes through */
    fake.busy_left = 0u;
    TEST_ASSERT_EQUAL(STM32_FLASH_OK, stm32_flash_lock(&fl));
    TEST_ASSERT_EQUAL_HEX32(FLASH_CR_LOCK, fake.regs.CR);
}

static void test_erase_write_protected(void)
{
    fake.wrp_sectors = 1u << 1;
    TEST_ASSERT_EQUAL(STM32_FLASH_ERR_PROGRAM, stm32_flash_erase_sector(&fl, 1u));
    TEST_ASSERT_EQUAL_HEX32(FLASH_SR_WRPERR, fl.last_errors);
    TEST_ASSERT_EQUAL_UINT16(1u, fl.errors);
    TEST_ASSERT_EQUAL_UINT32(7u, fake.log_len);
    expect_log(5u, FAKE_SR, FLASH_SR_WRPERR); /* cleared, write 1 */
    expect_log(6u, FAKE_CR, 0x80000000u);
    TEST_ASSERT_EQUAL_HEX32(0u, fake.regs.SR);
    TEST_ASSERT_EQUAL_HEX32(0x12345678u, fake.mem[SECTOR1_WORD]);
}

static void test_erase_operation_error(void)
{
    fake.inject_errors = FLASH_SR_OPERR;
    TEST_ASSERT_EQUAL(STM32_FLASH_ERR_PROGRAM, stm32_flash_erase_sector(&fl, 2u));
    TEST_ASSERT_EQUAL_HEX32(FLASH_SR_OPERR, fl.last_errors);
    TEST_ASSERT_EQUAL_HEX32(0u, fake.regs.SR);
    TEST_ASSERT_EQUAL_HEX32(FLASH_CR_LOCK, fake.regs.CR);
}

static void test_program_sequence(void)
{
    fake_reset(0xFFFFFFFFu, 3u);
    const uint8_t d[8] = {0x01u, 0x02u, 0x03u, 0x04u, 0xA5u, 0x5Au, 0x00u, 0xFFu};
    TEST_ASSERT_EQUAL(STM32_FLASH_OK, stm32_flash_program(&fl, 0x4000u, d, 8u));
    TEST_ASSERT_EQUAL_UINT32(7u, fake.log_len);
    expect_log(0u, FAKE_KEYR, 0x45670123u);
    expect_log(1u, FAKE_KEYR, 0xCDEF89ABu);
    expect_log(2u, FAKE_SR, 0xF3u);
    expect_log(3u, FAKE_CR, 0x201u);
    expect_log(4u, FAKE_MEM, 0x04030201u);
    TEST_ASSERT_EQUAL_HEX32(SECTOR1_WORD, fake.log[4].word);
    expect_log(5u, FAKE_MEM, 0xFF005AA5u);
    TEST_ASSERT_EQUAL_HEX32(SECTOR1_WORD + 1u, fake.log[5].word);
    expect_log(6u, FAKE_CR, 0x80000000u);
    /* SR reads: 1 idle check, then per word 3 busy + 1 idle + 1 for the flags */
    TEST_ASSERT_EQUAL_UINT32(11u, fake.sr_reads);
    TEST_ASSERT_EQUAL_HEX32(0x04030201u, fake.mem[SECTOR1_WORD]);
    TEST_ASSERT_EQUAL_HEX32(0xFF005AA5u, fake.mem[SECTOR1_WORD + 1u]);
    TEST_ASSERT_EQUAL_HEX32(0xFFFFFFFFu, fake.mem[SECTOR1_WORD + 2u]);
}

static void test_program_refuses_bad_spans(void)
{
    const uint8_t d[8] = {0};
    TEST_ASSERT_EQUAL(STM32_FLASH_ERR_RANGE, stm32_flash_program(&fl, 0x4002u, d, 4u));
    TEST_ASSERT_EQUAL(STM32_FLASH_ERR_RANGE, stm32_flash_program(&fl, 0x4000u, d, 6u));
    TEST_ASSERT_EQUAL(STM32_FLASH_ERR_RANGE, stm32_flash_program(&fl, 0xFFFFCu, d, 8u));
    TEST_ASSERT_EQUAL(STM32_FLASH_ERR_RANGE, stm32_flash_program(&fl, 0xFFFFFFFCu, d, 8u));
    TEST_ASSERT_EQUAL(STM32_FLASH_ERR_NULL, stm32_flash_program(&fl, 0x4000u, NULL, 4u));
    TEST_ASSERT_EQUAL(STM32_FLASH_OK, stm32_flash_program(&fl, 0x4000u, d, 0u));
    TEST_ASSERT_EQUAL(STM32_FLASH_OK, stm32_flash_program(&fl, 0xFFFFCu, d, 0u));
    TEST_ASSERT_EQUAL_UINT32(0u, fake.writes);
}

static void test_program_over_data_fails_verify(void)
{
    /* the words hold 0x12345678: programming 0xFFFFFFF0 can only clear bits */
    const uint8_t d[4] = {0xF0u, 0xFFu, 0xFFu, 0xFFu};
    TEST_ASSERT_EQUAL(STM32_FLASH_ERR_VERIFY, stm32_flash_program(&fl, 0x8000u, d, 4u));
    TEST_ASSERT_EQUAL_HEX32(0x12345670u, fake.mem[SECTOR2_WORD]);
    TEST_ASSERT_EQUAL_HEX32(FLASH_CR_LOCK, fake.regs.CR);
}

static void test_program_errors_stop_and_lock(void)
{
    fake_reset(0xFFFFFFFFu, 1u);
    fake.wrp_sectors = 1u << 2;
    const uint8_t d[8] = {1u, 2u, 3u, 4u, 5u, 6u, 7u, 8u};
    TEST_ASSERT_EQUAL(STM32_FLASH_ERR_PROGRAM, stm32_flash_program(&fl, 0x8000u, d, 8u));
    TEST_ASSERT_EQUAL_HEX32(FLASH_SR_WRPERR, fl.last_errors);
    TEST_ASSERT_EQUAL_UINT32(7u, fake.log_len); /* keys, SR, CR, one word, SR clear, lock */
    expect_log(4u, FAKE_MEM, 0x04030201u);
    expect_log(5u, FAKE_SR, FLASH_SR_WRPERR);
    expect_log(6u, FAKE_CR, 0x80000000u);
    TEST_ASSERT_EQUAL_HEX32(0xFFFFFFFFu, fake.mem[SECTOR2_WORD]);
    /* a parallelism or alignment error is reported the same way */
    fake.wrp_sectors = 0u;
    fake.inject_errors = FLASH_SR_PGAERR | FLASH_SR_PGPERR;
    TEST_ASSERT_EQUAL(STM32_FLASH_ERR_PROGRAM, stm32_flash_program(&fl, 0x8000u, d, 8u));
    TEST_ASSERT_EQUAL_HEX32(FLASH_SR_PGAERR | FLASH_SR_PGPERR, fl.last_errors);
    TEST_ASSERT_EQUAL_UINT16(2u, fl.errors);
    TEST_ASSERT_EQUAL_HEX32(0u, fake.regs.SR);
    /* and the next program starts clean and works */
    TEST_ASSERT_EQUAL(STM32_FLASH_OK, stm32_flash_program(&fl, 0x8000u, d, 8u));
    TEST_ASSERT_EQUAL_HEX32(0x08070605u, fake.mem[SECTOR2_WORD + 1u]);
}

static void test_program_busy_times_out(void)
{
    fake_reset(0xFFFFFFFFu, 1000u);
    const uint8_t d[8] = {0};
    TEST_ASSERT_EQUAL(STM32_FLASH_ERR_TIMEOUT, stm32_flash_program(&fl, 0x4000u, d, 8u));
    TEST_ASSERT_EQUAL_UINT32(5u, fake.log_len); /* keys, SR, CR, first word; then no CR write */
    expect_log(4u, FAKE_MEM, 0u);
    TEST_ASSERT_EQUAL_UINT16(1u, fl.timeouts);
}

static void test_read_little_endian_any_alignment(void)
{
    fake.mem[SECTOR1_WORD] = 0x44332211u;
    fake.mem[SECTOR1_WORD + 1u] = 0x88776655u;
    uint8_t b[6];
    TEST_ASSERT_EQUAL(STM32_FLASH_OK, stm32_flash_read(&fl, 0x4001u, b, 6u));
    const uint8_t expect[6] = {0x22u, 0x33u, 0x44u, 0x55u, 0x66u, 0x77u};
    TEST_ASSERT_EQUAL_HEX8_ARRAY(expect, b, 6u);
    TEST_ASSERT_EQUAL(STM32_FLASH_ERR_RANGE, stm32_flash_read(&fl, 0xFFFFEu, b, 4u));
    TEST_ASSERT_EQUAL(STM32_FLASH_ERR_NULL, stm32_flash_read(&fl, 0u, NULL, 4u));
    TEST_ASSERT_EQUAL(STM32_FLASH_OK, stm32_flash_read(&fl, 0xFFFFCu, b, 4u));
    TEST_ASSERT_EQUAL_UINT32(0u, fake.writes);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_sector_map);
    RUN_TEST(test_init_refuses);
    RUN_TEST(test_erase_sector1_sequence);
    RUN_TEST(test_erase_other_sectors_snb);
    RUN_TEST(test_erase_flushes_data_cache);
    RUN_TEST(test_already_unlocked_writes_no_keys);
    RUN_TEST(test_locked_until_reset);
    RUN_TEST(test_erase_busy_before_start_times_out);
    RUN_TEST(test_erase_never_ends_times_out_without_cr_write);
    RUN_TEST(test_erase_write_protected);
    RUN_TEST(test_erase_operation_error);
    RUN_TEST(test_program_sequence);
    RUN_TEST(test_program_refuses_bad_spans);
    RUN_TEST(test_program_over_data_fails_verify);
    RUN_TEST(test_program_errors_stop_and_lock);
    RUN_TEST(test_program_busy_times_out);
    RUN_TEST(test_read_little_endian_any_alignment);
    return UNITY_END();
}
