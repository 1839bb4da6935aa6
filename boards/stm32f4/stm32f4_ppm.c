/*
 * stm32f4_ppm.c - PPM input by timer input capture (see stm32f4_ppm.h).
 */
#include "stm32f4_ppm.h"

#include <stddef.h>

static void count32(volatile uint32_t *c)
{
    const uint32_t v = *c;
    if (v != UINT32_MAX) {
        *c = v + 1u;
    }
}

stm32_ppm_status_t stm32_ppm_init(stm32_ppm_t *p, stm32_tim_t *tim, uint8_t channel,
                                  uint32_t timer_clk_hz, stm32_ppm_edge_t edge)
{
    if (p == NULL || tim == NULL) {
        return STM32_PPM_ERR_NULL;
    }
    p->ready = 0u;
    if (channel < 1u || channel > 4u || timer_clk_hz < STM32_PPM_TICK_HZ ||
        timer_clk_hz % STM32_PPM_TICK_HZ != 0u || timer_clk_hz / STM32_PPM_TICK_HZ > 65536u ||
        (edge != STM32_PPM_RISING && edge != STM32_PPM_FALLING)) {
        return STM32_PPM_ERR_RANGE;
    }
    const uint32_t ch0_32 = (uint32_t)channel - 1u; /* channel in 1..4: 0..3 */
    const uint8_t ch0 = (uint8_t)ch0_32;
    const uint32_t psc = timer_clk_hz / STM32_PPM_TICK_HZ - 1u;
    /* Channels 1, 2 live in CCMR1 (low, high byte), 3, 4 in CCMR2. */
    const uint32_t ccmr_shift = 8u * (ch0_32 % 2u);
    const uint32_t icf = TIM_CCMR_ICF_CK_N8;
    const uint32_t ccmr_byte = (icf << TIM_CCMR_ICF_SHIFT) | TIM_CCMR_CCS_TI;
    const uint32_t ccmr = ccmr_byte << ccmr_shift;
    uint32_t ccer = TIM_CCER_CCE(ch0);
    if (edge == STM32_PPM_FALLING) {
        ccer |= TIM_CCER_CCP(ch0);
    }

    p->tim = tim;
    p->ch0 = ch0;
    p->last_capture = 0u;
    p->have_capture = 0u;
    p->wraps = 0u;
    p->in_frame = 0u;
    p->count = 0u;
    p->expected = 0u;
    p->candidate = 0u;
    p->seq = 0u;
    p->seq_read = 0u;
    p->frame_channels = 0u;
    for (unsigned i = 0u; i < STM32_PPM_MAX_CHANNELS; ++i) {
        p->building_us[i] = 0u;
        p->frame_us[i] = 0u;
    }
    p->frames_ok = 0u;
    p->bad_pulse = 0u;
    p->too_many = 0u;
    p->too_few = 0u;
    p->count_changes = 0u;
    p->overcaptures = 0u;
    p->long_gaps = 0u;

    tim->CR1 = 0u;
    tim->DIER = 0u;
    tim->CCER = 0u; /* CCxS is writable only with the channel off */
    tim->SMCR = 0u; /* no slave mode: the counter runs on the internal clock */
    tim->PSC = psc;
    tim->ARR = 0xFFFFu;
    if (ch0 < 2u) {
        tim->CCMR1 = ccmr;
        tim->CCMR2 = 0u;
    } else {
        tim->CCMR1 = 0u;
        tim->CCMR2 = ccmr;
    }
    tim->CCER = ccer;
    tim->EGR = TIM_EGR_UG; /* PSC is buffered: load it now */
    tim->SR = 0u;          /* UG raised UIF */
    tim->DIER = TIM_DIER_CCIE(ch0) | TIM_DIER_UIE;
    tim->CR1 = TIM_CR1_CEN;
    p->ready = 1u;
    return STM32_PPM_OK;
}

static void publish(stm32_ppm_t *p)
{
    p->seq = p->seq + 1u; /* odd: being written */
    for (unsigned i = 0u; i < STM32_PPM_MAX_CHANNELS; ++i) {
        if (i < p->count) {
            p->frame_us[i] = p->building_us[i];
        } else {
            p->frame_us[i] = 0u;
        }
    }
    p->frame_channels = p->count;
    p->seq = p->seq + 1u; /* even: complete */
    count32(&p->frames_ok);
}

/* A frame dropped: wait for the next sync; a new channel count must now be
 * seen in two frames in a row again. */
static void drop_frame(stm32_ppm_t *p, volatile uint32_t *reason)
{
    count32(reason);
    p->in_frame = 0u;
    p->candidate = 0u;
}

/* A sync gap ends the frame being built (if any) and starts the next. */
static void on_sync(stm32_ppm_t *p)
{
    if (p->in_frame != 0u) {
        if (p->count < STM32_PPM_MIN_CHANNELS) {
            count32(&p->too_few);
            p->candidate = 0u; /* "two frames in a row" */
        } else if (p->count == p->expected || p->count == p->candidate) {
            p->expected = p->count;
            p->candidate = 0u;
            publish(p);
        } else {
            count32(&p->count_changes);
            p->candidate = p->count;
        }
    }
    p->in_frame = 1u;
    p->count = 0u;
}

static void on_interval(stm32_ppm_t *p, uint32_t width_us)
{
    if (width_us > STM32_PPM_SYNC_US) {
        on_sync(p);
        return;
    }
    if (p->in_frame == 0u) {
        return; /* before the first sync, or after a dropped frame: wait */
    }
    if (width_us < STM32_PPM_PULSE_MIN_US || width_us > STM32_PPM_PULSE_MAX_US) {
        drop_frame(p, &p->bad_pulse);
        return;
    }
    if (p->count >= STM32_PPM_MAX_CHANNELS) {
        drop_frame(p, &p->too_many);
        return;
    }
    p->building_us[p->count] = (uint16_t)width_us;
    p->count++;
}

static void on_capture(stm32_ppm_t *p, uint16_t value, int lost_edge)
{
    const uint16_t last = p->last_capture;
    const uint8_t wraps = p->wraps;
    const uint8_t had = p->have_capture;
    p->last_capture = value;
    p->have_capture = 1u;
    p->wraps = 0u;
    if (lost_edge != 0) {
        drop_frame(p, &p->overcaptures); /* the interval spans a lost edge */
        return;
    }
    if (had == 0u) {
        return; /* the first edge: nothing to measure from */
    }
    /* Over 16 bits the difference is right whenever the counter wrapped at
     * most once and the value is below the last one (or it did not wrap). */
    const uint32_t diff = (uint32_t)value - (uint32_t)last;
    const uint32_t width_us = diff & 0xFFFFu;
    if (wraps >= 2u || (wraps == 1u && value >= last)) {
        count32(&p->long_gaps);
        on_sync(p); /* 65536 us or more without an edge: longer than any sync */
        return;
    }
    on_interval(p, width_us);
}

static void on_wrap(stm32_ppm_t *p)
{
    if (p->wraps < 2u) {
        p->wraps++;
    }
}

void stm32_ppm_isr(stm32_ppm_t *p)
{
    if (p == NULL || p->ready == 0u) {
        return;
    }
    stm32_tim_t *const t = p->tim;
    const uint32_t sr = t->SR;
    const uint32_t ccif = TIM_SR_CCIF(p->ch0);
    const uint32_t ccof = TIM_SR_CCOF(p->ch0);
    const uint32_t to_clear = sr & (TIM_SR_UIF | ccof);
    if (to_clear != 0u) {
        /* rc_w0: zeros clear the flags seen, ones leave the others alone
         * (a flag raised since the read above stays for the next call). */
        t->SR = TIM_SR_RC_W0_BITS & ~to_clear;
    }
    const uint8_t wrapped = ((sr & TIM_SR_UIF) != 0u) ? 1u : 0u;
    if ((sr & ccif) != 0u) {
        const uint32_t ccr = t->CCR[p->ch0] & 0xFFFFu; /* the read clears CCxIF */
        const uint16_t value = (uint16_t)ccr;
        /* Both pending: a capture in the lower half of the count came after
         * the wrap (the wrap is at most one handler latency old), one in the
         * upper half before it. */
        const uint8_t wrap_first = (wrapped != 0u && value < 0x8000u) ? 1u : 0u;
        if (wrap_first != 0u) {
            on_wrap(p);
        }
        on_capture(p, value, ((sr & ccof) != 0u) ? 1 : 0);
        if (wrapped != 0u && wrap_first == 0u) {
            on_wrap(p);
        }
    } else if (wrapped != 0u) {
        on_wrap(p);
    } else {
        /* neither: a spurious entry */
    }
}

stm32_ppm_status_t stm32_ppm_read_us(stm32_ppm_t *p, uint16_t pulse_us[], uint8_t count)
{
    if (p == NULL || pulse_us == NULL) {
        return STM32_PPM_ERR_NULL;
    }
    if (p->ready == 0u || count > STM32_PPM_MAX_CHANNELS) {
        return STM32_PPM_ERR_RANGE;
    }
    uint16_t copy[STM32_PPM_MAX_CHANNELS];
    uint8_t channels = 0u;
    uint32_t seq = 0u;
    uint8_t got = 0u;
    for (unsigned attempt = 0u; attempt < STM32_PPM_READ_TRIES && got == 0u; ++attempt) {
        seq = p->seq;
        if ((seq & 1u) != 0u) {
            continue; /* only while the handler itself is interrupted: not on one core */
        }
        for (unsigned i = 0u; i < STM32_PPM_MAX_CHANNELS; ++i) {
            copy[i] = p->frame_us[i];
        }
        channels = p->frame_channels;
        got = (p->seq == seq) ? 1u : 0u;
    }
    if (got == 0u) {
        return STM32_PPM_NO_DATA;
    }
    for (uint8_t i = 0u; i < count; ++i) {
        if (i < channels) {
            pulse_us[i] = copy[i];
        } else {
            pulse_us[i] = 0u;
        }
    }
    const stm32_ppm_status_t st = (seq != p->seq_read) ? STM32_PPM_OK : STM32_PPM_NO_DATA;
    p->seq_read = seq;
    return st;
}
