/*
 * matek_hw.c - the Matek F405-WING image's low-level base (see matek_hw.h):
 * the clocks, the 1 kHz SysTick time base, the tick budget's cycle marks,
 * the bounded delay, NVIC enables, GPIO ports and alternate-function pins.
 * The board files above it (board_matekf405wing.c, matek_sensors.c,
 * matek_rc.c, ...) use it; it uses none of them.
 *
 * The state is file-static: this is the firmware image, not the library.
 */
#include "matek_hw.h"

#include "stm32f4_regs.h"
#include "stm32f4_systick.h"

#define NVIC_ISER_BASE 0xE000E100u

static stm32_clocks_t clocks;
static volatile uint32_t ms_count; /* written by SysTick_Handler only */
static uint32_t systick_load;
/* Tick budget, in SysTick counts (= HCLK cycles on the board; see
 * matek_cycles): the worst time from board_rc_read_us's return to the next
 * board_wait_tick (the firmware step and the pulses), and of the board's
 * own reads (board_sensors_read + board_rc_read_us) in one tick. */
static uint32_t cyc_rc_out, cyc_io_start, cyc_io, step_max_cyc, io_max_cyc;

/* Named by the vector table (startup_stm32f405.c), which declares it weak. */
void SysTick_Handler(void);
void SysTick_Handler(void)
{
    ms_count = ms_count + 1u;
}

const stm32_clocks_t *matek_clocks(void)
{
    return &clocks;
}

uint32_t matek_time_ms(void)
{
    return ms_count;
}

/*
 * The time base's two parts: whole ms (the interrupt's count) and SysTick
 * counts into the current ms. ms, then the counter, then ms again: equal ms
 * means the interrupt did not run in between. The counter may still have
 * wrapped with its interrupt not yet taken (a few cycles' window): then the
 * SysTick exception is pending (ICSR.PENDSTSET, ARMv7-M B3.2.4) and the
 * counter has just reloaded (above half the period), so the ms is one more.
 */
#define SCB_ICSR_ADDR      0xE000ED04u
#define SCB_ICSR_PENDSTSET 0x04000000u /* bit 26 */
static void time_parts(uint32_t *ms, uint32_t *sub)
{
    // cppcheck-suppress misra-c2012-11.4 ; D-11.4-REG: SysTick register block address
    const stm32_systick_t *const st = (const stm32_systick_t *)STM32_SYSTICK_BASE;
    // cppcheck-suppress misra-c2012-11.4 ; D-11.4-REG: SCB ICSR register address
    const volatile uint32_t *const icsr = (const volatile uint32_t *)SCB_ICSR_ADDR;
    for (unsigned tries = 0u; tries < 3u; ++tries) {
        const uint32_t m1 = ms_count;
        const uint32_t val = st->VAL & SYSTICK_LOAD_MAX;
        const uint32_t pending = *icsr & SCB_ICSR_PENDSTSET;
        const uint32_t m2 = ms_count;
        if (m1 == m2 && val <= systick_load) {
            const uint32_t wrapped = (pending != 0u && val > systick_load / 2u) ? 1u : 0u;
            *ms = m1 + wrapped;
            *sub = systick_load - val;
            return;
        }
    }
    *ms = ms_count;
    *sub = 0u;
}

uint32_t matek_time_us(void)
{
    const uint32_t per_us = clocks.hclk_hz / 1000000u;
    uint32_t ms = 0u;
    uint32_t sub = 0u;
    time_parts(&ms, &sub);
    return ms * 1000u + ((per_us != 0u) ? (sub / per_us) : 0u);
}

uint32_t matek_cycles(void)
{
    uint32_t ms = 0u;
    uint32_t sub = 0u;
    time_parts(&ms, &sub);
    return ms * (systick_load + 1u) + sub;
}

void matek_budget_mark(uint8_t where)
{
    const uint32_t now = matek_cycles();
    if (where == MATEK_MARK_SENSORS_IN) {
        cyc_io_start = now;
        cyc_io = 0u;
    } else if (where == MATEK_MARK_SENSORS_OUT) {
        cyc_io = now - cyc_io_start;
    } else if (where == MATEK_MARK_RC_IN) {
        cyc_io_start = now;
    } else {
        cyc_io += now - cyc_io_start;
        cyc_rc_out = now;
        /* a "negative" span is a time-base glitch (an emulator's late
         * SysTick interrupt): not a measurement */
        if (cyc_io < 0x80000000u && cyc_io > io_max_cyc) {
            io_max_cyc = cyc_io;
        }
    }
}

void matek_delay_us(void *ctx, uint32_t us)
{
    (void)ctx;
    const uint32_t start = matek_time_us();
    /* The cap bounds the wait even if the time base stopped: each loop is
     * more than one core cycle. */
    const uint32_t cap = us * (clocks.sysclk_hz / 1000000u);
    for (uint32_t i = 0u; i < cap; ++i) {
        if (matek_time_us() - start >= us) {
            return;
        }
    }
}

void matek_nvic_enable(uint32_t irqn)
{
    // cppcheck-suppress misra-c2012-11.4 ; D-11.4-REG: NVIC ISER0..7 register address
    volatile uint32_t *const iser = (volatile uint32_t *)NVIC_ISER_BASE;
    iser[irqn / 32u] = (uint32_t)1u << (irqn % 32u);
}

stm32_gpio_t *matek_gpio(uint8_t port)
{
    static const uint32_t bases[3] = {STM32_GPIOA_BASE, STM32_GPIOB_BASE, STM32_GPIOC_BASE};
    // cppcheck-suppress misra-c2012-11.4 ; D-11.4-REG: GPIOA..C register block addresses
    return (stm32_gpio_t *)bases[(port < 3u) ? port : 0u];
}

void matek_pin_af(uint8_t port, uint8_t pin, uint8_t af, uint8_t open_drain)
{
    stm32_gpio_t *const g = matek_gpio(port);
    const uint32_t bit = (uint32_t)1u << pin;
    if (open_drain != 0u) {
        /* RM0090 8.4.2 OTYPER (1 = open drain), 8.4.4 PUPDR (01 = pull-up) */
        g->OTYPER |= bit;
        g->PUPDR = (g->PUPDR & ~((uint32_t)3u << (2u * pin))) | ((uint32_t)1u << (2u * pin));
    }
    stm32_gpio_set_af(g, pin, af);
}

/* Every peripheral clock the image uses (RM0090 7.3.10, 7.3.13, 7.3.14). */
static void clocks_enable(void)
{
    // cppcheck-suppress misra-c2012-11.4 ; D-11.4-REG: RCC register block address
    stm32_rcc_t *const rcc = (stm32_rcc_t *)STM32_RCC_BASE;
    rcc->AHB1ENR |= 0x7u; /* GPIOA, GPIOB, GPIOC */
    /* TIM3 1, TIM4 2, TIM5 3, TIM12 6, USART2 17, USART3 18, UART4 19, I2C1 21, I2C2 22 */
    rcc->APB1ENR |= 0x006E004Eu;
    /* TIM8 1, USART1 4, USART6 5, SPI1 12, SYSCFG 14 */
    rcc->APB2ENR |= 0x5032u;
    (void)rcc->APB2ENR; /* the enables take effect before the first access */
}

int matek_hw_start(void)
{
    // cppcheck-suppress misra-c2012-11.4 ; D-11.4-REG: RCC register block address
    stm32_rcc_t *const rcc = (stm32_rcc_t *)STM32_RCC_BASE;
    // cppcheck-suppress misra-c2012-11.4 ; D-11.4-REG: flash interface register block address
    stm32_flash_regs_t *const flash = (stm32_flash_regs_t *)STM32_FLASH_REGS_BASE;
    // cppcheck-suppress misra-c2012-11.4 ; D-11.4-REG: SysTick register block address
    stm32_systick_t *const systick = (stm32_systick_t *)STM32_SYSTICK_BASE;
    stm32_clock_init(rcc, flash, MATEK_CLOCK_SPINS, &clocks);
    clocks_enable();
    if (!stm32_systick_start(systick, clocks.hclk_hz, MATEK_TIMEBASE_HZ)) {
        return 0;
    }
    systick_load = systick->LOAD & SYSTICK_LOAD_MAX;
    return 1;
}

void matek_budget_tick(void)
{
    if (cyc_rc_out != 0u) {
        const uint32_t step = matek_cycles() - cyc_rc_out;
        if (step < 0x80000000u && step > step_max_cyc) {
            step_max_cyc = step;
        }
    }
}

uint32_t matek_budget_step_max_cyc(void)
{
    return step_max_cyc;
}

uint32_t matek_budget_io_max_cyc(void)
{
    return io_max_cyc;
}
