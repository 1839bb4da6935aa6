/*
 * test_stm32f4_pwm.c - the STM32F4 PWM, GPIO and SysTick drivers on fake
 * register blocks: every register value they write, exactly.
 *
 * Expected values, worked from RM0090:
 *   CCMR1 = CCMR2 = OC1M 110 (bits 6:4) | OC1PE (bit 3) | OC2M 110 (14:12)
 *                 | OC2PE (bit 11) = 0x60 | 0x08 | 0x6000 | 0x0800 = 0x6868
 *   CCER  = CC1E | CC2E | CC3E | CC4E = bits 0, 4, 8, 12 = 0x1111
 *   CR1   = ARPE (bit 7) | CEN (bit 0) = 0x81; with UDIS (bit 1) 0x83
 *   PSC   = f_timer / 1 MHz - 1;  ARR = 1e6 / f_frame - 1
 */
#include "unity.h"

#include "stm32f4_gpio.h"
#include "stm32f4_pwm.h"
#include "stm32f4_systick.h"

#include <string.h>

static stm32_tim_t tim3, tim4;
static stm32_pwm_t pwm;

void setUp(void)
{
    memset((void *)&tim3, 0, sizeof tim3);
    memset((void *)&tim4, 0, sizeof tim4);
    memset(&pwm, 0, sizeof pwm);
}

void tearDown(void) {}

static void assert_timer(const stm32_tim_t *t, uint32_t psc, uint32_t arr, uint32_t ccr)
{
    TEST_ASSERT_EQUAL_HEX32(psc, t->PSC);
    TEST_ASSERT_EQUAL_HEX32(arr, t->ARR);
    TEST_ASSERT_EQUAL_HEX32(0x6868u, t->CCMR1);
    TEST_ASSERT_EQUAL_HEX32(0x6868u, t->CCMR2);
    TEST_ASSERT_EQUAL_HEX32(0x1111u, t->CCER);
    TEST_ASSERT_EQUAL_HEX32(0x81u, t->CR1);
    TEST_ASSERT_EQUAL_HEX32(0x1u, t->EGR); /* UG was written (a fake keeps it) */
    TEST_ASSERT_EQUAL_HEX32(0x0u, t->SR);
    for (unsigned i = 0; i < 4u; ++i) {
        TEST_ASSERT_EQUAL_UINT32(ccr, t->CCR[i]);
    }
}

static void test_init_50hz_from_hsi(void)
{
    tim3.SR = 0x1u; /* a stale flag: init clears it */
    TEST_ASSERT_EQUAL(STM32_PWM_OK, stm32_pwm_init(&pwm, &tim3, &tim4, 16000000u, 50u, 1500u));
    assert_timer(&tim3, 15u, 19999u, 1500u);
    assert_timer(&tim4, 15u, 19999u, 1500u);
    TEST_ASSERT_EQUAL_UINT16(20000u, pwm.period_us);
    TEST_ASSERT_EQUAL_UINT32(0u, tim3.SMCR);
    TEST_ASSERT_EQUAL_UINT32(0u, tim3.DIER); /* no interrupts needed */
}

static void test_init_400hz_from_84mhz(void)
{
    TEST_ASSERT_EQUAL(STM32_PWM_OK, stm32_pwm_init(&pwm, &tim3, &tim4, 84000000u, 400u, 1000u));
    assert_timer(&tim3, 83u, 2499u, 1000u);
    assert_timer(&tim4, 83u, 2499u, 1000u);
}

static void test_init_rate_edges(void)
{
    TEST_ASSERT_EQUAL(STM32_PWM_OK, stm32_pwm_init(&pwm, &tim3, &tim4, 16000000u, 16u, 1500u));
    TEST_ASSERT_EQUAL_UINT32(62499u, tim3.ARR);
    TEST_ASSERT_EQUAL(STM32_PWM_OK, stm32_pwm_init(&pwm, &tim3, &tim4, 16000000u, 333u, 1500u));
    TEST_ASSERT_EQUAL_UINT32(3002u, tim3.ARR); /* round(1e6 / 333) = 3003 */
    TEST_ASSERT_EQUAL(STM32_PWM_OK, stm32_pwm_init(&pwm, &tim3, &tim4, 1000000u, 50u, 1500u));
    TEST_ASSERT_EQUAL_UINT32(0u, tim3.PSC); /* a 1 MHz timer clock: no prescaling */
    /* a start pulse longer than the 400 Hz frame is clamped to ARR */
    TEST_ASSERT_EQUAL(STM32_PWM_OK, stm32_pwm_init(&pwm, &tim3, &tim4, 16000000u, 400u, 3000u));
    TEST_ASSERT_EQUAL_UINT32(2499u, tim4.CCR[3]);
}

static void test_init_refuses_bad_arguments_without_writing(void)
{
    TEST_ASSERT_EQUAL(STM32_PWM_ERR_RANGE,
                      stm32_pwm_init(&pwm, &tim3, &tim4, 16500000u, 50u, 1500u));
    TEST_ASSERT_EQUAL(STM32_PWM_ERR_RANGE, stm32_pwm_init(&pwm, &tim3, &tim4, 999999u, 50u, 1500u));
    TEST_ASSERT_EQUAL(STM32_PWM_ERR_RANGE, stm32_pwm_init(&pwm, &tim3, &tim4, 0u, 50u, 1500u));
    TEST_ASSERT_EQUAL(STM32_PWM_ERR_RANGE,
                      stm32_pwm_init(&pwm, &tim3, &tim4, 16000000u, 15u, 1500u));
    TEST_ASSERT_EQUAL(STM32_PWM_ERR_RANGE,
                      stm32_pwm_init(&pwm, &tim3, &tim4, 16000000u, 401u, 1500u));
    TEST_ASSERT_EQUAL(STM32_PWM_ERR_NULL, stm32_pwm_init(&pwm, NULL, &tim4, 16000000u, 50u, 1500u));
    TEST_ASSERT_EQUAL(STM32_PWM_ERR_NULL,
                      stm32_pwm_init(NULL, &tim3, &tim4, 16000000u, 50u, 1500u));
    TEST_ASSERT_EQUAL_UINT32(0u, tim3.CR1);
    TEST_ASSERT_EQUAL_UINT32(0u, tim3.PSC);
    TEST_ASSERT_EQUAL_UINT32(0u, tim3.ARR);
    TEST_ASSERT_EQUAL_UINT32(0u, tim4.CCER);
    TEST_ASSERT_EQUAL_UINT8(0u, pwm.ready);
    /* and an unready driver writes nothing */
    TEST_ASSERT_EQUAL(STM32_PWM_ERR_RANGE, stm32_pwm_set_us(&pwm, 0u, 1500u));
    stm32_pwm_commit(&pwm);
    TEST_ASSERT_EQUAL_UINT32(0u, tim3.CCR[0]);
}

static void test_set_stages_and_commit_releases(void)
{
    TEST_ASSERT_EQUAL(STM32_PWM_OK, stm32_pwm_init(&pwm, &tim3, &tim4, 16000000u, 50u, 1500u));
    const uint16_t us[8] = {1000u, 1100u, 1200u, 1300u, 1700u, 1800u, 1900u, 2000u};
    TEST_ASSERT_EQUAL(STM32_PWM_OK, stm32_pwm_set_us(&pwm, 0u, us[0]));
    /* the first write already holds TIM3's update event off */
    TEST_ASSERT_EQUAL_HEX32(0x83u, tim3.CR1);
    TEST_ASSERT_EQUAL_HEX32(0x81u, tim4.CR1);
    for (uint8_t ch = 1; ch < 8u; ++ch) {
        TEST_ASSERT_EQUAL(STM32_PWM_OK, stm32_pwm_set_us(&pwm, ch, us[ch]));
    }
    TEST_ASSERT_EQUAL_HEX32(0x83u, tim3.CR1);
    TEST_ASSERT_EQUAL_HEX32(0x83u, tim4.CR1);
    for (unsigned i = 0; i < 4u; ++i) {
        TEST_ASSERT_EQUAL_UINT32(us[i], tim3.CCR[i]);
        TEST_ASSERT_EQUAL_UINT32(us[4u + i], tim4.CCR[i]);
    }
    stm32_pwm_commit(&pwm);
    TEST_ASSERT_EQUAL_HEX32(0x81u, tim3.CR1);
    TEST_ASSERT_EQUAL_HEX32(0x81u, tim4.CR1);
    /* nothing else moved */
    TEST_ASSERT_EQUAL_UINT32(19999u, tim3.ARR);
    TEST_ASSERT_EQUAL_HEX32(0x1111u, tim4.CCER);
}

static void test_set_clamps_and_refuses(void)
{
    TEST_ASSERT_EQUAL(STM32_PWM_OK, stm32_pwm_init(&pwm, &tim3, &tim4, 16000000u, 400u, 1500u));
    TEST_ASSERT_EQUAL(STM32_PWM_OK, stm32_pwm_set_us(&pwm, 7u, 2499u));
    TEST_ASSERT_EQUAL_UINT32(2499u, tim4.CCR[3]);
    TEST_ASSERT_EQUAL(STM32_PWM_CLAMPED, stm32_pwm_set_us(&pwm, 7u, 2500u));
    TEST_ASSERT_EQUAL_UINT32(2499u, tim4.CCR[3]);
    TEST_ASSERT_EQUAL(STM32_PWM_CLAMPED, stm32_pwm_set_us(&pwm, 2u, 65535u));
    TEST_ASSERT_EQUAL_UINT32(2499u, tim3.CCR[2]);
    TEST_ASSERT_EQUAL(STM32_PWM_OK, stm32_pwm_set_us(&pwm, 2u, 0u));
    TEST_ASSERT_EQUAL_UINT32(0u, tim3.CCR[2]);
    TEST_ASSERT_EQUAL(STM32_PWM_ERR_RANGE, stm32_pwm_set_us(&pwm, 8u, 1500u));
    TEST_ASSERT_EQUAL(STM32_PWM_ERR_NULL, stm32_pwm_set_us(NULL, 0u, 1500u));
    for (unsigned i = 0; i < 4u; ++i) {
        TEST_ASSERT_TRUE(tim3.CCR[i] <= tim3.ARR);
        TEST_ASSERT_TRUE(tim4.CCR[i] <= tim4.ARR);
    }
}

static void test_silence(void)
{
    TEST_ASSERT_EQUAL(STM32_PWM_OK, stm32_pwm_init(&pwm, &tim3, &tim4, 16000000u, 50u, 1500u));
    stm32_pwm_silence(&pwm);
    for (unsigned i = 0; i < 4u; ++i) {
        TEST_ASSERT_EQUAL_UINT32(0u, tim3.CCR[i]);
        TEST_ASSERT_EQUAL_UINT32(0u, tim4.CCR[i]);
    }
    TEST_ASSERT_EQUAL_HEX32(0x81u, tim3.CR1); /* committed */
    TEST_ASSERT_EQUAL_HEX32(0x81u, tim4.CR1);
}

static void test_gpio_af2_servo_pins(void)
{
    stm32_gpio_t a, b;
    memset((void *)&a, 0, sizeof a);
    memset((void *)&b, 0, sizeof b);
    a.MODER = 0xA8000000u; /* PA13..15 debug pins in AF after reset: must survive */
    stm32_gpio_set_af(&a, 6u, 2u);
    stm32_gpio_set_af(&a, 7u, 2u);
    TEST_ASSERT_EQUAL_HEX32(0xA800A000u, a.MODER); /* bits 13:12 and 15:14 = 10 */
    TEST_ASSERT_EQUAL_HEX32(0x22000000u, a.AFR[0]);
    TEST_ASSERT_EQUAL_HEX32(0x0u, a.AFR[1]);
    const uint8_t pins_b[] = {0u, 1u, 6u, 7u, 8u, 9u};
    for (unsigned i = 0; i < sizeof pins_b; ++i) {
        stm32_gpio_set_af(&b, pins_b[i], 2u);
    }
    TEST_ASSERT_EQUAL_HEX32(0x000AA00Au, b.MODER);
    TEST_ASSERT_EQUAL_HEX32(0x22000022u, b.AFR[0]);
    TEST_ASSERT_EQUAL_HEX32(0x00000022u, b.AFR[1]);
    /* re-routing a pin replaces its old function */
    b.AFR[1] = 0x000000F5u;
    stm32_gpio_set_af(&b, 8u, 2u);
    TEST_ASSERT_EQUAL_HEX32(0x000000F2u, b.AFR[1]);
    stm32_gpio_set_af(&b, 16u, 2u); /* ignored */
    stm32_gpio_set_af(&b, 3u, 16u); /* ignored */
    TEST_ASSERT_EQUAL_HEX32(0x000AA00Au, b.MODER);
}

static void test_rcc_enables(void)
{
    stm32_rcc_t r;
    memset((void *)&r, 0, sizeof r);
    r.AHB1ENR = 0x00100000u; /* CCMDATARAMEN at reset */
    r.APB1ENR = 0x10000000u; /* PWREN, say */
    stm32_rcc_enable_servo_clocks(&r);
    TEST_ASSERT_EQUAL_HEX32(0x00100003u, r.AHB1ENR);
    TEST_ASSERT_EQUAL_HEX32(0x10000006u, r.APB1ENR);
}

static void test_systick(void)
{
    stm32_systick_t s;
    memset((void *)&s, 0, sizeof s);
    TEST_ASSERT_EQUAL_INT(1, stm32_systick_start(&s, 16000000u, 40u));
    TEST_ASSERT_EQUAL_UINT32(399999u, s.LOAD);
    TEST_ASSERT_EQUAL_HEX32(0x7u, s.CTRL);
    TEST_ASSERT_EQUAL_INT(1, stm32_systick_start(&s, 168000000u, 400u));
    TEST_ASSERT_EQUAL_UINT32(419999u, s.LOAD);
    TEST_ASSERT_EQUAL_INT(1, stm32_systick_start(&s, 16000000u, 1u));
    TEST_ASSERT_EQUAL_UINT32(15999999u, s.LOAD);
    memset((void *)&s, 0, sizeof s);
    TEST_ASSERT_EQUAL_INT(0, stm32_systick_start(&s, 168000000u, 1u)); /* > 24 bits */
    TEST_ASSERT_EQUAL_INT(0, stm32_systick_start(&s, 16000000u, 0u));
    TEST_ASSERT_EQUAL_INT(0, stm32_systick_start(NULL, 16000000u, 40u));
    TEST_ASSERT_EQUAL_UINT32(0u, s.LOAD);
    TEST_ASSERT_EQUAL_UINT32(0u, s.CTRL);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_init_50hz_from_hsi);
    RUN_TEST(test_init_400hz_from_84mhz);
    RUN_TEST(test_init_rate_edges);
    RUN_TEST(test_init_refuses_bad_arguments_without_writing);
    RUN_TEST(test_set_stages_and_commit_releases);
    RUN_TEST(test_set_clamps_and_refuses);
    RUN_TEST(test_silence);
    RUN_TEST(test_gpio_af2_servo_pins);
    RUN_TEST(test_rcc_enables);
    RUN_TEST(test_systick);
    return UNITY_END();
}
