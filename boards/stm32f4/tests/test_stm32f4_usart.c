/*
 * test_stm32f4_usart.c - the USART driver on a fake register block.
 *
 * Expected values, worked from RM0090 (section 30.6):
 *   CR1 = UE (bit 13) | TE (bit 3) | RE (bit 2) = 0x200C; CR2 = CR3 = 0 (8N1)
 *   BRR = round(f_pclk / baud) with 16x oversampling:
 *         16 MHz, 115200 baud: 138.9 -> 139 = 0x8B (mantissa 8, fraction 11)
 *         84 MHz, 921600 baud: 91.1  -> 91  = 0x5B
 *   8E2 (SBUS; section 30.3.2 table 137, 30.6.4 CR1, 30.6.5 CR2):
 *         CR1 = UE | M (bit 12) | PCE (bit 10) | TE | RE, PS (bit 9) = 0
 *             = 0x2000 + 0x1000 + 0x0400 + 0x8 + 0x4 = 0x340C
 *         CR2 = STOP[13:12] = 10 (two stop bits) = 0x2000
 *   BRR and the real rate f_pclk / BRR (section 30.3.4: baud = f_pclk /
 *   (16 USARTDIV), BRR = USARTDIV * 16), error = (f_pclk / BRR - baud) / baud:
 *     CRSF 420000, PCLK2 84 MHz: 200 = 0xC8 (USARTDIV 12.5)      0 ppm
 *     CRSF 420000, PCLK1 42 MHz: 100 = 0x64 (USARTDIV 6.25)      0 ppm
 *     CRSF 420000, HSI 16 MHz:   38.10 -> 38 = 0x26: 421052.6 baud, +2506 ppm
 *     SBUS 100000, PCLK1 42 MHz: 420 = 0x1A4 (USARTDIV 26.25)    0 ppm
 *     SBUS 100000, PCLK2 84 MHz: 840 = 0x348 (USARTDIV 52.5)     0 ppm
 *     115200, 16 MHz: 139: 16e6 - 139 * 115200 = -12800; / 16012800 = -799 ppm
 *     115200, 84 MHz: 729.17 -> 729: +19200 / 83980800 = +228.6 -> +229 ppm
 *     115200, 42 MHz: 364.58 -> 365: -48000 / 42048000 = -1141.6 -> -1142 ppm
 *   All well inside the receiver's tolerance with 16x oversampling (RM0090
 *   section 30.3.5, about 3.75 % for 8-bit words with DIV_Fraction 0).
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

static void test_init_8e2_sbus_from_pclk1(void)
{
    regs.CR2 = 0x1000u; /* half a stop bit left over */
    regs.CR3 = 0x0300u;
    TEST_ASSERT_EQUAL(STM32_USART_OK,
                      stm32_usart_init_format(&usart, &regs, 42000000u, 100000u, STM32_USART_8E2));
    TEST_ASSERT_EQUAL_HEX32(0x1A4u, regs.BRR);
    TEST_ASSERT_EQUAL_HEX32(0x340Cu, regs.CR1);
    TEST_ASSERT_EQUAL_HEX32(0x2000u, regs.CR2);
    TEST_ASSERT_EQUAL_HEX32(0x0u, regs.CR3);
    TEST_ASSERT_EQUAL_UINT8(1u, usart.ready);
    /* even parity: PS clear */
    TEST_ASSERT_EQUAL_HEX32(0u, regs.CR1 & USART_CR1_PS);
    TEST_ASSERT_EQUAL(STM32_USART_OK,
                      stm32_usart_init_format(&usart, &regs, 84000000u, 100000u, STM32_USART_8E2));
    TEST_ASSERT_EQUAL_HEX32(0x348u, regs.BRR);
    /* back to 8N1 on the same block: M, PCE and STOP cleared */
    TEST_ASSERT_EQUAL(STM32_USART_OK,
                      stm32_usart_init_format(&usart, &regs, 84000000u, 420000u, STM32_USART_8N1));
    TEST_ASSERT_EQUAL_HEX32(0x200Cu, regs.CR1);
    TEST_ASSERT_EQUAL_HEX32(0x0u, regs.CR2);
}

static void test_init_420000_crsf(void)
{
    TEST_ASSERT_EQUAL(STM32_USART_OK, stm32_usart_init(&usart, &regs, 84000000u, 420000u));
    TEST_ASSERT_EQUAL_HEX32(0xC8u, regs.BRR);
    TEST_ASSERT_EQUAL_HEX32(0x200Cu, regs.CR1);
    TEST_ASSERT_EQUAL(STM32_USART_OK, stm32_usart_init(&usart, &regs, 42000000u, 420000u));
    TEST_ASSERT_EQUAL_HEX32(0x64u, regs.BRR);
    TEST_ASSERT_EQUAL(STM32_USART_OK, stm32_usart_init(&usart, &regs, 16000000u, 420000u));
    TEST_ASSERT_EQUAL_HEX32(0x26u, regs.BRR);
}

static void test_init_format_refused(void)
{
    regs.CR1 = 0x1234u;
    TEST_ASSERT_EQUAL(
        STM32_USART_ERR_RANGE,
        stm32_usart_init_format(&usart, &regs, 84000000u, 100000u, (stm32_usart_format_t)2));
    TEST_ASSERT_EQUAL(STM32_USART_ERR_RANGE,
                      stm32_usart_init_format(&usart, &regs, 84000000u, 1000u, STM32_USART_8E2));
    TEST_ASSERT_EQUAL_HEX32(0x1234u, regs.CR1);
    TEST_ASSERT_EQUAL_HEX32(0x0u, regs.CR2);
    TEST_ASSERT_EQUAL_HEX32(0x0u, regs.BRR);
    TEST_ASSERT_EQUAL_UINT8(0u, usart.ready);
    TEST_ASSERT_EQUAL(STM32_USART_ERR_NULL,
                      stm32_usart_init_format(NULL, &regs, 84000000u, 100000u, STM32_USART_8E2));
}

static void test_baud_error_ppm(void)
{
    int32_t ppm = 12345;
    TEST_ASSERT_EQUAL(STM32_USART_OK, stm32_usart_baud_error_ppm(84000000u, 420000u, &ppm));
    TEST_ASSERT_EQUAL_INT32(0, ppm);
    TEST_ASSERT_EQUAL(STM32_USART_OK, stm32_usart_baud_error_ppm(42000000u, 420000u, &ppm));
    TEST_ASSERT_EQUAL_INT32(0, ppm);
    TEST_ASSERT_EQUAL(STM32_USART_OK, stm32_usart_baud_error_ppm(42000000u, 100000u, &ppm));
    TEST_ASSERT_EQUAL_INT32(0, ppm);
    TEST_ASSERT_EQUAL(STM32_USART_OK, stm32_usart_baud_error_ppm(16000000u, 420000u, &ppm));
    TEST_ASSERT_EQUAL_INT32(2506, ppm);
    TEST_ASSERT_EQUAL(STM32_USART_OK, stm32_usart_baud_error_ppm(16000000u, 115200u, &ppm));
    TEST_ASSERT_EQUAL_INT32(-799, ppm);
    TEST_ASSERT_EQUAL(STM32_USART_OK, stm32_usart_baud_error_ppm(84000000u, 115200u, &ppm));
    TEST_ASSERT_EQUAL_INT32(229, ppm);
    TEST_ASSERT_EQUAL(STM32_USART_OK, stm32_usart_baud_error_ppm(42000000u, 115200u, &ppm));
    TEST_ASSERT_EQUAL_INT32(-1142, ppm);
    ppm = 7;
    TEST_ASSERT_EQUAL(STM32_USART_ERR_RANGE, stm32_usart_baud_error_ppm(16000000u, 2000000u, &ppm));
    TEST_ASSERT_EQUAL_INT32(7, ppm);
    TEST_ASSERT_EQUAL(STM32_USART_ERR_NULL, stm32_usart_baud_error_ppm(16000000u, 115200u, NULL));
}

static void test_read_flags(void)
{
    uint8_t b = 0;
    uint32_t err = 0xFFu;
    TEST_ASSERT_EQUAL(STM32_USART_OK,
                      stm32_usart_init_format(&usart, &regs, 42000000u, 100000u, STM32_USART_8E2));
    regs.SR = USART_SR_RXNE;
    regs.DR = 0x10Fu; /* 0x0F with its parity bit in bit 8 */
    TEST_ASSERT_EQUAL_INT(1, stm32_usart_read_flags(&usart, &b, &err));
    TEST_ASSERT_EQUAL_HEX8(0x0Fu, b);
    TEST_ASSERT_EQUAL_HEX32(0u, err);
    regs.SR = USART_SR_RXNE | USART_SR_PE | USART_SR_TXE | USART_SR_IDLE;
    TEST_ASSERT_EQUAL_INT(1, stm32_usart_read_flags(&usart, &b, &err));
    TEST_ASSERT_EQUAL_HEX32(USART_SR_PE, err); /* only the error bits */
    TEST_ASSERT_EQUAL_UINT16(1u, usart.parity);
    regs.SR = USART_SR_IDLE; /* idle alone: nothing to read */
    err = 0xFFu;
    TEST_ASSERT_EQUAL_INT(0, stm32_usart_read_flags(&usart, &b, &err));
    TEST_ASSERT_EQUAL_HEX32(0xFFu, err);
    TEST_ASSERT_EQUAL_INT(0, stm32_usart_read_flags(&usart, &b, NULL));
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
    RUN_TEST(test_init_8e2_sbus_from_pclk1);
    RUN_TEST(test_init_420000_crsf);
    RUN_TEST(test_init_format_refused);
    RUN_TEST(test_baud_error_ppm);
    RUN_TEST(test_read_flags);
    return UNITY_END();
}
