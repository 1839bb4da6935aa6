/*
 * test_stm32f4_usart.c - the USART driver on a fake register block.
 *
 * Expected values, worked from RM0090 (section 30.6):
 *   CR1 = UE (bit 13) | TE (bit 3) | RE (bit 2) = 0x200C; CR2 = CR3 = 0 (8N1)
 *   BRR = round(f_pclk / baud) with 16x oversampling:
 *         16 MHz, 115200 baud: 138.9 -> 139 = 0x8B (mantissa 8, fraction 11)
 *         84 MHz, 921600 baud: 91.1  -> 91  = 0x5B
 * A fake block keeps what was written and never changes a flag by itself, so
 * each test sets SR as the hardware would.
 */
#include "unity.h"

#include "stm32f4_usart.h"

#include <string.h>

static stm32_usart_regs_t regs;
static stm32_usart_t usart;

void setUp(void)
{
    memset((void *)&regs, 0, sizeof regs);
    memset(&usart, 0, sizeof usart);
}

void tearDown(void) {}

static void test_init_115200_from_hsi(void)
{
    regs.CR2 = 0x3000u; /* two stop bits left over: init writes one */
    regs.CR3 = 0x0300u; /* RTS/CTS left over: init clears it */
    TEST_ASSERT_EQUAL(STM32_USART_OK, stm32_usart_init(&usart, &regs, 16000000u, 115200u));
    TEST_ASSERT_EQUAL_HEX32(0x8Bu, regs.BRR);
    TEST_ASSERT_EQUAL_HEX32(0x200Cu, regs.CR1);
    TEST_ASSERT_EQUAL_HEX32(0x0u, regs.CR2);
    TEST_ASSERT_EQUAL_HEX32(0x0u, regs.CR3);
    TEST_ASSERT_EQUAL_UINT8(1u, usart.ready);
}

static void test_init_921600_from_84mhz(void)
{
    TEST_ASSERT_EQUAL(STM32_USART_OK, stm32_usart_init(&usart, &regs, 84000000u, 921600u));
    TEST_ASSERT_EQUAL_HEX32(0x5Bu, regs.BRR);
}

static void test_init_refuses_without_writing(void)
{
    regs.CR1 = 0x1234u;
    TEST_ASSERT_EQUAL(STM32_USART_ERR_NULL, stm32_usart_init(NULL, &regs, 16000000u, 115200u));
    TEST_ASSERT_EQUAL(STM32_USART_ERR_NULL, stm32_usart_init(&usart, NULL, 16000000u, 115200u));
    TEST_ASSERT_EQUAL(STM32_USART_ERR_RANGE, stm32_usart_init(&usart, &regs, 16000000u, 1199u));
    TEST_ASSERT_EQUAL(STM32_USART_ERR_RANGE, stm32_usart_init(&usart, &regs, 16000000u, 4000001u));
    /* BRR below 16 (USARTDIV < 1): 16 MHz / 2 Mbaud = 8 */
    TEST_ASSERT_EQUAL(STM32_USART_ERR_RANGE, stm32_usart_init(&usart, &regs, 16000000u, 2000000u));
    /* BRR over 16 bits: 84 MHz / 1200 baud = 70000 */
    TEST_ASSERT_EQUAL(STM32_USART_ERR_RANGE, stm32_usart_init(&usart, &regs, 84000000u, 1200u));
    TEST_ASSERT_EQUAL_HEX32(0x1234u, regs.CR1);
    TEST_ASSERT_EQUAL_HEX32(0x0u, regs.BRR);
    TEST_ASSERT_EQUAL_UINT8(0u, usart.ready);
    /* edges that fit: BRR = 16 and BRR = 0xFFFF */
    TEST_ASSERT_EQUAL(STM32_USART_OK, stm32_usart_init(&usart, &regs, 16000000u, 1000000u));
    TEST_ASSERT_EQUAL_HEX32(16u, regs.BRR);
    TEST_ASSERT_EQUAL(STM32_USART_OK, stm32_usart_init(&usart, &regs, 0xFFFFu * 1200u, 1200u));
    TEST_ASSERT_EQUAL_HEX32(0xFFFFu, regs.BRR);
}

static void test_read(void)
{
    uint8_t b = 0;
    TEST_ASSERT_EQUAL_INT(0, stm32_usart_read(&usart, &b)); /* not initialised */
    TEST_ASSERT_EQUAL(STM32_USART_OK, stm32_usart_init(&usart, &regs, 16000000u, 115200u));
    regs.SR = USART_SR_TXE | USART_SR_TC; /* idle: nothing received */
    regs.DR = 0x41u;
    TEST_ASSERT_EQUAL_INT(0, stm32_usart_read(&usart, &b));
    TEST_ASSERT_EQUAL_UINT8(0u, b);
    regs.SR = USART_SR_RXNE | USART_SR_TXE;
    regs.DR = 0x1A5u; /* a ninth bit would be dropped */
    TEST_ASSERT_EQUAL_INT(1, stm32_usart_read(&usart, &b));
    TEST_ASSERT_EQUAL_HEX8(0xA5u, b);
    TEST_ASSERT_EQUAL_UINT16(0u, usart.overrun);
    TEST_ASSERT_EQUAL_INT(0, stm32_usart_read(NULL, &b));
    TEST_ASSERT_EQUAL_INT(0, stm32_usart_read(&usart, NULL));
}

static void test_read_counts_errors(void)
{
    uint8_t b = 0;
    TEST_ASSERT_EQUAL(STM32_USART_OK, stm32_usart_init(&usart, &regs, 16000000u, 115200u));
    regs.SR = USART_SR_ORE; /* overrun without RXNE still leaves a byte in DR */
    regs.DR = 0x5Au;
    TEST_ASSERT_EQUAL_INT(1, stm32_usart_read(&usart, &b));
    TEST_ASSERT_EQUAL_HEX8(0x5Au, b);
    regs.SR = USART_SR_RXNE | USART_SR_FE | USART_SR_NF | USART_SR_PE;
    TEST_ASSERT_EQUAL_INT(1, stm32_usart_read(&usart, &b));
    TEST_ASSERT_EQUAL_UINT16(1u, usart.overrun);
    TEST_ASSERT_EQUAL_UINT16(1u, usart.framing);
    TEST_ASSERT_EQUAL_UINT16(1u, usart.noise);
    TEST_ASSERT_EQUAL_UINT16(1u, usart.parity);
    usart.framing = UINT16_MAX; /* saturates */
    TEST_ASSERT_EQUAL_INT(1, stm32_usart_read(&usart, &b));
    TEST_ASSERT_EQUAL_UINT16(UINT16_MAX, usart.framing);
}

static void test_write(void)
{
    const uint8_t msg[3] = {0xA5u, 0x5Au, 0x07u};
    TEST_ASSERT_EQUAL_UINT64(0u, (uint64_t)stm32_usart_write(&usart, msg, 3u, 10u));
    TEST_ASSERT_EQUAL(STM32_USART_OK, stm32_usart_init(&usart, &regs, 16000000u, 115200u));
    regs.SR = USART_SR_TXE;
    TEST_ASSERT_EQUAL_UINT64(3u, (uint64_t)stm32_usart_write(&usart, msg, 3u, 10u));
    TEST_ASSERT_EQUAL_HEX32(0x07u, regs.DR); /* the fake keeps the last byte */
    TEST_ASSERT_EQUAL_UINT16(0u, usart.tx_timeouts);
    TEST_ASSERT_EQUAL_UINT64(0u, (uint64_t)stm32_usart_write(&usart, NULL, 3u, 10u));
    TEST_ASSERT_EQUAL_UINT64(0u, (uint64_t)stm32_usart_write(&usart, msg, 0u, 10u));
}

static void test_write_times_out(void)
{
    const uint8_t msg[2] = {1u, 2u};
    TEST_ASSERT_EQUAL(STM32_USART_OK, stm32_usart_init(&usart, &regs, 16000000u, 115200u));
    regs.SR = 0u; /* TXE never comes */
    regs.DR = 0xEEu;
    TEST_ASSERT_EQUAL_UINT64(0u, (uint64_t)stm32_usart_write(&usart, msg, 2u, 1000u));
    TEST_ASSERT_EQUAL_HEX32(0xEEu, regs.DR); /* nothing written */
    TEST_ASSERT_EQUAL_UINT16(1u, usart.tx_timeouts);
    TEST_ASSERT_EQUAL_UINT64(0u, (uint64_t)stm32_usart_write(&usart, msg, 2u, 0u));
    TEST_ASSERT_EQUAL_UINT16(2u, usart.tx_timeouts);
}

static void test_rx_irq_enable(void)
{
    stm32_usart_enable_rx_irq(&usart); /* not initialised: nothing */
    TEST_ASSERT_EQUAL_HEX32(0x0u, regs.CR1);
    TEST_ASSERT_EQUAL(STM32_USART_OK, stm32_usart_init(&usart, &regs, 16000000u, 115200u));
    stm32_usart_enable_rx_irq(&usart);
    TEST_ASSERT_EQUAL_HEX32(0x202Cu, regs.CR1); /* + RXNEIE (bit 5) */
    stm32_usart_enable_rx_irq(NULL);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_init_115200_from_hsi);
    RUN_TEST(test_init_921600_from_84mhz);
    RUN_TEST(test_init_refuses_without_writing);
    RUN_TEST(test_read);
    RUN_TEST(test_read_counts_errors);
    RUN_TEST(test_write);
    RUN_TEST(test_write_times_out);
    RUN_TEST(test_rx_irq_enable);
    return UNITY_END();
}
