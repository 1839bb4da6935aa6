/*
 * stm32f4_pwm.c - the servo PWM driver (see stm32f4_pwm.h).
 */
#include "stm32f4_pwm.h"

#include <stddef.h>

/* PWM mode 1 with preload, for both channels of a CCMR register. */
static uint32_t ccmr_pwm1_pair(void)
{
    const uint32_t one = (TIM_CCMR_OCM_PWM1 << TIM_CCMR_OCM_SHIFT) | TIM_CCMR_OCPE;
    return one | (one << TIM_CCMR_CH_HI_SHIFT);
}

static void timer_setup(stm32_tim_t *t, uint32_t psc, uint32_t arr, uint16_t start_us)
{
    t->CR1 = 0u; /* stopped while we configure it */
    t->CCER = 0u;
    t->PSC = psc;
    t->ARR = arr;
    t->CCMR1 = ccmr_pwm1_pair();
    t->CCMR2 = ccmr_pwm1_pair();
    for (unsigned i = 0; i < 4u; ++i) {
        t->CCR[i] = (start_us > arr) ? arr : start_us;
    }
    t->CCER = TIM_CCER_CCE(0u) | TIM_CCER_CCE(1u) | TIM_CCER_CCE(2u) | TIM_CCER_CCE(3u);
    /* PSC and the CCR preloads only take effect at an update event: force
     * one now so the first frame already has the right period and pulses. */
    t->EGR = TIM_EGR_UG;
    t->SR = 0u; /* UG set the update flag; nobody wants it */
    t->CR1 = TIM_CR1_ARPE;
}

stm32_pwm_status_t stm32_pwm_init(stm32_pwm_t *pwm, stm32_tim_t *tim_a, stm32_tim_t *tim_b,
                                  uint32_t timer_clk_hz, uint16_t frame_hz, uint16_t start_us)
{
    if (pwm == NULL || tim_a == NULL || tim_b == NULL) {
        return STM32_PWM_ERR_NULL;
    }
    pwm->ready = 0u;
    if (timer_clk_hz < STM32_PWM_COUNT_HZ || timer_clk_hz % STM32_PWM_COUNT_HZ != 0u ||
        timer_clk_hz / STM32_PWM_COUNT_HZ > 65536u || frame_hz < STM32_PWM_HZ_MIN ||
        frame_hz > STM32_PWM_HZ_MAX) {
        return STM32_PWM_ERR_RANGE;
    }
    const uint32_t psc = timer_clk_hz / STM32_PWM_COUNT_HZ - 1u;
    const uint32_t frame = frame_hz;
    const uint32_t period = (STM32_PWM_COUNT_HZ + frame / 2u) / frame;
    pwm->tim[0] = tim_a;
    pwm->tim[1] = tim_b;
    pwm->period_us = (uint16_t)period;
    timer_setup(tim_a, psc, period - 1u, start_us);
    timer_setup(tim_b, psc, period - 1u, start_us);
    /* Start both counters back to back so their frames stay aligned. */
    tim_a->CR1 = TIM_CR1_ARPE | TIM_CR1_CEN;
    tim_b->CR1 = TIM_CR1_ARPE | TIM_CR1_CEN;
    pwm->ready = 1u;
    return STM32_PWM_OK;
}

stm32_pwm_status_t stm32_pwm_set_us(stm32_pwm_t *pwm, uint8_t channel, uint16_t pulse_us)
{
    if (pwm == NULL) {
        return STM32_PWM_ERR_NULL;
    }
    if (!pwm->ready || channel >= STM32_PWM_CHANNELS) {
        return STM32_PWM_ERR_RANGE;
    }
    stm32_tim_t *t = pwm->tim[channel / 4u];
    const uint32_t arr = (uint32_t)pwm->period_us - 1u;
    stm32_pwm_status_t st = STM32_PWM_OK;
    uint32_t ccr = pulse_us;
    if (ccr > arr) {
        ccr = arr; /* never a 100 % duty cycle: the pin falls once per frame */
        st = STM32_PWM_CLAMPED;
    }
    t->CR1 |= TIM_CR1_UDIS;
    t->CCR[channel % 4u] = ccr;
    return st;
}

void stm32_pwm_commit(stm32_pwm_t *pwm)
{
    if (pwm == NULL || !pwm->ready) {
        return;
    }
    pwm->tim[0]->CR1 &= ~TIM_CR1_UDIS;
    pwm->tim[1]->CR1 &= ~TIM_CR1_UDIS;
}

void stm32_pwm_silence(stm32_pwm_t *pwm)
{
    if (pwm == NULL || !pwm->ready) {
        return;
    }
    for (uint8_t ch = 0; ch < STM32_PWM_CHANNELS; ++ch) {
        (void)stm32_pwm_set_us(pwm, ch, 0u);
    }
    stm32_pwm_commit(pwm);
}
