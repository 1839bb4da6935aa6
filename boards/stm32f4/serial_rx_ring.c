/*
 * serial_rx_ring.c - the interrupt-to-tick byte ring (see serial_rx_ring.h).
 */
#include "serial_rx_ring.h"

static void count32(volatile uint32_t *c)
{
    const uint32_t v = *c;
    if (v != UINT32_MAX) {
        *c = v + 1u;
    }
}

serial_rx_ring_status_t serial_rx_ring_init(serial_rx_ring_t *r, volatile uint8_t *storage,
                                            uint32_t size)
{
    if (r == NULL || storage == NULL) {
        return SERIAL_RX_RING_ERR_NULL;
    }
    if (size < SERIAL_RX_RING_SIZE_MIN || size > SERIAL_RX_RING_SIZE_MAX ||
        (size & (size - 1u)) != 0u) {
        return SERIAL_RX_RING_ERR_SIZE;
    }
    r->buf = storage;
    r->mask = size - 1u;
    r->head = 0u;
    r->tail = 0u;
    r->dropped_full = 0u;
    r->dropped_error = 0u;
    return SERIAL_RX_RING_OK;
}

int serial_rx_ring_put(serial_rx_ring_t *r, uint8_t byte)
{
    if (r == NULL || r->buf == NULL) {
        return 0;
    }
    const uint32_t head = r->head;
    const uint32_t used = head - r->tail; /* one read of tail: the consumer may move it */
    if (used > r->mask) {
        count32(&r->dropped_full);
        return 0;
    }
    r->buf[head & r->mask] = byte; /* the byte first ... */
    r->head = head + 1u;           /* ... then the count that publishes it */
    return 1;
}

uint32_t serial_rx_ring_count(const serial_rx_ring_t *r)
{
    if (r == NULL) {
        return 0u;
    }
    const uint32_t head = r->head;
    return head - r->tail;
}

size_t serial_rx_ring_read(serial_rx_ring_t *r, uint8_t *out, size_t max)
{
    if (r == NULL || out == NULL || r->buf == NULL) {
        return 0u;
    }
    const uint32_t head = r->head; /* once: bytes stored after this wait for the next read */
    uint32_t tail = r->tail;
    size_t n = 0u;
    while (n < max && tail != head) {
        out[n] = r->buf[tail & r->mask];
        tail++;
        n++;
    }
    r->tail = tail; /* the slots are free only now, after they were read */
    return n;
}

int serial_rx_ring_isr(stm32_usart_t *u, serial_rx_ring_t *r)
{
    uint8_t byte = 0u;
    uint32_t errors = 0u;
    /* Read DR even without a ring: an unread byte would hold the line high. */
    if (stm32_usart_read_flags(u, &byte, &errors) == 0) {
        return 0;
    }
    if (r == NULL) {
        return 1;
    }
    if ((errors & (USART_SR_PE | USART_SR_FE)) != 0u) {
        count32(&r->dropped_error);
        return 1;
    }
    (void)serial_rx_ring_put(r, byte);
    return 1;
}
