/*
 * stm32f4_usart.c - the polled USART driver (see stm32f4_usart.h).
 */
#include "stm32f4_usart.h"

static void count(uint16_t *c)
{
    if (*c != UINT16_MAX) {
        (*c)++;
    }
}

stm32_usart_status_t stm32_usart_init(stm32_usart_t *u, stm32_usart_regs_t *regs, uint32_t pclk_hz,
                                      uint32_t baud)
{
    if (u == NULL || regs == NULL) {
        return STM32_USART_ERR_NULL;
    }
    u->ready = 0u;
    if (baud < STM32_USART_BAUD_MIN || baud > STM32_USART_BAUD_MAX) {
        return STM32_USART_ERR_RANGE;
    }
    const uint32_t brr = (pclk_hz + baud / 2u) / baud;
    if (brr < 16u || brr > 0xFFFFu) {
        return STM32_USART_ERR_RANGE;
    }
    u->regs = regs;
    u->overrun = 0u;
    u->framing = 0u;
    u->noise = 0u;
    u->parity = 0u;
    u->tx_timeouts = 0u;
    regs->CR1 = 0u; /* disabled while configured; M = 0, no parity, OVER8 = 0 */
    regs->CR2 = 0u; /* one stop bit */
    regs->CR3 = 0u; /* no flow control, no DMA */
    regs->BRR = brr;
    regs->CR1 = USART_CR1_UE | USART_CR1_TE | USART_CR1_RE;
    u->ready = 1u;
    return STM32_USART_OK;
}

int stm32_usart_read(stm32_usart_t *u, uint8_t *byte)
{
    if (u == NULL || byte == NULL || !u->ready) {
        return 0;
    }
    const uint32_t sr = u->regs->SR;
    if ((sr & (USART_SR_RXNE | USART_SR_ORE)) == 0u) {
        return 0;
    }
    if ((sr & USART_SR_ORE) != 0u) {
        count(&u->overrun);
    }
    if ((sr & USART_SR_FE) != 0u) {
        count(&u->framing);
    }
    if ((sr & USART_SR_NF) != 0u) {
        count(&u->noise);
    }
    if ((sr & USART_SR_PE) != 0u) {
        count(&u->parity);
    }
    *byte = (uint8_t)(u->regs->DR & 0xFFu); /* SR then DR: clears RXNE and the errors */
    return 1;
}

void stm32_usart_enable_rx_irq(stm32_usart_t *u)
{
    if (u == NULL || !u->ready) {
        return;
    }
    u->regs->CR1 |= USART_CR1_RXNEIE;
}

size_t stm32_usart_write(stm32_usart_t *u, const uint8_t *data, size_t n, uint32_t spin_limit)
{
    if (u == NULL || data == NULL || !u->ready) {
        return 0u;
    }
    for (size_t i = 0; i < n; ++i) {
        uint32_t spins = 0u;
        while ((u->regs->SR & USART_SR_TXE) == 0u) {
            if (++spins >= spin_limit) {
                count(&u->tx_timeouts);
                return i;
            }
        }
        u->regs->DR = data[i];
    }
    return n;
}
