/*
 * test_param_store_power_cut.c - the fault-injection sweep: with a good set
 * A in one slot, a save of set B is cut by a power loss at every byte it
 * programs (the byte at the cut left untouched, or torn: half its bits
 * cleared, either half) and at every point of the erase (three models, see
 * sim_flash.h). After each cut the board "reboots" (power on, load) and
 * must come up with exactly A or exactly B: loaded = 1, the payload byte
 * for byte one of the two sets with its sequence number, never a mix,
 * never defaults. Then a save without a cut must succeed and load B: a cut
 * never leaves the store stuck.
 *
 * Counts, for a payload of L bytes: a save programs 20 (header) + L padded
 * to 4 + 4 (CRC) + 4 (commit) bytes; L = 37 -> 68 bytes, L = 40 -> 68
 * bytes, L = 1 -> 32 bytes. B becomes the loaded set only once the last
 * commit byte is fully programmed; every earlier cut must give A.
 * Starting points: A (seq 2) in slot 1 over an older A0 (seq 1) in slot 0,
 * so B goes over A0; and the wrap: A at 0xFFFFFFFF in slot 0, B to be 0 in
 * slot 1 (over 0xFFFFFFFE).
 */
#include "unity.h"

#include "crc32.h"
#include "sim_flash.h"

#include <string.h>

#define SLOT  256u
#define L_MAX 40u

static uint8_t mem[2u * SLOT];
static uint8_t start[2u * SLOT]; /* the flash with A in place */
static sim_flash_t sim;
static param_flash_t flash;
static param_store_t store;
static uint8_t set_a[L_MAX], set_b[L_MAX];
static uint32_t seq_a;
static uint8_t slot_a;

void setUp(void)
{
    sim_flash_init(&sim, mem, SLOT, 2u, PARAM_STORE_ALIGN);
    sim_flash_bind(&sim, &flash);
    store.flash = &flash;
    store.schema_id = 0x7A11u;
    store.schema_version = 1u;
}

void tearDown(void)
{
    TEST_ASSERT_EQUAL_UINT32(0u, sim.nor_violations);
    TEST_ASSERT_EQUAL_UINT32(0u, sim.align_violations);
    TEST_ASSERT_EQUAL_UINT32(0u, sim.range_violations);
}

static void make_sets(uint32_t len)
{
    store.length = len;
    for (uint32_t k = 0u; k < L_MAX; ++k) {
        set_a[k] = (uint8_t)(0xA0u + k);
        set_b[k] = (uint8_t)(0x0Bu * (k + 1u));
    }
}

/* A0 then A by the store itself: A ends in slot 1 with sequence 2. */
static void start_normal(uint32_t len)
{
    make_sets(len);
    uint8_t a0[L_MAX];
    memset(a0, 0x3C, sizeof a0);
    TEST_ASSERT_EQUAL(PARAM_STORE_OK, param_store_save(&store, a0, NULL, NULL));
    TEST_ASSERT_EQUAL(PARAM_STORE_OK, param_store_save(&store, set_a, &slot_a, &seq_a));
    TEST_ASSERT_EQUAL_UINT8(1u, slot_a);
    TEST_ASSERT_EQUAL_UINT32(2u, seq_a);
    memcpy(start, mem, sizeof mem);
}

/* A at sequence 0xFFFFFFFF in slot 0, so B would be 0: a first record's
 * sequence is patched to 0xFFFFFFFD (CRC redone, per the layout in
 * param_store.h), then the store saves 0xFFFFFFFE into slot 1 and A into
 * slot 0. */
static void start_wrap(uint32_t len)
{
    make_sets(len);
    uint8_t a0[L_MAX];
    memset(a0, 0x3C, sizeof a0);
    TEST_ASSERT_EQUAL(PARAM_STORE_OK, param_store_save(&store, a0, NULL, NULL));
    mem[12] = 0xFDu;
    mem[13] = 0xFFu;
    mem[14] = 0xFFu;
    mem[15] = 0xFFu;
    const uint32_t padded = (len + 3u) & ~3u;
    const uint32_t c = crc32_iso_hdlc(0u, mem, 20u + padded);
    for (uint32_t i = 0u; i < 4u; ++i) {
        mem[20u + padded + i] = (uint8_t)((c >> (8u * i)) & 0xFFu);
    }
    uint32_t seq = 0u;
    TEST_ASSERT_EQUAL(PARAM_STORE_OK, param_store_save(&store, a0, NULL, &seq));
    TEST_ASSERT_EQUAL_HEX32(0xFFFFFFFEu, seq);
    TEST_ASSERT_EQUAL(PARAM_STORE_OK, param_store_save(&store, set_a, &slot_a, &seq_a));
    TEST_ASSERT_EQUAL_UINT8(0u, slot_a);
    TEST_ASSERT_EQUAL_HEX32(0xFFFFFFFFu, seq_a);
    memcpy(start, mem, sizeof mem);
}

/* After a cut: reboot and load; exactly A or exactly B. Returns 1 for B. */
static int reboot_and_check(void)
{
    sim_flash_power_on(&sim);
    uint8_t out[L_MAX];
    memset(out, 0xEE, sizeof out);
    param_store_load_t r;
    const param_store_status_t st = param_store_load(&store, out, &r);
    TEST_ASSERT_TRUE_MESSAGE(st == PARAM_STORE_OK || st == PARAM_STORE_CORRUPT, "load status");
    TEST_ASSERT_EQUAL_UINT8_MESSAGE(1u, r.loaded, "booted on defaults");
    if (r.sequence == seq_a) {
        TEST_ASSERT_EQUAL_UINT8(slot_a, r.slot);
        TEST_ASSERT_EQUAL_HEX8_ARRAY(set_a, out, store.length);
        return 0;
    }
    TEST_ASSERT_EQUAL_UINT32_MESSAGE(seq_a + 1u, r.sequence, "neither A nor B");
    TEST_ASSERT_EQUAL_UINT8(1u - slot_a, r.slot);
    TEST_ASSERT_EQUAL_HEX8_ARRAY(set_b, out, store.length);
    TEST_ASSERT_EQUAL(PARAM_STORE_OK, st); /* B complete: A is still there, valid */
    return 1;
}

/* A save without a cut works after any cut, and loads B. */
static void recover(void)
{
    uint8_t slot = 9u;
    uint32_t seq = 0u;
    TEST_ASSERT_EQUAL(PARAM_STORE_OK, param_store_save(&store, set_b, &slot, &seq));
    uint8_t out[L_MAX];
    param_store_load_t r;
    TEST_ASSERT_EQUAL(PARAM_STORE_OK, param_store_load(&store, out, &r));
    TEST_ASSERT_EQUAL_HEX8_ARRAY(set_b, out, store.length);
}

static uint32_t save_bytes(void)
{
    memcpy(mem, start, sizeof mem);
    sim_flash_power_on(&sim);
    TEST_ASSERT_EQUAL(PARAM_STORE_OK, param_store_save(&store, set_b, NULL, NULL));
    const uint32_t bytes = sim.programmed; /* before the reboot restarts the count */
    TEST_ASSERT_EQUAL_INT(1, reboot_and_check());
    return bytes;
}

static void sweep_program_cuts(void)
{
    const uint32_t total = save_bytes();
    TEST_ASSERT_EQUAL_UINT32(20u + ((store.length + 3u) & ~3u) + 8u, total);
    static const uint8_t torn[3] = {0x00u, 0x55u, 0xAAu};
    uint32_t a_count = 0u;
    for (uint32_t t = 0u; t < 3u; ++t) {
        for (uint32_t n = 0u; n < total; ++n) {
            memcpy(mem, start, sizeof mem);
            sim_flash_power_on(&sim);
            sim_flash_cut_program(&sim, n, torn[t]);
            TEST_ASSERT_NOT_EQUAL(PARAM_STORE_OK, param_store_save(&store, set_b, NULL, NULL));
            TEST_ASSERT_EQUAL_INT_MESSAGE(0, reboot_and_check(), "B before its commit");
            a_count++;
            recover();
        }
    }
    TEST_ASSERT_EQUAL_UINT32(3u * total, a_count);
    /* the last commit byte fully programmed, power lost right after: B */
    memcpy(mem, start, sizeof mem);
    sim_flash_power_on(&sim);
    sim_flash_cut_program(&sim, total - 1u, 0xFFu);
    TEST_ASSERT_NOT_EQUAL(PARAM_STORE_OK, param_store_save(&store, set_b, NULL, NULL));
    TEST_ASSERT_EQUAL_INT(1, reboot_and_check());
}

static void sweep_erase_cuts(void)
{
    uint32_t runs = 0u;
    for (uint32_t model = 0u; model < 2u; ++model) {
        for (uint32_t k = 0u; k <= SLOT; ++k) {
            memcpy(mem, start, sizeof mem);
            sim_flash_power_on(&sim);
            sim_flash_cut_erase(&sim, (sim_erase_model_t)model, k);
            TEST_ASSERT_EQUAL(PARAM_STORE_ERR_FLASH, param_store_save(&store, set_b, NULL, NULL));
            TEST_ASSERT_EQUAL_INT(0, reboot_and_check());
            recover();
            runs++;
        }
    }
    for (uint32_t seed = 1u; seed <= 300u; ++seed) {
        memcpy(mem, start, sizeof mem);
        sim_flash_power_on(&sim);
        sim_flash_cut_erase(&sim, SIM_ERASE_NOISE, seed);
        TEST_ASSERT_EQUAL(PARAM_STORE_ERR_FLASH, param_store_save(&store, set_b, NULL, NULL));
        TEST_ASSERT_EQUAL_INT(0, reboot_and_check());
        recover();
        runs++;
    }
    TEST_ASSERT_EQUAL_UINT32(2u * (SLOT + 1u) + 300u, runs);
}

static void test_cut_every_byte_len37(void)
{
    start_normal(37u);
    sweep_program_cuts();
}

static void test_cut_every_byte_len40(void)
{
    start_normal(40u);
    sweep_program_cuts();
}

static void test_cut_every_byte_len1(void)
{
    start_normal(1u);
    sweep_program_cuts();
}

static void test_cut_every_byte_across_the_wrap(void)
{
    start_wrap(37u);
    sweep_program_cuts();
}

static void test_cut_during_erase(void)
{
    start_normal(37u);
    sweep_erase_cuts();
}

static void test_cut_during_erase_across_the_wrap(void)
{
    start_wrap(40u);
    sweep_erase_cuts();
}

/* Cut after cut with no good save between: every one still gives A. */
static void test_repeated_cuts(void)
{
    start_normal(37u);
    const uint32_t total = save_bytes();
    memcpy(mem, start, sizeof mem);
    for (uint32_t n = 0u; n < total; n += 3u) {
        sim_flash_power_on(&sim);
        if ((n % 2u) == 0u) {
            sim_flash_cut_program(&sim, n, 0x55u);
        } else {
            sim_flash_cut_erase(&sim, SIM_ERASE_NOISE, n + 1u);
        }
        TEST_ASSERT_NOT_EQUAL(PARAM_STORE_OK, param_store_save(&store, set_b, NULL, NULL));
        TEST_ASSERT_EQUAL_INT(0, reboot_and_check());
    }
    recover();
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_cut_every_byte_len37);
    RUN_TEST(test_cut_every_byte_len40);
    RUN_TEST(test_cut_every_byte_len1);
    RUN_TEST(test_cut_every_byte_across_the_wrap);
    RUN_TEST(test_cut_during_erase);
    RUN_TEST(test_cut_during_erase_across_the_wrap);
    RUN_TEST(test_repeated_cuts);
    return UNITY_END();
}
