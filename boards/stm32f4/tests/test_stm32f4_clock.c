/*
 * test_stm32f4_clock.c - the 168 MHz clock set-up and its HSI fallback on
 * fake RCC and FLASH blocks (plain memory: a ready flag is "set" by
 * presetting it, and stays as written).
 *
 * Expected values, worked from RM0090 (see stm32f4_clock.h):
 *   PLLCFGR = PLLQ 7 << 24 | PLLSRC 1 << 22 | PLLP 00 << 16 | PLLN 336 << 6
 *           | PLLM 8 = 0x07000000 | 0x00400000 | 0x5400 | 0x08 = 0x07405408
 *   CFGR    = PPRE2 100 << 13 | PPRE1 101 << 10 | SW 10 = 0x8000 | 0x1400 | 2
 *           = 0x9402 (| SWS 10 << 2 = 0x8 preset by the test: 0x940A)
 *   ACR     = DCEN 0x400 | ICEN 0x200 | PRFTEN 0x100 | LATENCY 5 = 0x705
 *   clocks  = 168 / 168 / 42 / 84 MHz; timers 84 (APB1 x2) / 168 (APB2 x2)
 */
#include "unity.h"

#include "stm32f4_clock.h"

#include <string.h>

static stm32_rcc_t rcc;
static stm32_flash_regs_t flash;
static stm32_clocks_t clk;

void setUp(void)
{
    memset((void *)&rcc, 0, sizeof rcc);
    memset((void *)&flash, 0, sizeof flash);
    memset(&clk, 0xA5, sizeof clk);
}

void tearDown(void) {}

static void assert_hsi(uint8_t why)
{
    TEST_ASSERT_EQUAL_UINT8(why, clk.source);
    TEST_ASSERT_EQUAL_UINT32(16000000u, clk.sysclk_hz);
    TEST_ASSERT_EQUAL_UINT32(16000000u, clk.hclk_hz);
    TEST_ASSERT_EQUAL_UINT32(16000000u, clk.pclk1_hz);
    TEST_ASSERT_EQUAL_UINT32(16000000u, clk.pclk2_hz);
    TEST_ASSERT_EQUAL_UINT32(16000000u, clk.tim_apb1_hz);
    TEST_ASSERT_EQUAL_UINT32(16000000u, clk.tim_apb2_hz);
    TEST_ASSERT_EQUAL_HEX32(0u, rcc.CFGR & (RCC_CFGR_SW | RCC_CFGR_PRE));
    TEST_ASSERT_EQUAL_HEX32(0u, rcc.CR & (RCC_CR_HSEON | RCC_CR_PLLON));
}

static void test_pll_168(void)
{
    rcc.CR = RCC_CR_HSERDY | RCC_CR_PLLRDY;
    rcc.CFGR = 0x8u; /* SWS = PLL */
    stm32_clock_init(&rcc, &flash, 100u, &clk);
    TEST_ASSERT_EQUAL_UINT8(STM32_CLOCK_PLL_HSE, clk.source);
    TEST_ASSERT_EQUAL_HEX32(0x07405408u, rcc.PLLCFGR);
    TEST_ASSERT_EQUAL_HEX32(0x940Au, rcc.CFGR);
    TEST_ASSERT_EQUAL_HEX32(0x705u, flash.ACR);
    TEST_ASSERT_EQUAL_HEX32(RCC_CR_HSEON | RCC_CR_PLLON, rcc.CR & (RCC_CR_HSEON | RCC_CR_PLLON));
    TEST_ASSERT_EQUAL_UINT32(168000000u, clk.sysclk_hz);
    TEST_ASSERT_EQUAL_UINT32(168000000u, clk.hclk_hz);
    TEST_ASSERT_EQUAL_UINT32(42000000u, clk.pclk1_hz);
    TEST_ASSERT_EQUAL_UINT32(84000000u, clk.pclk2_hz);
    TEST_ASSERT_EQUAL_UINT32(84000000u, clk.tim_apb1_hz);
    TEST_ASSERT_EQUAL_UINT32(168000000u, clk.tim_apb2_hz);
}

/* QEMU's netduinoplus2 and a board with a dead crystal: RCC reads 0. */
static void test_no_hse_stays_on_hsi(void)
{
    stm32_clock_init(&rcc, &flash, 100u, &clk);
    assert_hsi(STM32_CLOCK_HSI_NO_HSE);
    TEST_ASSERT_EQUAL_HEX32(0u, flash.ACR); /* nothing raised */
    TEST_ASSERT_EQUAL_HEX32(0u, rcc.PLLCFGR);
}

static void test_no_pll_falls_back(void)
{
    rcc.CR = RCC_CR_HSERDY;
    stm32_clock_init(&rcc, &flash, 100u, &clk);
    assert_hsi(STM32_CLOCK_HSI_NO_PLL);
}

static void test_no_switch_falls_back(void)
{
    rcc.CR = RCC_CR_HSERDY | RCC_CR_PLLRDY; /* SWS stays HSI */
    stm32_clock_init(&rcc, &flash, 100u, &clk);
    assert_hsi(STM32_CLOCK_HSI_NO_SWITCH);
}

static void test_zero_spin_limit_is_one_read(void)
{
    rcc.CR = RCC_CR_HSERDY | RCC_CR_PLLRDY;
    rcc.CFGR = 0x8u;
    stm32_clock_init(&rcc, &flash, 0u, &clk);
    TEST_ASSERT_EQUAL_UINT8(STM32_CLOCK_PLL_HSE, clk.source);
    stm32_clock_init(NULL, &flash, 1u, &clk);
    TEST_ASSERT_EQUAL_UINT8(STM32_CLOCK_HSI_NO_HSE, clk.source);
    TEST_ASSERT_EQUAL_UINT32(16000000u, clk.pclk1_hz);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_pll_168);
    RUN_TEST(test_no_hse_stays_on_hsi);
    RUN_TEST(test_no_pll_falls_back);
    RUN_TEST(test_no_switch_falls_back);
    RUN_TEST(test_zero_spin_limit_is_one_read);
    return UNITY_END();
}
