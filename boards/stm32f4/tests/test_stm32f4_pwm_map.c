/*
 * test_stm32f4_pwm_map.c - servo outputs over several timers, on fake
 * register blocks, with the Matek F405-WING map (boards/matekf405wing):
 * S1 TIM4 CH2, S2 TIM4 CH1, S3 TIM3 CH3, S4 TIM3 CH4, S5 TIM8 CH3,
 * S6 TIM8 CH4, S7 TIM12 CH1, S8 TIM12 CH2.
 *
 * Expected values, worked from RM0090 (168 MHz: APB1 timers 84 MHz, APB2
 * timers 168 MHz, clock tree 6.2):
 *   PSC  TIM3/TIM4/TIM12 = 84 - 1 = 83 = 0x53; TIM8 = 168 - 1 = 167 = 0xA7
 *   50 Hz: period round(1e6 / 50) = 20000 us, ARR = 19999 = 0x4E1F
 *   CCMR byte per channel: OCxM 110 (bits 6:4) | OCxPE (bit 3) = 0x68;
 *     channels 1+2 in CCMR1, 3+4 in CCMR2: a pair = 0x6868
 *   CCER CCxE at bit 4(x-1): CH1+CH2 = 0x0011, CH3+CH4 = 0x1100
 *   BDTR.MOE = bit 15 = 0x8000 on TIM8 only (17.4.18)
 *   CR1 = ARPE (bit 7) | CEN (bit 0) = 0x81; staged (UDIS, bit 1) 0x83
 */
#include "unity.h"

#include "stm32f4_pwm_map.h"

#include <string.h>

static stm32_tim_t tim3, tim4, tim8, tim12;
static stm32_pwm_map_t pwm;
static stm32_pwm_map_out_t map[8];

void setUp(void)
{
    memset((void *)&tim3, 0, sizeof tim3);
    memset((void *)&tim4, 0, sizeof tim4);
    memset((void *)&tim8, 0, sizeof tim8);
    memset((void *)&tim12, 0, sizeof tim12);
    memset(&pwm, 0, sizeof pwm);
    const stm32_pwm_map_out_t m[8] = {{&tim4, 84000000u, 2u, 0u},  {&tim4, 84000000u, 1u, 0u},
                                      {&tim3, 84000000u, 3u, 0u},  {&tim3, 84000000u, 4u, 0u},
                                      {&tim8, 168000000u, 3u, 1u}, {&tim8, 168000000u, 4u, 1u},
                                      {&tim12, 84000000u, 1u, 0u}, {&tim12, 84000000u, 2u, 0u}};
    memcpy(map, m, sizeof map);
}

void tearDown(void) {}

static void test_init_writes_every_timer(void)
{
    TEST_ASSERT_EQUAL(STM32_PWM_MAP_OK, stm32_pwm_map_init(&pwm, map, 8u, 50u, 1500u));
    TEST_ASSERT_EQUAL_UINT16(20000u, pwm.period_us);
    TEST_ASSERT_EQUAL_HEX32(0x53u, tim4.PSC);
    TEST_ASSERT_EQUAL_HEX32(0x53u, tim3.PSC);
    TEST_ASSERT_EQUAL_HEX32(0x53u, tim12.PSC);
    TEST_ASSERT_EQUAL_HEX32(0xA7u, tim8.PSC);
    TEST_ASSERT_EQUAL_HEX32(0x4E1Fu, tim4.ARR);
    TEST_ASSERT_EQUAL_HEX32(0x4E1Fu, tim8.ARR);
    TEST_ASSERT_EQUAL_HEX32(0x6868u, tim4.CCMR1);
    TEST_ASSERT_EQUAL_HEX32(0x0u, tim4.CCMR2);
    TEST_ASSERT_EQUAL_HEX32(0x0011u, tim4.CCER);
    TEST_ASSERT_EQUAL_HEX32(0x0u, tim3.CCMR1);
    TEST_ASSERT_EQUAL_HEX32(0x6868u, tim3.CCMR2);
    TEST_ASSERT_EQUAL_HEX32(0x1100u, tim3.CCER);
    TEST_ASSERT_EQUAL_HEX32(0x6868u, tim8.CCMR2);
    TEST_ASSERT_EQUAL_HEX32(0x1100u, tim8.CCER);
    TEST_ASSERT_EQUAL_HEX32(0x8000u, tim8.BDTR);
    TEST_ASSERT_EQUAL_HEX32(0x0u, tim12.BDTR);
    TEST_ASSERT_EQUAL_HEX32(0x6868u, tim12.CCMR1);
    TEST_ASSERT_EQUAL_HEX32(0x0011u, tim12.CCER);
    TEST_ASSERT_EQUAL_HEX32(1500u, tim4.CCR[0]);
    TEST_ASSERT_EQUAL_HEX32(1500u, tim4.CCR[1]);
    TEST_ASSERT_EQUAL_HEX32(0u, tim4.CCR[2]); /* unused channel untouched */
    TEST_ASSERT_EQUAL_HEX32(1500u, tim8.CCR[3]);
    TEST_ASSERT_EQUAL_HEX32(0x81u, tim4.CR1);
    TEST_ASSERT_EQUAL_HEX32(0x81u, tim8.CR1);
    TEST_ASSERT_EQUAL_HEX32(0x81u, tim12.CR1);
    TEST_ASSERT_EQUAL_HEX32(0x1u, tim3.EGR);
}

static void test_start_zero_is_silent(void)
{
    TEST_ASSERT_EQUAL(STM32_PWM_MAP_OK, stm32_pwm_map_init(&pwm, map, 8u, 50u, 0u));
    for (uint8_t i = 0u; i < 8u; ++i) {
        TEST_ASSERT_EQUAL_UINT16(0u, stm32_pwm_map_readback_us(&pwm, i));
    }
}

static void test_stage_then_commit(void)
{
    TEST_ASSERT_EQUAL(STM32_PWM_MAP_OK, stm32_pwm_map_init(&pwm, map, 8u, 50u, 1500u));
    TEST_ASSERT_EQUAL(STM32_PWM_MAP_OK, stm32_pwm_map_set_us(&pwm, 0u, 1100u));
    TEST_ASSERT_EQUAL(STM32_PWM_MAP_OK, stm32_pwm_map_set_us(&pwm, 6u, 1900u));
    TEST_ASSERT_EQUAL_HEX32(1100u, tim4.CCR[1]); /* S1 = TIM4 CH2 */
    TEST_ASSERT_EQUAL_HEX32(1900u, tim12.CCR[0]);
    TEST_ASSERT_EQUAL_HEX32(0x83u, tim4.CR1);
    TEST_ASSERT_EQUAL_HEX32(0x83u, tim12.CR1);
    TEST_ASSERT_EQUAL_HEX32(0x81u, tim8.CR1); /* not staged */
    stm32_pwm_map_commit(&pwm);
    TEST_ASSERT_EQUAL_HEX32(0x81u, tim4.CR1);
    TEST_ASSERT_EQUAL_HEX32(0x81u, tim12.CR1);
    TEST_ASSERT_EQUAL_UINT16(1100u, stm32_pwm_map_readback_us(&pwm, 0u));
    TEST_ASSERT_EQUAL_UINT16(1900u, stm32_pwm_map_readback_us(&pwm, 6u));
}

static void test_clamp_and_silence(void)
{
    TEST_ASSERT_EQUAL(STM32_PWM_MAP_OK, stm32_pwm_map_init(&pwm, map, 8u, 400u, 1500u));
    TEST_ASSERT_EQUAL_UINT16(2500u, pwm.period_us);
    TEST_ASSERT_EQUAL(STM32_PWM_MAP_CLAMPED, stm32_pwm_map_set_us(&pwm, 4u, 3000u));
    TEST_ASSERT_EQUAL_HEX32(2499u, tim8.CCR[2]);
    stm32_pwm_map_silence(&pwm);
    for (uint8_t i = 0u; i < 8u; ++i) {
        TEST_ASSERT_EQUAL_UINT16(0u, stm32_pwm_map_readback_us(&pwm, i));
    }
    TEST_ASSERT_EQUAL_HEX32(0x81u, tim8.CR1);
}

static void test_bad_arguments_write_nothing(void)
{
    TEST_ASSERT_EQUAL(STM32_PWM_MAP_ERR_NULL, stm32_pwm_map_init(NULL, map, 8u, 50u, 0u));
    TEST_ASSERT_EQUAL(STM32_PWM_MAP_ERR_RANGE, stm32_pwm_map_init(&pwm, map, 0u, 50u, 0u));
    TEST_ASSERT_EQUAL(STM32_PWM_MAP_ERR_RANGE, stm32_pwm_map_init(&pwm, map, 9u, 50u, 0u));
    TEST_ASSERT_EQUAL(STM32_PWM_MAP_ERR_RANGE, stm32_pwm_map_init(&pwm, map, 8u, 15u, 0u));
    TEST_ASSERT_EQUAL(STM32_PWM_MAP_ERR_RANGE, stm32_pwm_map_init(&pwm, map, 8u, 401u, 0u));
    map[7].channel = 5u;
    TEST_ASSERT_EQUAL(STM32_PWM_MAP_ERR_RANGE, stm32_pwm_map_init(&pwm, map, 8u, 50u, 0u));
    map[7].channel = 2u;
    map[3].timer_clk_hz = 84500000u; /* not a whole number of MHz */
    TEST_ASSERT_EQUAL(STM32_PWM_MAP_ERR_RANGE, stm32_pwm_map_init(&pwm, map, 8u, 50u, 0u));
    TEST_ASSERT_EQUAL_HEX32(0u, tim4.PSC);
    TEST_ASSERT_EQUAL_HEX32(0u, tim3.CR1);
    TEST_ASSERT_EQUAL_HEX32(0u, tim8.BDTR);
    TEST_ASSERT_EQUAL(STM32_PWM_MAP_ERR_RANGE, stm32_pwm_map_set_us(&pwm, 0u, 1000u));
    map[3].timer_clk_hz = 84000000u;
    TEST_ASSERT_EQUAL(STM32_PWM_MAP_OK, stm32_pwm_map_init(&pwm, map, 4u, 50u, 0u));
    TEST_ASSERT_EQUAL(STM32_PWM_MAP_ERR_RANGE, stm32_pwm_map_set_us(&pwm, 4u, 1000u));
    TEST_ASSERT_EQUAL_UINT16(0u, stm32_pwm_map_readback_us(&pwm, 4u));
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_init_writes_every_timer);
    RUN_TEST(test_start_zero_is_silent);
    RUN_TEST(test_stage_then_commit);
    RUN_TEST(test_clamp_and_silence);
    RUN_TEST(test_bad_arguments_write_nothing);
    return UNITY_END();
}
