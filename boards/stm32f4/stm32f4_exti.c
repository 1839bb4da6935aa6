/*
 * stm32f4_exti.c - a GPIO edge interrupt through SYSCFG and EXTI (see
 * stm32f4_exti.h).
 */
#include "stm32f4_exti.h"

int stm32_exti_route(stm32_syscfg_t *syscfg, stm32_exti_t *exti, uint8_t port, uint8_t line,
                     stm32_exti_edge_t edge)
{
    if (syscfg == NULL || exti == NULL || line >= STM32_EXTI_LINES || port > 8u) {
        return -1;
    }
    const uint32_t bit = (uint32_t)1u << line;
    const uint32_t shift = 4u * ((uint32_t)line % 4u);
    const uint32_t field = (uint32_t)0xFu << shift;
    exti->IMR &= ~bit; /* masked while it is rerouted */
    syscfg->EXTICR[line / 4u] = (syscfg->EXTICR[line / 4u] & ~field) | ((uint32_t)port << shift);
    if (edge == STM32_EXTI_RISING) {
        exti->RTSR |= bit;
        exti->FTSR &= ~bit;
    } else {
        exti->FTSR |= bit;
        exti->RTSR &= ~bit;
    }
    exti->PR = bit;
    exti->IMR |= bit;
    return 0;
}

int stm32_exti_take(stm32_exti_t *exti, uint8_t line)
{
    if (exti == NULL || line >= STM32_EXTI_LINES) {
        return 0;
    }
    const uint32_t bit = (uint32_t)1u << line;
    if ((exti->PR & bit) == 0u) {
        return 0;
    }
    exti->PR = bit; /* rc_w1: only this line is cleared */
    return 1;
}
