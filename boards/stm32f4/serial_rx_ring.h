/*
 * serial_rx_ring.h - the receive path of a serial link: the USART's receive
 * interrupt puts each byte into a ring buffer (serial_rx_ring_isr), and the
 * control tick takes what has arrived (serial_rx_ring_read) and hands it to
 * a link (boards/common/rc_serial_link.h, gps_ubx_link.h).
 *
 * One producer (the interrupt handler) and one consumer (the tick), no lock:
 *
 *   - head counts the bytes ever stored; only the producer writes it.
 *   - tail counts the bytes ever taken;  only the consumer writes it.
 *   Both run free (uint32, wrapping); head - tail is the number waiting, and
 *   a byte's slot is its count & (size - 1), so size is a power of two.
 *
 * When the ring is full an arriving byte is dropped and counted
 * (dropped_full): unread bytes are never overwritten, so the consumer sees
 * a gap in the stream (which the frame decoders resynchronise over), never
 * a torn mix of old and new bytes.
 *
 * Memory ordering, Cortex-M4 (STM32F405: one core, no data cache, SRAM):
 * the interrupt handler preempts the tick on the same core, and a core sees
 * its own memory accesses in program order (ARMv7-M architecture reference
 * manual, DDI 0403, section A3.7 "Memory access order"; ARM application note
 * AN321 "Cortex-M programming guide to memory barrier instructions": no DMB
 * is needed between an interrupt handler and the code it interrupts on one
 * core). What remains is the compiler: the storage, head and tail are all
 * volatile, so their accesses are neither merged nor reordered among
 * themselves, and
 *   - the producer writes the byte, then head (the byte is in place before
 *     the consumer can count it);
 *   - the consumer reads head once, copies the bytes below it, then writes
 *     tail (a slot is freed only after it was read).
 * Each index is one aligned 32-bit word, written by one side only, so each
 * read of it is whole (a single LDR/STR). On a multi-core or cached part
 * this would need barriers; the STM32F405 is neither.
 *
 * The state is the caller's serial_rx_ring_t and its storage.
 */
#ifndef HT_SERIAL_RX_RING_H
#define HT_SERIAL_RX_RING_H

#include <stddef.h>
#include <stdint.h>

#include "stm32f4_usart.h"

#define SERIAL_RX_RING_SIZE_MIN 2u
/* head - tail must stay below 2^31 for the free-running counts: any
 * practical size is far below. */
#define SERIAL_RX_RING_SIZE_MAX 0x8000u

typedef enum {
    SERIAL_RX_RING_OK = 0,
    SERIAL_RX_RING_ERR_NULL = 1,
    SERIAL_RX_RING_ERR_SIZE = 2 /* not a power of two in [MIN, MAX]: nothing written */
} serial_rx_ring_status_t;

typedef struct {
    volatile uint8_t *buf;           /* the caller's storage, size bytes */
    uint32_t mask;                   /* size - 1 */
    volatile uint32_t head;          /* bytes stored (producer only) */
    volatile uint32_t tail;          /* bytes taken (consumer only) */
    volatile uint32_t dropped_full;  /* bytes dropped, ring full (producer only; saturates) */
    volatile uint32_t dropped_error; /* bytes dropped by the ISR: parity or framing error */
} serial_rx_ring_t;

/*
 * Use storage (size bytes, a power of two in [SERIAL_RX_RING_SIZE_MIN,
 * SERIAL_RX_RING_SIZE_MAX]) as an empty ring. Call before the interrupt
 * is enabled.
 */
serial_rx_ring_status_t serial_rx_ring_init(serial_rx_ring_t *r, volatile uint8_t *storage,
                                            uint32_t size);

/* Producer: store one byte. Returns 1, or 0 when the ring was full (the byte
 * is dropped and counted) or r is NULL. */
int serial_rx_ring_put(serial_rx_ring_t *r, uint8_t byte);

/* Consumer: the number of bytes waiting. */
uint32_t serial_rx_ring_count(const serial_rx_ring_t *r);

/* Consumer: take up to max bytes, oldest first, into out. Returns how many.
 * 0 on NULL arguments. */
size_t serial_rx_ring_read(serial_rx_ring_t *r, uint8_t *out, size_t max);

/*
 * The USART's receive interrupt handler body (RXNEIE, see
 * stm32_usart_enable_rx_irq): reads at most one byte (SR then DR, which also
 * clears an overrun, so the interrupt line falls) and puts it into the ring.
 * The USART interrupt fires again while another byte waits, so one byte per
 * call keeps the handler's time bounded. A byte received with a parity or a
 * framing error (SR.PE, SR.FE) is dropped and counted (dropped_error): SBUS
 * has no checksum, and a missing byte makes its frame fail the end-byte
 * test, where a corrupted byte would pass. Noise (NF) and overrun (ORE) are
 * counted by the driver (stm32_usart_t) and the byte kept: the majority
 * vote gave its value, and on an overrun DR holds the older, intact byte.
 * Returns 1 when a byte was read from DR (stored or not), 0 otherwise.
 */
int serial_rx_ring_isr(stm32_usart_t *u, serial_rx_ring_t *r);

#endif /* HT_SERIAL_RX_RING_H */
