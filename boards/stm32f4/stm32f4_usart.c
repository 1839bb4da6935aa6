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

/* BRR = round(pclk / baud) (16x oversampling), 0 if outside [16, 0xFFFF] or
 * the baud outside the driver's range. */
static uint32_t brr_of(uint32_t pclk_hz, uint32_t baud)
{
    if (baud < STM32_USART_BAUD_MIN || baud > STM32_USART_BAUD_MAX) {
        return 0u;
    }
    const uint32_t half = baud / 2u;
    const uint64_t rounded = ((uint64_t)pclk_hz + (uint64_t)half) / (uint64_t)baud;
    if (rounded < 16u || rounded > 0xFFFFu) {
        return 0u;
    }
    return (uint32_t)rounded;
}

stm32_usart_status_t stm32_usart_init(stm32_usart_t *u, stm32_usart_regs_t *regs, uint32_t pclk_hz,
                                      uint32_t baud)
{
    return stm32_usart_init_format(u, regs, pclk_hz, baud, STM32_USART_8N1);
}

stm32_usart_status_t stm32_usart_init_format(stm32_usart_t *u, stm32_usart_regs_t *regs,
                                             uint32_t pclk_hz, uint32_t baud,
                                             stm32_usart_format_t format)
{
    if (u == NULL || regs == NULL) {
        return STM32_USART_ERR_NULL;
    }
    u->ready = 0u;
    uint32_t cr1_format;
    uint32_t cr2;
    switch (format) {
    case STM32_USART_8N1:
        cr1_format = 0u; /* M = 0: 8 data bits; PCE = 0: no parity */
        cr2 = USART_CR2_STOP_1;
        break;
    case STM32_USART_8E2:
        /* M = 1: the 9-bit word holds 8 data bits and the parity bit, which
         * PCE = 1 puts in the MSB; PS = 0 is even parity (SBUS). */
        cr1_format = USART_CR1_M | USART_CR1_PCE;
        cr2 = USART_CR2_STOP_2;
        break;
    default:
        return STM32_USART_ERR_RANGE;
    }
    const uint32_t brr = brr_of(pclk_hz, baud);
    if (brr == 0u) {
        return STM32_USART_ERR_RANGE;
    }
    u->regs = regs;
    u->overrun = 0u;
    u->framing = 0u;
    u->noise = 0u;
    u->parity = 0u;
    u->tx_timeouts = 0u;
    regs->CR1 = 0u; /* disabled while configured (M, PCE take effect with UE low) */
    regs->CR2 = cr2;
    regs->CR3 = 0u; /* no flow control, no DMA */
    regs->BRR = brr;
    regs->CR1 = USART_CR1_UE | USART_CR1_TE | USART_CR1_RE | cr1_format;
    u->ready = 1u;
    return STM32_USART_OK;
}

stm32_usart_status_t stm32_usart_baud_error_ppm(uint32_t pclk_hz, uint32_t baud, int32_t *error_ppm)
{
    if (error_ppm == NULL) {
        return STM32_USART_ERR_NULL;
    }
    const uint32_t brr = brr_of(pclk_hz, baud);
    if (brr == 0u) {
        return STM32_USART_ERR_RANGE;
    }
    /* (pclk / brr - baud) / baud = (pclk - brr * baud) / (brr * baud) */
    const int64_t made = (int64_t)brr * (int64_t)baud;
    const int64_t diff = (int64_t)pclk_hz - made;
    const int64_t scaled = diff * 1000000;
    const int64_t half = made / 2;
    int64_t ppm;
    if (scaled >= 0) {
        ppm = (scaled + half) / made;
    } else {
        ppm = (scaled - half) / made;
    }
    /* |diff| <= baud / 2 + 1 and brr >= 16, so |ppm| < 32000: fits. */
    *error_ppm = (int32_t)ppm;
    return STM32_USART_OK;
}

int stm32_usart_read_flags(stm32_usart_t *u, uint8_t *byte, uint32_t *errors)
{
    if (u == NULL || byte == NULL || errors == NULL || !u->ready) {
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
    /* SR then DR: clears RXNE and the errors. With M = 1 and PCE = 1 bit 8
     * is the parity bit, so the byte is bits 0..7 in both formats. */
    *byte = (uint8_t)(u->regs->DR & 0xFFu);
    *errors = sr & USART_SR_ERRORS;
    return 1;
}

int stm32_usart_read(stm32_usart_t *u, uint8_t *byte)
{
    uint32_t errors = 0u;
    return stm32_usart_read_flags(u, byte, &errors);
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
