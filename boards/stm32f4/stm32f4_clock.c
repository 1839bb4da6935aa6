/*
 * stm32f4_clock.c - HSE + PLL to 168 MHz, or the HSI fallback (see
 * stm32f4_clock.h for the register fields and the worked values).
 */
#include "stm32f4_clock.h"

#include <stddef.h>

/* Wait until (*reg & mask) == want, at most spins reads: 1 when it came. */
static int wait_bits(const volatile uint32_t *reg, uint32_t mask, uint32_t want, uint32_t spins)
{
    for (uint32_t i = 0u; i < spins; ++i) {
        if ((*reg & mask) == want) {
            return 1;
        }
    }
    return 0;
}

void stm32_clock_hsi(stm32_clocks_t *out)
{
    if (out == NULL) {
        return;
    }
    out->sysclk_hz = STM32_HSI_HZ;
    out->hclk_hz = STM32_HSI_HZ;
    out->pclk1_hz = STM32_HSI_HZ;
    out->pclk2_hz = STM32_HSI_HZ;
    out->tim_apb1_hz = STM32_HSI_HZ; /* APB prescalers 1: timers at PCLK */
    out->tim_apb2_hz = STM32_HSI_HZ;
    out->source = (uint8_t)STM32_CLOCK_PLL_HSE; /* overwritten by the caller */
}

/* Back to HSI: SW = 00, prescalers /1, PLL and HSE off. */
static void fall_back(stm32_rcc_t *rcc, stm32_clock_source_t why, stm32_clocks_t *out)
{
    rcc->CFGR &= ~(RCC_CFGR_SW | RCC_CFGR_PRE);
    rcc->CR &= ~(RCC_CR_PLLON | RCC_CR_HSEON);
    stm32_clock_hsi(out);
    out->source = (uint8_t)why;
}

void stm32_clock_init(stm32_rcc_t *rcc, stm32_flash_regs_t *flash, uint32_t spin_limit,
                      stm32_clocks_t *out)
{
    if (out == NULL) {
        return;
    }
    if (rcc == NULL || flash == NULL) {
        stm32_clock_hsi(out);
        out->source = (uint8_t)STM32_CLOCK_HSI_NO_HSE;
        return;
    }
    const uint32_t spins = (spin_limit == 0u) ? 1u : spin_limit;
    rcc->CR |= RCC_CR_HSEON;
    if (!wait_bits(&rcc->CR, RCC_CR_HSERDY, RCC_CR_HSERDY, spins)) {
        fall_back(rcc, STM32_CLOCK_HSI_NO_HSE, out);
        return;
    }
    /* Wait states before the clock rises (RM0090 3.5.1, "increasing the CPU
     * frequency"): written, then checked by reading ACR back. */
    flash->ACR = STM32_CLOCK_ACR_168;
    if ((flash->ACR & FLASH_ACR_LAT) != (STM32_CLOCK_ACR_168 & FLASH_ACR_LAT)) {
        fall_back(rcc, STM32_CLOCK_HSI_NO_FLASH, out);
        return;
    }
    /* APB prescalers before the switch, so neither bus ever runs above its
     * limit (APB1 42 MHz, APB2 84 MHz: DS8626 table 14). */
    rcc->CFGR = (rcc->CFGR & ~RCC_CFGR_PRE) | STM32_CLOCK_CFGR_PRE;
    rcc->PLLCFGR = STM32_CLOCK_PLLCFGR_168;
    rcc->CR |= RCC_CR_PLLON;
    if (!wait_bits(&rcc->CR, RCC_CR_PLLRDY, RCC_CR_PLLRDY, spins)) {
        fall_back(rcc, STM32_CLOCK_HSI_NO_PLL, out);
        return;
    }
    rcc->CFGR = (rcc->CFGR & ~RCC_CFGR_SW) | 0x2u;
    if (!wait_bits(&rcc->CFGR, RCC_CFGR_SWS, 0x8u, spins)) {
        fall_back(rcc, STM32_CLOCK_HSI_NO_SWITCH, out);
        return;
    }
    out->sysclk_hz = 168000000u;
    out->hclk_hz = 168000000u;
    out->pclk1_hz = 42000000u;
    out->pclk2_hz = 84000000u;
    out->tim_apb1_hz = 84000000u;  /* PPRE1 /4: timers at 2 x PCLK1 */
    out->tim_apb2_hz = 168000000u; /* PPRE2 /2: timers at 2 x PCLK2 */
    out->source = (uint8_t)STM32_CLOCK_PLL_HSE;
}
