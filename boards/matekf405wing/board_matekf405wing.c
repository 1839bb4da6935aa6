/*
 * board_matekf405wing.c - board.h for the Matek F405-WING (STM32F405RGT6):
 * 168 MHz from the 8 MHz crystal (16 MHz HSI when it does not start), a
 * 1 kHz SysTick time base, eight servo outputs S1..S8 on TIM4/TIM3/TIM8/TIM12,
 * LED and beeper. The sensors and the receiver are their own files
 * (matek_sensors.c, matek_rc.c), and so are the clocks, the time base and
 * the pin helpers they share (matek_hw.c); the pins are matekf405wing_pins.h.
 *
 * The control tick (board_wait_tick) is paced by the time base: one tick
 * every 1000 / control_hz ms (5 ms at the firmware's 200 Hz IMU rate). While
 * it waits, the loop sleeps (WFI) and, at each wake (SysTick, the IMU's
 * data-ready, a received byte: at least every millisecond), reads the IMU
 * sample that data-ready announced and feeds the receiver's bytes to its
 * link. The interrupt handlers only count or queue bytes.
 *
 * The board's state is file-static: this is the firmware image, not the
 * library.
 */
#include "helical/board.h"

#include "matek_board.h"
#include "matek_console.h"
#include "matek_hw.h"
#include "matek_params_boot.h"
#include "matek_rc.h"
#include "matek_sensors.h"
#include "matekf405wing_pins.h"
#include "stm32f4_pwm_map.h"
#include "stm32f4_regs.h"

#include <stddef.h>

#define HEARTBEAT_TICKS 400u /* 2 s at 200 Hz */

static stm32_pwm_map_t servos;
static uint32_t next_tick_ms, tick_frac;
static uint16_t tick_ms_whole, tick_hz;
static uint32_t ticks, late_total;
static uint8_t failsafe_now;

static const uint8_t servo_port[MATEK_SERVOS] = {1u, 1u, 1u, 1u, 2u, 2u, 1u, 1u};
static const uint8_t servo_pin[MATEK_SERVOS] = {MATEK_S1_PIN, MATEK_S2_PIN, MATEK_S3_PIN,
                                                MATEK_S4_PIN, MATEK_S5_PIN, MATEK_S6_PIN,
                                                MATEK_S7_PIN, MATEK_S8_PIN};
static const uint8_t servo_af[MATEK_SERVOS] = {MATEK_AF_TIM3_4, MATEK_AF_TIM3_4, MATEK_AF_TIM3_4,
                                               MATEK_AF_TIM3_4, MATEK_AF_TIM8,   MATEK_AF_TIM8,
                                               MATEK_AF_TIM12,  MATEK_AF_TIM12};

static int servos_init(const board_config_t *cfg)
{
    // cppcheck-suppress misra-c2012-11.4 ; D-11.4-REG: TIM3 register block address
    stm32_tim_t *const tim3 = (stm32_tim_t *)STM32_TIM3_BASE;
    // cppcheck-suppress misra-c2012-11.4 ; D-11.4-REG: TIM4 register block address
    stm32_tim_t *const tim4 = (stm32_tim_t *)STM32_TIM4_BASE;
    // cppcheck-suppress misra-c2012-11.4 ; D-11.4-REG: TIM8 register block address
    stm32_tim_t *const tim8 = (stm32_tim_t *)MATEK_TIM8_BASE;
    // cppcheck-suppress misra-c2012-11.4 ; D-11.4-REG: TIM12 register block address
    stm32_tim_t *const tim12 = (stm32_tim_t *)MATEK_TIM12_BASE;
    const uint32_t apb1 = matek_clocks()->tim_apb1_hz;
    const uint32_t apb2 = matek_clocks()->tim_apb2_hz;
    const stm32_pwm_map_out_t map[MATEK_SERVOS] = {
        {tim4, apb1, 2u, 0u}, {tim4, apb1, 1u, 0u}, {tim3, apb1, 3u, 0u},  {tim3, apb1, 4u, 0u},
        {tim8, apb2, 3u, 1u}, {tim8, apb2, 4u, 1u}, {tim12, apb1, 1u, 0u}, {tim12, apb1, 2u, 0u}};
    /* Timers first, pins second: a pin only sees the timer once it runs. */
    if (stm32_pwm_map_init(&servos, map, (uint8_t)MATEK_SERVOS, cfg->servo_frame_hz,
                           cfg->servo_start_us) != STM32_PWM_MAP_OK) {
        return 0;
    }
    for (unsigned i = 0u; i < MATEK_SERVOS; ++i) {
        matek_pin_af(servo_port[i], servo_pin[i], servo_af[i], 0u);
    }
    return 1;
}

static void clock_report(void)
{
    static const char *const why[5] = {
        "HSE 8 MHz + PLL: 168 MHz (APB1 42, APB2 84)", "HSE never ready: HSI 16 MHz",
        "flash wait states refused: HSI 16 MHz", "PLL never locked: HSI 16 MHz",
        "switch to PLL not seen: HSI 16 MHz"};
    matek_console_puts("matekf405wing: clock ");
    const uint8_t source = matek_clocks()->source;
    matek_console_puts(why[(source < 5u) ? source : 1u]);
    matek_console_puts("\r\n");
}

static void params_report(void)
{
    static const char *const what[6] = {"stored set loaded",
                                        "store blank: defaults",
                                        "store corrupt: defaults",
                                        "stored set of another schema or table: defaults",
                                        "stored set refused: defaults",
                                        "stored set loaded (other slot corrupt)"};
    const matek_params_report_t *r = matek_params_report();
    matek_console_puts("params: ");
    matek_console_puts(what[(r->result < 6u) ? r->result : 2u]);
    if (r->result == (uint8_t)MATEK_PARAMS_LOADED ||
        r->result == (uint8_t)MATEK_PARAMS_LOADED_OTHER_CORRUPT) {
        matek_console_puts(", sequence ");
        matek_console_put_u32(r->sequence);
    } else if (r->result == (uint8_t)MATEK_PARAMS_REFUSED) {
        matek_console_puts(", row ");
        matek_console_puts((r->bad_index >= 0) ? r->bad_id : "?");
        matek_console_puts(" (check ");
        matek_console_put_u32(r->bad);
        matek_console_puts(", block ");
        matek_console_put_u32(r->bad_block);
        matek_console_puts(", field ");
        matek_console_put_i32(r->bad_sub);
        matek_console_puts(")");
        if (r->reason[0] != '\0') {
            matek_console_puts(": ");
            matek_console_puts(r->reason);
        }
    } else {
        /* nothing more to say */
    }
    matek_console_puts("\r\n");
}

/* LED PA14 and beeper PC15 as outputs, both off. */
static void indicators_init(void)
{
    stm32_gpio_set_output(matek_gpio(0u), MATEK_LED_PIN, 0u);
    stm32_gpio_set_output(matek_gpio(2u), MATEK_BEEPER_PIN, 0u);
}

board_status_t board_init(const board_config_t *cfg)
{
    const board_status_t st = board_config_check(cfg);
    if (st != BOARD_OK) {
        return st;
    }
    /* The clocks and the 1 kHz time base first: the sensors' start-up delays
     * run on it. */
    if (matek_hw_start() == 0) {
        return BOARD_ERR_HW;
    }
    matek_console_init();
    clock_report();
    params_report();
    if (!servos_init(cfg)) {
        matek_console_puts("servos: timer set-up refused\r\n");
        matek_console_flush();
        return BOARD_ERR_HW;
    }
    matek_console_puts("servos: S1..S8 on TIM4/TIM3/TIM8/TIM12, ");
    matek_console_put_u32(cfg->servo_frame_hz);
    matek_console_puts(" Hz, start pulse ");
    matek_console_put_u32(cfg->servo_start_us);
    matek_console_puts((cfg->servo_start_us == 0u) ? " us (silent until the first commit)\r\n"
                                                   : " us\r\n");
    indicators_init();
    matek_console_flush();
    matek_sensors_init();
    matek_console_flush();
    matek_rc_init();
    matek_console_flush();
    tick_hz = cfg->control_hz;
    tick_ms_whole = (uint16_t)(MATEK_TIMEBASE_HZ / tick_hz);
    tick_frac = 0u;
    next_tick_ms = matek_time_ms() + tick_ms_whole;
    return BOARD_OK;
}

uint8_t board_servo_count(void)
{
    return (uint8_t)MATEK_SERVOS;
}

/* The next tick's time: whole ms plus a carried remainder, so any rate in
 * [1, 400] Hz keeps its average period exactly. */
static void advance_tick(void)
{
    next_tick_ms += tick_ms_whole;
    tick_frac += MATEK_TIMEBASE_HZ % tick_hz;
    if (tick_frac >= tick_hz) {
        tick_frac -= tick_hz;
        next_tick_ms += 1u;
    }
}

static void heartbeat(void)
{
    stm32_gpio_write(matek_gpio(0u), MATEK_LED_PIN, (uint8_t)((ticks / HEARTBEAT_TICKS) & 1u));
    matek_console_puts("hb ticks ");
    matek_console_put_u32(ticks);
    matek_console_puts(" late ");
    matek_console_put_u32(late_total);
    matek_console_puts(" imu ");
    matek_console_put_u32(matek_sensors_imu_samples());
    matek_console_puts(" fs ");
    matek_console_put_u32(failsafe_now);
    matek_console_puts(" step_max_cyc ");
    matek_console_put_u32(matek_budget_step_max_cyc());
    matek_console_puts(" io_max_cyc ");
    matek_console_put_u32(matek_budget_io_max_cyc());
    matek_console_puts(" servo_us");
    for (uint8_t i = 0u; i < MATEK_SERVOS; ++i) {
        matek_console_puts(" ");
        matek_console_put_u32(stm32_pwm_map_readback_us(&servos, i));
    }
    matek_console_puts("\r\n");
}

uint16_t board_wait_tick(void)
{
    matek_budget_tick();
    for (;;) {
        matek_sensors_poll();
        matek_rc_poll();
        matek_console_pump();
        if ((int32_t)(matek_time_ms() - next_tick_ms) >= 0) {
            break;
        }
        /* Sleep until an interrupt; masked, so one arriving between the check
         * and the WFI still ends it (ARMv7-M: WFI wakes on a pending
         * interrupt even while PRIMASK is set). */
        __asm__ volatile("cpsid i" ::: "memory");
        if ((int32_t)(matek_time_ms() - next_tick_ms) < 0) {
            __asm__ volatile("wfi");
        }
        __asm__ volatile("cpsie i" ::: "memory");
    }
    uint32_t late = 0u;
    advance_tick();
    while ((int32_t)(matek_time_ms() - next_tick_ms) >= 0 && late < UINT16_MAX) {
        advance_tick(); /* ticks missed: skipped, counted */
        ++late;
    }
    late_total += late;
    ++ticks;
    if ((ticks % HEARTBEAT_TICKS) == 0u) {
        heartbeat();
    }
    return (uint16_t)late;
}

board_status_t board_servo_write_us(uint8_t channel, uint16_t pulse_us)
{
    const stm32_pwm_map_status_t st = stm32_pwm_map_set_us(&servos, channel, pulse_us);
    return (st == STM32_PWM_MAP_OK || st == STM32_PWM_MAP_CLAMPED) ? BOARD_OK : BOARD_ERR_RANGE;
}

void board_servo_commit(void)
{
    stm32_pwm_map_commit(&servos);
}

uint16_t matek_servo_readback_us(uint8_t channel)
{
    return stm32_pwm_map_readback_us(&servos, channel);
}

void board_failsafe(board_failsafe_t reason)
{
    static const char *const why[4] = {"none (left)", "RC lost", "sensors (no IMU samples)",
                                       "configuration refused: outputs silenced"};
    const uint32_t r = (uint32_t)reason;
    failsafe_now = (uint8_t)r;
    if (reason == BOARD_FS_CONFIG) {
        stm32_pwm_map_silence(&servos);
    }
    /* The beeper sounds for as long as any failsafe lasts. */
    stm32_gpio_write(matek_gpio(2u), MATEK_BEEPER_PIN, (uint8_t)((r != 0u) ? 1u : 0u));
    matek_console_puts("failsafe: ");
    matek_console_puts(why[(r < 4u) ? r : 3u]);
    matek_console_puts("\r\n");
}
