/*
 * dspic33_oc_pwm.h - servo PWM on the dsPIC33FJ output-compare modules in
 * PWM mode, all eight clocked by one 16-bit timer (Timer2 or Timer3).
 *
 * In PWM mode the OCx pin goes high when the timer rolls over (TMRy = PRy)
 * and low when TMRy reaches OCxR; OCxR is reloaded from OCxRS at each
 * rollover. So the pulse is OCxRS timer counts long and a new OCxRS takes
 * effect at the start of the next frame.
 *
 * Resolution: one timer count = prescale / Fcy. The driver picks the
 * smallest prescaler (1, 8, 64, 256) whose frame fits 16 bits: at Fcy =
 * 40 MHz and 50 Hz that is 1:64, 1.6 us per count; at 400 Hz 1:8, 0.2 us.
 *
 * State lives in a caller-owned dspic_pwm_t; the SFR blocks are passed by
 * pointer, so host tests run this on fakes.
 */
#ifndef HT_DSPIC33_OC_PWM_H
#define HT_DSPIC33_OC_PWM_H

#include <stdint.h>

#include "dspic33fj_regs.h"

#define DSPIC_PWM_HZ_MIN 50u
#define DSPIC_PWM_HZ_MAX 400u
#define DSPIC_FCY_HZ_MIN 1000000u
#define DSPIC_FCY_HZ_MAX 70000000u /* dsPIC33EP's top; the FJ stops at 40 MHz */
/* commit() will not start writing within this many instruction cycles of a
 * frame boundary (writing 8 OCxRS takes well under it). */
#define DSPIC_PWM_GUARD_TCY    64u
#define DSPIC_PWM_COMMIT_POLLS 2000u /* bound on the wait for the window to pass */

typedef enum {
    DSPIC_PWM_OK = 0,
    DSPIC_PWM_ERR_NULL = 1,
    DSPIC_PWM_ERR_RANGE = 2, /* bad Fcy, rate, timer or channel: nothing written */
    DSPIC_PWM_CLAMPED = 3,   /* pulse longer than the frame: a full frame staged */
    DSPIC_PWM_LATE = 4       /* commit: the guard window never passed (timer
                                stopped?); written anyway */
} dspic_pwm_status_t;

typedef struct {
    dspic_tmr23_t *tmr;
    dspic_oc_t *oc;         /* OC1..OC8, consecutive */
    uint8_t timer;          /* 2 or 3 */
    uint16_t prescale;      /* 1, 8, 64 or 256 */
    uint16_t period_counts; /* PRy + 1 */
    uint16_t guard_counts;  /* commit's guard window before PRy */
    uint32_t fcy_khz;
    uint16_t staged[DSPIC_OC_COUNT]; /* OCxRS values waiting for commit */
    uint8_t ready;
} dspic_pwm_t;

/*
 * Stop the timer, put OC1..OC8 in PWM mode on it with start_us, set the
 * period, start the timer. timer is 2 or 3. Bad arguments write nothing.
 */
dspic_pwm_status_t dspic_pwm_init(dspic_pwm_t *pwm, dspic_tmr23_t *tmr, dspic_oc_t *oc,
                                  uint8_t timer, uint32_t fcy_hz, uint16_t frame_hz,
                                  uint16_t start_us);

/* Timer counts for a pulse: round(pulse_us * Fcy / (prescale * 1e6)),
 * clamped to the frame (PRy + 1 counts would be a constant high). */
uint16_t dspic_pwm_counts(const dspic_pwm_t *pwm, uint16_t pulse_us);

/* Stage a pulse (nothing is written to the SFRs until commit). */
dspic_pwm_status_t dspic_pwm_set_us(dspic_pwm_t *pwm, uint8_t channel, uint16_t pulse_us);

/*
 * Write every staged OCxRS in one burst, outside the guard window before the
 * frame boundary, so all eight take effect at the same rollover.
 */
dspic_pwm_status_t dspic_pwm_commit(dspic_pwm_t *pwm);

#endif /* HT_DSPIC33_OC_PWM_H */
