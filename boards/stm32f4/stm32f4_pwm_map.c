/*
 * stm32f4_pwm_map.c - servo outputs on a list of timer channels (see
 * stm32f4_pwm_map.h). Register fields: RM0090 18.4 (TIM2..TIM5), 17.4
 * (TIM1/TIM8) and 19.4 (TIM9..TIM14): CR1, CCMR1/2, CCER, PSC, ARR and
 * CCR1..4 sit at the same offsets in all three families.
 */
#include "stm32f4_pwm_map.h"

#include <stddef.h>

#define COUNT_HZ 1000000u

/* Is t already among map[0..n)? */
static int seen_before(const stm32_pwm_map_out_t map[], uint8_t n, const stm32_tim_t *t)
{
    for (uint8_t i = 0u; i < n; ++i) {
        if (map[i].tim == t) {
            return 1;
        }
    }
    return 0;
}

static int map_ok(const stm32_pwm_map_out_t map[], uint8_t count)
{
    for (uint8_t i = 0u; i < count; ++i) {
        const uint32_t clk = map[i].timer_clk_hz;
        if (map[i].tim == NULL || map[i].channel < 1u || map[i].channel > 4u || clk < COUNT_HZ ||
            (clk % COUNT_HZ) != 0u || (clk / COUNT_HZ) > 65536u) {
            return 0;
        }
    }
    return 1;
}

/* PWM mode 1 with preload, in the CCMR byte of channel ch (1..4). */
static void channel_pwm1(stm32_tim_t *t, uint8_t ch)
{
    const uint32_t ocm = TIM_CCMR_OCM_PWM1;
    const uint32_t one = (ocm << TIM_CCMR_OCM_SHIFT) | TIM_CCMR_OCPE;
    const uint32_t ch0 = (uint32_t)ch - 1u;
    const uint32_t shift = (ch0 % 2u) * TIM_CCMR_CH_HI_SHIFT;
    const uint32_t byte_mask = 0xFFu;
    const uint32_t field = byte_mask << shift;
    if (ch <= 2u) {
        t->CCMR1 = (t->CCMR1 & ~field) | (one << shift);
    } else {
        t->CCMR2 = (t->CCMR2 & ~field) | (one << shift);
    }
}

stm32_pwm_map_status_t stm32_pwm_map_init(stm32_pwm_map_t *p, const stm32_pwm_map_out_t map[],
                                          uint8_t count, uint16_t frame_hz, uint16_t start_us)
{
    if (p == NULL || map == NULL) {
        return STM32_PWM_MAP_ERR_NULL;
    }
    p->ready = 0u;
    if (count == 0u || count > STM32_PWM_MAP_MAX || frame_hz < STM32_PWM_MAP_HZ_MIN ||
        frame_hz > STM32_PWM_MAP_HZ_MAX || !map_ok(map, count)) {
        return STM32_PWM_MAP_ERR_RANGE;
    }
    const uint32_t frame = frame_hz;
    const uint32_t period = (COUNT_HZ + frame / 2u) / frame;
    const uint32_t arr = period - 1u;
    const uint32_t start = (start_us > arr) ? arr : (uint32_t)start_us;
    p->count = count;
    p->period_us = (uint16_t)period;
    for (uint8_t i = 0u; i < count; ++i) {
        p->out[i] = map[i];
    }
    /* Each timer once: stopped, its clock divided to 1 us counts. */
    for (uint8_t i = 0u; i < count; ++i) {
        stm32_tim_t *t = map[i].tim;
        if (!seen_before(map, i, t)) {
            t->CR1 = 0u;
            t->CCER = 0u;
            t->PSC = map[i].timer_clk_hz / COUNT_HZ - 1u;
            t->ARR = arr;
        }
    }
    for (uint8_t i = 0u; i < count; ++i) {
        stm32_tim_t *t = map[i].tim;
        const uint32_t ch0_32 = (uint32_t)map[i].channel - 1u;
        const uint8_t ch0 = (uint8_t)ch0_32;
        channel_pwm1(t, map[i].channel);
        t->CCR[ch0] = start;
        t->CCER |= TIM_CCER_CCE(ch0);
        if (map[i].advanced != 0u) {
            t->BDTR = TIM_BDTR_MOE; /* no break input, no dead time */
        }
    }
    /* An update event loads PSC and the preloads, then start back to back. */
    for (uint8_t i = 0u; i < count; ++i) {
        stm32_tim_t *t = map[i].tim;
        if (!seen_before(map, i, t)) {
            t->EGR = TIM_EGR_UG;
            t->SR = 0u;
        }
    }
    for (uint8_t i = 0u; i < count; ++i) {
        stm32_tim_t *t = map[i].tim;
        if (!seen_before(map, i, t)) {
            t->CR1 = TIM_CR1_ARPE | TIM_CR1_CEN;
        }
    }
    p->ready = 1u;
    return STM32_PWM_MAP_OK;
}

stm32_pwm_map_status_t stm32_pwm_map_set_us(stm32_pwm_map_t *p, uint8_t output, uint16_t pulse_us)
{
    if (p == NULL) {
        return STM32_PWM_MAP_ERR_NULL;
    }
    if (p->ready == 0u || output >= p->count) {
        return STM32_PWM_MAP_ERR_RANGE;
    }
    stm32_tim_t *t = p->out[output].tim;
    const uint32_t arr = (uint32_t)p->period_us - 1u;
    t->CR1 |= TIM_CR1_UDIS;
    const uint8_t ch0 = (uint8_t)(p->out[output].channel - 1u);
    if ((uint32_t)pulse_us > arr) {
        t->CCR[ch0] = arr;
        return STM32_PWM_MAP_CLAMPED;
    }
    t->CCR[ch0] = pulse_us;
    return STM32_PWM_MAP_OK;
}

void stm32_pwm_map_commit(stm32_pwm_map_t *p)
{
    if (p == NULL || p->ready == 0u) {
        return;
    }
    for (uint8_t i = 0u; i < p->count; ++i) {
        p->out[i].tim->CR1 &= ~TIM_CR1_UDIS;
    }
}

void stm32_pwm_map_silence(stm32_pwm_map_t *p)
{
    if (p == NULL || p->ready == 0u) {
        return;
    }
    for (uint8_t i = 0u; i < p->count; ++i) {
        (void)stm32_pwm_map_set_us(p, i, 0u);
    }
    stm32_pwm_map_commit(p);
}

uint16_t stm32_pwm_map_readback_us(const stm32_pwm_map_t *p, uint8_t output)
{
    if (p == NULL || p->ready == 0u || output >= p->count) {
        return 0u;
    }
    const uint8_t ch0 = (uint8_t)(p->out[output].channel - 1u);
    const uint32_t ccr = p->out[output].tim->CCR[ch0];
    return (uint16_t)(ccr & 0xFFFFu);
}
