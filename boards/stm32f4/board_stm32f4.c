/*
 * board_stm32f4.c - board.h for a bare STM32F405: SysTick control tick,
 * eight servos on TIM3/TIM4. Clocks: the reset HSI (16 MHz), so nothing waits
 * on an oscillator or PLL ready flag (the image also runs where RCC is not
 * modelled and reads 0). RC input and sensors are separate files
 * (boards/common/rc_none.c, sensors_level.c), so a receiver driver or a
 * simulator link replaces one file in the image's source list.
 *
 * The board's state is file-static: this is the firmware image, not the
 * library.
 */
#include "helical/board.h"

#include "board_stm32f4.h"
#include "stm32f4_gpio.h"
#include "stm32f4_pwm.h"
#include "stm32f4_regs.h"
#include "stm32f4_systick.h"

#include <stddef.h>

/* The register blocks are reached at their fixed addresses (RM0090 memory
 * map): each function names the blocks it uses, as a const pointer made from
 * the address, the one place an integer becomes a pointer
 * (docs/static-analysis.md, D-11.4-REG). */

#define CPU_HZ   STM32_HSI_HZ
#define TIMER_HZ STM32_HSI_HZ /* APB1 prescaler 1: timers run at PCLK1 */

static stm32_pwm_t servo_pwm;
static volatile uint32_t tick_count; /* written by SysTick_Handler only */
static uint32_t tick_seen;

/* Servo n: TIM3 CH1..4 on PA6, PA7, PB0, PB1; TIM4 CH1..4 on PB6..PB9, all
 * AF2 (datasheet DS8626, alternate function mapping). */
static void servo_pins(void)
{
    // cppcheck-suppress misra-c2012-11.4 ; D-11.4-REG: GPIOA register block address
    stm32_gpio_t *const gpioa = (stm32_gpio_t *)STM32_GPIOA_BASE;
    // cppcheck-suppress misra-c2012-11.4 ; D-11.4-REG: GPIOB register block address
    stm32_gpio_t *const gpiob = (stm32_gpio_t *)STM32_GPIOB_BASE;
    static const uint8_t pins_b[6] = {0u, 1u, 6u, 7u, 8u, 9u};
    stm32_gpio_set_af(gpioa, 6u, GPIO_AF2_TIM3_TIM4_TIM5);
    stm32_gpio_set_af(gpioa, 7u, GPIO_AF2_TIM3_TIM4_TIM5);
    for (unsigned i = 0; i < sizeof pins_b; ++i) {
        stm32_gpio_set_af(gpiob, pins_b[i], GPIO_AF2_TIM3_TIM4_TIM5);
    }
}

/* Named by the vector table (startup_stm32f405.c), which declares it weak. */
void SysTick_Handler(void);
void SysTick_Handler(void)
{
    tick_count = tick_count + 1u;
}

board_status_t board_init(const board_config_t *cfg)
{
    // cppcheck-suppress misra-c2012-11.4 ; D-11.4-REG: RCC register block address
    stm32_rcc_t *const rcc = (stm32_rcc_t *)STM32_RCC_BASE;
    // cppcheck-suppress misra-c2012-11.4 ; D-11.4-REG: TIM3 register block address
    stm32_tim_t *const tim3 = (stm32_tim_t *)STM32_TIM3_BASE;
    // cppcheck-suppress misra-c2012-11.4 ; D-11.4-REG: TIM4 register block address
    stm32_tim_t *const tim4 = (stm32_tim_t *)STM32_TIM4_BASE;
    // cppcheck-suppress misra-c2012-11.4 ; D-11.4-REG: SysTick register block address
    stm32_systick_t *const systick = (stm32_systick_t *)STM32_SYSTICK_BASE;
    board_status_t st = board_config_check(cfg);
    if (st != BOARD_OK) {
        return st;
    }
    stm32_rcc_enable_servo_clocks(rcc);
    /* Timers first, pins second: the pins only see PWM once it is set up. */
    if (stm32_pwm_init(&servo_pwm, tim3, tim4, TIMER_HZ, cfg->servo_frame_hz,
                       cfg->servo_start_us) != STM32_PWM_OK) {
        return BOARD_ERR_HW;
    }
    servo_pins();
    tick_seen = tick_count;
    if (!stm32_systick_start(systick, CPU_HZ, cfg->control_hz)) {
        return BOARD_ERR_HW;
    }
    return BOARD_OK;
}

uint8_t board_servo_count(void)
{
    return (uint8_t)STM32_PWM_CHANNELS;
}

uint16_t board_wait_tick(void)
{
    while (tick_count == tick_seen) {
        __asm__ volatile("wfi"); /* sleep until SysTick (or any interrupt) */
    }
    const uint32_t now = tick_count;
    const uint32_t late = now - tick_seen - 1u;
    tick_seen = now;
    return (late > UINT16_MAX) ? (uint16_t)UINT16_MAX : (uint16_t)late;
}

board_status_t board_servo_write_us(uint8_t channel, uint16_t pulse_us)
{
    const stm32_pwm_status_t st = stm32_pwm_set_us(&servo_pwm, channel, pulse_us);
    return (st == STM32_PWM_OK || st == STM32_PWM_CLAMPED) ? BOARD_OK : BOARD_ERR_RANGE;
}

void board_servo_commit(void)
{
    stm32_pwm_commit(&servo_pwm);
}

void board_failsafe(board_failsafe_t reason)
{
    /* The loop has already chosen failsafe pulses; with a refused
     * configuration it writes none, so stop the pulses here. */
    if (reason == BOARD_FS_CONFIG) {
        stm32_pwm_silence(&servo_pwm);
    }
}

const stm32_pwm_t *board_stm32f4_pwm(void)
{
    return &servo_pwm;
}
