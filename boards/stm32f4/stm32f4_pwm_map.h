/*
 * stm32f4_pwm_map.h - servo outputs on any mix of timer channels, 1 us per
 * count, one frame per period: for boards whose servo pins sit on several
 * timers (the Matek F405-WING: TIM4, TIM3, TIM8, TIM12), where
 * stm32f4_pwm.h's "two timers, four channels each" does not fit.
 *
 * Each output names its timer block, its compare channel (1..4), the
 * timer's input clock and whether it is an advanced timer (TIM1/TIM8: the
 * outputs only drive their pins once BDTR.MOE is set, RM0090 17.4.18).
 * Outputs sharing a timer share its prescaler and period; every timer gets
 * the same period. The state lives in a caller-owned stm32_pwm_map_t; the
 * timers are passed by pointer, so host tests run this on fake blocks.
 */
#ifndef HT_STM32F4_PWM_MAP_H
#define HT_STM32F4_PWM_MAP_H

#include <stdint.h>

#include "stm32f4_regs.h"

#define STM32_PWM_MAP_MAX    8u /* outputs */
#define STM32_PWM_MAP_HZ_MIN 16u
#define STM32_PWM_MAP_HZ_MAX 400u
#define TIM_BDTR_MOE         0x8000u /* bit 15: main output enable (advanced timers) */

typedef enum {
    STM32_PWM_MAP_OK = 0,
    STM32_PWM_MAP_ERR_NULL = 1,
    STM32_PWM_MAP_ERR_RANGE = 2, /* bad clock, rate, channel or count: nothing written */
    STM32_PWM_MAP_CLAMPED = 3    /* the pulse exceeded the frame: ARR written instead */
} stm32_pwm_map_status_t;

/* One output: where its pulse comes out. */
typedef struct {
    stm32_tim_t *tim;
    uint32_t timer_clk_hz; /* the timer's input clock, a whole number of MHz */
    uint8_t channel;       /* 1..4 */
    uint8_t advanced;      /* 1: TIM1/TIM8 (BDTR.MOE needed) */
} stm32_pwm_map_out_t;

typedef struct {
    stm32_pwm_map_out_t out[STM32_PWM_MAP_MAX];
    uint8_t count;
    uint16_t period_us; /* frame length: ARR + 1 */
    uint8_t ready;
} stm32_pwm_map_t;

/*
 * Configure and start every timer used by map[0..count): for each timer,
 * once: CR1 = 0, PSC = clk / 1 MHz - 1, ARR = period - 1 (period =
 * round(1e6 / frame_hz)), then per output channel PWM mode 1 with compare
 * preload (CCMR), CCR = start_us (clamped to ARR), CCxE; advanced timers
 * BDTR = MOE; then EGR = UG, SR = 0 and CR1 = ARPE | CEN. Bad arguments
 * (count 0 or > 8, a channel outside 1..4, a clock not a whole number of MHz
 * or over 65536 MHz, a rate outside [16, 400] Hz) write no register.
 */
stm32_pwm_map_status_t stm32_pwm_map_init(stm32_pwm_map_t *p, const stm32_pwm_map_out_t map[],
                                          uint8_t count, uint16_t frame_hz, uint16_t start_us);

/* Stage a pulse: CCR written with the timer's update event held off
 * (CR1.UDIS), so it reaches the pin at the first frame after commit. */
stm32_pwm_map_status_t stm32_pwm_map_set_us(stm32_pwm_map_t *p, uint8_t output, uint16_t pulse_us);

/* Release the update events of every timer (UDIS cleared). */
void stm32_pwm_map_commit(stm32_pwm_map_t *p);

/* Every output to 0 us (pins low, no pulses), committed. */
void stm32_pwm_map_silence(stm32_pwm_map_t *p);

/* The compare register of an output (the pulse in us once committed),
 * 0 before init or for an output out of range. */
uint16_t stm32_pwm_map_readback_us(const stm32_pwm_map_t *p, uint8_t output);

#endif /* HT_STM32F4_PWM_MAP_H */
