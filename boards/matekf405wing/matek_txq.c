/*
 * matek_txq.c - transmit queues pumped from the main loop (no interrupt:
 * QEMU's USART model raises no TXE interrupt, and the loop wakes at least
 * every millisecond anyway): the console's (matek_console.c) and the GPS's.
 */
#include "matek_txq.h"

#include "matek_hw.h"
#include "matekf405wing_pins.h"
#include "stm32f4_regs.h"

#define QMASK (MATEK_TXQ_SIZE - 1u)

void matek_txq_init(matek_txq_t *q, stm32_usart_t *u)
{
    q->u = u;
    q->head = 0u;
    q->tail = 0u;
    q->dropped = 0u;
}

size_t matek_txq_write(matek_txq_t *q, const uint8_t *bytes, size_t n)
{
    size_t i = 0u;
    while (i < n && (q->head - q->tail) < MATEK_TXQ_SIZE) {
        q->buf[q->head & QMASK] = bytes[i];
        q->head += 1u;
        ++i;
    }
    if (i < n) {
        q->dropped += (uint32_t)(n - i);
    }
    return i;
}

void matek_txq_pump(matek_txq_t *q, uint32_t max_bytes)
{
    if (q->u == NULL || q->u->ready == 0u) {
        return;
    }
    for (uint32_t k = 0u; k < max_bytes && q->tail != q->head; ++k) {
        if ((q->u->regs->SR & USART_SR_TXE) == 0u) {
            return;
        }
        q->u->regs->DR = q->buf[q->tail & QMASK];
        q->tail += 1u;
    }
}

void matek_txq_drain(matek_txq_t *q)
{
    if (q->u == NULL || q->u->ready == 0u) {
        q->tail = q->head;
        return;
    }
    while (q->tail != q->head) {
        uint32_t spins = 0u;
        while ((q->u->regs->SR & USART_SR_TXE) == 0u && spins < MATEK_TX_SPINS) {
            ++spins;
        }
        if (spins >= MATEK_TX_SPINS) {
            q->dropped += q->head - q->tail; /* TXE never came: give up */
            q->tail = q->head;
            return;
        }
        q->u->regs->DR = q->buf[q->tail & QMASK];
        q->tail += 1u;
    }
}
