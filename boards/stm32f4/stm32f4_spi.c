/*
 * stm32f4_spi.c - the polled SPI master driver (see stm32f4_spi.h).
 */
#include "stm32f4_spi.h"

#include <stddef.h>

#include "stm32f4_gpio.h"

/* Mode 3, master, software NSS held high inside the SPI (RM0090 28.3.3:
 * with SSM = 1 the SSI bit stands for NSS; low would be a mode fault). */
#define SPI_CR1_BASE (SPI_CR1_CPHA | SPI_CR1_CPOL | SPI_CR1_MSTR | SPI_CR1_SSI | SPI_CR1_SSM)

static void count(uint16_t *c)
{
    if (*c != UINT16_MAX) {
        (*c)++;
    }
}

/* Wait until (SR & mask) == want, at most limit reads. 1 when it came. */
static int wait_sr(const stm32_spi_regs_t *regs, uint32_t mask, uint32_t want, uint32_t limit)
{
    for (uint32_t spins = 0u; spins < limit; ++spins) {
        if ((regs->SR & mask) == want) {
            return 1;
        }
    }
    return 0;
}

int stm32_spi_baud_field(uint32_t pclk_hz, uint32_t max_sck_hz, uint32_t *sck_hz)
{
    if (pclk_hz == 0u || max_sck_hz == 0u) {
        return -1;
    }
    for (uint32_t br = 0u; br <= SPI_BR_MAX; ++br) {
        const uint32_t sck = pclk_hz >> (br + 1u);
        if (sck <= max_sck_hz && sck > 0u) {
            if (sck_hz != NULL) {
                *sck_hz = sck;
            }
            return (int)br;
        }
    }
    return -1;
}

stm32_spi_status_t stm32_spi_init(stm32_spi_t *spi, stm32_spi_regs_t *regs, stm32_gpio_t *cs_port,
                                  uint8_t cs_pin, uint32_t pclk_hz, uint32_t max_sck_hz,
                                  uint32_t spin_limit)
{
    if (spi == NULL || regs == NULL || cs_port == NULL) {
        return STM32_SPI_ERR_NULL;
    }
    spi->ready = 0u;
    uint32_t sck_hz = 0u;
    const int br = stm32_spi_baud_field(pclk_hz, max_sck_hz, &sck_hz);
    if (br < 0 || cs_pin > 15u || spin_limit == 0u) {
        return STM32_SPI_ERR_RANGE;
    }
    spi->regs = regs;
    spi->cs_port = cs_port;
    spi->cs_pin = cs_pin;
    spi->pclk_hz = pclk_hz;
    spi->sck_hz = sck_hz;
    spi->spin_limit = spin_limit;
    spi->timeouts = 0u;
    stm32_gpio_set_output(cs_port, cs_pin, 1u); /* deselected before it drives */
    const uint32_t br_bits = (uint32_t)br << SPI_CR1_BR_SHIFT;
    regs->CR1 = 0u;     /* disabled while configured */
    regs->CR2 = 0u;     /* no interrupts, no DMA */
    regs->I2SCFGR = 0u; /* SPI mode, not I2S */
    regs->CR1 = SPI_CR1_BASE | br_bits;
    regs->CR1 = SPI_CR1_BASE | br_bits | SPI_CR1_SPE;
    spi->ready = 1u;
    return STM32_SPI_OK;
}

stm32_spi_status_t stm32_spi_set_clock(stm32_spi_t *spi, uint32_t max_sck_hz)
{
    if (spi == NULL) {
        return STM32_SPI_ERR_NULL;
    }
    if (!spi->ready) {
        return STM32_SPI_ERR_NOT_READY;
    }
    uint32_t sck_hz = 0u;
    const int br = stm32_spi_baud_field(spi->pclk_hz, max_sck_hz, &sck_hz);
    if (br < 0) {
        return STM32_SPI_ERR_RANGE;
    }
    const uint32_t br_bits = (uint32_t)br << SPI_CR1_BR_SHIFT;
    const uint32_t cr1 = spi->regs->CR1 & ~(SPI_CR1_BR_MASK | SPI_CR1_SPE);
    spi->regs->CR1 = cr1;
    spi->regs->CR1 = cr1 | br_bits;
    spi->regs->CR1 = cr1 | br_bits | SPI_CR1_SPE;
    spi->sck_hz = sck_hz;
    return STM32_SPI_OK;
}

void stm32_spi_select(stm32_spi_t *spi)
{
    if (spi == NULL || !spi->ready) {
        return;
    }
    stm32_gpio_write(spi->cs_port, spi->cs_pin, 0u);
}

void stm32_spi_deselect(stm32_spi_t *spi)
{
    if (spi == NULL || !spi->ready) {
        return;
    }
    stm32_gpio_write(spi->cs_port, spi->cs_pin, 1u);
}

/* The bytes of one transfer; 1 when all came without a timeout. */
static int shift_bytes(stm32_spi_regs_t *regs, const uint8_t *tx, uint8_t *rx, uint16_t n,
                       uint32_t limit)
{
    for (uint16_t i = 0u; i < n; ++i) {
        if (!wait_sr(regs, SPI_SR_TXE, SPI_SR_TXE, limit)) {
            return 0;
        }
        uint8_t out = 0u;
        if (tx != NULL) {
            out = tx[i];
        }
        regs->DR = out;
        if (!wait_sr(regs, SPI_SR_RXNE, SPI_SR_RXNE, limit)) {
            return 0;
        }
        const uint32_t dr = regs->DR; /* clears RXNE (and OVR after the SR read) */
        if (rx != NULL) {
            rx[i] = (uint8_t)(dr & 0xFFu);
        }
    }
    /* RM0090 28.3.8: the frame is over when TXE is set and BSY is clear. */
    return wait_sr(regs, SPI_SR_TXE | SPI_SR_BSY, SPI_SR_TXE, limit);
}

stm32_spi_status_t stm32_spi_transfer(stm32_spi_t *spi, const uint8_t *tx, uint8_t *rx, uint16_t n)
{
    if (spi == NULL) {
        return STM32_SPI_ERR_NULL;
    }
    if (!spi->ready) {
        return STM32_SPI_ERR_NOT_READY;
    }
    if (n == 0u) {
        return STM32_SPI_OK;
    }
    if ((spi->regs->SR & SPI_SR_RXNE) != 0u) {
        (void)spi->regs->DR; /* a stale byte would shift every answer by one */
    }
    stm32_spi_select(spi);
    const int done = shift_bytes(spi->regs, tx, rx, n, spi->spin_limit);
    stm32_spi_deselect(spi);
    if (!done) {
        count(&spi->timeouts);
        return STM32_SPI_ERR_TIMEOUT;
    }
    return STM32_SPI_OK;
}

int stm32_spi_bus_xfer(void *ctx, const uint8_t *tx, uint8_t *rx, uint16_t n)
{
    // cppcheck-suppress misra-c2012-11.5 ; D-11.5-CTX: the seam's context is the stm32_spi_t
    return (int)stm32_spi_transfer((stm32_spi_t *)ctx, tx, rx, n);
}

int stm32_spi_bus_set_clock(void *ctx, uint32_t max_sck_hz)
{
    // cppcheck-suppress misra-c2012-11.5 ; D-11.5-CTX: the seam's context is the stm32_spi_t
    return (int)stm32_spi_set_clock((stm32_spi_t *)ctx, max_sck_hz);
}

void stm32_rcc_enable_spi1(stm32_rcc_t *rcc)
{
    if (rcc == NULL) {
        return;
    }
    rcc->AHB1ENR |= RCC_AHB1ENR_GPIOAEN;
    rcc->APB2ENR |= RCC_APB2ENR_SPI1EN;
    /* RM0090: no access in the two cycles after an enable; the read back
     * provides that delay. */
    (void)rcc->APB2ENR;
}
