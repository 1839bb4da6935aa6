/*
 * stm32f4_systick.c - see stm32f4_systick.h.
 */
#include "stm32f4_systick.h"

#include <stddef.h>

int stm32_systick_start(stm32_systick_t *st, uint32_t cpu_hz, uint32_t tick_hz)
{
    if (st == NULL || tick_hz == 0u || cpu_hz < tick_hz) {
        return 0;
    }
    const uint32_t reload = (cpu_hz + tick_hz / 2u) / tick_hz;
    if (reload < 2u || reload - 1u > SYSTICK_LOAD_MAX) {
        return 0;
    }
    st->CTRL = 0u;
    st->LOAD = reload - 1u;
    st->VAL = 0u; /* any write clears the counter */
    st->CTRL = SYSTICK_CTRL_CLKSOURCE | SYSTICK_CTRL_TICKINT | SYSTICK_CTRL_ENABLE;
    return 1;
}
