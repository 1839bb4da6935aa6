/*
 * startup_stm32f405.c - the vector table and the reset handler: copy .data
 * from flash, zero .bss, call main. No FPU set-up: the whole image is built
 * soft-float (integer-only code, so no lazy FPU stacking on interrupts).
 */
#include <stdint.h>

/* Linker-script symbols (stm32f405.ld): addresses without a size, under the
 * names the linker script gives them (docs/static-analysis.md, D-LINKER). */
// NOLINTBEGIN(bugprone-reserved-identifier,cert-dcl37-c,cert-dcl51-cpp): D-LINKER, stm32f405.ld
// cppcheck-suppress misra-c2012-8.11 ; D-LINKER: linker symbols have no C size
extern uint32_t _sidata[], _sdata[], _edata[], _sbss[], _ebss[], _estack[];
// NOLINTEND(bugprone-reserved-identifier,cert-dcl37-c,cert-dcl51-cpp)

int main(void);
void Reset_Handler(void);
void Default_Handler(void);

/* The handlers a board may define; everything else traps in Default_Handler. */
void NMI_Handler(void) __attribute__((weak, alias("Default_Handler")));
void HardFault_Handler(void) __attribute__((weak, alias("Default_Handler")));
void MemManage_Handler(void) __attribute__((weak, alias("Default_Handler")));
void BusFault_Handler(void) __attribute__((weak, alias("Default_Handler")));
void UsageFault_Handler(void) __attribute__((weak, alias("Default_Handler")));
void SVC_Handler(void) __attribute__((weak, alias("Default_Handler")));
void DebugMon_Handler(void) __attribute__((weak, alias("Default_Handler")));
void PendSV_Handler(void) __attribute__((weak, alias("Default_Handler")));
void SysTick_Handler(void) __attribute__((weak, alias("Default_Handler")));
void USART1_IRQHandler(void) __attribute__((weak, alias("Default_Handler")));
/* Used by the Matek F405-WING image (boards/matekf405wing): the IMU's
 * data-ready line, the receiver and GPS UARTs, the PPM timer. */
void EXTI4_IRQHandler(void) __attribute__((weak, alias("Default_Handler")));
void USART2_IRQHandler(void) __attribute__((weak, alias("Default_Handler")));
void USART3_IRQHandler(void) __attribute__((weak, alias("Default_Handler")));
void TIM5_IRQHandler(void) __attribute__((weak, alias("Default_Handler")));
void USART6_IRQHandler(void) __attribute__((weak, alias("Default_Handler")));
void UART4_IRQHandler(void) __attribute__((weak, alias("Default_Handler")));

/* 16 system exceptions (the first is the initial stack pointer) and the 82
 * STM32F405 interrupt lines (RM0090 table 61: positions 0..81). A struct
 * keeps the stack pointer a data pointer and the rest function pointers. */
#define STM32F405_IRQ_COUNT 82

typedef void (*vector_t)(void);

/* Four interrupt lines that trap in Default_Handler. */
#define DEFAULT_X4 Default_Handler, Default_Handler, Default_Handler, Default_Handler

typedef struct {
    uint32_t *initial_sp;
    vector_t system[15];
    vector_t irq[STM32F405_IRQ_COUNT];
} vector_table_t;

/* Read by the core at reset and on each exception, kept by the linker script
 * (KEEP(*(.isr_vector))); declared first for MISRA 8.4. */
extern const vector_table_t vector_table;
__attribute__((section(".isr_vector"), used)) const vector_table_t vector_table = {
    _estack,
    {
        Reset_Handler,
        NMI_Handler,
        HardFault_Handler,
        MemManage_Handler,
        BusFault_Handler,
        UsageFault_Handler,
        0,
        0,
        0,
        0,
        SVC_Handler,
        DebugMon_Handler,
        0,
        PendSV_Handler,
        SysTick_Handler,
    },
    /* The netduinoplus2 flight image enables no peripheral interrupt; its HIL
     * image enables USART1's (position 37); the Matek F405-WING image also
     * EXTI4 (10), USART2 (38), USART3 (39), TIM5 (50) and USART6 (71)
     * (RM0090 table 61). Any other stops in Default_Handler where a
     * debugger can see it. */
    /* one entry (or four) per line, so the positions can be counted */
    // clang-format off
    {
        DEFAULT_X4,        /* 0..3 */
        Default_Handler,   /* 4 */
        Default_Handler,   /* 5 */
        Default_Handler,   /* 6 EXTI0 */
        Default_Handler,   /* 7 */
        Default_Handler,   /* 8 */
        Default_Handler,   /* 9 */
        EXTI4_IRQHandler,  /* 10 */
        Default_Handler,   /* 11 */
        DEFAULT_X4,        /* 12..15 */
        DEFAULT_X4,        /* 16..19 */
        DEFAULT_X4,        /* 20..23 */
        DEFAULT_X4,        /* 24..27 */
        DEFAULT_X4,        /* 28..31 */
        DEFAULT_X4,        /* 32..35 */
        Default_Handler,   /* 36 */
        USART1_IRQHandler, /* 37 */
        USART2_IRQHandler, /* 38 */
        USART3_IRQHandler, /* 39 */
        DEFAULT_X4,        /* 40..43 */
        DEFAULT_X4,        /* 44..47 */
        Default_Handler,   /* 48 */
        Default_Handler,   /* 49 */
        TIM5_IRQHandler,   /* 50 */
        Default_Handler,   /* 51 */
        UART4_IRQHandler,  /* 52 */
        Default_Handler,   /* 53 */
        Default_Handler,   /* 54 */
        Default_Handler,   /* 55 */
        DEFAULT_X4,        /* 56..59 */
        DEFAULT_X4,        /* 60..63 */
        DEFAULT_X4,        /* 64..67 */
        Default_Handler,   /* 68 */
        Default_Handler,   /* 69 */
        Default_Handler,   /* 70 */
        USART6_IRQHandler, /* 71 */
        DEFAULT_X4,        /* 72..75 */
        DEFAULT_X4,        /* 76..79 */
        Default_Handler,   /* 80 */
        Default_Handler,   /* 81 */
    },
    // clang-format on
};

void Reset_Handler(void)
{
    const uint32_t *src = _sidata;
    uint32_t *dst = _sdata;
    /* The linker symbols delimit one region each (.data, .bss); C sees them as
     * separate objects (docs/static-analysis.md, D-LINKER). */
    // cppcheck-suppress comparePointers ; D-LINKER: _sdata.._edata is one region
    while (dst < _edata) {
        *dst = *src;
        ++dst;
        ++src;
    }
    dst = _sbss;
    // cppcheck-suppress comparePointers ; D-LINKER: _sbss.._ebss is one region
    while (dst < _ebss) {
        *dst = 0u;
        ++dst;
    }
    (void)main();
    for (;;) {
        /* main does not return; if it does, stay here */
    }
}

void Default_Handler(void)
{
    for (;;) {
    }
}
