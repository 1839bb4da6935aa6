/*
 * test_stm32f4_exti.c - the data-ready edge interrupt on fake SYSCFG/EXTI
 * blocks: PC4 -> EXTI4, rising edge (the Matek F405-WING IMU INT pin).
 *
 * Expected values (RM0090 9.2.4, 12.3):
 *   line 4 is in EXTICR2 (EXTICR[1]) bits 3:0; port C = 0010: field 0x2
 *   RTSR/IMR/PR bit 4 = 0x10; FTSR bit 4 cleared
 */
#include "unity.h"

#include "stm32f4_exti.h"

#include <string.h>

static stm32_syscfg_t syscfg;
static stm32_exti_t exti;

void setUp(void)
{
    memset((void *)&syscfg, 0, sizeof syscfg);
    memset((void *)&exti, 0, sizeof exti);
}

void tearDown(void) {}

static void test_pc4_rising(void)
{
    syscfg.EXTICR[1] = 0xFFFFu; /* other lines' ports kept */
    exti.FTSR = 0x30u;
    exti.IMR = 0x1u;
    TEST_ASSERT_EQUAL_INT(
        0, stm32_exti_route(&syscfg, &exti, STM32_EXTI_PORT_C, 4u, STM32_EXTI_RISING));
    TEST_ASSERT_EQUAL_HEX32(0xFFF2u, syscfg.EXTICR[1]);
    TEST_ASSERT_EQUAL_HEX32(0x0u, syscfg.EXTICR[0]);
    TEST_ASSERT_EQUAL_HEX32(0x10u, exti.RTSR);
    TEST_ASSERT_EQUAL_HEX32(0x20u, exti.FTSR);
    TEST_ASSERT_EQUAL_HEX32(0x10u, exti.PR);
    TEST_ASSERT_EQUAL_HEX32(0x11u, exti.IMR);
}

static void test_line_15_falling(void)
{
    TEST_ASSERT_EQUAL_INT(0, stm32_exti_route(&syscfg, &exti, 1u, 15u, STM32_EXTI_FALLING));
    TEST_ASSERT_EQUAL_HEX32(0x1000u, syscfg.EXTICR[3]); /* bits 15:12, port B */
    TEST_ASSERT_EQUAL_HEX32(0x8000u, exti.FTSR);
    TEST_ASSERT_EQUAL_HEX32(0x0u, exti.RTSR);
}

static void test_take_clears_only_its_line(void)
{
    exti.PR = 0x20u;
    TEST_ASSERT_EQUAL_INT(0, stm32_exti_take(&exti, 4u));
    TEST_ASSERT_EQUAL_HEX32(0x20u, exti.PR); /* not written */
    exti.PR = 0x30u;
    TEST_ASSERT_EQUAL_INT(1, stm32_exti_take(&exti, 4u));
    TEST_ASSERT_EQUAL_HEX32(0x10u, exti.PR); /* the write was bit 4 alone */
}

static void test_bad_arguments(void)
{
    TEST_ASSERT_EQUAL_INT(-1, stm32_exti_route(&syscfg, &exti, 2u, 16u, STM32_EXTI_RISING));
    TEST_ASSERT_EQUAL_INT(-1, stm32_exti_route(&syscfg, &exti, 9u, 4u, STM32_EXTI_RISING));
    TEST_ASSERT_EQUAL_INT(-1, stm32_exti_route(NULL, &exti, 2u, 4u, STM32_EXTI_RISING));
    TEST_ASSERT_EQUAL_HEX32(0u, exti.IMR);
    TEST_ASSERT_EQUAL_INT(0, stm32_exti_take(NULL, 4u));
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_pc4_rising);
    RUN_TEST(test_line_15_falling);
    RUN_TEST(test_take_clears_only_its_line);
    RUN_TEST(test_bad_arguments);
    return UNITY_END();
}
