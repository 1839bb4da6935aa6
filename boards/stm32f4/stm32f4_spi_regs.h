/*
 * stm32f4_spi_regs.h - the STM32F405 SPI register block and the bits the IMU
 * link uses. Offsets, addresses and bit positions are from RM0090 (section
 * 28.5, SPI and I2S registers; section 2.3, memory map; section 7.3.14,
 * RCC_APB2ENR) and the STM32F405 datasheet's alternate-function table (SPI1
 * on PA5/PA6/PA7, AF5).
 */
#ifndef HT_STM32F4_SPI_REGS_H
#define HT_STM32F4_SPI_REGS_H

#include <stddef.h>
#include <stdint.h>

typedef struct {
    volatile uint32_t CR1;     /* 0x00 control 1: mode, baud rate, enable */
    volatile uint32_t CR2;     /* 0x04 control 2: interrupt and DMA enables */
    volatile uint32_t SR;      /* 0x08 status */
    volatile uint32_t DR;      /* 0x0C data: a write loads TX, a read takes RX */
    volatile uint32_t CRCPR;   /* 0x10 CRC polynomial (unused) */
    volatile uint32_t RXCRCR;  /* 0x14 RX CRC (unused) */
    volatile uint32_t TXCRCR;  /* 0x18 TX CRC (unused) */
    volatile uint32_t I2SCFGR; /* 0x1C I2S configuration: must stay 0 (SPI mode) */
    volatile uint32_t I2SPR;   /* 0x20 I2S prescaler (unused) */
} stm32_spi_regs_t;

_Static_assert((size_t)offsetof(stm32_spi_regs_t, CR2) == 0x04u, "SPI CR2 offset");
_Static_assert((size_t)offsetof(stm32_spi_regs_t, SR) == 0x08u, "SPI SR offset");
_Static_assert((size_t)offsetof(stm32_spi_regs_t, DR) == 0x0Cu, "SPI DR offset");
_Static_assert((size_t)offsetof(stm32_spi_regs_t, I2SCFGR) == 0x1Cu, "SPI I2SCFGR offset");
_Static_assert((size_t)offsetof(stm32_spi_regs_t, I2SPR) == 0x20u, "SPI I2SPR offset");

#define STM32_SPI1_BASE 0x40013000u /* APB2: clocked by PCLK2 */
#define STM32_SPI2_BASE 0x40003800u /* APB1: PCLK1 */
#define STM32_SPI3_BASE 0x40003C00u /* APB1: PCLK1 */

/* SPI_CR1 (RM0090 28.5.1) */
#define SPI_CR1_CPHA     0x0001u /* 1: data captured on the second (rising, with CPOL=1) edge */
#define SPI_CR1_CPOL     0x0002u /* 1: SCK idles high */
#define SPI_CR1_MSTR     0x0004u /* master */
#define SPI_CR1_BR_SHIFT 3u      /* BR[2:0] at bits 5:3: f_SCK = f_PCLK / 2^(BR+1) */
#define SPI_CR1_BR_MASK  0x0038u
#define SPI_CR1_SPE      0x0040u /* SPI enable */
#define SPI_CR1_LSBFIRST 0x0080u /* 0: MSB first (both IMUs want MSB first) */
#define SPI_CR1_SSI                                                                                \
    0x0100u                 /* internal NSS level when SSM = 1: must be 1 in master                \
                               mode, or the SPI sees a mode fault (MODF) */
#define SPI_CR1_SSM 0x0200u /* software slave management: NSS pin not used */
#define SPI_CR1_DFF 0x0800u /* 0: 8-bit frames */
#define SPI_BR_MAX  7u      /* f_PCLK / 256 */

/* SPI_SR (RM0090 28.5.3) */
#define SPI_SR_RXNE 0x0001u /* a received byte waits in DR */
#define SPI_SR_TXE  0x0002u /* DR may take the next byte */
#define SPI_SR_MODF 0x0020u /* mode fault */
#define SPI_SR_OVR  0x0040u /* overrun: a byte arrived while RXNE was set */
#define SPI_SR_BSY  0x0080u /* a frame is being shifted */

/* RCC_APB2ENR (offset 0x44, RM0090 7.3.14) */
#define RCC_APB2ENR_SPI1EN 0x1000u /* bit 12 */

/* SPI1_SCK PA5, SPI1_MISO PA6, SPI1_MOSI PA7: alternate function 5 */
#define GPIO_AF5_SPI1_2 5u

#endif /* HT_STM32F4_SPI_REGS_H */
