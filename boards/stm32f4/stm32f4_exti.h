/*
 * stm32f4_exti.h - one GPIO pin as an edge interrupt: SYSCFG_EXTICRx routes
 * the pin's port to EXTI line n (= the pin number), EXTI arms the edge.
 * Used for the IMU's data-ready line (PC4 -> EXTI4 on the Matek
 * F405-WING). Register blocks passed by pointer, so host tests run it on
 * fakes.
 *
 * RM0090 rev 19:
 *   SYSCFG at 0x40013800 (9.2): MEMRMP 0x00, PMC 0x04, EXTICR1..4 0x08..0x14;
 *     EXTICRk holds lines 4(k-1)..4(k-1)+3, 4 bits each: 0 = port A, 1 = B,
 *     2 = C, ... (9.2.3-9.2.6). Clocked by RCC_APB2ENR.SYSCFGEN (bit 14).
 *   EXTI at 0x40013C00 (12.3): IMR 0x00, EMR 0x04, RTSR 0x08, FTSR 0x0C,
 *     SWIER 0x10, PR 0x14 (rc_w1: writing 1 clears a pending line).
 *   Interrupt lines (table 61): EXTI0..4 at positions 6..10, EXTI9_5 23,
 *     EXTI15_10 40.
 */
#ifndef HT_STM32F4_EXTI_H
#define HT_STM32F4_EXTI_H

#include <stddef.h>
#include <stdint.h>

typedef struct {
    volatile uint32_t MEMRMP;    /* 0x00 */
    volatile uint32_t PMC;       /* 0x04 */
    volatile uint32_t EXTICR[4]; /* 0x08..0x14 */
    volatile uint32_t RESERVED[2];
    volatile uint32_t CMPCR; /* 0x20 */
} stm32_syscfg_t;
_Static_assert((size_t)offsetof(stm32_syscfg_t, EXTICR) == 0x08u, "SYSCFG EXTICR1 offset");
_Static_assert((size_t)offsetof(stm32_syscfg_t, CMPCR) == 0x20u, "SYSCFG CMPCR offset");

typedef struct {
    volatile uint32_t IMR;   /* 0x00 interrupt mask: 1 = enabled */
    volatile uint32_t EMR;   /* 0x04 */
    volatile uint32_t RTSR;  /* 0x08 rising edge */
    volatile uint32_t FTSR;  /* 0x0C falling edge */
    volatile uint32_t SWIER; /* 0x10 */
    volatile uint32_t PR;    /* 0x14 pending, write 1 to clear */
} stm32_exti_t;
_Static_assert((size_t)offsetof(stm32_exti_t, PR) == 0x14u, "EXTI PR offset");

#define STM32_SYSCFG_BASE    0x40013800u
#define STM32_EXTI_BASE      0x40013C00u
#define RCC_APB2ENR_SYSCFGEN 0x4000u /* bit 14 */
#define STM32_EXTI4_IRQN     10u
#define STM32_EXTI_PORT_A    0u
#define STM32_EXTI_PORT_C    2u
#define STM32_EXTI_LINES     16u

typedef enum { STM32_EXTI_RISING = 0, STM32_EXTI_FALLING = 1 } stm32_exti_edge_t;

/*
 * Route port (0 = A .. 8 = I) pin line (0..15) to EXTI line `line` on one
 * edge and unmask it, in this order: IMR bit cleared, EXTICR field, RTSR /
 * FTSR, PR cleared (a stale edge does not fire at once), IMR bit set. Other
 * lines untouched. Returns 0, or -1 (nothing written) for a bad line or
 * port or a NULL block.
 */
int stm32_exti_route(stm32_syscfg_t *syscfg, stm32_exti_t *exti, uint8_t port, uint8_t line,
                     stm32_exti_edge_t edge);

/* The handler's first act: 1 when the line was pending (and is now cleared). */
int stm32_exti_take(stm32_exti_t *exti, uint8_t line);

#endif /* HT_STM32F4_EXTI_H */
