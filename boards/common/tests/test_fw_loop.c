/*
 * test_fw_loop.c - the portable control tick on a fake board: start-up in
 * failsafe, manual pass-through, stabilised flight, RC and sensor timeouts,
 * a refused configuration, and that every tick commits all channels at once.
 */
#include "unity.h"

#include "fake_board.h"
#include "fw_loop.h"

static fw_config_t cfg;
static fw_state_t fw;

void setUp(void)
{
    fake_board_reset();
    fw_config_default(&cfg);
    TEST_ASSERT_EQUAL_INT(1, fw_init(&fw, &cfg));
}

void tearDown(void) {}

static void ticks(unsigned n)
{
    for (unsigned i = 0; i < n; ++i) {
        fw_tick(&fw, 0u);
    }
}

static void assert_committed(const uint16_t *want, unsigned n)
{
    for (unsigned i = 0; i < n; ++i) {
        TEST_ASSERT_EQUAL_UINT16(want[i], fake_board.committed_us[i]);
    }
}

static void test_starts_in_failsafe_until_rc(void)
{
    /* No tick yet: the first one has a fresh frame -> out of failsafe at once
     * (rc_age is reset by it). Without RC the first tick is RC_LOST. */
    fake_board.rc_status = BOARD_ERR_NO_DATA;
    ticks(1);
    TEST_ASSERT_EQUAL_UINT8(FW_MODE_FAILSAFE, fw.mode);
    TEST_ASSERT_EQUAL(BOARD_FS_RC_LOST, fake_board.last_failsafe);
    TEST_ASSERT_EQUAL_UINT32(1, fake_board.failsafe_calls);
    /* level attitude, no rates: the law commands neutral surfaces, idle */
    const uint16_t want[5] = {1500, 1500, 1000, 1500, 1500};
    assert_committed(want, 5);
    ticks(5);
    TEST_ASSERT_EQUAL_UINT32(1, fake_board.failsafe_calls); /* told once */
}

static void test_manual_pass_through(void)
{
    fake_board.rc_us[0] = 1750; /* aileron +0.5 */
    fake_board.rc_us[1] = 1400; /* elevator -0.2 */
    fake_board.rc_us[2] = 1600; /* throttle 0.6 */
    fake_board.rc_us[3] = 1300; /* rudder -0.4 */
    fake_board.rc_us[4] = 1000; /* mode: manual */
    ticks(1);
    TEST_ASSERT_EQUAL_UINT8(FW_MODE_MANUAL, fw.mode);
    const uint16_t want[5] = {1750, 1400, 1600, 1300, 1250};
    assert_committed(want, 5);
    TEST_ASSERT_EQUAL_UINT32(5, fake_board.writes);
    TEST_ASSERT_EQUAL_UINT32(1, fake_board.commits);
    TEST_ASSERT_EQUAL_UINT32(0, fake_board.writes_since_commit);
    TEST_ASSERT_EQUAL_UINT32(0, fake_board.failsafe_calls); /* never entered */
}

static void test_stabilised_turns_the_right_way(void)
{
    fake_board.rc_us[4] = 2000; /* stabilised */
    ticks(1);
    TEST_ASSERT_EQUAL_UINT8(FW_MODE_STABILISED, fw.mode);
    TEST_ASSERT_EQUAL_UINT16(1500, fake_board.committed_us[0]); /* level, sticks centred */
    fake_board.rc_us[0] = 2000; /* full right stick: turn right at 0.5 rad/s */
    ticks(1);
    /* a right turn from level needs right bank: aileron + (roll right) */
    TEST_ASSERT_TRUE(fake_board.committed_us[0] > 1500);
    TEST_ASSERT_TRUE(fake_board.committed_us[4] < 1500); /* the mirrored servo */
    TEST_ASSERT_EQUAL_UINT16(3000u - fake_board.committed_us[0], fake_board.committed_us[4]);
    TEST_ASSERT_EQUAL_UINT16(1000, fake_board.committed_us[2]); /* stick throttle idle */
}

static void test_rc_timeout_edge(void)
{
    fake_board.rc_us[4] = 1000;
    fake_board.rc_us[0] = 1750;
    ticks(1);
    TEST_ASSERT_EQUAL_UINT8(FW_MODE_MANUAL, fw.mode);
    fake_board.rc_status = BOARD_ERR_NO_DATA;
    ticks(cfg.rc_timeout_ticks - 1u);
    TEST_ASSERT_EQUAL_UINT8(FW_MODE_MANUAL, fw.mode); /* last sticks held */
    TEST_ASSERT_EQUAL_UINT16(1750, fake_board.committed_us[0]);
    TEST_ASSERT_EQUAL_UINT32(0, fake_board.failsafe_calls);
    ticks(1);
    TEST_ASSERT_EQUAL_UINT8(FW_MODE_FAILSAFE, fw.mode);
    TEST_ASSERT_EQUAL(BOARD_FS_RC_LOST, fake_board.last_failsafe);
    TEST_ASSERT_EQUAL_UINT16(1500, fake_board.committed_us[0]); /* wings level */
    TEST_ASSERT_EQUAL_UINT16(1000, fake_board.committed_us[2]);
    /* RC back: out of failsafe, and the hook hears it */
    fake_board.rc_status = BOARD_OK;
    ticks(1);
    TEST_ASSERT_EQUAL_UINT8(FW_MODE_MANUAL, fw.mode);
    TEST_ASSERT_EQUAL(BOARD_FS_NONE, fake_board.last_failsafe);
    TEST_ASSERT_EQUAL_UINT32(2, fake_board.failsafe_calls);
}

static void test_glitched_rc_pulse_counts_as_missing(void)
{
    fake_board.rc_us[4] = 1000;
    ticks(1);
    fake_board.rc_us[1] = 0; /* elevator channel dead */
    ticks(cfg.rc_timeout_ticks);
    TEST_ASSERT_EQUAL(BOARD_FS_RC_LOST, fake_board.last_failsafe);
}

static void test_sensor_timeout_uses_failsafe_pulses(void)
{
    fake_board.rc_us[4] = 2000;
    ticks(1);
    fake_board.sensor_status = BOARD_ERR_NO_DATA;
    ticks(cfg.sensor_timeout_ticks - 1u);
    TEST_ASSERT_EQUAL_UINT8(FW_MODE_STABILISED, fw.mode);
    ticks(1);
    TEST_ASSERT_EQUAL_UINT8(FW_MODE_FAILSAFE, fw.mode);
    TEST_ASSERT_EQUAL(BOARD_FS_SENSORS, fake_board.last_failsafe);
    const uint16_t want[5] = {1500, 1500, 1000, 1500, 1500};
    assert_committed(want, 5);
}

static void test_refused_config_writes_nothing(void)
{
    cfg.out.ch[1].min_us = 2100u; /* inverted end points */
    cfg.out.ch[1].max_us = 2000u;
    TEST_ASSERT_EQUAL_INT(0, fw_init(&fw, &cfg));
    ticks(3);
    TEST_ASSERT_EQUAL_UINT32(0, fake_board.writes);
    TEST_ASSERT_EQUAL_UINT32(0, fake_board.commits);
    TEST_ASSERT_EQUAL(BOARD_FS_CONFIG, fake_board.last_failsafe);
    TEST_ASSERT_EQUAL_UINT32(1, fake_board.failsafe_calls);
    /* more channels than the board has is refused too */
    fw_config_default(&cfg);
    fake_board.servo_count = 4;
    TEST_ASSERT_EQUAL_INT(0, fw_init(&fw, &cfg));
    /* a bad law parameter as well */
    fw_config_default(&cfg);
    fake_board.servo_count = 8;
    cfg.law.v_min_cm_s = 0;
    TEST_ASSERT_EQUAL_INT(0, fw_init(&fw, &cfg));
    TEST_ASSERT_EQUAL_INT(0, fw_init(&fw, NULL));
    TEST_ASSERT_EQUAL_INT(0, fw_init(NULL, &cfg));
}

static void test_back_from_sensor_failsafe_keeps_the_pilots_mode(void)
{
    fake_board.rc_us[4] = 1000; /* manual */
    fake_board.rc_us[0] = 1750;
    ticks(1);
    fake_board.sensor_status = BOARD_ERR_NO_DATA;
    ticks(cfg.sensor_timeout_ticks);
    TEST_ASSERT_EQUAL_UINT8(FW_MODE_FAILSAFE, fw.mode);
    /* sensors back, but this tick brings no RC frame (within the timeout) */
    fake_board.sensor_status = BOARD_OK;
    fake_board.rc_status = BOARD_ERR_NO_DATA;
    ticks(1);
    TEST_ASSERT_EQUAL_UINT8(FW_MODE_MANUAL, fw.mode);
    TEST_ASSERT_EQUAL_UINT16(1750, fake_board.committed_us[0]);
    TEST_ASSERT_EQUAL(BOARD_FS_NONE, fake_board.last_failsafe);
}

static void test_late_ticks_are_counted(void)
{
    fw_tick(&fw, 3u);
    fw_tick(&fw, 0u);
    fw_tick(&fw, 2u);
    TEST_ASSERT_EQUAL_UINT32(3, fw.ticks);
    TEST_ASSERT_EQUAL_UINT32(5, fw.late_ticks);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_starts_in_failsafe_until_rc);
    RUN_TEST(test_manual_pass_through);
    RUN_TEST(test_stabilised_turns_the_right_way);
    RUN_TEST(test_rc_timeout_edge);
    RUN_TEST(test_glitched_rc_pulse_counts_as_missing);
    RUN_TEST(test_sensor_timeout_uses_failsafe_pulses);
    RUN_TEST(test_refused_config_writes_nothing);
    RUN_TEST(test_back_from_sensor_failsafe_keeps_the_pilots_mode);
    RUN_TEST(test_late_ticks_are_counted);
    return UNITY_END();
}
