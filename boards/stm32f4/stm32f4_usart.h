/*
 * stm32f4_usart.h - a polled USART driver (8N1 or 8E2, 16x oversampling)
 * against a register block passed by pointer, so host tests run it on a
 * fake block. The firmware's HIL link uses USART1 (QEMU's -serial #0 on
 * netduinoplus2); the receiver and GPS links (docs/drivers/serial_links.md)
 * receive through serial_rx_ring.h.
 *
 * Nothing here waits without a bound: a transmit waits at most spin_limit
 * status reads per byte, and a receive never waits.
 */
#ifndef HT_STM32F4_USART_H
#define HT_STM32F4_USART_H

#include <stddef.h>
#include <stdint.h>

#include "stm32f4_usart_regs.h"

#define STM32_USART_BAUD_MIN 1200u
#define STM32_USART_BAUD_MAX 4000000u

typedef enum {
    STM32_USART_OK = 0,
    STM32_USART_ERR_NULL = 1,
    STM32_USART_ERR_RANGE = 2 /* the baud rate cannot be made from this clock: nothing written */
} stm32_usart_status_t;

/*
 * Frame formats (RM0090 section 30.3.2, table 137 "Frame formats"):
 *   8N1: M = 0, PCE = 0, STOP = 00 - GPS, CRSF (420000 baud), the HIL link.
 *   8E2: M = 1 (a 9-bit word: 8 data bits and the parity bit), PCE = 1,
 *        PS = 0 (even), STOP = 10 (two stop bits) - SBUS at 100000 baud.
 *        The STM32F405 cannot invert its RX pin: SBUS needs the board's own
 *        inverter (the Matek F405-WING has one on the RX2 pad).
 */
typedef enum { STM32_USART_8N1 = 0, STM32_USART_8E2 = 1 } stm32_usart_format_t;

/* Driver state, owned by the caller. The counters saturate at UINT16_MAX. */
typedef struct {
    stm32_usart_regs_t *regs;
    uint16_t overrun, framing, noise, parity; /* receive errors seen in SR */
    uint16_t tx_timeouts;                     /* bytes not sent: TXE stayed low */
    uint8_t ready;                            /* 1 after a successful init */
} stm32_usart_t;

/*
 * Configure 8N1 at baud from the peripheral clock pclk_hz and enable the
 * USART, its transmitter and receiver (UE | TE | RE). BRR = round(pclk_hz /
 * baud) (16x oversampling: USARTDIV = pclk / (16 baud), BRR holds it with a
 * 4-bit fraction), which must lie in [16, 0xFFFF].
 */
stm32_usart_status_t stm32_usart_init(stm32_usart_t *u, stm32_usart_regs_t *regs, uint32_t pclk_hz,
                                      uint32_t baud);

/*
 * As stm32_usart_init, in the given frame format. An unknown format returns
 * STM32_USART_ERR_RANGE and writes nothing. Written: CR1 = 0, CR2 (STOP),
 * CR3 = 0, BRR, then CR1 = UE | TE | RE (| M | PCE for 8E2).
 * pclk_hz is PCLK2 for USART1/6 and PCLK1 for USART2/3, UART4/5.
 */
stm32_usart_status_t stm32_usart_init_format(stm32_usart_t *u, stm32_usart_regs_t *regs,
                                             uint32_t pclk_hz, uint32_t baud,
                                             stm32_usart_format_t format);

/*
 * The baud rate error of what BRR = round(pclk_hz / baud) makes, in parts per
 * million, rounded to nearest: (pclk_hz / BRR - baud) / baud * 1e6 (RM0090
 * section 30.3.4: Tx/Rx baud = f_pclk / (16 USARTDIV), and BRR is USARTDIV
 * with a 4-bit fraction, so pclk / BRR is the real rate). For example
 * 84 MHz / 420000 = 200 exactly: 0 ppm; 16 MHz / 115200: BRR 139, -799 ppm.
 * Returns STM32_USART_ERR_RANGE (error_ppm untouched) where init would.
 */
stm32_usart_status_t stm32_usart_baud_error_ppm(uint32_t pclk_hz, uint32_t baud,
                                                int32_t *error_ppm);

/*
 * One received byte, if any: returns 1 and writes *byte when RXNE was set
 * (reading DR clears it), 0 when nothing is waiting. Errors flagged in SR
 * (overrun, framing, noise, parity) are counted; the byte is still handed on
 * (the frame CRC above decides), and the SR-then-DR read sequence clears them.
 */
int stm32_usart_read(stm32_usart_t *u, uint8_t *byte);

/*
 * As stm32_usart_read, and *errors receives the SR error flags that came with
 * the byte (USART_SR_PE | FE | NF | ORE bits; 0 when clean), so that an
 * interrupt handler can drop a byte whose parity or framing was wrong
 * (serial_rx_ring_isr does). errors may not be NULL.
 */
int stm32_usart_read_flags(stm32_usart_t *u, uint8_t *byte, uint32_t *errors);

/*
 * Let the receiver interrupt (RXNEIE): the USART's line goes active while a
 * byte waits (or an overrun is flagged); the handler calls stm32_usart_read.
 */
void stm32_usart_enable_rx_irq(stm32_usart_t *u);

/*
 * Send n bytes, each after TXE is seen set within spin_limit status reads.
 * Returns the number of bytes written; stops at the first timeout (counted).
 */
size_t stm32_usart_write(stm32_usart_t *u, const uint8_t *data, size_t n, uint32_t spin_limit);

#endif /* HT_STM32F4_USART_H */
