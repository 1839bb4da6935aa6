/*
 * stm32f4_spi.h - a polled SPI master driver (mode 3, 8-bit, MSB first,
 * software chip select on a GPIO pin) against a register block passed by
 * pointer, so host tests run it on a fake block. The IMU on SPI1 uses it.
 *
 * Nothing here waits without a bound: every wait for TXE, RXNE or BSY reads
 * SR at most spin_limit times, then gives up with STM32_SPI_ERR_TIMEOUT and
 * releases the chip select.
 *
 * The chip drivers in boards/devices/ do not call this file: they talk to a
 * bus interface ({ctx, xfer, set_clock, delay_us}, boards/devices/imu_spi.h).
 * stm32_spi_bus_xfer and stm32_spi_bus_set_clock below have exactly those
 * signatures, with ctx = the stm32_spi_t, so the board fills the interface
 * with them and the host tests fill it with a simulated chip instead.
 */
#ifndef HT_STM32F4_SPI_H
#define HT_STM32F4_SPI_H

#include <stdint.h>

#include "stm32f4_regs.h"
#include "stm32f4_spi_regs.h"

typedef enum {
    STM32_SPI_OK = 0,
    STM32_SPI_ERR_NULL = 1,
    STM32_SPI_ERR_RANGE = 2,    /* no prescaler gives an SCK at or below the maximum, a pin
                                   above 15 or a zero spin limit: nothing written */
    STM32_SPI_ERR_TIMEOUT = 3,  /* TXE, RXNE or BSY did not come within spin_limit reads */
    STM32_SPI_ERR_NOT_READY = 4 /* not initialised */
} stm32_spi_status_t;

/* Driver state, owned by the caller. The counter saturates at UINT16_MAX. */
typedef struct {
    stm32_spi_regs_t *regs;
    stm32_gpio_t *cs_port; /* chip select: low while a transfer runs */
    uint8_t cs_pin;
    uint8_t ready;       /* 1 after a successful init */
    uint32_t pclk_hz;    /* the SPI's peripheral clock (PCLK2 for SPI1) */
    uint32_t sck_hz;     /* the SCK the current prescaler gives */
    uint32_t spin_limit; /* SR reads per wait */
    uint16_t timeouts;   /* transfers abandoned on a timeout */
} stm32_spi_t;

/*
 * The baud-rate field for the fastest SCK at or below max_sck_hz:
 * f_SCK = pclk_hz / 2^(BR+1), BR in [0, 7] (RM0090 28.5.1). Writes the
 * resulting SCK to *sck_hz (may be NULL). Returns BR, or -1 when even
 * pclk / 256 is too fast (or pclk_hz or max_sck_hz is 0).
 */
int stm32_spi_baud_field(uint32_t pclk_hz, uint32_t max_sck_hz, uint32_t *sck_hz);

/*
 * Configure the SPI as master, mode 3 (CPOL = 1, CPHA = 1: both IMUs accept
 * modes 0 and 3), 8-bit frames, MSB first, full duplex, software NSS
 * (SSM = SSI = 1), the prescaler from stm32_spi_baud_field, no CRC, no
 * interrupts or DMA, and enable it. The chip-select pin becomes a push-pull
 * output, high (deselected) before it is driven. The SCK/MISO/MOSI pins'
 * alternate function (AF5 on PA5/PA6/PA7 for SPI1) and the clocks
 * (stm32_rcc_enable_spi1) are the board's job.
 */
stm32_spi_status_t stm32_spi_init(stm32_spi_t *spi, stm32_spi_regs_t *regs, stm32_gpio_t *cs_port,
                                  uint8_t cs_pin, uint32_t pclk_hz, uint32_t max_sck_hz,
                                  uint32_t spin_limit);

/*
 * Change the SCK to the fastest at or below max_sck_hz (the MPU-6000 takes
 * 1 MHz for register writes, 20 MHz for sensor reads). The SPI is disabled
 * while BR changes (RM0090: BR must not change during a transfer; every
 * transfer here has ended, BSY low, before it returns). RANGE: nothing changed.
 */
stm32_spi_status_t stm32_spi_set_clock(stm32_spi_t *spi, uint32_t max_sck_hz);

/* Chip select low / high (one BSRR write). */
void stm32_spi_select(stm32_spi_t *spi);
void stm32_spi_deselect(stm32_spi_t *spi);

/*
 * One full-duplex transfer of n bytes framed by the chip select: for each
 * byte wait TXE, write tx[i] (0x00 when tx is NULL), wait RXNE, read rx[i]
 * (dropped when rx is NULL); after the last byte wait TXE and BSY low, then
 * deselect. A byte left in DR from before is read and dropped first, so rx[0]
 * always answers tx[0]. On a timeout the chip select is released, the count
 * goes up and STM32_SPI_ERR_TIMEOUT is returned (rx then holds what came).
 * n = 0 is OK and touches nothing.
 */
stm32_spi_status_t stm32_spi_transfer(stm32_spi_t *spi, const uint8_t *tx, uint8_t *rx, uint16_t n);

/* The bus-interface adapters (ctx is a stm32_spi_t *): 0 on success, else
 * the stm32_spi_status_t. */
int stm32_spi_bus_xfer(void *ctx, const uint8_t *tx, uint8_t *rx, uint16_t n);
int stm32_spi_bus_set_clock(void *ctx, uint32_t max_sck_hz);

/* Clock GPIOA (SCK, MISO, MOSI and the chip select PA4 on the Matek
 * F405-WING) and SPI1 (read-modify-write: other enables kept). */
void stm32_rcc_enable_spi1(stm32_rcc_t *rcc);

#endif /* HT_STM32F4_SPI_H */
