/*
 * tick_budget_main.c - the firmware step's worst cost on the target, for
 * scripts/cross_builds.sh: an image (ht_matekf405wing_budget.elf, built
 * with the Matek F405-WING preset) that calls fw_step 12 000 times (60 s
 * at 200 Hz) on synthetic inputs - IMU every call, GPS 3-D fix at 5 Hz, baro
 * at 50 Hz, pitot at 25 Hz, RC at 50 Hz - while the mode switch walks
 * through manual, fly-by-wire and waypoint (three waypoints), then the RC
 * stops (RC loss: return-to-home). Each call is timed with SysTick, free
 * running at the core clock, and the worst call (and the worst call that
 * ran the control chain) are printed on USART1:
 *   budget: calls N control K step_max_cyc A control_max_cyc B
 * Under QEMU with -icount shift=0 each instruction is 1 ns of virtual time and
 * SysTick counts at the model's 168 MHz, so instructions = cycles / 0.168.
 * Not a board (no board.h) and not a test of the step: a measurement.
 * Integer only; the synthetic inputs come from a fixed LCG.
 */
#include "fw_step.h"
#include "stm32f4_regs.h"
#include "stm32f4_usart.h"

#include <stddef.h>

#define CALLS 12000u

static fw_config_t cfg;
static fw_t fw;
static fw_inputs_t in;
static fw_output_t out;
static stm32_usart_t con;
static const ht_waypoint_t wps[3] = {{500, 0, 100}, {500, 500, 120}, {0, 500, 100}};

static void put(const char *s)
{
    size_t n = 0u;
    while (s[n] != '\0') {
        ++n;
    }
    (void)stm32_usart_write(&con, (const uint8_t *)s, n, 100000u);
}

static void put_u32(uint32_t v)
{
    char d[11];
    uint32_t n = 0u;
    do {
        d[n] = (char)('0' + (char)(v % 10u));
        v /= 10u;
        ++n;
    } while (v != 0u && n < 10u);
    char o[12];
    for (uint32_t i = 0u; i < n; ++i) {
        o[i] = d[n - 1u - i];
    }
    o[n] = '\0';
    put(o);
}

static uint32_t lcg = 12345u;
static int32_t noise(int32_t amp)
{
    lcg = lcg * 1664525u + 1013904223u;
    const int32_t r = (int32_t)((lcg >> 16) & 0xFFFFu) - 32768;
    return (r * amp) / 32768;
}

static void inputs(uint32_t k)
{
    board_sensors_t *s = &in.sensors;
    s->imu_fresh = 1u;
    for (unsigned i = 0u; i < 3u; ++i) {
        s->imu.gyro_rad_s[i] = noise(3000); /* +/-0.05 rad/s */
        s->imu.accel_g[i] = noise(2000);
    }
    s->imu.accel_g[2] -= 65536; /* level: (0, 0, -1 g) */
    s->gps.fresh = (uint8_t)((k % 40u) == 0u);
    s->gps.fix = 3u;
    s->gps.lat_e7 = 473977000 + (int32_t)(k / 40u) * 135; /* ~15 m/s north */
    s->gps.lon_e7 = 85456000;
    s->gps.alt_cm = 50000;
    s->gps.vel_ned_cm_s[0] = 1500;
    s->gps.vel_ned_cm_s[1] = noise(100);
    s->gps.vel_ned_cm_s[2] = 0;
    s->baro_fresh = (uint8_t)((k % 4u) == 0u);
    s->baro_alt_cm = 50000 + noise(50);
    s->airspeed_fresh = (uint8_t)((k % 8u) == 0u);
    s->airspeed_cm_s = (int16_t)(1500 + noise(100));
    /* RC at 50 Hz for 48 s (switch: manual, FBW, waypoint), then silence */
    const uint32_t phase = k / 4000u;
    in.rc_fresh = (uint8_t)(((k % 4u) == 0u) && k < 9600u);
    for (unsigned i = 0u; i < 8u; ++i) {
        in.rc_us[i] = (uint16_t)(1500 + noise(200));
    }
    in.rc_us[2] = 1400u;
    in.rc_us[4] = (phase == 0u) ? 1000u : ((phase == 1u) ? 1500u : 2000u);
}

int main(void)
{
    // cppcheck-suppress misra-c2012-11.4 ; D-11.4-REG: SysTick register block address
    stm32_systick_t *const st = (stm32_systick_t *)STM32_SYSTICK_BASE;
    // cppcheck-suppress misra-c2012-11.4 ; D-11.4-REG: RCC register block address
    stm32_rcc_t *const rcc = (stm32_rcc_t *)STM32_RCC_BASE;
    // cppcheck-suppress misra-c2012-11.4 ; D-11.4-REG: USART1 register block address
    stm32_usart_regs_t *const usart1 = (stm32_usart_regs_t *)STM32_USART1_BASE;
    rcc->APB2ENR |= RCC_APB2ENR_USART1EN;
    (void)stm32_usart_init(&con, usart1, STM32_HSI_HZ, 115200u);
    fw_config_default(&cfg);
    cfg.waypoints = wps;
    cfg.waypoint_count = 3u;
    if (fw_init(&fw, &cfg) == 0) {
        put("budget: fw_init refused\r\n");
        for (;;) {
        }
    }
    in.rc_count = 8u;
    st->LOAD = SYSTICK_LOAD_MAX; /* free running, no interrupt */
    st->VAL = 0u;
    st->CTRL = SYSTICK_CTRL_ENABLE | SYSTICK_CTRL_CLKSOURCE;
    uint32_t step_max = 0u, control_max = 0u, control = 0u;
    for (uint32_t k = 0u; k < CALLS; ++k) {
        inputs(k);
        const uint32_t t0 = st->VAL;
        const int ran = fw_step(&fw, &in, &out);
        const uint32_t t1 = st->VAL;
        const uint32_t d = (t0 - t1) & SYSTICK_LOAD_MAX; /* a down counter */
        step_max = (d > step_max) ? d : step_max;
        if (ran != 0) {
            ++control;
            control_max = (d > control_max) ? d : control_max;
            in.rc_fresh = 0u;
        }
    }
    put("budget: calls ");
    put_u32(CALLS);
    put(" control ");
    put_u32(control);
    put(" step_max_cyc ");
    put_u32(step_max);
    put(" control_max_cyc ");
    put_u32(control_max);
    put(" modes_failsafe ");
    put_u32(out.modes.failsafe);
    put("\r\n");
    for (;;) {
        __asm__ volatile("wfi");
    }
}
