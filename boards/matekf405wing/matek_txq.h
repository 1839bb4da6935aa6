/*
 * matek_txq.h - non-blocking UART transmit queues pumped from the main loop
 * (matek_txq.c): the console's and the GPS's.
 */
#ifndef HT_MATEK_TXQ_H
#define HT_MATEK_TXQ_H

#include <stddef.h>
#include <stdint.h>

#include "stm32f4_usart.h"

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

#endif /* HT_MATEK_TXQ_H */
