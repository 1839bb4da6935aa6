/*
 * stm32f4_pwm.h - eight servo outputs on two general-purpose timers (TIM3 and
 * TIM4 on the STM32F405 image), 1 us per count, one frame per period.
 *
 * Servo channel n (0..7) is timer (n / 4), compare channel (n % 4) + 1.
 * The state lives in a caller-owned stm32_pwm_t; the timers are passed by
 * pointer, so host tests run this on fake register blocks.
 */
#ifndef HT_STM32F4_PWM_H
#define HT_STM32F4_PWM_H

#include <stdint.h>

#include "stm32f4_regs.h"

#define STM32_PWM_CHANNELS 8u
/* The counter runs at 1 MHz and ARR is 16 bits: at most 65536 us per frame,
 * so the slowest frame is 16 Hz (62500 us). 400 Hz is the fastest servo rate
 * we support (2500 us frames still hold a 2100 us pulse). */
#define STM32_PWM_HZ_MIN   16u
#define STM32_PWM_HZ_MAX   400u
#define STM32_PWM_COUNT_HZ 1000000u

typedef enum {
    STM32_PWM_OK = 0,
    STM32_PWM_ERR_NULL = 1,
    STM32_PWM_ERR_RANGE = 2, /* bad clock, rate or channel: nothing written */
    STM32_PWM_CLAMPED = 3    /* the pulse exceeded the frame: ARR written instead */
} stm32_pwm_status_t;

typedef struct {
    stm32_tim_t *tim[2]; /* servos 0-3, servos 4-7 */
    uint16_t period_us;  /* frame length: ARR + 1 */
    uint8_t ready;       /* 1 after a successful init */
} stm32_pwm_t;

/*
 * Configure and start both timers: PWM mode 1 with compare preload on all
 * four channels, ARR buffered, every channel at start_us, counters enabled.
 * timer_clk_hz is the timers' input clock (16 MHz from reset HSI; 84 MHz with
 * the usual 168 MHz PLL set-up) and must be a whole number of MHz, at most
 * 65536 MHz. frame_hz in [STM32_PWM_HZ_MIN, STM32_PWM_HZ_MAX]; the period is
 * round(1e6 / frame_hz) us. Bad arguments write no register.
 */
stm32_pwm_status_t stm32_pwm_init(stm32_pwm_t *pwm, stm32_tim_t *tim_a, stm32_tim_t *tim_b,
                                  uint32_t timer_clk_hz, uint16_t frame_hz, uint16_t start_us);

/*
 * Stage a pulse: the compare register is written, but the timer's update
 * event is held off (CR1.UDIS) so the new value does not reach the pin until
 * stm32_pwm_commit(). A pulse longer than the frame is clamped to ARR.
 */
stm32_pwm_status_t stm32_pwm_set_us(stm32_pwm_t *pwm, uint8_t channel, uint16_t pulse_us);

/*
 * Release the update events: at the end of the current frame each timer
 * transfers all its staged compare values at once. The two timers were
 * started together with the same period, so their frame ends are a few
 * timer-clock cycles apart.
 */
void stm32_pwm_commit(stm32_pwm_t *pwm);

/* Every channel to 0 us (the pins stay low: no servo pulses), committed. */
void stm32_pwm_silence(stm32_pwm_t *pwm);

#endif /* HT_STM32F4_PWM_H */
