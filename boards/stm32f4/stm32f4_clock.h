/*
 * stm32f4_clock.h - the STM32F405's system clock: an 8 MHz crystal (HSE)
 * through the main PLL to 168 MHz, AHB 168, APB1 42, APB2 84 MHz, with a
 * fallback to the 16 MHz HSI it runs on after reset when the crystal or the
 * PLL never reports ready (a board with a dead crystal, or an emulator such
 * as QEMU's netduinoplus2 that does not model the RCC). Every wait is a
 * bounded number of status reads. The result says which clocks are actually
 * running, and every driver computes its dividers from it.
 *
 * Register fields (RM0090 rev 19):
 *   RCC_CR (7.3.1): HSEON bit 16, HSERDY bit 17, PLLON bit 24, PLLRDY bit 25
 *   RCC_PLLCFGR (7.3.2): PLLM 5:0, PLLN 14:6, PLLP 17:16 (00 = /2),
 *     PLLSRC bit 22 (1 = HSE), PLLQ 27:24
 *   RCC_CFGR (7.3.3): SW 1:0 and SWS 3:2 (00 HSI, 01 HSE, 10 PLL),
 *     HPRE 7:4 (0xxx = /1), PPRE1 12:10 and PPRE2 15:13 (0xx /1, 100 /2, 101 /4)
 *   FLASH_ACR (3.9.1): LATENCY 2:0, PRFTEN bit 8, ICEN bit 9, DCEN bit 10;
 *     table 10 (3.5.1): 5 wait states for 150 < HCLK <= 168 MHz at 2.7-3.6 V,
 *     set and read back before SYSCLK rises
 *   clock tree (6.2): a timer on an APB with a prescaler other than 1 runs at
 *     twice that APB's clock
 * PLL: f_VCO_in = 8 MHz / M(8) = 1 MHz (1-2 MHz recommended), f_VCO = 1 MHz *
 * N(336) = 336 MHz (192-432), SYSCLK = 336 / P(2) = 168 MHz, USB 336 / Q(7) =
 * 48 MHz. PWR_CR.VOS keeps its F405 reset value, scale 1 (needed at 168 MHz).
 */
#ifndef HT_STM32F4_CLOCK_H
#define HT_STM32F4_CLOCK_H

#include <stdint.h>

#include "stm32f4_flash_regs.h"
#include "stm32f4_regs.h"

#define RCC_CR_HSEON   0x00010000u
#define RCC_CR_HSERDY  0x00020000u
#define RCC_CR_PLLON   0x01000000u
#define RCC_CR_PLLRDY  0x02000000u
#define RCC_CFGR_SW    0x3u
#define RCC_CFGR_SWS   0xCu
#define RCC_CFGR_PRE   0xFCF0u /* HPRE, PPRE1, PPRE2 */
#define FLASH_ACR_LAT  0x7u
#define FLASH_ACR_PRFT 0x100u
#define FLASH_ACR_ICEN 0x200u

/* The values written for 168 MHz (worked in the header comment above). */
#define STM32_CLOCK_PLLCFGR_168 0x07405408u /* Q 7, SRC HSE, P 00, N 336, M 8 */
#define STM32_CLOCK_CFGR_PRE    0x9400u     /* PPRE2 100 (/2), PPRE1 101 (/4), HPRE /1 */
#define STM32_CLOCK_ACR_168     0x705u      /* DCEN | ICEN | PRFTEN | 5 WS */
#define STM32_CLOCK_HSE_HZ      8000000u

typedef enum {
    STM32_CLOCK_PLL_HSE = 0,      /* 168 MHz from the crystal */
    STM32_CLOCK_HSI_NO_HSE = 1,   /* HSERDY never came: still on HSI */
    STM32_CLOCK_HSI_NO_FLASH = 2, /* FLASH_ACR did not take the wait states */
    STM32_CLOCK_HSI_NO_PLL = 3,   /* PLLRDY never came */
    STM32_CLOCK_HSI_NO_SWITCH = 4 /* SWS never showed the PLL */
} stm32_clock_source_t;

/* What runs after stm32_clock_init, in Hz. */
typedef struct {
    uint32_t sysclk_hz, hclk_hz;
    uint32_t pclk1_hz, pclk2_hz;
    uint32_t tim_apb1_hz, tim_apb2_hz; /* the timers' input clocks */
    uint8_t source;                    /* stm32_clock_source_t */
} stm32_clocks_t;

/* The reset clocks: HSI 16 MHz everywhere. */
void stm32_clock_hsi(stm32_clocks_t *out);

/*
 * HSE on, wait HSERDY; FLASH_ACR = 5 WS with prefetch and caches, read
 * back; prescalers (CFGR PRE fields); PLLCFGR; PLL on, wait PLLRDY; SW = PLL,
 * wait SWS = PLL. Each wait reads its flag at most spin_limit times
 * (0 is read as 1). On any failure the steps taken are undone (SW back to
 * HSI, prescalers /1, PLL and HSE off; the extra flash wait states are
 * harmless at 16 MHz and stay) and out says HSI 16 MHz, with the reason.
 */
void stm32_clock_init(stm32_rcc_t *rcc, stm32_flash_regs_t *flash, uint32_t spin_limit,
                      stm32_clocks_t *out);

#endif /* HT_STM32F4_CLOCK_H */
