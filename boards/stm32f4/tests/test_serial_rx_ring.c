/*
 * test_serial_rx_ring.c - the interrupt-to-tick byte ring, and its USART
 * interrupt handler on a fake register block.
 *
 * Worked values:
 *   size 8: mask 7; byte number k (counting from 0) lives in slot k & 7.
 *   After start bytes were stored and taken, a full ring holds bytes
 *   start .. start + 7 in slots start & 7, (start + 1) & 7, ...; a ninth
 *   byte is dropped (dropped_full 1) and the first one is still in its slot.
 *   Free-running counts: head = tail = 0xFFFFFFFC, 8 bytes stored: head =
 *   0x00000004, head - tail = 8 (mod 2^32).
 *   USART (RM0090 section 30.6.1): SR.PE bit 0, FE bit 1, NF bit 2, ORE bit
 *   3, RXNE bit 5; with 8E2 the DR's bit 8 is the parity bit and is dropped.
 */
#include "unity.h"

#include "serial_rx_ring.h"

#include <string.h>

static stm32_usart_regs_t regs;
static stm32_usart_t usart;
static serial_rx_ring_t ring;
static volatile uint8_t storage[64];

void setUp(void)
{
    memset((void *)&regs, 0, sizeof regs);
    memset(&usart, 0, sizeof usart);
    memset(&ring, 0, sizeof ring);
    for (size_t i = 0; i < sizeof storage; ++i) {
        storage[i] = 0xEEu;
    }
}

void tearDown(void) {}

static void test_init_sizes(void)
{
    TEST_ASSERT_EQUAL(SERIAL_RX_RING_ERR_NULL, serial_rx_ring_init(NULL, storage, 8u));
    TEST_ASSERT_EQUAL(SERIAL_RX_RING_ERR_NULL, serial_rx_ring_init(&ring, NULL, 8u));
    const uint32_t bad[] = {0u, 1u, 3u, 6u, 12u, 0x10000u, 0xFFFFFFFFu, 0x80000000u};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; ++i) {
        ring.mask = 0x55u;
        TEST_ASSERT_EQUAL(SERIAL_RX_RING_ERR_SIZE, serial_rx_ring_init(&ring, storage, bad[i]));
        TEST_ASSERT_EQUAL_HEX32(0x55u, ring.mask); /* nothing written */
    }
    TEST_ASSERT_EQUAL(SERIAL_RX_RING_OK, serial_rx_ring_init(&ring, storage, 2u));
    TEST_ASSERT_EQUAL_HEX32(1u, ring.mask);
    TEST_ASSERT_EQUAL(SERIAL_RX_RING_OK, serial_rx_ring_init(&ring, storage, 0x8000u));
    TEST_ASSERT_EQUAL_HEX32(0x7FFFu, ring.mask);
    TEST_ASSERT_EQUAL_UINT32(0u, serial_rx_ring_count(&ring));
}

static void test_put_read_in_order(void)
{
    uint8_t out[8] = {0};
    TEST_ASSERT_EQUAL(SERIAL_RX_RING_OK, serial_rx_ring_init(&ring, storage, 8u));
    TEST_ASSERT_EQUAL_UINT64(0u, (uint64_t)serial_rx_ring_read(&ring, out, sizeof out));
    TEST_ASSERT_EQUAL_INT(1, serial_rx_ring_put(&ring, 0x11u));
    TEST_ASSERT_EQUAL_INT(1, serial_rx_ring_put(&ring, 0x22u));
    TEST_ASSERT_EQUAL_INT(1, serial_rx_ring_put(&ring, 0x33u));
    TEST_ASSERT_EQUAL_UINT32(3u, serial_rx_ring_count(&ring));
    TEST_ASSERT_EQUAL_UINT64(2u, (uint64_t)serial_rx_ring_read(&ring, out, 2u)); /* max 2 */
    TEST_ASSERT_EQUAL_HEX8(0x11u, out[0]);
    TEST_ASSERT_EQUAL_HEX8(0x22u, out[1]);
    TEST_ASSERT_EQUAL_UINT32(1u, serial_rx_ring_count(&ring));
    TEST_ASSERT_EQUAL_UINT64(1u, (uint64_t)serial_rx_ring_read(&ring, out, sizeof out));
    TEST_ASSERT_EQUAL_HEX8(0x33u, out[0]);
    TEST_ASSERT_EQUAL_UINT64(0u, (uint64_t)serial_rx_ring_read(&ring, out, 0u));
    TEST_ASSERT_EQUAL_UINT64(0u, (uint64_t)serial_rx_ring_read(&ring, NULL, 4u));
    TEST_ASSERT_EQUAL_UINT64(0u, (uint64_t)serial_rx_ring_read(NULL, out, 4u));
    TEST_ASSERT_EQUAL_INT(0, serial_rx_ring_put(NULL, 1u));
    TEST_ASSERT_EQUAL_UINT32(0u, serial_rx_ring_count(NULL));
}

/* For every starting slot of rings of 2..32 bytes: fill completely, one more
 * byte is dropped without overwriting, then everything comes back in order,
 * read in chunks of every size. */
static void test_wrap_at_every_index(void)
{
    for (uint32_t size = 2u; size <= 32u; size *= 2u) {
        for (uint32_t start = 0u; start < size; ++start) {
            for (size_t chunk = 1u; chunk <= size; ++chunk) {
                uint8_t out[32];
                TEST_ASSERT_EQUAL(SERIAL_RX_RING_OK, serial_rx_ring_init(&ring, storage, size));
                for (uint32_t k = 0; k < start; ++k) { /* move head and tail to start */
                    TEST_ASSERT_EQUAL_INT(1, serial_rx_ring_put(&ring, 0xAAu));
                    TEST_ASSERT_EQUAL_UINT64(1u, (uint64_t)serial_rx_ring_read(&ring, out, 1u));
                }
                for (uint32_t k = 0; k < size; ++k) {
                    TEST_ASSERT_EQUAL_INT(1, serial_rx_ring_put(&ring, (uint8_t)(k + 1u)));
                }
                TEST_ASSERT_EQUAL_UINT32(size, serial_rx_ring_count(&ring));
                TEST_ASSERT_EQUAL_INT(0, serial_rx_ring_put(&ring, 0xFFu)); /* full */
                TEST_ASSERT_EQUAL_UINT32(1u, ring.dropped_full);
                TEST_ASSERT_EQUAL_HEX8(1u, storage[start & (size - 1u)]); /* not overwritten */
                size_t got = 0u;
                while (got < size) {
                    const size_t n = serial_rx_ring_read(&ring, &out[got], chunk);
                    TEST_ASSERT_TRUE(n > 0u && n <= chunk);
                    got += n;
                }
                TEST_ASSERT_EQUAL_UINT64(size, (uint64_t)got);
                for (uint32_t k = 0; k < size; ++k) {
                    TEST_ASSERT_EQUAL_HEX8((uint8_t)(k + 1u), out[k]);
                }
                TEST_ASSERT_EQUAL_UINT32(0u, serial_rx_ring_count(&ring));
            }
        }
    }
}

/* The free-running counts pass 2^32 without a hiccup. */
static void test_counts_wrap_2_32(void)
{
    uint8_t out[8];
    TEST_ASSERT_EQUAL(SERIAL_RX_RING_OK, serial_rx_ring_init(&ring, storage, 8u));
    ring.head = 0xFFFFFFFCu;
    ring.tail = 0xFFFFFFFCu;
    for (uint8_t k = 0; k < 8u; ++k) {
        TEST_ASSERT_EQUAL_INT(1, serial_rx_ring_put(&ring, (uint8_t)(0x40u + k)));
    }
    TEST_ASSERT_EQUAL_HEX32(0x00000004u, ring.head);
    TEST_ASSERT_EQUAL_UINT32(8u, serial_rx_ring_count(&ring));
    TEST_ASSERT_EQUAL_INT(0, serial_rx_ring_put(&ring, 0x99u));
    TEST_ASSERT_EQUAL_UINT64(8u, (uint64_t)serial_rx_ring_read(&ring, out, sizeof out));
    for (uint8_t k = 0; k < 8u; ++k) {
        TEST_ASSERT_EQUAL_HEX8((uint8_t)(0x40u + k), out[k]);
    }
    TEST_ASSERT_EQUAL_HEX32(0x00000004u, ring.tail);
}

static void test_overflow_drops_newest(void)
{
    uint8_t out[16];
    TEST_ASSERT_EQUAL(SERIAL_RX_RING_OK, serial_rx_ring_init(&ring, storage, 8u));
    for (uint8_t k = 0; k < 13u; ++k) {
        (void)serial_rx_ring_put(&ring, k);
    }
    TEST_ASSERT_EQUAL_UINT32(5u, ring.dropped_full);
    TEST_ASSERT_EQUAL_UINT64(3u, (uint64_t)serial_rx_ring_read(&ring, out, 3u));
    TEST_ASSERT_EQUAL_HEX8(0u, out[0]);
    TEST_ASSERT_EQUAL_HEX8(2u, out[2]);
    for (uint8_t k = 20; k < 24u; ++k) { /* room for 3: the 4th is dropped */
        (void)serial_rx_ring_put(&ring, k);
    }
    TEST_ASSERT_EQUAL_UINT32(6u, ring.dropped_full);
    TEST_ASSERT_EQUAL_UINT64(8u, (uint64_t)serial_rx_ring_read(&ring, out, sizeof out));
    const uint8_t want[8] = {3u, 4u, 5u, 6u, 7u, 20u, 21u, 22u};
    TEST_ASSERT_EQUAL_HEX8_ARRAY(want, out, 8);
    ring.dropped_full = UINT32_MAX - 1u; /* saturates */
    for (uint8_t k = 0; k < 12u; ++k) {
        (void)serial_rx_ring_put(&ring, k);
    }
    TEST_ASSERT_EQUAL_UINT32(UINT32_MAX, ring.dropped_full);
}

/* The interrupt handler and the tick, interleaved at random (as preemption
 * would place them): every byte taken is the next byte stored, in order;
 * bytes are dropped only when the ring was full. */
static void test_random_interleaving(void)
{
    uint32_t lcg = 12345u;
    uint8_t next_put = 0u;
    uint8_t next_get = 0u;
    uint32_t expect_dropped = 0u;
    TEST_ASSERT_EQUAL(SERIAL_RX_RING_OK, serial_rx_ring_init(&ring, storage, 16u));
    for (uint32_t step = 0; step < 200000u; ++step) {
        lcg = lcg * 1664525u + 1013904223u;
        const uint32_t op = (lcg >> 24) % 8u;
        if (op < 5u) {
            const uint32_t before = serial_rx_ring_count(&ring);
            const int stored = serial_rx_ring_put(&ring, next_put);
            TEST_ASSERT_EQUAL_INT(before < 16u ? 1 : 0, stored);
            if (stored) {
                next_put++;
            } else {
                expect_dropped++;
            }
        } else {
            uint8_t out[16];
            const size_t max = (size_t)((lcg >> 8) % 17u);
            const size_t n = serial_rx_ring_read(&ring, out, max);
            for (size_t i = 0; i < n; ++i) {
                TEST_ASSERT_EQUAL_HEX8(next_get, out[i]);
                next_get++;
            }
        }
    }
    TEST_ASSERT_TRUE(expect_dropped > 0u); /* the mix of operations did fill it */
    TEST_ASSERT_EQUAL_UINT32(expect_dropped, ring.dropped_full);
}

static void test_isr_moves_bytes(void)
{
    uint8_t out[8];
    TEST_ASSERT_EQUAL(SERIAL_RX_RING_OK, serial_rx_ring_init(&ring, storage, 8u));
    TEST_ASSERT_EQUAL(STM32_USART_OK,
                      stm32_usart_init_format(&usart, &regs, 42000000u, 100000u, STM32_USART_8E2));
    regs.SR = USART_SR_TXE; /* nothing received */
    TEST_ASSERT_EQUAL_INT(0, serial_rx_ring_isr(&usart, &ring));
    TEST_ASSERT_EQUAL_UINT32(0u, serial_rx_ring_count(&ring));
    regs.SR = USART_SR_RXNE;
    regs.DR = 0x10Fu; /* 0x0F, parity bit 1 */
    TEST_ASSERT_EQUAL_INT(1, serial_rx_ring_isr(&usart, &ring));
    regs.DR = 0x0A5u;
    regs.SR = USART_SR_RXNE | USART_SR_NF; /* noise: kept, counted */
    TEST_ASSERT_EQUAL_INT(1, serial_rx_ring_isr(&usart, &ring));
    regs.DR = 0x033u;
    regs.SR = USART_SR_ORE | USART_SR_RXNE; /* overrun: DR's byte is intact */
    TEST_ASSERT_EQUAL_INT(1, serial_rx_ring_isr(&usart, &ring));
    regs.DR = 0x044u;
    regs.SR = USART_SR_RXNE | USART_SR_PE; /* parity error: dropped */
    TEST_ASSERT_EQUAL_INT(1, serial_rx_ring_isr(&usart, &ring));
    regs.SR = USART_SR_RXNE | USART_SR_FE; /* framing error: dropped */
    TEST_ASSERT_EQUAL_INT(1, serial_rx_ring_isr(&usart, &ring));
    TEST_ASSERT_EQUAL_UINT64(3u, (uint64_t)serial_rx_ring_read(&ring, out, sizeof out));
    TEST_ASSERT_EQUAL_HEX8(0x0Fu, out[0]);
    TEST_ASSERT_EQUAL_HEX8(0xA5u, out[1]);
    TEST_ASSERT_EQUAL_HEX8(0x33u, out[2]);
    TEST_ASSERT_EQUAL_UINT32(2u, ring.dropped_error);
    TEST_ASSERT_EQUAL_UINT16(1u, usart.noise);
    TEST_ASSERT_EQUAL_UINT16(1u, usart.overrun);
    TEST_ASSERT_EQUAL_UINT16(1u, usart.parity);
    TEST_ASSERT_EQUAL_UINT16(1u, usart.framing);
    /* a full ring: the handler still reads DR (the line must fall), drops */
    regs.SR = USART_SR_RXNE;
    for (int k = 0; k < 10; ++k) {
        TEST_ASSERT_EQUAL_INT(1, serial_rx_ring_isr(&usart, &ring));
    }
    TEST_ASSERT_EQUAL_UINT32(8u, serial_rx_ring_count(&ring));
    TEST_ASSERT_EQUAL_UINT32(2u, ring.dropped_full);
    /* no ring: the byte is still read; no USART: nothing */
    TEST_ASSERT_EQUAL_INT(1, serial_rx_ring_isr(&usart, NULL));
    TEST_ASSERT_EQUAL_INT(0, serial_rx_ring_isr(NULL, &ring));
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_init_sizes);
    RUN_TEST(test_put_read_in_order);
    RUN_TEST(test_wrap_at_every_index);
    RUN_TEST(test_counts_wrap_2_32);
    RUN_TEST(test_overflow_drops_newest);
    RUN_TEST(test_random_interleaving);
    RUN_TEST(test_isr_moves_bytes);
    return UNITY_END();
}
