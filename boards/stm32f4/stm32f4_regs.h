/*
 * stm32f4_regs.h - the few STM32F405 peripherals the board uses, as register
 * blocks. Offsets, addresses and bit positions are from the reference manual
 * RM0090 (STM32F405/415/407/417/427/437/429/439) and the Cortex-M4 generic
 * user guide (SysTick); each block's layout is checked against RM0090's
 * offsets at compile time below.
 *
 * Drivers take a pointer to a block, so host tests pass an ordinary struct
 * in RAM (a fake) and the firmware passes the fixed address.
 */
#ifndef HT_STM32F4_REGS_H
#define HT_STM32F4_REGS_H

#include <stddef.h>
#include <stdint.h>

/* --- general-purpose timers TIM2..TIM5 (RM0090 section 18.4) ------------ */
typedef struct {
    volatile uint32_t CR1;       /* 0x00 control 1 */
    volatile uint32_t CR2;       /* 0x04 */
    volatile uint32_t SMCR;      /* 0x08 slave mode */
    volatile uint32_t DIER;      /* 0x0C interrupt/DMA enable */
    volatile uint32_t SR;        /* 0x10 status */
    volatile uint32_t EGR;       /* 0x14 event generation */
    volatile uint32_t CCMR1;     /* 0x18 capture/compare mode, channels 1-2 */
    volatile uint32_t CCMR2;     /* 0x1C channels 3-4 */
    volatile uint32_t CCER;      /* 0x20 capture/compare enable */
    volatile uint32_t CNT;       /* 0x24 counter */
    volatile uint32_t PSC;       /* 0x28 prescaler: f_cnt = f_ck / (PSC + 1) */
    volatile uint32_t ARR;       /* 0x2C auto-reload: period = ARR + 1 counts */
    volatile uint32_t RESERVED0; /* 0x30 (RCR on the advanced timers) */
    volatile uint32_t CCR[4];    /* 0x34, 0x38, 0x3C, 0x40 compare, channels 1-4 */
    volatile uint32_t BDTR;      /* 0x44 break and dead-time: TIM1/TIM8 only, reserved on
                                    the others (RM0090 17.4.18) */
    volatile uint32_t DCR;       /* 0x48 */
    volatile uint32_t DMAR;      /* 0x4C */
    volatile uint32_t OR;        /* 0x50 option (TIM2, TIM5 only) */
} stm32_tim_t;

_Static_assert((size_t)offsetof(stm32_tim_t, EGR) == 0x14u, "TIM EGR offset");
_Static_assert((size_t)offsetof(stm32_tim_t, CCMR1) == 0x18u, "TIM CCMR1 offset");
_Static_assert((size_t)offsetof(stm32_tim_t, CCER) == 0x20u, "TIM CCER offset");
_Static_assert((size_t)offsetof(stm32_tim_t, PSC) == 0x28u, "TIM PSC offset");
_Static_assert((size_t)offsetof(stm32_tim_t, ARR) == 0x2Cu, "TIM ARR offset");
_Static_assert((size_t)offsetof(stm32_tim_t, CCR) == 0x34u, "TIM CCR1 offset");
_Static_assert((size_t)offsetof(stm32_tim_t, BDTR) == 0x44u, "TIM1/8 BDTR offset");
_Static_assert((size_t)offsetof(stm32_tim_t, DCR) == 0x48u, "TIM DCR offset");
_Static_assert((size_t)offsetof(stm32_tim_t, OR) == 0x50u, "TIM OR offset");

#define STM32_TIM2_BASE 0x40000000u /* APB1; TIM2 and TIM5 have 32-bit counters */
#define STM32_TIM3_BASE 0x40000400u /* APB1 */
#define STM32_TIM4_BASE 0x40000800u
#define STM32_TIM5_BASE 0x40000C00u
/* Their interrupt lines (RM0090 table 61) */
#define STM32_TIM2_IRQN 28u
#define STM32_TIM3_IRQN 29u
#define STM32_TIM4_IRQN 30u
#define STM32_TIM5_IRQN 50u

/* TIMx_CR1 */
#define TIM_CR1_CEN  (1u << 0) /* counter enable */
#define TIM_CR1_UDIS (1u << 1) /* update event disabled: preloads are not transferred */
#define TIM_CR1_ARPE (1u << 7) /* ARR is buffered */
/* TIMx_EGR */
#define TIM_EGR_UG (1u << 0) /* re-initialise the counter, load the preloads */
/* TIMx_CCMRx (output compare): the channel 1/3 field at bit 0, 2/4 at bit 8 */
#define TIM_CCMR_OCPE        (1u << 3) /* compare preload enable (OCxPE) */
#define TIM_CCMR_OCM_SHIFT   4u        /* OCxM[2:0] at bits 6:4 */
#define TIM_CCMR_OCM_PWM1    6u        /* 110: PWM mode 1, high while CNT < CCR */
#define TIM_CCMR_CH_HI_SHIFT 8u        /* the second channel of the pair */
/* TIMx_CCMRx (input capture, section 18.4.7): per channel byte, CCxS[1:0]
 * = 01 maps ICx on TIx; ICxPSC[3:2] = 00 captures every edge; ICxF[7:4] is
 * the input filter (0011: sampled at f_CK_INT, a level must hold N = 8
 * samples). */
#define TIM_CCMR_CCS_TI    1u
#define TIM_CCMR_ICF_SHIFT 4u
#define TIM_CCMR_ICF_CK_N8 3u
/* TIMx_CCER: CCxE at bit 4*(x-1); CCxP one above: for an input, 0 captures
 * rising edges, 1 falling ones (section 18.4.9) */
#define TIM_CCER_CCE(ch0) ((uint32_t)1u << ((uint32_t)4u * (uint32_t)(ch0))) /* ch0 = channel - 1  \
                                                                              */
#define TIM_CCER_CCP(ch0) ((uint32_t)2u << ((uint32_t)4u * (uint32_t)(ch0)))
/* TIMx_DIER (section 18.4.4): UIE bit 0, CCxIE bit x */
#define TIM_DIER_UIE       (1u << 0)
#define TIM_DIER_CCIE(ch0) ((uint32_t)2u << (ch0))
/* TIMx_SR (section 18.4.5), rc_w0 (write 0 clears, 1 leaves): UIF bit 0,
 * CCxIF bit x (also cleared by reading CCRx), CCxOF bit x + 8 (a capture
 * came while CCxIF was still set: an edge was lost) */
#define TIM_SR_UIF        (1u << 0)
#define TIM_SR_CCIF(ch0)  ((uint32_t)2u << (ch0))
#define TIM_SR_CCOF(ch0)  ((uint32_t)0x200u << (ch0))
#define TIM_SR_RC_W0_BITS 0x1E5Fu /* UIF, CC1IF..CC4IF, TIF, CC1OF..CC4OF */

/* --- RCC (RM0090 section 7.3) -------------------------------------------- */
typedef struct {
    volatile uint32_t CR;           /* 0x00 */
    volatile uint32_t PLLCFGR;      /* 0x04 */
    volatile uint32_t CFGR;         /* 0x08 */
    volatile uint32_t CIR;          /* 0x0C */
    volatile uint32_t AHB1RSTR;     /* 0x10 */
    volatile uint32_t AHB2RSTR;     /* 0x14 */
    volatile uint32_t AHB3RSTR;     /* 0x18 */
    volatile uint32_t RESERVED0;    /* 0x1C */
    volatile uint32_t APB1RSTR;     /* 0x20 */
    volatile uint32_t APB2RSTR;     /* 0x24 */
    volatile uint32_t RESERVED1[2]; /* 0x28, 0x2C */
    volatile uint32_t AHB1ENR;      /* 0x30 */
    volatile uint32_t AHB2ENR;      /* 0x34 */
    volatile uint32_t AHB3ENR;      /* 0x38 */
    volatile uint32_t RESERVED2;    /* 0x3C */
    volatile uint32_t APB1ENR;      /* 0x40 */
    volatile uint32_t APB2ENR;      /* 0x44 */
} stm32_rcc_t;

_Static_assert((size_t)offsetof(stm32_rcc_t, AHB1ENR) == 0x30u, "RCC AHB1ENR offset");
_Static_assert((size_t)offsetof(stm32_rcc_t, APB1ENR) == 0x40u, "RCC APB1ENR offset");

#define STM32_RCC_BASE 0x40023800u

#define RCC_AHB1ENR_GPIOAEN (1u << 0)
#define RCC_AHB1ENR_GPIOBEN (1u << 1)
#define RCC_APB1ENR_TIM3EN  (1u << 1)
#define RCC_APB1ENR_TIM4EN  (1u << 2)

/* After reset the STM32F4 runs from the 16 MHz HSI with the AHB and APB
 * prescalers at 1, so SYSCLK = HCLK = PCLK1 = 16 MHz, and the APB1 timers
 * are clocked at PCLK1 (x1 because the APB1 prescaler is 1). */
#define STM32_HSI_HZ 16000000u

/* --- GPIO (RM0090 section 8.4) ------------------------------------------- */
typedef struct {
    volatile uint32_t MODER;   /* 0x00 2 bits per pin: 10 = alternate function */
    volatile uint32_t OTYPER;  /* 0x04 */
    volatile uint32_t OSPEEDR; /* 0x08 */
    volatile uint32_t PUPDR;   /* 0x0C */
    volatile uint32_t IDR;     /* 0x10 */
    volatile uint32_t ODR;     /* 0x14 */
    volatile uint32_t BSRR;    /* 0x18 */
    volatile uint32_t LCKR;    /* 0x1C */
    volatile uint32_t AFR[2];  /* 0x20 AFRL (pins 0-7), 0x24 AFRH (8-15): 4 bits per pin */
} stm32_gpio_t;

_Static_assert((size_t)offsetof(stm32_gpio_t, AFR) == 0x20u, "GPIO AFRL offset");

#define STM32_GPIOA_BASE 0x40020000u
#define STM32_GPIOB_BASE 0x40020400u
#define STM32_GPIOC_BASE 0x40020800u

#define GPIO_MODER_OUTPUT       1u /* general-purpose output */
#define GPIO_MODER_AF           2u
#define GPIO_OSPEEDR_FAST       2u  /* 10: fast speed (RM0090 8.4.3) */
#define GPIO_BSRR_RESET_SHIFT   16u /* BSRR bits 31:16 reset a pin, 15:0 set it */
#define GPIO_AF2_TIM3_TIM4_TIM5 2u  /* AF2 selects TIM3..TIM5 channels */

/* --- SysTick (ARMv7-M, at 0xE000E010) ----------------------------------- */
typedef struct {
    volatile uint32_t CTRL;  /* 0x00 */
    volatile uint32_t LOAD;  /* 0x04 reload value, 24 bits */
    volatile uint32_t VAL;   /* 0x08 current value */
    volatile uint32_t CALIB; /* 0x0C */
} stm32_systick_t;

#define STM32_SYSTICK_BASE 0xE000E010u

#define SYSTICK_CTRL_ENABLE    (1u << 0)
#define SYSTICK_CTRL_TICKINT   (1u << 1)
#define SYSTICK_CTRL_CLKSOURCE (1u << 2) /* 1 = processor clock */
#define SYSTICK_LOAD_MAX       0x00FFFFFFu

#endif /* HT_STM32F4_REGS_H */
