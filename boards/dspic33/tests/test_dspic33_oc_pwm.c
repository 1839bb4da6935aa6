/*
 * test_dspic33_oc_pwm.c - the dsPIC33FJ output-compare servo driver on fake
 * SFR blocks: every SFR value, exactly.
 *
 * Expected values, worked from the datasheet's bit positions:
 *   TxCON = TON (bit 15) | TCKPS << 4: 1:1 0x8000, 1:8 0x8010, 1:64 0x8020
 *   OCxCON = OCM 110 = 0x0006 on Timer2; | OCTSEL (bit 3) = 0x000E on Timer3
 *   PRy = Fcy / (prescale * f_frame) - 1
 *   OCxRS = round(pulse_us * Fcy / (prescale * 1e6))
 */
#include "unity.h"

#include "dspic33_oc_pwm.h"

#include <string.h>

static dspic_tmr23_t tmr;
static dspic_oc_t oc[DSPIC_OC_COUNT];
static dspic_pwm_t pwm;

void setUp(void)
{
    memset((void *)&tmr, 0, sizeof tmr);
    memset((void *)oc, 0, sizeof oc);
    memset(&pwm, 0, sizeof pwm);
}

void tearDown(void) {}

static void assert_oc(uint16_t occon, uint16_t ocr, uint16_t ocrs)
{
    for (unsigned i = 0; i < DSPIC_OC_COUNT; ++i) {
        TEST_ASSERT_EQUAL_HEX16(occon, oc[i].OCCON);
        TEST_ASSERT_EQUAL_UINT16(ocr, oc[i].OCR);
        TEST_ASSERT_EQUAL_UINT16(ocrs, oc[i].OCRS);
    }
}

static void test_udb_40mips_50hz(void)
{
    TEST_ASSERT_EQUAL(DSPIC_PWM_OK, dspic_pwm_init(&pwm, &tmr, oc, 2u, 40000000u, 50u, 1500u));
    TEST_ASSERT_EQUAL_HEX16(0x8020u, tmr.T2CON); /* on, 1:64 */
    TEST_ASSERT_EQUAL_UINT16(12499u, tmr.PR2);   /* 40e6 / 64 / 50 = 12500 counts */
    TEST_ASSERT_EQUAL_HEX16(0u, tmr.T3CON);      /* Timer3 untouched */
    TEST_ASSERT_EQUAL_UINT16(0u, tmr.PR3);
    assert_oc(0x0006u, 938u, 938u);              /* 1500 us = 937.5 counts -> 938 */
    TEST_ASSERT_EQUAL_UINT16(64u, pwm.prescale); /* 1.6 us per count */
}

static void test_16mips_50hz_and_400hz(void)
{
    TEST_ASSERT_EQUAL(DSPIC_PWM_OK, dspic_pwm_init(&pwm, &tmr, oc, 2u, 16000000u, 50u, 1500u));
    TEST_ASSERT_EQUAL_HEX16(0x8010u, tmr.T2CON); /* 1:8: 0.5 us per count */
    TEST_ASSERT_EQUAL_UINT16(39999u, tmr.PR2);
    assert_oc(0x0006u, 3000u, 3000u);
    setUp();
    TEST_ASSERT_EQUAL(DSPIC_PWM_OK, dspic_pwm_init(&pwm, &tmr, oc, 2u, 40000000u, 400u, 1000u));
    TEST_ASSERT_EQUAL_HEX16(0x8010u, tmr.T2CON); /* 1:8: 0.2 us per count */
    TEST_ASSERT_EQUAL_UINT16(12499u, tmr.PR2);
    assert_oc(0x0006u, 5000u, 5000u);
    setUp();
    TEST_ASSERT_EQUAL(DSPIC_PWM_OK, dspic_pwm_init(&pwm, &tmr, oc, 2u, 1000000u, 400u, 1500u));
    TEST_ASSERT_EQUAL_HEX16(0x8000u, tmr.T2CON); /* 1:1 */
    TEST_ASSERT_EQUAL_UINT16(2499u, tmr.PR2);
    assert_oc(0x0006u, 1500u, 1500u);
}

static void test_timer3_and_70mips(void)
{
    TEST_ASSERT_EQUAL(DSPIC_PWM_OK, dspic_pwm_init(&pwm, &tmr, oc, 3u, 70000000u, 50u, 2000u));
    TEST_ASSERT_EQUAL_HEX16(0x8020u, tmr.T3CON); /* 70e6/64/50 = 21875 counts */
    TEST_ASSERT_EQUAL_UINT16(21874u, tmr.PR3);
    TEST_ASSERT_EQUAL_HEX16(0u, tmr.T2CON);
    assert_oc(0x000Eu, 2188u, 2188u); /* 2000 us = 2187.5 -> 2188 */
}

static void test_prescaler_choice_at_the_16_bit_edge(void)
{
    /* 26.214 MHz / 8 / 50 = 65535 counts: the largest frame 1:8 holds. */
    TEST_ASSERT_EQUAL(DSPIC_PWM_OK, dspic_pwm_init(&pwm, &tmr, oc, 2u, 26214000u, 50u, 0u));
    TEST_ASSERT_EQUAL_HEX16(0x8010u, tmr.T2CON);
    TEST_ASSERT_EQUAL_UINT16(65534u, tmr.PR2);
    assert_oc(0x0006u, 0u, 0u); /* start at 0: no pulses */
    setUp();
    /* 26.215 MHz: 65537.5 -> 65538 counts at 1:8 does not fit: 1:64 */
    TEST_ASSERT_EQUAL(DSPIC_PWM_OK, dspic_pwm_init(&pwm, &tmr, oc, 2u, 26215000u, 50u, 0u));
    TEST_ASSERT_EQUAL_HEX16(0x8020u, tmr.T2CON);
    TEST_ASSERT_EQUAL_UINT16(8191u, tmr.PR2); /* 8192.19 -> 8192 counts */
}

static void test_frc_pll_clock_not_whole_khz(void)
{
    /* FRC 7.37 MHz x 43 / 8 = 39.61375 MHz: 1:64, 12379.3 -> 12379 counts */
    TEST_ASSERT_EQUAL(DSPIC_PWM_OK, dspic_pwm_init(&pwm, &tmr, oc, 2u, 39613750u, 50u, 1500u));
    TEST_ASSERT_EQUAL_HEX16(0x8020u, tmr.T2CON);
    TEST_ASSERT_EQUAL_UINT16(12378u, tmr.PR2);
    assert_oc(0x0006u, 928u, 928u); /* 1500 us = 928.45 counts */
}

static void test_bad_arguments_write_nothing(void)
{
    TEST_ASSERT_EQUAL(DSPIC_PWM_ERR_RANGE,
                      dspic_pwm_init(&pwm, &tmr, oc, 1u, 40000000u, 50u, 1500u));
    TEST_ASSERT_EQUAL(DSPIC_PWM_ERR_RANGE,
                      dspic_pwm_init(&pwm, &tmr, oc, 4u, 40000000u, 50u, 1500u));
    TEST_ASSERT_EQUAL(DSPIC_PWM_ERR_RANGE, dspic_pwm_init(&pwm, &tmr, oc, 2u, 999000u, 50u, 1500u));
    TEST_ASSERT_EQUAL(DSPIC_PWM_ERR_RANGE,
                      dspic_pwm_init(&pwm, &tmr, oc, 2u, 70001000u, 50u, 1500u));
    TEST_ASSERT_EQUAL(DSPIC_PWM_ERR_RANGE,
                      dspic_pwm_init(&pwm, &tmr, oc, 2u, 40000000u, 49u, 1500u));
    TEST_ASSERT_EQUAL(DSPIC_PWM_ERR_RANGE,
                      dspic_pwm_init(&pwm, &tmr, oc, 2u, 40000000u, 401u, 1500u));
    TEST_ASSERT_EQUAL(DSPIC_PWM_ERR_NULL, dspic_pwm_init(&pwm, NULL, oc, 2u, 40000000u, 50u, 0u));
    TEST_ASSERT_EQUAL(DSPIC_PWM_ERR_NULL, dspic_pwm_init(&pwm, &tmr, NULL, 2u, 40000000u, 50u, 0u));
    TEST_ASSERT_EQUAL(DSPIC_PWM_ERR_NULL, dspic_pwm_init(NULL, &tmr, oc, 2u, 40000000u, 50u, 0u));
    TEST_ASSERT_EQUAL_HEX16(0u, tmr.T2CON);
    TEST_ASSERT_EQUAL_UINT16(0u, tmr.PR2);
    assert_oc(0u, 0u, 0u);
    TEST_ASSERT_EQUAL(DSPIC_PWM_ERR_RANGE, dspic_pwm_set_us(&pwm, 0u, 1500u));
    TEST_ASSERT_EQUAL(DSPIC_PWM_ERR_RANGE, dspic_pwm_commit(&pwm));
    TEST_ASSERT_EQUAL_UINT16(0u, dspic_pwm_counts(&pwm, 1500u));
    assert_oc(0u, 0u, 0u);
}

static void test_stage_then_commit_all_together(void)
{
    TEST_ASSERT_EQUAL(DSPIC_PWM_OK, dspic_pwm_init(&pwm, &tmr, oc, 2u, 16000000u, 50u, 1500u));
    const uint16_t us[8] = {1000u, 1100u, 1200u, 1300u, 1700u, 1800u, 1900u, 2000u};
    for (uint8_t ch = 0; ch < 8u; ++ch) {
        TEST_ASSERT_EQUAL(DSPIC_PWM_OK, dspic_pwm_set_us(&pwm, ch, us[ch]));
    }
    assert_oc(0x0006u, 3000u, 3000u); /* nothing written before commit */
    tmr.TMR2 = 100u;                  /* early in the frame */
    TEST_ASSERT_EQUAL(DSPIC_PWM_OK, dspic_pwm_commit(&pwm));
    for (unsigned i = 0; i < 8u; ++i) {
        TEST_ASSERT_EQUAL_UINT16((uint16_t)(2u * us[i]), oc[i].OCRS);
        TEST_ASSERT_EQUAL_UINT16(3000u, oc[i].OCR); /* the hardware reloads OCR */
    }
}

static void test_commit_guard_window(void)
{
    /* 1:8 -> guard = 64 / 8 + 1 = 9 counts before PR2 = 39999 */
    TEST_ASSERT_EQUAL(DSPIC_PWM_OK, dspic_pwm_init(&pwm, &tmr, oc, 2u, 16000000u, 50u, 1500u));
    TEST_ASSERT_EQUAL_UINT16(9u, pwm.guard_counts);
    TEST_ASSERT_EQUAL(DSPIC_PWM_OK, dspic_pwm_set_us(&pwm, 0u, 1234u));
    tmr.TMR2 = 39989u; /* last count outside the window */
    TEST_ASSERT_EQUAL(DSPIC_PWM_OK, dspic_pwm_commit(&pwm));
    TEST_ASSERT_EQUAL_UINT16(2468u, oc[0].OCRS);
    TEST_ASSERT_EQUAL(DSPIC_PWM_OK, dspic_pwm_set_us(&pwm, 0u, 1235u));
    tmr.TMR2 = 39990u; /* inside: a fake timer never moves -> LATE, still written */
    TEST_ASSERT_EQUAL(DSPIC_PWM_LATE, dspic_pwm_commit(&pwm));
    TEST_ASSERT_EQUAL_UINT16(2470u, oc[0].OCRS);
}

static void test_counts_rounding_and_clamps(void)
{
    TEST_ASSERT_EQUAL(DSPIC_PWM_OK, dspic_pwm_init(&pwm, &tmr, oc, 2u, 40000000u, 50u, 1500u));
    /* 1.6 us per count: 1 us = 0.625 -> 1, 2 us = 1.25 -> 1, 4 us = 2.5 (a tie,
     * rounded up) -> 3 */
    TEST_ASSERT_EQUAL_UINT16(0u, dspic_pwm_counts(&pwm, 0u));
    TEST_ASSERT_EQUAL_UINT16(1u, dspic_pwm_counts(&pwm, 1u));
    TEST_ASSERT_EQUAL_UINT16(1u, dspic_pwm_counts(&pwm, 2u)); /* 1.25 */
    TEST_ASSERT_EQUAL_UINT16(3u, dspic_pwm_counts(&pwm, 4u));
    TEST_ASSERT_EQUAL_UINT16(1250u, dspic_pwm_counts(&pwm, 2000u));
    TEST_ASSERT_EQUAL_UINT16(12499u, dspic_pwm_counts(&pwm, 20000u)); /* whole frame -> PR2 */
    TEST_ASSERT_EQUAL(DSPIC_PWM_CLAMPED, dspic_pwm_set_us(&pwm, 7u, 20000u));
    TEST_ASSERT_EQUAL(DSPIC_PWM_OK, dspic_pwm_set_us(&pwm, 7u, 19998u)); /* 12498.75 -> 12499 */
    TEST_ASSERT_EQUAL(DSPIC_PWM_CLAMPED, dspic_pwm_set_us(&pwm, 7u, 65535u));
    TEST_ASSERT_EQUAL_UINT16(12499u, pwm.staged[7]);
    TEST_ASSERT_EQUAL(DSPIC_PWM_ERR_RANGE, dspic_pwm_set_us(&pwm, 8u, 1500u));
    TEST_ASSERT_EQUAL(DSPIC_PWM_ERR_NULL, dspic_pwm_set_us(NULL, 0u, 1500u));
    TEST_ASSERT_EQUAL(DSPIC_PWM_ERR_NULL, dspic_pwm_commit(NULL));
    /* every pulse: never above PR2, monotonic */
    uint16_t prev = 0u;
    for (uint32_t us = 0; us <= 65535u; ++us) {
        const uint16_t c = dspic_pwm_counts(&pwm, (uint16_t)us);
        TEST_ASSERT_TRUE(c <= tmr.PR2);
        TEST_ASSERT_TRUE(c >= prev);
        prev = c;
    }
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_udb_40mips_50hz);
    RUN_TEST(test_16mips_50hz_and_400hz);
    RUN_TEST(test_timer3_and_70mips);
    RUN_TEST(test_prescaler_choice_at_the_16_bit_edge);
    RUN_TEST(test_frc_pll_clock_not_whole_khz);
    RUN_TEST(test_bad_arguments_write_nothing);
    RUN_TEST(test_stage_then_commit_all_together);
    RUN_TEST(test_commit_guard_window);
    RUN_TEST(test_counts_rounding_and_clamps);
    return UNITY_END();
}
