/*
 * test_param_store.c - the two-slot parameter store on the simulated NOR
 * flash: the record layout byte for byte, load's statuses, slot choice,
 * sequence wrap, 1000 saves, argument and flash failures. The power-cut
 * sweep is in test_param_store_power_cut.c.
 *
 * Worked record (param_store.h layout): schema 0x0102 version 3, sequence 1,
 * payload 01 02 03 04 05 (5 bytes, padded with 3 zeros):
 *   00: 48 54 50 53  magic "HTPS" = 0x53505448
 *   04: 01 00        format 1
 *   06: 02 01        schema id 0x0102
 *   08: 03 00        schema version 3
 *   10: 00 00        reserved
 *   12: 01 00 00 00  sequence 1
 *   16: 05 00 00 00  length 5
 *   20: 01 02 03 04 05 00 00 00
 *   28: 42 34 5B 73  CRC-32/ISO-HDLC of bytes 0..27 = 0x735B3442 (zlib.crc32)
 *   32: 43 4D 49 54  commit "CMIT" = 0x54494D43
 *   36: FF ...       erased
 */
#include "unity.h"

#include "crc32.h"
#include "sim_flash.h"

#include <string.h>

#define SLOT 256u

static uint8_t mem[2u * SLOT];
static sim_flash_t sim;
static param_flash_t flash;
static param_store_t store;

void setUp(void)
{
    sim_flash_init(&sim, mem, SLOT, 2u, PARAM_STORE_ALIGN);
    sim_flash_bind(&sim, &flash);
    store.flash = &flash;
    store.schema_id = 0x0102u;
    store.schema_version = 3u;
    store.length = 5u;
}

void tearDown(void)
{
    /* No test may make the store break NOR rules or the program unit. */
    TEST_ASSERT_EQUAL_UINT32(0u, sim.nor_violations);
    TEST_ASSERT_EQUAL_UINT32(0u, sim.align_violations);
    TEST_ASSERT_EQUAL_UINT32(0u, sim.range_violations);
}

static void put32(uint8_t *p, uint32_t v)
{
    for (uint32_t i = 0u; i < 4u; ++i) {
        p[i] = (uint8_t)((v >> (8u * i)) & 0xFFu);
    }
}

/* The test's own encoder of the documented layout, written straight into
 * slot's memory (commit 0: leave the commit word erased). */
static void craft(uint32_t slot, uint16_t schema, uint16_t version, uint32_t seq,
                  const uint8_t *payload, uint32_t len, int commit)
{
    uint8_t *r = &mem[slot * SLOT];
    memset(r, 0xFF, SLOT);
    const uint32_t padded = (len + 3u) & ~3u;
    put32(&r[0], 0x53505448u);
    r[4] = 1u;
    r[5] = 0u;
    r[6] = (uint8_t)(schema & 0xFFu);
    r[7] = (uint8_t)(schema >> 8);
    r[8] = (uint8_t)(version & 0xFFu);
    r[9] = (uint8_t)(version >> 8);
    r[10] = 0u;
    r[11] = 0u;
    put32(&r[12], seq);
    put32(&r[16], len);
    memset(&r[20], 0, padded);
    memcpy(&r[20], payload, len);
    put32(&r[20u + padded], crc32_iso_hdlc(0u, r, 20u + padded));
    if (commit) {
        put32(&r[24u + padded], 0x54494D43u);
    }
}

static const uint8_t P5[5] = {1u, 2u, 3u, 4u, 5u};

static void test_layout_byte_for_byte(void)
{
    uint8_t slot = 9u;
    uint32_t seq = 0u;
    TEST_ASSERT_EQUAL(PARAM_STORE_OK, param_store_save(&store, P5, &slot, &seq));
    TEST_ASSERT_EQUAL_UINT8(0u, slot);
    TEST_ASSERT_EQUAL_UINT32(1u, seq);
    const uint8_t expect[36] = {0x48, 0x54, 0x50, 0x53, 0x01, 0x00, 0x02, 0x01, 0x03,
                                0x00, 0x00, 0x00, 0x01, 0x00, 0x00, 0x00, 0x05, 0x00,
                                0x00, 0x00, 0x01, 0x02, 0x03, 0x04, 0x05, 0x00, 0x00,
                                0x00, 0x42, 0x34, 0x5B, 0x73, 0x43, 0x4D, 0x49, 0x54};
    TEST_ASSERT_EQUAL_HEX8_ARRAY(expect, mem, 36u);
    for (uint32_t i = 36u; i < 2u * SLOT; ++i) {
        TEST_ASSERT_EQUAL_HEX8(0xFFu, mem[i]);
    }
    /* The test's encoder makes the same bytes. */
    uint8_t copy[SLOT];
    memcpy(copy, mem, SLOT);
    craft(0u, 0x0102u, 3u, 1u, P5, 5u, 1);
    TEST_ASSERT_EQUAL_HEX8_ARRAY(copy, mem, SLOT);
}

static void test_blank_boots_on_defaults(void)
{
    uint8_t out[5] = {0xEEu, 0xEEu, 0xEEu, 0xEEu, 0xEEu};
    param_store_load_t r;
    TEST_ASSERT_EQUAL(PARAM_STORE_BLANK, param_store_load(&store, out, &r));
    TEST_ASSERT_EQUAL(PARAM_STORE_BLANK, r.status);
    TEST_ASSERT_EQUAL_UINT8(0u, r.loaded);
    TEST_ASSERT_EQUAL(PARAM_SLOT_BLANK, r.slots[0].state);
    TEST_ASSERT_EQUAL(PARAM_SLOT_BLANK, r.slots[1].state);
    TEST_ASSERT_EQUAL_HEX8(0xEEu, out[0]); /* not touched */
}

static void test_save_then_load(void)
{
    TEST_ASSERT_EQUAL(PARAM_STORE_OK, param_store_save(&store, P5, NULL, NULL));
    uint8_t out[5] = {0};
    param_store_load_t r;
    TEST_ASSERT_EQUAL(PARAM_STORE_OK, param_store_load(&store, out, &r));
    TEST_ASSERT_EQUAL_UINT8(1u, r.loaded);
    TEST_ASSERT_EQUAL_UINT8(0u, r.slot);
    TEST_ASSERT_EQUAL_UINT32(1u, r.sequence);
    TEST_ASSERT_EQUAL_HEX8_ARRAY(P5, out, 5u);
    TEST_ASSERT_EQUAL(PARAM_SLOT_VALID, r.slots[0].state);
    TEST_ASSERT_EQUAL(PARAM_SLOT_BLANK, r.slots[1].state);
    TEST_ASSERT_EQUAL_UINT32(5u, r.slots[0].length);
    TEST_ASSERT_EQUAL_HEX16(0x0102u, r.slots[0].schema_id);
    TEST_ASSERT_EQUAL_UINT16(3u, r.slots[0].schema_version);
}

static void test_corrupt_both_boots_on_defaults(void)
{
    craft(0u, 0x0102u, 3u, 1u, P5, 5u, 1);
    craft(1u, 0x0102u, 3u, 2u, P5, 5u, 1);
    mem[22] ^= 0x10u;       /* slot 0: a payload bit flipped, CRC fails */
    mem[SLOT + 3u] = 0x00u; /* slot 1: magic broken */
    uint8_t out[5];
    param_store_load_t r;
    TEST_ASSERT_EQUAL(PARAM_STORE_CORRUPT, param_store_load(&store, out, &r));
    TEST_ASSERT_EQUAL_UINT8(0u, r.loaded);
    TEST_ASSERT_EQUAL(PARAM_SLOT_CORRUPT, r.slots[0].state);
    TEST_ASSERT_EQUAL(PARAM_SLOT_CORRUPT, r.slots[1].state);
    /* one stray programmed byte in an otherwise erased slot is corrupt too */
    memset(mem, 0xFF, sizeof mem);
    mem[SLOT + SLOT - 1u] = 0xFEu;
    TEST_ASSERT_EQUAL(PARAM_STORE_CORRUPT, param_store_load(&store, out, &r));
    TEST_ASSERT_EQUAL(PARAM_SLOT_BLANK, r.slots[0].state);
    TEST_ASSERT_EQUAL(PARAM_SLOT_CORRUPT, r.slots[1].state);
    /* and the next save goes into slot 0 with sequence 1 */
    uint8_t slot = 9u;
    uint32_t seq = 0u;
    TEST_ASSERT_EQUAL(PARAM_STORE_OK, param_store_save(&store, P5, &slot, &seq));
    TEST_ASSERT_EQUAL_UINT8(0u, slot);
    TEST_ASSERT_EQUAL_UINT32(1u, seq);
}

static void test_one_corrupt_boots_on_the_other_and_says_so(void)
{
    const uint8_t old[5] = {9u, 8u, 7u, 6u, 5u};
    craft(0u, 0x0102u, 3u, 7u, old, 5u, 1);
    craft(1u, 0x0102u, 3u, 8u, P5, 5u, 1);
    mem[SLOT + 30u] ^= 0x01u; /* the newer one's CRC broken */
    uint8_t out[5];
    param_store_load_t r;
    TEST_ASSERT_EQUAL(PARAM_STORE_CORRUPT, param_store_load(&store, out, &r));
    TEST_ASSERT_EQUAL_UINT8(1u, r.loaded);
    TEST_ASSERT_EQUAL_UINT8(0u, r.slot);
    TEST_ASSERT_EQUAL_UINT32(7u, r.sequence);
    TEST_ASSERT_EQUAL_HEX8_ARRAY(old, out, 5u);
    /* the next save replaces the corrupt slot, not the good one */
    uint8_t slot = 9u;
    uint32_t seq = 0u;
    TEST_ASSERT_EQUAL(PARAM_STORE_OK, param_store_save(&store, P5, &slot, &seq));
    TEST_ASSERT_EQUAL_UINT8(1u, slot);
    TEST_ASSERT_EQUAL_UINT32(8u, seq);
    TEST_ASSERT_EQUAL(PARAM_STORE_OK, param_store_load(&store, out, &r));
}

static void test_commit_word_is_required(void)
{
    /* header, payload and a right CRC, but no commit word: a write that was
     * cut just before its end must not count even though its CRC holds */
    craft(1u, 0x0102u, 3u, 5u, P5, 5u, 0);
    uint8_t out[5];
    param_store_load_t r;
    TEST_ASSERT_EQUAL(PARAM_STORE_CORRUPT, param_store_load(&store, out, &r));
    TEST_ASSERT_EQUAL_UINT8(0u, r.loaded);
    craft(1u, 0x0102u, 3u, 5u, P5, 5u, 1); /* with it: valid */
    TEST_ASSERT_EQUAL(PARAM_STORE_OK, param_store_load(&store, out, &r));
    TEST_ASSERT_EQUAL_UINT8(1u, r.slot);
    /* a wrong commit value is not a commit */
    mem[SLOT + 32u] = 0x42u;
    TEST_ASSERT_EQUAL(PARAM_STORE_CORRUPT, param_store_load(&store, out, &r));
}

static void test_bad_header_fields(void)
{
    uint8_t out[5];
    param_store_load_t r;
    craft(0u, 0x0102u, 3u, 5u, P5, 5u, 1);
    mem[4] = 2u; /* another format */
    TEST_ASSERT_EQUAL(PARAM_STORE_CORRUPT, param_store_load(&store, out, &r));
    craft(0u, 0x0102u, 3u, 5u, P5, 5u, 1);
    put32(&mem[16], SLOT); /* a length past the slot: never read past it */
    TEST_ASSERT_EQUAL(PARAM_STORE_CORRUPT, param_store_load(&store, out, &r));
    put32(&mem[16], 0xFFFFFFF0u);
    TEST_ASSERT_EQUAL(PARAM_STORE_CORRUPT, param_store_load(&store, out, &r));
}

static void test_schema_mismatch_boots_on_defaults(void)
{
    uint8_t out[5] = {0xEEu, 0xEEu, 0xEEu, 0xEEu, 0xEEu};
    param_store_load_t r;
    craft(0u, 0x0102u, 2u, 4u, P5, 5u, 1); /* older version of the schema */
    TEST_ASSERT_EQUAL(PARAM_STORE_SCHEMA_MISMATCH, param_store_load(&store, out, &r));
    TEST_ASSERT_EQUAL_UINT8(0u, r.loaded);
    TEST_ASSERT_EQUAL_UINT8(0u, r.slot);
    TEST_ASSERT_EQUAL_UINT16(2u, r.slots[0].schema_version);
    craft(0u, 0x0999u, 3u, 4u, P5, 5u, 1); /* another schema */
    TEST_ASSERT_EQUAL(PARAM_STORE_SCHEMA_MISMATCH, param_store_load(&store, out, &r));
    TEST_ASSERT_EQUAL_HEX16(0x0999u, r.slots[0].schema_id);
    craft(0u, 0x0102u, 3u, 4u, P5, 4u, 1); /* another length */
    TEST_ASSERT_EQUAL(PARAM_STORE_SCHEMA_MISMATCH, param_store_load(&store, out, &r));
    TEST_ASSERT_EQUAL_UINT32(4u, r.slots[0].length);
    /* an older record of the right schema does not win over a newer other one */
    craft(1u, 0x0102u, 3u, 3u, P5, 5u, 1);
    TEST_ASSERT_EQUAL(PARAM_STORE_SCHEMA_MISMATCH, param_store_load(&store, out, &r));
    TEST_ASSERT_EQUAL_UINT8(0u, r.loaded);
    TEST_ASSERT_EQUAL_HEX8(0xEEu, out[0]);
    /* saving the new schema replaces the older slot, with the next sequence */
    uint8_t slot = 9u;
    uint32_t seq = 0u;
    TEST_ASSERT_EQUAL(PARAM_STORE_OK, param_store_save(&store, P5, &slot, &seq));
    TEST_ASSERT_EQUAL_UINT8(1u, slot);
    TEST_ASSERT_EQUAL_UINT32(5u, seq);
    TEST_ASSERT_EQUAL(PARAM_STORE_OK, param_store_load(&store, out, &r));
    TEST_ASSERT_EQUAL_HEX8_ARRAY(P5, out, 5u);
}

static void test_serial_number_order(void)
{
    TEST_ASSERT_EQUAL_INT(1, param_store_seq_newer(1u, 0u));
    TEST_ASSERT_EQUAL_INT(0, param_store_seq_newer(0u, 1u));
    TEST_ASSERT_EQUAL_INT(0, param_store_seq_newer(5u, 5u));
    TEST_ASSERT_EQUAL_INT(1, param_store_seq_newer(0u, 0xFFFFFFFFu)); /* the wrap */
    TEST_ASSERT_EQUAL_INT(0, param_store_seq_newer(0xFFFFFFFFu, 0u));
    TEST_ASSERT_EQUAL_INT(1, param_store_seq_newer(0x7FFFFFFFu, 0u)); /* furthest ahead */
    TEST_ASSERT_EQUAL_INT(0, param_store_seq_newer(0x80000000u, 0u)); /* unordered */
    TEST_ASSERT_EQUAL_INT(0, param_store_seq_newer(0u, 0x80000000u));
    TEST_ASSERT_EQUAL_INT(1, param_store_seq_newer(0x80000000u, 0x7FFFFFFFu));
}

static void test_sequence_wraps(void)
{
    const uint8_t old[5] = {9u, 9u, 9u, 9u, 9u};
    uint8_t out[5];
    param_store_load_t r;
    craft(1u, 0x0102u, 3u, 0xFFFFFFFFu, old, 5u, 1);
    craft(0u, 0x0102u, 3u, 0xFFFFFFFEu, P5, 5u, 1);
    TEST_ASSERT_EQUAL(PARAM_STORE_OK, param_store_load(&store, out, &r));
    TEST_ASSERT_EQUAL_UINT8(1u, r.slot);
    TEST_ASSERT_EQUAL_HEX32(0xFFFFFFFFu, r.sequence);
    uint8_t slot = 9u;
    uint32_t seq = 1u;
    TEST_ASSERT_EQUAL(PARAM_STORE_OK, param_store_save(&store, P5, &slot, &seq));
    TEST_ASSERT_EQUAL_UINT8(0u, slot);
    TEST_ASSERT_EQUAL_HEX32(0x00000000u, seq); /* 0xFFFFFFFF + 1 */
    TEST_ASSERT_EQUAL(PARAM_STORE_OK, param_store_load(&store, out, &r));
    TEST_ASSERT_EQUAL_UINT8(0u, r.slot); /* 0 is newer than 0xFFFFFFFF */
    TEST_ASSERT_EQUAL_HEX32(0u, r.sequence);
    TEST_ASSERT_EQUAL_HEX8_ARRAY(P5, out, 5u);
    TEST_ASSERT_EQUAL(PARAM_STORE_OK, param_store_save(&store, old, &slot, &seq));
    TEST_ASSERT_EQUAL_UINT8(1u, slot);
    TEST_ASSERT_EQUAL_HEX32(1u, seq);
}

static void test_thousand_saves_alternate(void)
{
    store.length = 37u; /* a tail of one byte and three of padding */
    uint8_t p[37];
    uint8_t out[37];
    param_store_load_t r;
    for (uint32_t i = 0u; i < 1000u; ++i) {
        for (uint32_t k = 0u; k < sizeof p; ++k) {
            p[k] = (uint8_t)((i * 7u + k) & 0xFFu);
        }
        uint8_t slot = 9u;
        uint32_t seq = 0u;
        TEST_ASSERT_EQUAL(PARAM_STORE_OK, param_store_save(&store, p, &slot, &seq));
        TEST_ASSERT_EQUAL_UINT8((uint8_t)(i % 2u), slot);
        TEST_ASSERT_EQUAL_UINT32(i + 1u, seq);
        TEST_ASSERT_EQUAL(PARAM_STORE_OK, param_store_load(&store, out, &r));
        TEST_ASSERT_EQUAL_UINT8(slot, r.slot);
        TEST_ASSERT_EQUAL_UINT32(i + 1u, r.sequence);
        TEST_ASSERT_EQUAL_HEX8_ARRAY(p, out, sizeof p);
        if (i > 0u) { /* the other slot keeps the previous record */
            TEST_ASSERT_EQUAL(PARAM_SLOT_VALID, r.slots[1u - slot].state);
            TEST_ASSERT_EQUAL_UINT32(i, r.slots[1u - slot].sequence);
        }
    }
    TEST_ASSERT_EQUAL_UINT32(1000u, sim.erases);
}

static void test_sizes(void)
{
    TEST_ASSERT_EQUAL_UINT32(0u, param_store_max_payload(27u));
    TEST_ASSERT_EQUAL_UINT32(0u, param_store_max_payload(28u));
    TEST_ASSERT_EQUAL_UINT32(228u, param_store_max_payload(256u));
    TEST_ASSERT_EQUAL_UINT32(16356u, param_store_max_payload(16384u));
    /* the largest payload fills the slot to the last byte */
    static uint8_t big[228];
    for (uint32_t k = 0u; k < sizeof big; ++k) {
        big[k] = (uint8_t)(k ^ 0x5Au);
    }
    store.length = 228u;
    TEST_ASSERT_EQUAL(PARAM_STORE_OK, param_store_save(&store, big, NULL, NULL));
    TEST_ASSERT_EQUAL_HEX8(0x43u, mem[SLOT - 4u]); /* the commit word ends the slot */
    static uint8_t out[228];
    param_store_load_t r;
    TEST_ASSERT_EQUAL(PARAM_STORE_OK, param_store_load(&store, out, &r));
    TEST_ASSERT_EQUAL_HEX8_ARRAY(big, out, sizeof big);
    store.length = 229u;
    TEST_ASSERT_EQUAL(PARAM_STORE_ERR_ARG, param_store_save(&store, big, NULL, NULL));
    TEST_ASSERT_EQUAL(PARAM_STORE_ERR_ARG, param_store_load(&store, out, &r));
    /* an empty payload is a record too */
    store.length = 0u;
    TEST_ASSERT_EQUAL(PARAM_STORE_OK, param_store_save(&store, NULL, NULL, NULL));
    TEST_ASSERT_EQUAL(PARAM_STORE_OK, param_store_load(&store, NULL, &r));
    TEST_ASSERT_EQUAL_UINT8(1u, r.loaded);
    TEST_ASSERT_EQUAL_UINT8(1u, r.slot);
}

static void test_bad_arguments(void)
{
    uint8_t out[5];
    param_store_load_t r;
    TEST_ASSERT_EQUAL(PARAM_STORE_ERR_ARG, param_store_load(NULL, out, &r));
    TEST_ASSERT_EQUAL(PARAM_STORE_ERR_ARG, r.status);
    TEST_ASSERT_EQUAL(PARAM_STORE_ERR_ARG, param_store_load(&store, out, NULL));
    TEST_ASSERT_EQUAL(PARAM_STORE_ERR_ARG, param_store_load(&store, NULL, &r));
    TEST_ASSERT_EQUAL(PARAM_STORE_ERR_ARG, param_store_save(NULL, P5, NULL, NULL));
    TEST_ASSERT_EQUAL(PARAM_STORE_ERR_ARG, param_store_save(&store, NULL, NULL, NULL));
    flash.slot_size = 254u; /* not a multiple of the program unit */
    TEST_ASSERT_EQUAL(PARAM_STORE_ERR_ARG, param_store_save(&store, P5, NULL, NULL));
    flash.slot_size = SLOT;
    flash.read = NULL;
    TEST_ASSERT_EQUAL(PARAM_STORE_ERR_ARG, param_store_load(&store, out, &r));
    TEST_ASSERT_EQUAL(PARAM_STORE_ERR_ARG, param_store_save(&store, P5, NULL, NULL));
    store.flash = NULL;
    TEST_ASSERT_EQUAL(PARAM_STORE_ERR_ARG, param_store_save(&store, P5, NULL, NULL));
    TEST_ASSERT_EQUAL_UINT32(0u, sim.erases);
    TEST_ASSERT_EQUAL_UINT32(0u, sim.program_calls);
}

/* A flash that fails on demand, over the sim. */
static int fail_erase;
static int fail_program_call; /* fail the Nth program call (1-based), 0: never */
static int flip_program;      /* program one bit wrong, silently */
static int program_calls;

static int bad_erase(void *ctx, uint32_t slot)
{
    if (fail_erase == 1) {
        return -7;
    }
    if (fail_erase == 2) {
        return 0; /* says done, erased nothing */
    }
    return sim_flash_erase(ctx, slot);
}

static int bad_program(void *ctx, uint32_t slot, uint32_t offset, const uint8_t *bytes, uint32_t n)
{
    ++program_calls;
    if (program_calls == fail_program_call) {
        return -7;
    }
    if (flip_program && offset == 0u && n == PARAM_STORE_HEADER) {
        uint8_t copy[PARAM_STORE_HEADER];
        memcpy(copy, bytes, n);
        copy[0] = (uint8_t)(copy[0] & 0xF7u); /* 'H' 0x48 programmed as 0x40 */
        return sim_flash_program(ctx, slot, offset, copy, n);
    }
    return sim_flash_program(ctx, slot, offset, bytes, n);
}

static void use_bad_flash(void)
{
    flash.erase = bad_erase;
    flash.program = bad_program;
    fail_erase = 0;
    fail_program_call = 0;
    flip_program = 0;
    program_calls = 0;
}

static void expect_still_first(void)
{
    uint8_t out[5];
    param_store_load_t r;
    const param_store_status_t st = param_store_load(&store, out, &r);
    TEST_ASSERT_TRUE(st == PARAM_STORE_OK || st == PARAM_STORE_CORRUPT);
    TEST_ASSERT_EQUAL_UINT8(1u, r.loaded);
    TEST_ASSERT_EQUAL_UINT8(0u, r.slot);
    TEST_ASSERT_EQUAL_UINT32(1u, r.sequence);
    TEST_ASSERT_EQUAL_HEX8_ARRAY(P5, out, 5u);
}

static void test_flash_failures_keep_the_good_record(void)
{
    const uint8_t other[5] = {5u, 5u, 5u, 5u, 5u};
    TEST_ASSERT_EQUAL(PARAM_STORE_OK, param_store_save(&store, P5, NULL, NULL));
    memset(&mem[SLOT], 0x00, SLOT); /* slot 1: old junk to be erased */
    use_bad_flash();
    fail_erase = 1;
    TEST_ASSERT_EQUAL(PARAM_STORE_ERR_FLASH, param_store_save(&store, other, NULL, NULL));
    expect_still_first();
    fail_erase = 2; /* an erase that did not erase: the blank check catches it */
    TEST_ASSERT_EQUAL(PARAM_STORE_ERR_VERIFY, param_store_save(&store, other, NULL, NULL));
    expect_still_first();
    fail_erase = 0;
    for (int call = 1; call <= 4; ++call) { /* header, body, tail, crc */
        program_calls = 0;
        fail_program_call = call;
        TEST_ASSERT_EQUAL(PARAM_STORE_ERR_FLASH, param_store_save(&store, other, NULL, NULL));
        expect_still_first();
    }
    program_calls = 0;
    fail_program_call = 5; /* the commit word */
    TEST_ASSERT_EQUAL(PARAM_STORE_ERR_FLASH, param_store_save(&store, other, NULL, NULL));
    expect_still_first();
    fail_program_call = 0;
    flip_program = 1; /* a bit programmed wrong: the read-back catches it, no commit */
    store.length = 5u;
    TEST_ASSERT_EQUAL(PARAM_STORE_ERR_VERIFY, param_store_save(&store, other, NULL, NULL));
    TEST_ASSERT_EQUAL_HEX32(
        0xFFFFFFFFu, (uint32_t)mem[SLOT + 32u] | ((uint32_t)mem[SLOT + 33u] << 8) |
                         ((uint32_t)mem[SLOT + 34u] << 16) | ((uint32_t)mem[SLOT + 35u] << 24));
    expect_still_first();
    flip_program = 0;
    TEST_ASSERT_EQUAL(PARAM_STORE_OK, param_store_save(&store, other, NULL, NULL));
}

static int fail_read_slot = -1;
static int bad_read(void *ctx, uint32_t slot, uint32_t offset, uint8_t *bytes, uint32_t n)
{
    if ((int)slot == fail_read_slot) {
        return -7;
    }
    return sim_flash_read(ctx, slot, offset, bytes, n);
}

static void test_read_failure_is_corrupt(void)
{
    TEST_ASSERT_EQUAL(PARAM_STORE_OK, param_store_save(&store, P5, NULL, NULL));
    TEST_ASSERT_EQUAL(PARAM_STORE_OK, param_store_save(&store, P5, NULL, NULL));
    flash.read = bad_read;
    fail_read_slot = 1;
    uint8_t out[5];
    param_store_load_t r;
    TEST_ASSERT_EQUAL(PARAM_STORE_CORRUPT, param_store_load(&store, out, &r));
    TEST_ASSERT_EQUAL_UINT8(1u, r.loaded);
    TEST_ASSERT_EQUAL_UINT8(0u, r.slot);
    TEST_ASSERT_EQUAL(PARAM_SLOT_CORRUPT, r.slots[1].state);
    fail_read_slot = -1;
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_layout_byte_for_byte);
    RUN_TEST(test_blank_boots_on_defaults);
    RUN_TEST(test_save_then_load);
    RUN_TEST(test_corrupt_both_boots_on_defaults);
    RUN_TEST(test_one_corrupt_boots_on_the_other_and_says_so);
    RUN_TEST(test_commit_word_is_required);
    RUN_TEST(test_bad_header_fields);
    RUN_TEST(test_schema_mismatch_boots_on_defaults);
    RUN_TEST(test_serial_number_order);
    RUN_TEST(test_sequence_wraps);
    RUN_TEST(test_thousand_saves_alternate);
    RUN_TEST(test_sizes);
    RUN_TEST(test_bad_arguments);
    RUN_TEST(test_flash_failures_keep_the_good_record);
    RUN_TEST(test_read_failure_is_corrupt);
    return UNITY_END();
}
