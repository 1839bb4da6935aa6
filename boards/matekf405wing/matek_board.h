/*
 * matek_board.h - what the Matek F405-WING board files share among
 * themselves (never included by portable code: board.h is the seam).
 *
 * board_matekf405wing.c  clocks, 1 kHz time base, servos, tick, failsafe
 * matek_sensors.c        IMU (SPI1 + EXTI4), baro (I2C1), pitot (I2C2), GPS (USART3)
 * matek_rc.c             receiver: SBUS (USART2), CRSF (USART6) or PPM (TIM5)
 * matek_txq.c            non-blocking UART transmit queues, the console (USART1)
 * matek_params_boot.c    the parameter store, loaded before board_init
 * matek_mavlink.c        the MAVLink ground-station link (UART4)
 */
#ifndef HT_MATEK_BOARD_H
#define HT_MATEK_BOARD_H

#include <stddef.h>
#include <stdint.h>

#include "link/fw_link.h"
#include "matek_param_blob.h"
#include "stm32f4_clock.h"
#include "stm32f4_gpio.h"
#include "stm32f4_usart.h"

/* Bounded-wait budgets, in status reads (a read is several core cycles).
 * Chosen for 168 MHz and valid (only shorter in time) at 16 MHz. */
#define MATEK_SPI_SPINS 20000u /* one byte at 656 kHz is ~2000 cycles */
#define MATEK_I2C_SPINS 4000u  /* one byte at 400 kHz is 3780 cycles */
#define MATEK_TX_SPINS                                                                             \
    20000u                        /* one byte at 9600 baud is 175000 cycles: per byte,             \
                                     used only when a queue is drained */
#define MATEK_CLOCK_SPINS 200000u /* HSE start-up is ~2 ms typical (DS8626) */

/* --- board_matekf405wing.c ----------------------------------------------- */
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
/* imu_spi_bus_t.delay_us: waits on the time base, at most us * SYSCLK MHz loops. */
void matek_delay_us(void *ctx, uint32_t us);
void matek_nvic_enable(uint32_t irqn);
stm32_gpio_t *matek_gpio(uint8_t port); /* 0 = A, 1 = B, 2 = C */
/* A pin as an alternate function; open_drain for I2C (with the pull-up on). */
void matek_pin_af(uint8_t port, uint8_t pin, uint8_t af, uint8_t open_drain);

/* --- matek_txq.c ---------------------------------------------------------- */
#define MATEK_TXQ_SIZE 1024u /* a power of two */
typedef struct {
    stm32_usart_t *u;
    uint8_t buf[MATEK_TXQ_SIZE];
    uint32_t head, tail; /* free-running; only the main loop touches them */
    uint32_t dropped;
} matek_txq_t;
void matek_txq_init(matek_txq_t *q, stm32_usart_t *u);
/* Queue up to n bytes; returns how many fitted (the rest are counted). */
size_t matek_txq_write(matek_txq_t *q, const uint8_t *bytes, size_t n);
/* Move bytes to the USART while TXE is set, at most max_bytes. */
void matek_txq_pump(matek_txq_t *q, uint32_t max_bytes);
/* Pump until empty, at most MATEK_TX_SPINS status reads per byte. */
void matek_txq_drain(matek_txq_t *q);

/* The console on USART1 (115200 8N1). In the HIL image the link owns
 * USART1 and these print nothing (matek_console_none.c). */
void matek_console_init(void);
void matek_console_puts(const char *s);
void matek_console_put_u32(uint32_t v);
void matek_console_put_i32(int32_t v);
void matek_console_pump(void);
void matek_console_flush(void);

/* --- matek_sensors.c ------------------------------------------------------ */
void matek_sensors_init(void);
/* Every wake of the tick loop: the IMU sample on data-ready (1 kHz). */
void matek_sensors_poll(void);
uint32_t matek_sensors_imu_samples(void);

/* --- matek_rc.c ----------------------------------------------------------- */
void matek_rc_init(void);
/* Every wake of the tick loop (<= 1 ms apart: SBUS needs <= 3 ms). */
void matek_rc_poll(void);

/* --- matek_params_boot.c -------------------------------------------------- */
const matek_params_report_t *matek_params_report(void);
/* The link's stored parameters when the boot load accepted a set, else NULL
 * (fw_board_link_init puts them into the link). */
const fw_link_params_t *matek_params_link(void);
/* fw_link_save_fn: every row the link exposes into the store (a flash sector
 * erase: the loop stalls). 0 = saved. */
int matek_params_save(void *ctx, const fw_config_t *cfg, const fw_link_params_t *link);

#endif /* HT_MATEK_BOARD_H */
