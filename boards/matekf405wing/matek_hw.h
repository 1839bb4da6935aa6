/*
 * matek_hw.h - the Matek F405-WING image's low-level base (matek_hw.c): the
 * clocks, the 1 kHz time base, the tick budget's marks, the bounded delay,
 * NVIC enables and GPIO pins. Every other board file may use it; it uses
 * none of them (never included by portable code: board.h is the seam).
 */
#ifndef HT_MATEK_HW_H
#define HT_MATEK_HW_H

#include <stdint.h>

#include "stm32f4_clock.h"
#include "stm32f4_gpio.h"

/* Bounded-wait budgets, in status reads (a read is several core cycles).
 * Chosen for 168 MHz and valid (only shorter in time) at 16 MHz. */
#define MATEK_SPI_SPINS 20000u /* one byte at 656 kHz is ~2000 cycles */
#define MATEK_I2C_SPINS 4000u  /* one byte at 400 kHz is 3780 cycles */
#define MATEK_TX_SPINS                                                                             \
    20000u                        /* one byte at 9600 baud is 175000 cycles: per byte,             \
                                     used only when a queue is drained */
#define MATEK_CLOCK_SPINS 200000u /* HSE start-up is ~2 ms typical (DS8626) */

/* The time base's rate: SysTick_Handler counts ms. */
#define MATEK_TIMEBASE_HZ 1000u

/* The clocks (168 MHz from the crystal, else 16 MHz HSI), every peripheral
 * clock the image uses, then the 1 kHz time base. 1 = running; 0 = the
 * SysTick refused the rate (no time base). */
int matek_hw_start(void);

const stm32_clocks_t *matek_clocks(void);
uint32_t matek_time_ms(void);
uint32_t matek_time_us(void);
/* SysTick counts since boot (HCLK cycles on the board), for the tick budget. */
uint32_t matek_cycles(void);
#define MATEK_MARK_SENSORS_IN  0u
#define MATEK_MARK_SENSORS_OUT 1u
#define MATEK_MARK_RC_IN       2u
#define MATEK_MARK_RC_OUT      3u
void matek_budget_mark(uint8_t where);
/* At the start of each board_wait_tick: the time since MATEK_MARK_RC_OUT
 * (the firmware step and the pulses) into the worst step time. */
void matek_budget_tick(void);
/* The worst step time and the worst of the board's own reads in one tick,
 * SysTick counts. */
uint32_t matek_budget_step_max_cyc(void);
uint32_t matek_budget_io_max_cyc(void);
/* imu_spi_bus_t.delay_us: waits on the time base, at most us * SYSCLK MHz loops. */
void matek_delay_us(void *ctx, uint32_t us);
void matek_nvic_enable(uint32_t irqn);
stm32_gpio_t *matek_gpio(uint8_t port); /* 0 = A, 1 = B, 2 = C */
/* A pin as an alternate function; open_drain for I2C (with the pull-up on). */
void matek_pin_af(uint8_t port, uint8_t pin, uint8_t af, uint8_t open_drain);

#endif /* HT_MATEK_HW_H */
