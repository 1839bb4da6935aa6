/*
 * stm32f4_usart.h - a polled USART driver (8N1, 16x oversampling) against a
 * register block passed by pointer, so host tests run it on a fake block.
 * The firmware's HIL link uses USART1 (QEMU's -serial #0 on netduinoplus2).
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
 * One received byte, if any: returns 1 and writes *byte when RXNE was set
 * (reading DR clears it), 0 when nothing is waiting. Errors flagged in SR
 * (overrun, framing, noise, parity) are counted; the byte is still handed on
 * (the frame CRC above decides), and the SR-then-DR read sequence clears them.
 */
int stm32_usart_read(stm32_usart_t *u, uint8_t *byte);

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
