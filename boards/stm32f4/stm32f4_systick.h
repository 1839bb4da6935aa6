/*
 * stm32f4_systick.h - the control tick from the Cortex-M SysTick timer.
 */
#ifndef HT_STM32F4_SYSTICK_H
#define HT_STM32F4_SYSTICK_H

#include <stdint.h>

#include "stm32f4_regs.h"

/*
 * Interrupt at tick_hz from the processor clock cpu_hz: LOAD = round(cpu_hz /
 * tick_hz) - 1. Returns 0 when the reload does not fit SysTick's 24 bits (or
 * is zero) and writes nothing, 1 when started.
 */
int stm32_systick_start(stm32_systick_t *st, uint32_t cpu_hz, uint32_t tick_hz);

#endif /* HT_STM32F4_SYSTICK_H */
