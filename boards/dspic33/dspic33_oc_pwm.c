/*
 * dspic33_oc_pwm.c - see dspic33_oc_pwm.h. Written for a 16-bit int (XC16):
 * every product is formed in uint32_t explicitly.
 */
#include "dspic33_oc_pwm.h"

#include <stddef.h>

static volatile uint16_t *timer_count(const dspic_pwm_t *pwm)
{
    return (pwm->timer == 2u) ? &pwm->tmr->TMR2 : &pwm->tmr->TMR3;
}

dspic_pwm_status_t dspic_pwm_init(dspic_pwm_t *pwm, dspic_tmr23_t *tmr, dspic_oc_t *oc,
                                  uint8_t timer, uint32_t fcy_hz, uint16_t frame_hz,
                                  uint16_t start_us)
{
    static const uint16_t prescales[4] = {1u, 8u, 64u, 256u}; /* index = TCKPS */
    if (pwm == NULL || tmr == NULL || oc == NULL) {
        return DSPIC_PWM_ERR_NULL;
    }
    pwm->ready = 0u;
    if ((timer != 2u && timer != 3u) || fcy_hz < DSPIC_FCY_HZ_MIN || fcy_hz > DSPIC_FCY_HZ_MAX ||
        frame_hz < DSPIC_PWM_HZ_MIN || frame_hz > DSPIC_PWM_HZ_MAX) {
        return DSPIC_PWM_ERR_RANGE;
    }
    /* The smallest prescaler whose frame fits the 16-bit period register:
     * the finest resolution the clock allows. */
    uint16_t tckps = 0u;
    uint32_t counts = 0u;
    for (tckps = 0u; tckps < 4u; ++tckps) {
        const uint32_t div = (uint32_t)prescales[tckps] * frame_hz;
        counts = (fcy_hz + div / 2u) / div;
        if (counts <= 65535u) {
            break;
        }
    }
    /* (A frame of exactly 65536 counts moves on to the next prescaler, so
     * period_counts always fits 16 bits.) */
    if (tckps == 4u || counts < 2u) {
        return DSPIC_PWM_ERR_RANGE;
    }
    pwm->tmr = tmr;
    pwm->oc = oc;
    pwm->timer = timer;
    pwm->prescale = prescales[tckps];
    pwm->period_counts = (uint16_t)counts;
    /* Pulse widths are converted with Fcy in whole kHz (32-bit products on a
     * 16-bit core); the rounding costs < 13 ppm at 40 MHz. */
    pwm->fcy_khz = (fcy_hz + 500u) / 1000u;
    pwm->guard_counts = (uint16_t)(DSPIC_PWM_GUARD_TCY / pwm->prescale + 1u);
    pwm->ready = 1u;

    const uint16_t tcon = (uint16_t)(tckps << DSPIC_TCON_TCKPS_SHIFT);
    const uint16_t start = dspic_pwm_counts(pwm, start_us);
    if (timer == 2u) {
        tmr->T2CON = 0u; /* stopped, 16-bit, internal clock */
        tmr->TMR2 = 0u;
        tmr->PR2 = (uint16_t)(counts - 1u);
    } else {
        tmr->T3CON = 0u;
        tmr->TMR3 = 0u;
        tmr->PR3 = (uint16_t)(counts - 1u);
    }
    const uint16_t octsel = (timer == 3u) ? (uint16_t)DSPIC_OCCON_OCTSEL : 0u;
    const uint16_t occon = (uint16_t)(DSPIC_OCCON_OCM_PWM | octsel);
    for (uint8_t i = 0; i < DSPIC_OC_COUNT; ++i) {
        oc[i].OCCON = DSPIC_OCCON_OCM_OFF; /* mode changes go through "off" */
        oc[i].OCR = start;                 /* the first frame's duty */
        oc[i].OCRS = start;                /* and every frame's after it */
        oc[i].OCCON = occon;
        pwm->staged[i] = start;
    }
    if (timer == 2u) {
        tmr->T2CON = (uint16_t)(tcon | DSPIC_TCON_TON);
    } else {
        tmr->T3CON = (uint16_t)(tcon | DSPIC_TCON_TON);
    }
    return DSPIC_PWM_OK;
}

/* Counts for a pulse and whether it had to be clamped to the frame. */
static uint16_t counts_of(const dspic_pwm_t *pwm, uint16_t pulse_us, int *clamped)
{
    /* No frame is longer than 20000 us (>= 50 Hz): clamping the pulse there
     * first keeps us * fcy_khz below 20000 * 70000 = 1.4e9 < 2^32. */
    uint32_t us = pulse_us;
    *clamped = 0;
    if (us > 1000000u / DSPIC_PWM_HZ_MIN) {
        us = 1000000u / DSPIC_PWM_HZ_MIN;
        *clamped = 1;
    }
    const uint32_t div = (uint32_t)pwm->prescale * 1000u;
    uint32_t c = (us * pwm->fcy_khz + div / 2u) / div;
    const uint32_t top = (uint32_t)pwm->period_counts - 1u; /* = PRy: never 100 % */
    if (c > top) {
        c = top;
        *clamped = 1;
    }
    return (uint16_t)c;
}

uint16_t dspic_pwm_counts(const dspic_pwm_t *pwm, uint16_t pulse_us)
{
    if (pwm == NULL || !pwm->ready) {
        return 0u;
    }
    int clamped;
    return counts_of(pwm, pulse_us, &clamped);
}

dspic_pwm_status_t dspic_pwm_set_us(dspic_pwm_t *pwm, uint8_t channel, uint16_t pulse_us)
{
    if (pwm == NULL) {
        return DSPIC_PWM_ERR_NULL;
    }
    if (!pwm->ready || channel >= DSPIC_OC_COUNT) {
        return DSPIC_PWM_ERR_RANGE;
    }
    int clamped;
    pwm->staged[channel] = counts_of(pwm, pulse_us, &clamped);
    return clamped ? DSPIC_PWM_CLAMPED : DSPIC_PWM_OK;
}

dspic_pwm_status_t dspic_pwm_commit(dspic_pwm_t *pwm)
{
    if (pwm == NULL) {
        return DSPIC_PWM_ERR_NULL;
    }
    if (!pwm->ready) {
        return DSPIC_PWM_ERR_RANGE;
    }
    /* OCxR reloads from OCxRS at the rollover: if the burst straddled one,
     * some channels would change a frame before the others. */
    const volatile uint16_t *tmr = timer_count(pwm);
    const uint16_t last = (uint16_t)(pwm->period_counts - 1u);
    const uint16_t window = (last > pwm->guard_counts) ? (uint16_t)(last - pwm->guard_counts) : 0u;
    dspic_pwm_status_t st = DSPIC_PWM_LATE;
    for (uint16_t n = 0; n < DSPIC_PWM_COMMIT_POLLS; ++n) {
        if (*tmr < window) {
            st = DSPIC_PWM_OK;
            break;
        }
    }
    for (uint8_t i = 0; i < DSPIC_OC_COUNT; ++i) {
        pwm->oc[i].OCRS = pwm->staged[i];
    }
    return st;
}
