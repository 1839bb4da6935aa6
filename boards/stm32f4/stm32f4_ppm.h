/*
 * stm32f4_ppm.h - a PPM (pulse-position) receiver input on one input-capture
 * channel of a general-purpose timer (TIM2..TIM5, RM0090 section 18).
 *
 * The timer counts 1 us ticks (PSC = f_timer / 1 MHz - 1) over 16 bits
 * (ARR = 0xFFFF, so TIM2/TIM5's 32-bit counters wrap at 16 bits as well)
 * and captures every edge of one polarity. The interrupt handler
 * (stm32_ppm_isr) takes each capture and the width of the interval since
 * the previous one:
 *
 *   > STM32_PPM_SYNC_US (2700 us)              the sync gap: a frame ends, the next starts
 *   STM32_PPM_PULSE_MIN_US .. _MAX_US
 *   (750 .. 2250 us)                           a channel
 *   anything else                              noise: the frame is dropped (counted)
 *                                              and the next sync awaited
 *
 * 2700 us: a channel is at most 2250 us here and a PPM sync gap at least
 * about 3000 us in common encoders (a 22.5 ms frame of 8 channels at
 * 2000 us leaves 6.5 ms); 2700 sits between with room on both sides.
 *
 * A frame is published when it ended with a sync, had STM32_PPM_MIN_CHANNELS
 * .. STM32_PPM_MAX_CHANNELS channels, no bad interval, and the channel count
 * of the last published frame. The last rule matters: a lost edge merges
 * two channels into one interval above 2700 us, which looks like a sync;
 * the channels after it would otherwise be published as channels 1, 2, ...
 * So a new channel count (the first frame after start-up included) is
 * counted and published only when two frames in a row carry it.
 *
 * Intervals longer than the 16-bit counter: the update interrupt (UIE)
 * counts wraps since the last capture, so a signal that stopped and came
 * back after 65.536 ms or more is a sync, not an aliased pulse width.
 *
 * Sharing between the handler and the tick: the handler publishes a frame
 * under a sequence count (odd while it writes); stm32_ppm_read_us copies and
 * retries, at most STM32_PPM_READ_TRIES times, if the handler ran in
 * between (one core, so no barrier is needed: see serial_rx_ring.h).
 *
 * The timer is the driver's alone (its prescaler and period serve nothing
 * else). The pin (alternate function) and the NVIC line are the board's.
 */
#ifndef HT_STM32F4_PPM_H
#define HT_STM32F4_PPM_H

#include <stdint.h>

#include "stm32f4_regs.h"

#define STM32_PPM_TICK_HZ      1000000u /* 1 us per count */
#define STM32_PPM_SYNC_US      2700u    /* an interval above this is the sync gap */
#define STM32_PPM_PULSE_MIN_US 750u
#define STM32_PPM_PULSE_MAX_US 2250u
#define STM32_PPM_MIN_CHANNELS 4u
#define STM32_PPM_MAX_CHANNELS 12u
#define STM32_PPM_READ_TRIES   3u

typedef enum {
    STM32_PPM_OK = 0, /* a new frame since the previous read */
    STM32_PPM_ERR_NULL = 1,
    STM32_PPM_ERR_RANGE = 2, /* bad clock, channel or count: nothing written */
    STM32_PPM_NO_DATA = 3    /* no new frame (the output holds the last one) */
} stm32_ppm_status_t;

typedef enum { STM32_PPM_RISING = 0, STM32_PPM_FALLING = 1 } stm32_ppm_edge_t;

typedef struct {
    stm32_tim_t *tim;
    uint8_t ch0;   /* capture channel - 1 */
    uint8_t ready; /* 1 after a successful init */

    /* the interrupt handler's own */
    uint16_t last_capture;
    uint8_t have_capture;
    uint8_t wraps; /* counter wraps since last_capture, saturating at 2 */
    uint8_t in_frame;
    uint8_t count;
    uint8_t expected;  /* channel count of the last published frame (0: none yet) */
    uint8_t candidate; /* a new count seen once, published if the next frame has it */
    uint16_t building_us[STM32_PPM_MAX_CHANNELS];

    /* published by the handler */
    volatile uint32_t seq; /* odd while a frame is being written */
    volatile uint16_t frame_us[STM32_PPM_MAX_CHANNELS];
    volatile uint8_t frame_channels;

    /* counters, written by the handler only (saturating) */
    volatile uint32_t frames_ok;
    volatile uint32_t bad_pulse;     /* a frame dropped for an interval outside the bands */
    volatile uint32_t too_many;      /* a frame dropped: more than STM32_PPM_MAX_CHANNELS */
    volatile uint32_t too_few;       /* a frame dropped: fewer than STM32_PPM_MIN_CHANNELS */
    volatile uint32_t count_changes; /* a complete frame not published: a new channel count */
    volatile uint32_t overcaptures;  /* CCxOF: an edge lost, the frame dropped */
    volatile uint32_t long_gaps;     /* no edge for 65536 us or more */

    /* the reader's own */
    uint32_t seq_read;
} stm32_ppm_t;

/*
 * Configure and start the timer: input capture on channel (1..4), 1 us
 * counts from timer_clk_hz (a whole number of MHz, 1..65536 MHz; the APB1
 * timers run at 2 x PCLK1 when the APB1 prescaler is not 1, e.g. 84 MHz
 * with PCLK1 = 42 MHz, and at PCLK1 = 16 MHz from reset), edge polarity
 * edge. Written, in order: CR1 = 0, DIER = 0, CCER = 0 (a channel's CCxS
 * may only be written while it is off, section 18.4.7), SMCR = 0, PSC, ARR
 * = 0xFFFF, CCMR1/CCMR2 (this channel's byte: CCxS = 01, ICxF = 0011, the
 * rest 0), CCER = CCxE (| CCxP for falling), EGR = UG (loads PSC), SR = 0,
 * DIER = CCxIE | UIE, CR1 = CEN. Bad arguments write no register.
 */
stm32_ppm_status_t stm32_ppm_init(stm32_ppm_t *p, stm32_tim_t *tim, uint8_t channel,
                                  uint32_t timer_clk_hz, stm32_ppm_edge_t edge);

/* The timer's interrupt handler body (capture and update). Bounded: a few
 * register accesses and at most one frame copy. */
void stm32_ppm_isr(stm32_ppm_t *p);

/*
 * The last published frame's channels [0, count) in microseconds; channels
 * the frame did not carry read 0, as do all before the first frame.
 * STM32_PPM_OK when the frame is new since the previous call,
 * STM32_PPM_NO_DATA when not (or when the handler kept rewriting it for
 * STM32_PPM_READ_TRIES copies: pulse_us is then untouched),
 * STM32_PPM_ERR_RANGE for count > STM32_PPM_MAX_CHANNELS or before init.
 */
stm32_ppm_status_t stm32_ppm_read_us(stm32_ppm_t *p, uint16_t pulse_us[], uint8_t count);

#endif /* HT_STM32F4_PPM_H */
