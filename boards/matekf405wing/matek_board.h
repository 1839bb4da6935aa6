/*
 * matek_board.h - board_matekf405wing.c's own declarations besides board.h
 * (never included by portable code: board.h is the seam). The board's
 * files, each with its own header, from the base up:
 *
 * matek_hw.c             clocks, 1 kHz time base, tick budget, delay, NVIC, pins
 * matek_txq.c            non-blocking UART transmit queues
 * matek_console.c        the console (USART1; matek_console_none.c in the HIL image)
 * matek_params_boot.c    the parameter store, loaded before board_init
 * matek_sensors.c        IMU (SPI1 + EXTI4), baro (I2C1), pitot (I2C2), GPS (USART3)
 * matek_rc.c             receiver: SBUS (USART2), CRSF (USART6) or PPM (TIM5)
 * matek_mavlink.c        the MAVLink ground-station link (UART4)
 * board_matekf405wing.c  board_init, servos, tick, failsafe (uses the ones above)
 * board_matekf405wing_hil.c  the HIL/PIL image's link (USART1)
 *
 * Each uses only files listed above it (and matek_param_blob.c), never one
 * below: the include graph is one way.
 */
#ifndef HT_MATEK_BOARD_H
#define HT_MATEK_BOARD_H

#include <stdint.h>

/* A servo output's pulse as its timer holds it, us (the HIL read-back). */
uint16_t matek_servo_readback_us(uint8_t channel);

#endif /* HT_MATEK_BOARD_H */
