/*
 * test_stm32f4_ppm.c - the PPM input-capture driver on a fake timer block.
 *
 * Register values, worked from RM0090 section 18.4 (TIM2..TIM5):
 *   84 MHz timer clock (APB1 at 42 MHz, prescaler 2: timers at 2 x PCLK1):
 *     PSC = 84 - 1 = 83 = 0x53 -> 1 us per count; ARR = 0xFFFF
 *   16 MHz (reset HSI): PSC = 15 = 0xF
 *   channel 1, rising edges:
 *     CCMR1 = IC1F 0011 (bits 7:4) | CC1S 01 (bits 1:0) = 0x31, CCMR2 = 0
 *     CCER  = CC1E (bit 0) = 0x1; falling: | CC1P (bit 1) = 0x3
 *     DIER  = CC1IE (bit 1) | UIE (bit 0) = 0x3
 *   channel 4: CCMR2 = 0x31 << 8 = 0x3100, CCMR1 = 0; CCER = CC4E (bit 12)
 *     = 0x1000, falling | CC4P (bit 13) = 0x3000; DIER = CC4IE (bit 4) | UIE
 *     = 0x11
 *   EGR = UG = 0x1; CR1 = CEN = 0x1; SR = 0 after init
 *   SR write to clear UIF only (rc_w0): 0x1E5F & ~0x1 = 0x1E5E
 * Timing: edges at absolute times t (us); the fake counter reads t mod 65536
 * and raises the update flag at every multiple of 65536.
 * Bands: width > 2700 sync; 750..2250 a channel; else a bad pulse.
 */
#include "unity.h"

#include "stm32f4_ppm.h"

#include <string.h>

static stm32_tim_t tim;
static stm32_ppm_t ppm;
static uint32_t clock_us; /* the fake timer's absolute time of the last event */

void setUp(void)
{
    memset((void *)&tim, 0, sizeof tim);
    memset(&ppm, 0, sizeof ppm);
    clock_us = 0u;
}

void tearDown(void) {}

/* Move the fake to time t: each counter wrap on the way raises UIF and the
 * handler runs for it; then an edge at t is captured. */
static void edge_at(uint32_t t)
{
    while ((clock_us >> 16) != (t >> 16)) {
        clock_us = ((clock_us >> 16) + 1u) << 16;
        tim.SR = TIM_SR_UIF;
        stm32_ppm_isr(&ppm);
    }
    clock_us = t;
    tim.CCR[ppm.ch0] = t & 0xFFFFu;
    tim.SR = TIM_SR_CCIF(ppm.ch0);
    stm32_ppm_isr(&ppm);
}

/* An edge at t whose interrupt comes late, after the counter wrapped: UIF
 * and CCxIF pending together in one handler call. */
static void edge_with_pending_wrap(uint32_t t)
{
    clock_us = t;
    tim.CCR[ppm.ch0] = t & 0xFFFFu;
    tim.SR = TIM_SR_CCIF(ppm.ch0) | TIM_SR_UIF;
    stm32_ppm_isr(&ppm);
}

static const uint16_t W8[8] = {1000u, 1100u, 1200u, 1500u, 1600u, 1700u, 1800u, 2000u};

/* Channel edges of one frame starting at t (the edge ending the sync), the
 * sync after it sync_us long. Returns the time of the next frame's first
 * edge. */
static uint32_t frame_at(uint32_t t, const uint16_t *w, unsigned n, uint32_t sync_us)
{
    for (unsigned i = 0; i < n; ++i) {
        t += w[i];
        edge_at(t);
    }
    t += sync_us;
    edge_at(t);
    return t;
}

/* The first edge (nothing to measure from) and a sync 5000 us later. */
static uint32_t lead_in(uint32_t t)
{
    edge_at(t);
    edge_at(t + 5000u);
    return t + 5000u;
}

static void init_ch1_84mhz(void)
{
    TEST_ASSERT_EQUAL(STM32_PPM_OK, stm32_ppm_init(&ppm, &tim, 1u, 84000000u, STM32_PPM_RISING));
}

static void test_init_registers_ch1(void)
{
    tim.CCMR2 = 0x6868u; /* left from PWM: cleared */
    tim.SR = 0x1Fu;
    init_ch1_84mhz();
    TEST_ASSERT_EQUAL_HEX32(0x53u, tim.PSC);
    TEST_ASSERT_EQUAL_HEX32(0xFFFFu, tim.ARR);
    TEST_ASSERT_EQUAL_HEX32(0x31u, tim.CCMR1);
    TEST_ASSERT_EQUAL_HEX32(0x0u, tim.CCMR2);
    TEST_ASSERT_EQUAL_HEX32(0x1u, tim.CCER);
    TEST_ASSERT_EQUAL_HEX32(0x3u, tim.DIER);
    TEST_ASSERT_EQUAL_HEX32(0x1u, tim.EGR);
    TEST_ASSERT_EQUAL_HEX32(0x0u, tim.SR);
    TEST_ASSERT_EQUAL_HEX32(0x1u, tim.CR1);
    TEST_ASSERT_EQUAL_HEX32(0x0u, tim.SMCR);
    TEST_ASSERT_EQUAL_UINT8(1u, ppm.ready);
    TEST_ASSERT_EQUAL(STM32_PPM_OK, stm32_ppm_init(&ppm, &tim, 1u, 16000000u, STM32_PPM_FALLING));
    TEST_ASSERT_EQUAL_HEX32(0xFu, tim.PSC);
    TEST_ASSERT_EQUAL_HEX32(0x3u, tim.CCER);
}

static void test_init_registers_ch4(void)
{
    tim.CCMR1 = 0x6868u;
    TEST_ASSERT_EQUAL(STM32_PPM_OK, stm32_ppm_init(&ppm, &tim, 4u, 84000000u, STM32_PPM_RISING));
    TEST_ASSERT_EQUAL_HEX32(0x0u, tim.CCMR1);
    TEST_ASSERT_EQUAL_HEX32(0x3100u, tim.CCMR2);
    TEST_ASSERT_EQUAL_HEX32(0x1000u, tim.CCER);
    TEST_ASSERT_EQUAL_HEX32(0x11u, tim.DIER);
    TEST_ASSERT_EQUAL(STM32_PPM_OK, stm32_ppm_init(&ppm, &tim, 4u, 84000000u, STM32_PPM_FALLING));
    TEST_ASSERT_EQUAL_HEX32(0x3000u, tim.CCER);
    TEST_ASSERT_EQUAL(STM32_PPM_OK, stm32_ppm_init(&ppm, &tim, 2u, 84000000u, STM32_PPM_RISING));
    TEST_ASSERT_EQUAL_HEX32(0x3100u, tim.CCMR1);
    TEST_ASSERT_EQUAL_HEX32(0x10u, tim.CCER);
    TEST_ASSERT_EQUAL_HEX32(0x5u, tim.DIER);
}

static void test_init_refused(void)
{
    tim.CR1 = 0x1234u;
    TEST_ASSERT_EQUAL(STM32_PPM_ERR_NULL, stm32_ppm_init(NULL, &tim, 1u, 84000000u, 0));
    TEST_ASSERT_EQUAL(STM32_PPM_ERR_NULL, stm32_ppm_init(&ppm, NULL, 1u, 84000000u, 0));
    TEST_ASSERT_EQUAL(STM32_PPM_ERR_RANGE, stm32_ppm_init(&ppm, &tim, 0u, 84000000u, 0));
    TEST_ASSERT_EQUAL(STM32_PPM_ERR_RANGE, stm32_ppm_init(&ppm, &tim, 5u, 84000000u, 0));
    TEST_ASSERT_EQUAL(STM32_PPM_ERR_RANGE, stm32_ppm_init(&ppm, &tim, 1u, 84500000u, 0));
    TEST_ASSERT_EQUAL(STM32_PPM_ERR_RANGE, stm32_ppm_init(&ppm, &tim, 1u, 500000u, 0));
    TEST_ASSERT_EQUAL(STM32_PPM_ERR_RANGE,
                      stm32_ppm_init(&ppm, &tim, 1u, 84000000u, (stm32_ppm_edge_t)2));
    TEST_ASSERT_EQUAL_HEX32(0x1234u, tim.CR1);
    TEST_ASSERT_EQUAL_HEX32(0x0u, tim.PSC);
    TEST_ASSERT_EQUAL_UINT8(0u, ppm.ready);
    uint16_t out[8];
    TEST_ASSERT_EQUAL(STM32_PPM_ERR_RANGE, stm32_ppm_read_us(&ppm, out, 8u));
    stm32_ppm_isr(&ppm); /* not ready: nothing */
    stm32_ppm_isr(NULL);
}

static void test_frames_published(void)
{
    uint16_t out[10];
    init_ch1_84mhz();
    memset(out, 0xAA, sizeof out);
    TEST_ASSERT_EQUAL(STM32_PPM_NO_DATA, stm32_ppm_read_us(&ppm, out, 8u));
    TEST_ASSERT_EQUAL_UINT16(0u, out[0]); /* nothing yet: 0 */
    uint32_t t = 1000u;
    edge_at(t); /* the first edge: nothing to measure */
    t += 5000u;
    edge_at(t); /* a sync */
    t = frame_at(t, W8, 8u, 6000u);
    /* the first complete frame only announces its channel count */
    TEST_ASSERT_EQUAL_UINT32(1u, ppm.count_changes);
    TEST_ASSERT_EQUAL(STM32_PPM_NO_DATA, stm32_ppm_read_us(&ppm, out, 8u));
    t = frame_at(t, W8, 8u, 6000u);
    TEST_ASSERT_EQUAL(STM32_PPM_OK, stm32_ppm_read_us(&ppm, out, 10u));
    TEST_ASSERT_EQUAL_UINT16_ARRAY(W8, out, 8);
    TEST_ASSERT_EQUAL_UINT16(0u, out[8]); /* beyond the frame */
    TEST_ASSERT_EQUAL_UINT16(0u, out[9]);
    memset(out, 0, sizeof out);
    TEST_ASSERT_EQUAL(STM32_PPM_NO_DATA, stm32_ppm_read_us(&ppm, out, 8u));
    TEST_ASSERT_EQUAL_UINT16_ARRAY(W8, out, 8); /* the last frame held */
    (void)frame_at(t, W8, 8u, 6000u);
    TEST_ASSERT_EQUAL(STM32_PPM_OK, stm32_ppm_read_us(&ppm, out, 4u));
    TEST_ASSERT_EQUAL_UINT32(2u, ppm.frames_ok);
    TEST_ASSERT_EQUAL_UINT32(0u, ppm.bad_pulse);
    TEST_ASSERT_EQUAL(STM32_PPM_ERR_RANGE, stm32_ppm_read_us(&ppm, out, 13u));
    TEST_ASSERT_EQUAL(STM32_PPM_ERR_NULL, stm32_ppm_read_us(&ppm, NULL, 4u));
}

/* The next multiple of 65536 after t, with room for a sync before it. */
static uint32_t wrap_after(uint32_t *t)
{
    uint32_t w = ((*t >> 16) + 1u) << 16;
    while (w - *t < 4000u) {
        *t = frame_at(*t, W8, 8u, 6000u);
        w = ((*t >> 16) + 1u) << 16;
    }
    return w;
}

/* Frames across the 16-bit wrap, the wrap's interrupt taken on its own. */
static void test_wrap_around(void)
{
    uint16_t out[8];
    init_ch1_84mhz();
    uint32_t t = lead_in(65536u - 14000u); /* the sync ends at 65536 - 9000 */
    t = frame_at(t, W8, 8u, 7000u);        /* channel 7 ends past 65536 */
    TEST_ASSERT_TRUE(t > 65536u);
    t = frame_at(t, W8, 8u, 7000u);
    TEST_ASSERT_EQUAL_UINT32(0u, ppm.bad_pulse);
    TEST_ASSERT_EQUAL(STM32_PPM_OK, stm32_ppm_read_us(&ppm, out, 8u));
    TEST_ASSERT_EQUAL_UINT16_ARRAY(W8, out, 8);
}

/* Channel 1 ends 500 us after a wrap and its interrupt comes with UIF
 * pending: the capture (0x01F4, lower half) came after the wrap, so the wrap
 * is counted first and the width is 1500 us. */
static void test_wrap_before_capture(void)
{
    uint16_t out[8];
    init_ch1_84mhz();
    uint32_t t = lead_in(1000u);
    t = frame_at(t, W8, 8u, 6000u);
    t = frame_at(t, W8, 8u, 6000u);
    (void)stm32_ppm_read_us(&ppm, out, 8u);
    const uint32_t w = wrap_after(&t);
    const uint32_t frames = ppm.frames_ok;
    edge_at(w - 1000u); /* a sync */
    edge_with_pending_wrap(w + 500u);
    TEST_ASSERT_EQUAL_HEX32(0x01F4u, tim.CCR[0]);
    uint32_t u = w + 500u;
    for (unsigned i = 1; i < 8u; ++i) {
        u += W8[i];
        edge_at(u);
    }
    edge_at(u + 6000u);
    TEST_ASSERT_EQUAL_UINT32(0u, ppm.bad_pulse);
    TEST_ASSERT_EQUAL_UINT32(0u, ppm.long_gaps);
    TEST_ASSERT_EQUAL_UINT32(frames + 1u, ppm.frames_ok);
    TEST_ASSERT_EQUAL(STM32_PPM_OK, stm32_ppm_read_us(&ppm, out, 8u));
    TEST_ASSERT_EQUAL_UINT16(1500u, out[0]);
    TEST_ASSERT_EQUAL_UINT16_ARRAY(&W8[1], &out[1], 7);
}

/* Channel 8 ends 100 us before a wrap and its interrupt comes after it,
 * UIF pending: the capture (0xFF9C, upper half) came first, so its width is
 * measured before the wrap is counted; the sync after it spans the wrap. */
static void test_wrap_after_capture(void)
{
    uint16_t out[8];
    init_ch1_84mhz();
    uint32_t t = lead_in(1000u);
    t = frame_at(t, W8, 8u, 6000u);
    t = frame_at(t, W8, 8u, 6000u);
    (void)stm32_ppm_read_us(&ppm, out, 8u);
    const uint32_t frames = ppm.frames_ok;
    uint32_t w = wrap_after(&t);
    if (w - t < 11900u + 2800u) { /* room for a sync and 7 channels */
        t = frame_at(t, W8, 8u, 6000u);
        w = wrap_after(&t);
    }
    uint32_t u = w - 100u - 11900u; /* 11900 = the sum of W8 */
    edge_at(u);                     /* a sync */
    for (unsigned i = 0; i < 7u; ++i) {
        u += W8[i];
        edge_at(u);
    }
    u += W8[7];
    TEST_ASSERT_EQUAL_UINT32(w - 100u, u);
    edge_with_pending_wrap(u);
    TEST_ASSERT_EQUAL_HEX32(0xFF9Cu, tim.CCR[0]);
    clock_us = w; /* that call took the wrap */
    edge_at(u + 6000u);
    TEST_ASSERT_EQUAL_UINT32(0u, ppm.bad_pulse);
    TEST_ASSERT_EQUAL_UINT32(0u, ppm.long_gaps);
    TEST_ASSERT_EQUAL_UINT32(frames + 1u, ppm.frames_ok);
    TEST_ASSERT_EQUAL(STM32_PPM_OK, stm32_ppm_read_us(&ppm, out, 8u));
    TEST_ASSERT_EQUAL_UINT16_ARRAY(W8, out, 8);
}

/* Joining mid-frame: the channels before the first sync are ignored. */
static void test_sync_in_the_middle(void)
{
    uint16_t out[8];
    init_ch1_84mhz();
    uint32_t t = 3000u;
    edge_at(t);
    for (unsigned i = 5; i < 8u; ++i) { /* the tail of a frame */
        t += W8[i];
        edge_at(t);
    }
    t += 8000u;
    edge_at(t); /* the sync */
    t = frame_at(t, W8, 8u, 8000u);
    t = frame_at(t, W8, 8u, 8000u);
    TEST_ASSERT_EQUAL_UINT32(0u, ppm.bad_pulse);
    TEST_ASSERT_EQUAL_UINT32(0u, ppm.too_few);
    TEST_ASSERT_EQUAL_UINT32(1u, ppm.frames_ok);
    TEST_ASSERT_EQUAL(STM32_PPM_OK, stm32_ppm_read_us(&ppm, out, 8u));
    TEST_ASSERT_EQUAL_UINT16_ARRAY(W8, out, 8);
}

/* A glitch splits channel 3 (1200 us) into 300 + 900 us: the frame is
 * dropped and counted; the next frame is published (same channel count). */
static void test_noise_drops_frame(void)
{
    uint16_t out[8];
    init_ch1_84mhz();
    uint32_t t = lead_in(1000u);
    t = frame_at(t, W8, 8u, 6000u);
    t = frame_at(t, W8, 8u, 6000u);
    TEST_ASSERT_EQUAL(STM32_PPM_OK, stm32_ppm_read_us(&ppm, out, 8u));
    const uint16_t noisy[9] = {1000u, 1100u, 300u, 900u, 1500u, 1600u, 1700u, 1800u, 2000u};
    t = frame_at(t, noisy, 9u, 6000u);
    TEST_ASSERT_EQUAL_UINT32(1u, ppm.bad_pulse);
    TEST_ASSERT_EQUAL(STM32_PPM_NO_DATA, stm32_ppm_read_us(&ppm, out, 8u));
    (void)frame_at(t, W8, 8u, 6000u);
    TEST_ASSERT_EQUAL(STM32_PPM_OK, stm32_ppm_read_us(&ppm, out, 8u));
    TEST_ASSERT_EQUAL_UINT16_ARRAY(W8, out, 8);
    TEST_ASSERT_EQUAL_UINT32(2u, ppm.frames_ok);
}

/* The band edges: 750 and 2250 are channels, 749, 2251 and 2700 bad;
 * 2701 is a sync. */
static void test_band_edges(void)
{
    uint16_t out[8];
    init_ch1_84mhz();
    const uint16_t edges_ok[4] = {750u, 2250u, 750u, 2250u};
    uint32_t t = lead_in(1000u);
    t = frame_at(t, edges_ok, 4u, 2701u);
    t = frame_at(t, edges_ok, 4u, 2701u);
    TEST_ASSERT_EQUAL(STM32_PPM_OK, stm32_ppm_read_us(&ppm, out, 4u));
    TEST_ASSERT_EQUAL_UINT16_ARRAY(edges_ok, out, 4);
    const uint16_t bad[3] = {749u, 2251u, 2700u};
    for (unsigned k = 0; k < 3u; ++k) {
        const uint16_t w[4] = {1500u, bad[k], 1500u, 1500u};
        t = frame_at(t, w, 4u, 2701u);
        TEST_ASSERT_EQUAL_UINT32(k + 1u, ppm.bad_pulse);
    }
    TEST_ASSERT_EQUAL(STM32_PPM_NO_DATA, stm32_ppm_read_us(&ppm, out, 4u));
}

/* 13 channels: too many, dropped; 12 would be taken (as a new count). */
static void test_too_many_channels(void)
{
    uint16_t out[12];
    uint16_t w13[13];
    for (unsigned i = 0; i < 13u; ++i) {
        w13[i] = (uint16_t)(1000u + 50u * i);
    }
    init_ch1_84mhz();
    uint32_t t = lead_in(1000u);
    t = frame_at(t, w13, 13u, 4000u);
    t = frame_at(t, w13, 13u, 4000u);
    TEST_ASSERT_EQUAL_UINT32(2u, ppm.too_many);
    TEST_ASSERT_EQUAL_UINT32(0u, ppm.frames_ok);
    t = frame_at(t, w13, 12u, 4000u);
    t = frame_at(t, w13, 12u, 4000u);
    TEST_ASSERT_EQUAL(STM32_PPM_OK, stm32_ppm_read_us(&ppm, out, 12u));
    TEST_ASSERT_EQUAL_UINT16_ARRAY(w13, out, 12);
}

/* A lost edge merges channels 3 and 4 (1200 + 1500 = 2700 ... + 1600 with
 * channel 5 lost too, 4300 us: a false sync). Channels 6..8 then look like
 * a frame of their own and must not be published as channels 1..3, nor
 * channels 1, 2 as a frame. */
static void test_lost_edge_false_sync(void)
{
    uint16_t out[8];
    init_ch1_84mhz();
    uint32_t t = lead_in(1000u);
    t = frame_at(t, W8, 8u, 6000u);
    t = frame_at(t, W8, 8u, 6000u);
    TEST_ASSERT_EQUAL(STM32_PPM_OK, stm32_ppm_read_us(&ppm, out, 8u));
    /* 1000, 1100, [1200+1500+1600 = 4300: sync], 1700, 1800, 2000, 1000, 1100 */
    const uint16_t broken[8] = {1000u, 1100u, 4300u, 1700u, 1800u, 2000u, 1000u, 1100u};
    t = frame_at(t, broken, 8u, 6000u);
    TEST_ASSERT_EQUAL_UINT32(1u, ppm.too_few); /* 1000, 1100 */
    /* 1700 .. 1100: 5 channels, a new count: not published */
    TEST_ASSERT_EQUAL_UINT32(2u, ppm.count_changes); /* start-up, and this one */
    TEST_ASSERT_EQUAL_UINT32(1u, ppm.frames_ok);
    TEST_ASSERT_EQUAL(STM32_PPM_NO_DATA, stm32_ppm_read_us(&ppm, out, 8u));
    TEST_ASSERT_EQUAL_UINT16_ARRAY(W8, out, 8);
    (void)frame_at(t, W8, 8u, 6000u); /* back: published at once */
    TEST_ASSERT_EQUAL(STM32_PPM_OK, stm32_ppm_read_us(&ppm, out, 8u));
    TEST_ASSERT_EQUAL_UINT16_ARRAY(W8, out, 8);
}

/* The signal stops for 65536 + 1500 us: a 16-bit difference alone would
 * read 1500 us, a channel; counted wraps make it a long gap (a sync). */
static void test_long_gap_not_aliased(void)
{
    uint16_t out[8];
    init_ch1_84mhz();
    uint32_t t = lead_in(1000u);
    t = frame_at(t, W8, 8u, 6000u);
    t = frame_at(t, W8, 8u, 6000u);
    TEST_ASSERT_EQUAL(STM32_PPM_OK, stm32_ppm_read_us(&ppm, out, 8u));
    /* three channels, then silence */
    for (unsigned i = 0; i < 3u; ++i) {
        t += W8[i];
        edge_at(t);
    }
    t += 65536u + 1500u;
    edge_at(t);
    TEST_ASSERT_EQUAL_UINT32(1u, ppm.long_gaps);
    TEST_ASSERT_EQUAL_UINT32(1u, ppm.too_few); /* the 3 channels before the gap */
    TEST_ASSERT_EQUAL_UINT32(0u, ppm.bad_pulse);
    /* the gap was a sync: the frame after it is whole */
    t = frame_at(t, W8, 8u, 6000u);
    TEST_ASSERT_EQUAL(STM32_PPM_OK, stm32_ppm_read_us(&ppm, out, 8u));
    TEST_ASSERT_EQUAL_UINT16_ARRAY(W8, out, 8);
    /* exactly one wrap, value above the last: 65536 + 200 us */
    t += 65536u + 200u;
    edge_at(t);
    TEST_ASSERT_EQUAL_UINT32(2u, ppm.long_gaps);
}

static void test_overcapture_drops_frame(void)
{
    uint16_t out[8];
    init_ch1_84mhz();
    uint32_t t = lead_in(1000u);
    t = frame_at(t, W8, 8u, 6000u);
    t = frame_at(t, W8, 8u, 6000u);
    (void)stm32_ppm_read_us(&ppm, out, 8u);
    t += 1000u;
    edge_at(t);
    t += 1100u;
    clock_us = t;
    tim.CCR[0] = t & 0xFFFFu;
    tim.SR = TIM_SR_CCIF(0u) | TIM_SR_CCOF(0u);
    stm32_ppm_isr(&ppm);
    TEST_ASSERT_EQUAL_UINT32(1u, ppm.overcaptures);
    TEST_ASSERT_EQUAL_HEX32(0x1E5Fu & ~0x200u, tim.SR); /* CC1OF cleared, the rest left */
    for (unsigned i = 2; i < 8u; ++i) {
        t += W8[i];
        edge_at(t);
    }
    t += 6000u;
    edge_at(t);
    TEST_ASSERT_EQUAL(STM32_PPM_NO_DATA, stm32_ppm_read_us(&ppm, out, 8u));
    (void)frame_at(t, W8, 8u, 6000u);
    TEST_ASSERT_EQUAL(STM32_PPM_OK, stm32_ppm_read_us(&ppm, out, 8u));
}

static void test_update_flag_cleared(void)
{
    init_ch1_84mhz();
    tim.SR = TIM_SR_UIF;
    stm32_ppm_isr(&ppm);
    TEST_ASSERT_EQUAL_HEX32(0x1E5Eu, tim.SR);
    TEST_ASSERT_EQUAL_UINT8(1u, ppm.wraps);
    tim.SR = TIM_SR_UIF;
    stm32_ppm_isr(&ppm);
    tim.SR = TIM_SR_UIF;
    stm32_ppm_isr(&ppm);
    TEST_ASSERT_EQUAL_UINT8(2u, ppm.wraps); /* saturates */
    tim.SR = 0x0u;                          /* a spurious call: nothing written */
    stm32_ppm_isr(&ppm);
    TEST_ASSERT_EQUAL_HEX32(0x0u, tim.SR);
}

/* A frame being written (odd sequence) is never read: the bounded retries
 * give up with NO_DATA and leave the output alone. */
static void test_read_gives_up_on_torn_frame(void)
{
    uint16_t out[8];
    init_ch1_84mhz();
    uint32_t t = lead_in(1000u);
    t = frame_at(t, W8, 8u, 6000u);
    (void)frame_at(t, W8, 8u, 6000u);
    ppm.seq |= 1u;
    memset(out, 0x11, sizeof out);
    TEST_ASSERT_EQUAL(STM32_PPM_NO_DATA, stm32_ppm_read_us(&ppm, out, 8u));
    TEST_ASSERT_EQUAL_HEX16(0x1111u, out[0]);
    ppm.seq++;
    TEST_ASSERT_EQUAL(STM32_PPM_OK, stm32_ppm_read_us(&ppm, out, 8u));
    TEST_ASSERT_EQUAL_UINT16_ARRAY(W8, out, 8);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_init_registers_ch1);
    RUN_TEST(test_init_registers_ch4);
    RUN_TEST(test_init_refused);
    RUN_TEST(test_frames_published);
    RUN_TEST(test_wrap_around);
    RUN_TEST(test_wrap_before_capture);
    RUN_TEST(test_wrap_after_capture);
    RUN_TEST(test_sync_in_the_middle);
    RUN_TEST(test_noise_drops_frame);
    RUN_TEST(test_band_edges);
    RUN_TEST(test_too_many_channels);
    RUN_TEST(test_lost_edge_false_sync);
    RUN_TEST(test_long_gap_not_aliased);
    RUN_TEST(test_overcapture_drops_frame);
    RUN_TEST(test_update_flag_cleared);
    RUN_TEST(test_read_gives_up_on_torn_frame);
    return UNITY_END();
}
