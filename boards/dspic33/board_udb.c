/*
 * board_udb.c - board.h for a dsPIC33FJ256GP710A board (UDB4/UDB5), built by
 * XC16 only: the host build tests dspic33_oc_pwm.c on fake SFRs instead.
 *
 * Not compiled or run here (no XC16 on this machine): it is written against
 * the datasheet's register map (dspic33fj_regs.h) and keeps to what the host
 * tests prove of the driver. The oscillator is whatever the configuration
 * bits and any start-up code select; this file does no clock switching and
 * waits on no oscillator flag. Tell it the resulting instruction clock:
 *   xc16-gcc -mcpu=33FJ256GP710A -DHT_DSPIC_FCY_HZ=40000000 ...
 *
 * Servo n (0..7) = OC(n+1) on RDn, PWM from Timer2. Control tick = Timer1
 * period flag, polled. RC input and sensors: boards/common/rc_none.c and
 * sensors_level.c until a receiver driver and an IMU/DCM (or the simulator
 * link) replace them.
 */
#ifndef __XC16__
#error "board_udb.c is for XC16; the host build tests dspic33_oc_pwm.c only"
#endif
#ifndef HT_DSPIC_FCY_HZ
#error "define HT_DSPIC_FCY_HZ: the instruction clock (Fcy) your oscillator set-up gives"
#endif

#include "helical/board.h"

#include "dspic33_oc_pwm.h"
#include "dspic33fj_regs.h"

#include <stddef.h>

/* The SFRs are reached at their fixed addresses (datasheet register map):
 * each is a const pointer made from the address, the one place an integer
 * becomes a pointer (docs/static-analysis.md, D-11.4-REG). IFS0 is shared by
 * two functions; the others are local to the function that uses them. */
// cppcheck-suppress misra-c2012-11.4 ; D-11.4-REG: IFS0 register address
static volatile uint16_t *const udb_ifs0 = (volatile uint16_t *)DSPIC_IFS0_ADDR;

static dspic_pwm_t servo_pwm;

/* Timer1 at control_hz: the smallest prescaler whose period fits 16 bits. */
static int tick_start(uint32_t fcy_hz, uint16_t hz)
{
    // cppcheck-suppress misra-c2012-11.4 ; D-11.4-REG: Timer1 register block address
    dspic_tmr1_t *const udb_tmr1 = (dspic_tmr1_t *)DSPIC_TMR1_ADDR;
    const uint16_t t1if = DSPIC_IFS0_T1IF;
    static const uint16_t prescales[4] = {1u, 8u, 64u, 256u};
    for (uint16_t tckps = 0u; tckps < 4u; ++tckps) {
        const uint32_t div = (uint32_t)prescales[tckps] * hz;
        const uint32_t counts = (fcy_hz + div / 2u) / div;
        if (counts >= 2u && counts <= 65535u) {
            udb_tmr1->T1CON = 0u;
            udb_tmr1->TMR1 = 0u;
            udb_tmr1->PR1 = (uint16_t)(counts - 1u);
            *udb_ifs0 &= (uint16_t)~t1if;
            udb_tmr1->T1CON = (uint16_t)(DSPIC_TCON_TON | (tckps << DSPIC_TCON_TCKPS_SHIFT));
            return 1;
        }
    }
    return 0;
}

board_status_t board_init(const board_config_t *cfg)
{
    // cppcheck-suppress misra-c2012-11.4 ; D-11.4-REG: Timer2/3 register block address
    dspic_tmr23_t *const udb_tmr23 = (dspic_tmr23_t *)DSPIC_TMR23_ADDR;
    // cppcheck-suppress misra-c2012-11.4 ; D-11.4-REG: OC1..OC8 register block address
    dspic_oc_t *const udb_oc1 = (dspic_oc_t *)DSPIC_OC1_ADDR;
    // cppcheck-suppress misra-c2012-11.4 ; D-11.4-REG: TRISD register address
    volatile uint16_t *const udb_trisd = (volatile uint16_t *)DSPIC_TRISD_ADDR;
    const uint16_t rd0_7 = 0x00FFu;
    board_status_t st = board_config_check(cfg);
    if (st != BOARD_OK) {
        return st;
    }
    if (dspic_pwm_init(&servo_pwm, udb_tmr23, udb_oc1, 2u, HT_DSPIC_FCY_HZ, cfg->servo_frame_hz,
                       cfg->servo_start_us) != DSPIC_PWM_OK) {
        return BOARD_ERR_HW;
    }
    *udb_trisd &= (uint16_t)~rd0_7; /* RD0..RD7 outputs */
    return (tick_start(HT_DSPIC_FCY_HZ, cfg->control_hz) != 0) ? BOARD_OK : BOARD_ERR_HW;
}

uint8_t board_servo_count(void)
{
    return (uint8_t)DSPIC_OC_COUNT;
}

/* A polled flag cannot count missed periods: 1 means the previous tick's
 * work overran into this period, 0 that it did not. */
uint16_t board_wait_tick(void)
{
    const uint16_t t1if = DSPIC_IFS0_T1IF;
    uint16_t late = 0u;
    if ((*udb_ifs0 & t1if) != 0u) {
        late = 1u;
    }
    while ((*udb_ifs0 & t1if) == 0u) {
    }
    *udb_ifs0 &= (uint16_t)~t1if;
    return late;
}

board_status_t board_servo_write_us(uint8_t channel, uint16_t pulse_us)
{
    const dspic_pwm_status_t st = dspic_pwm_set_us(&servo_pwm, channel, pulse_us);
    return (st == DSPIC_PWM_OK || st == DSPIC_PWM_CLAMPED) ? BOARD_OK : BOARD_ERR_RANGE;
}

void board_servo_commit(void)
{
    (void)dspic_pwm_commit(&servo_pwm);
}

void board_failsafe(board_failsafe_t reason)
{
    if (reason == BOARD_FS_CONFIG) {
        for (uint8_t ch = 0; ch < DSPIC_OC_COUNT; ++ch) {
            (void)dspic_pwm_set_us(&servo_pwm, ch, 0u); /* 0 counts: pins stay low */
        }
        (void)dspic_pwm_commit(&servo_pwm);
    }
}
