/*
 * test_stm32f4_spi.c - the SPI master driver and the chip-select GPIO output
 * on fake register blocks.
 *
 * Expected values, worked from RM0090 (section 28.5.1 SPI_CR1, 8.4 GPIO):
 *   CR1 = CPHA (bit 0) | CPOL (bit 1) | MSTR (bit 2) | SSI (bit 8) | SSM (bit 9)
 *       = 0x0307; with SPE (bit 6) 0x0347; BR[2:0] at bits 5:3.
 *   f_SCK = f_PCLK / 2^(BR+1), the fastest at or below the maximum:
 *     16 MHz (HSI), max  1 MHz (MPU-6000 registers): /16  = 1 MHz,     BR 3, CR1 0x035F
 *     16 MHz,       max 20 MHz (MPU-6000 data):      /2   = 8 MHz,     BR 0, CR1 0x0347
 *     84 MHz (PCLK2 at 168 MHz), max 1 MHz:          /128 = 656.25 kHz, BR 6, CR1 0x0377
 *     84 MHz,       max 20 MHz:                      /8   = 10.5 MHz,  BR 2, CR1 0x0357
 *     84 MHz,       max 24 MHz (ICM-42688-P):        /4   = 21 MHz,    BR 1, CR1 0x034F
 *     84 MHz,       max 328125 Hz:                   /256,             BR 7, CR1 0x037F
 *     84 MHz,       max 328124 Hz: none (RANGE)
 *   Chip select PA4: BSRR = 1 << 4 = 0x10 (high), 1 << (4 + 16) = 0x100000 (low);
 *   MODER bits 9:8 = 01 (output), OSPEEDR bits 9:8 = 10 (fast), OTYPER bit 4 = 0.
 *   RCC: AHB1ENR GPIOAEN bit 0, APB2ENR SPI1EN bit 12 (0x1000).
 * A fake block keeps what was written and never changes a flag by itself:
 * with SR = TXE | RXNE each byte written to DR reads back (a loopback), with
 * SR = 0 TXE never comes.
 */
#include "unity.h"

#include "stm32f4_gpio.h"
#include "stm32f4_spi.h"

#include <string.h>

static stm32_spi_regs_t regs;
static stm32_gpio_t gpioa;
static stm32_spi_t spi;

void setUp(void)
{
    memset((void *)&regs, 0, sizeof regs);
    memset((void *)&gpioa, 0, sizeof gpioa);
    memset(&spi, 0, sizeof spi);
}

void tearDown(void) {}

static void init_ok(uint32_t pclk_hz, uint32_t max_hz)
{
    TEST_ASSERT_EQUAL(STM32_SPI_OK, stm32_spi_init(&spi, &regs, &gpioa, 4u, pclk_hz, max_hz, 100u));
}

static void test_baud_field_edges(void)
{
    uint32_t sck = 0u;
    TEST_ASSERT_EQUAL_INT(3, stm32_spi_baud_field(16000000u, 1000000u, &sck));
    TEST_ASSERT_EQUAL_UINT32(1000000u, sck);
    TEST_ASSERT_EQUAL_INT(4, stm32_spi_baud_field(16000000u, 999999u, &sck)); /* just below */
    TEST_ASSERT_EQUAL_UINT32(500000u, sck);
    TEST_ASSERT_EQUAL_INT(0, stm32_spi_baud_field(16000000u, 20000000u, &sck));
    TEST_ASSERT_EQUAL_UINT32(8000000u, sck);
    TEST_ASSERT_EQUAL_INT(0, stm32_spi_baud_field(16000000u, 8000000u, &sck)); /* exact /2 */
    TEST_ASSERT_EQUAL_INT(1, stm32_spi_baud_field(16000000u, 7999999u, &sck));
    TEST_ASSERT_EQUAL_UINT32(4000000u, sck);
    TEST_ASSERT_EQUAL_INT(6, stm32_spi_baud_field(84000000u, 1000000u, &sck));
    TEST_ASSERT_EQUAL_UINT32(656250u, sck);
    TEST_ASSERT_EQUAL_INT(2, stm32_spi_baud_field(84000000u, 20000000u, &sck));
    TEST_ASSERT_EQUAL_UINT32(10500000u, sck);
    TEST_ASSERT_EQUAL_INT(1, stm32_spi_baud_field(84000000u, 24000000u, &sck));
    TEST_ASSERT_EQUAL_UINT32(21000000u, sck);
    TEST_ASSERT_EQUAL_INT(7, stm32_spi_baud_field(84000000u, 328125u, &sck));
    TEST_ASSERT_EQUAL_UINT32(328125u, sck);
    TEST_ASSERT_EQUAL_INT(-1, stm32_spi_baud_field(84000000u, 328124u, &sck));
    TEST_ASSERT_EQUAL_INT(-1, stm32_spi_baud_field(0u, 1000000u, &sck));
    TEST_ASSERT_EQUAL_INT(-1, stm32_spi_baud_field(16000000u, 0u, &sck));
    TEST_ASSERT_EQUAL_INT(2, stm32_spi_baud_field(16000000u, 2000000u, NULL));
}

static void test_init_mode3_1mhz_from_hsi(void)
{
    regs.CR2 = 0x00E3u;     /* interrupts and DMA left over: init clears them */
    regs.I2SCFGR = 0x0800u; /* I2S mode left over: init returns to SPI */
    gpioa.MODER = 0xFFFFFFFFu;
    gpioa.OTYPER = 0xFFFFu;
    init_ok(16000000u, 1000000u);
    TEST_ASSERT_EQUAL_HEX32(0x035Fu, regs.CR1);
    TEST_ASSERT_EQUAL_HEX32(0x0u, regs.CR2);
    TEST_ASSERT_EQUAL_HEX32(0x0u, regs.I2SCFGR);
    TEST_ASSERT_EQUAL_UINT32(1000000u, spi.sck_hz);
    TEST_ASSERT_EQUAL_UINT8(1u, spi.ready);
    /* PA4 a push-pull output, fast, driven high (deselected) */
    TEST_ASSERT_EQUAL_HEX32(0x10u, gpioa.BSRR);
    TEST_ASSERT_EQUAL_HEX32(0xFFFFFDFFu, gpioa.MODER);
    TEST_ASSERT_EQUAL_HEX32(0x200u, gpioa.OSPEEDR);
    TEST_ASSERT_EQUAL_HEX32(0xFFEFu, gpioa.OTYPER);
}

static void test_init_other_clocks(void)
{
    init_ok(16000000u, 20000000u);
    TEST_ASSERT_EQUAL_HEX32(0x0347u, regs.CR1);
    init_ok(84000000u, 1000000u);
    TEST_ASSERT_EQUAL_HEX32(0x0377u, regs.CR1);
    init_ok(84000000u, 20000000u);
    TEST_ASSERT_EQUAL_HEX32(0x0357u, regs.CR1);
    init_ok(84000000u, 24000000u);
    TEST_ASSERT_EQUAL_HEX32(0x034Fu, regs.CR1);
    init_ok(84000000u, 328125u);
    TEST_ASSERT_EQUAL_HEX32(0x037Fu, regs.CR1);
}

static void test_init_refuses_without_writing(void)
{
    regs.CR1 = 0x1234u;
    TEST_ASSERT_EQUAL(STM32_SPI_ERR_NULL,
                      stm32_spi_init(NULL, &regs, &gpioa, 4u, 16000000u, 1000000u, 10u));
    TEST_ASSERT_EQUAL(STM32_SPI_ERR_NULL,
                      stm32_spi_init(&spi, NULL, &gpioa, 4u, 16000000u, 1000000u, 10u));
    TEST_ASSERT_EQUAL(STM32_SPI_ERR_NULL,
                      stm32_spi_init(&spi, &regs, NULL, 4u, 16000000u, 1000000u, 10u));
    TEST_ASSERT_EQUAL(STM32_SPI_ERR_RANGE,
                      stm32_spi_init(&spi, &regs, &gpioa, 4u, 84000000u, 328124u, 10u));
    TEST_ASSERT_EQUAL(STM32_SPI_ERR_RANGE,
                      stm32_spi_init(&spi, &regs, &gpioa, 16u, 16000000u, 1000000u, 10u));
    TEST_ASSERT_EQUAL(STM32_SPI_ERR_RANGE,
                      stm32_spi_init(&spi, &regs, &gpioa, 4u, 16000000u, 1000000u, 0u));
    TEST_ASSERT_EQUAL_HEX32(0x1234u, regs.CR1);
    TEST_ASSERT_EQUAL_HEX32(0x0u, gpioa.BSRR);
    TEST_ASSERT_EQUAL_HEX32(0x0u, gpioa.MODER);
    TEST_ASSERT_EQUAL_UINT8(0u, spi.ready);
}

static void test_set_clock(void)
{
    TEST_ASSERT_EQUAL(STM32_SPI_ERR_NOT_READY, stm32_spi_set_clock(&spi, 1000000u));
    TEST_ASSERT_EQUAL(STM32_SPI_ERR_NULL, stm32_spi_set_clock(NULL, 1000000u));
    init_ok(16000000u, 1000000u);
    TEST_ASSERT_EQUAL(STM32_SPI_OK, stm32_spi_set_clock(&spi, 20000000u));
    TEST_ASSERT_EQUAL_HEX32(0x0347u, regs.CR1);
    TEST_ASSERT_EQUAL_UINT32(8000000u, spi.sck_hz);
    TEST_ASSERT_EQUAL(STM32_SPI_OK, stm32_spi_set_clock(&spi, 1000000u));
    TEST_ASSERT_EQUAL_HEX32(0x035Fu, regs.CR1);
    TEST_ASSERT_EQUAL(STM32_SPI_ERR_RANGE, stm32_spi_set_clock(&spi, 62499u)); /* < 16M/256 */
    TEST_ASSERT_EQUAL_HEX32(0x035Fu, regs.CR1);
    TEST_ASSERT_EQUAL_UINT32(1000000u, spi.sck_hz);
    /* through the bus adapter */
    TEST_ASSERT_EQUAL_INT(0, stm32_spi_bus_set_clock(&spi, 24000000u));
    TEST_ASSERT_EQUAL_HEX32(0x0347u, regs.CR1);
    TEST_ASSERT_EQUAL_INT((int)STM32_SPI_ERR_RANGE, stm32_spi_bus_set_clock(&spi, 1u));
}

static void test_select_deselect(void)
{
    stm32_spi_select(&spi); /* not initialised: nothing */
    TEST_ASSERT_EQUAL_HEX32(0x0u, gpioa.BSRR);
    init_ok(16000000u, 1000000u);
    stm32_spi_select(&spi);
    TEST_ASSERT_EQUAL_HEX32(0x00100000u, gpioa.BSRR);
    stm32_spi_deselect(&spi);
    TEST_ASSERT_EQUAL_HEX32(0x10u, gpioa.BSRR);
    stm32_spi_select(NULL);
    stm32_spi_deselect(NULL);
}

static void test_transfer_loopback(void)
{
    const uint8_t tx[4] = {0xF5u, 0x00u, 0xA5u, 0x3Cu};
    uint8_t rx[4] = {0u, 0u, 0u, 0u};
    TEST_ASSERT_EQUAL(STM32_SPI_ERR_NOT_READY, stm32_spi_transfer(&spi, tx, rx, 4u));
    init_ok(16000000u, 1000000u);
    regs.SR = SPI_SR_TXE | SPI_SR_RXNE; /* BSY low */
    TEST_ASSERT_EQUAL(STM32_SPI_OK, stm32_spi_transfer(&spi, tx, rx, 4u));
    TEST_ASSERT_EQUAL_HEX8_ARRAY(tx, rx, 4);
    TEST_ASSERT_EQUAL_HEX32(0x3Cu, regs.DR);    /* the last byte sent */
    TEST_ASSERT_EQUAL_HEX32(0x10u, gpioa.BSRR); /* deselected at the end */
    TEST_ASSERT_EQUAL_UINT16(0u, spi.timeouts);
    /* no tx: zeros go out; no rx: nothing stored */
    memset(rx, 0xEE, sizeof rx);
    TEST_ASSERT_EQUAL(STM32_SPI_OK, stm32_spi_transfer(&spi, NULL, rx, 3u));
    TEST_ASSERT_EQUAL_HEX8(0x00u, rx[0]);
    TEST_ASSERT_EQUAL_HEX8(0x00u, rx[2]);
    TEST_ASSERT_EQUAL_HEX8(0xEEu, rx[3]);
    TEST_ASSERT_EQUAL(STM32_SPI_OK, stm32_spi_transfer(&spi, tx, NULL, 2u));
    TEST_ASSERT_EQUAL_HEX32(0x00u, regs.DR);
    /* through the bus adapter */
    TEST_ASSERT_EQUAL_INT(0, stm32_spi_bus_xfer(&spi, tx, rx, 4u));
    TEST_ASSERT_EQUAL_HEX8_ARRAY(tx, rx, 4);
    /* n = 0 touches nothing */
    regs.DR = 0x77u;
    gpioa.BSRR = 0u;
    TEST_ASSERT_EQUAL(STM32_SPI_OK, stm32_spi_transfer(&spi, tx, rx, 0u));
    TEST_ASSERT_EQUAL_HEX32(0x77u, regs.DR);
    TEST_ASSERT_EQUAL_HEX32(0x0u, gpioa.BSRR);
    TEST_ASSERT_EQUAL(STM32_SPI_ERR_NULL, stm32_spi_transfer(NULL, tx, rx, 1u));
}

static void test_transfer_times_out(void)
{
    const uint8_t tx[2] = {0x75u | 0x80u, 0x00u};
    uint8_t rx[2] = {0u, 0u};
    init_ok(16000000u, 1000000u);
    /* TXE never comes: nothing written, chip select released */
    regs.SR = 0u;
    regs.DR = 0xEEu;
    TEST_ASSERT_EQUAL(STM32_SPI_ERR_TIMEOUT, stm32_spi_transfer(&spi, tx, rx, 2u));
    TEST_ASSERT_EQUAL_HEX32(0xEEu, regs.DR);
    TEST_ASSERT_EQUAL_HEX32(0x10u, gpioa.BSRR);
    TEST_ASSERT_EQUAL_UINT16(1u, spi.timeouts);
    /* TXE but never RXNE: the first byte went out, then the wait gave up */
    regs.SR = SPI_SR_TXE;
    TEST_ASSERT_EQUAL(STM32_SPI_ERR_TIMEOUT, stm32_spi_transfer(&spi, tx, rx, 2u));
    TEST_ASSERT_EQUAL_HEX32(0xF5u, regs.DR);
    TEST_ASSERT_EQUAL_UINT16(2u, spi.timeouts);
    /* every byte exchanged but BSY stays high */
    regs.SR = SPI_SR_TXE | SPI_SR_RXNE | SPI_SR_BSY;
    TEST_ASSERT_EQUAL(STM32_SPI_ERR_TIMEOUT, stm32_spi_transfer(&spi, tx, rx, 2u));
    TEST_ASSERT_EQUAL_HEX8_ARRAY(tx, rx, 2);
    TEST_ASSERT_EQUAL_HEX32(0x10u, gpioa.BSRR);
    TEST_ASSERT_EQUAL_UINT16(3u, spi.timeouts);
    TEST_ASSERT_EQUAL_INT((int)STM32_SPI_ERR_TIMEOUT, stm32_spi_bus_xfer(&spi, tx, rx, 2u));
    spi.timeouts = UINT16_MAX; /* saturates */
    TEST_ASSERT_EQUAL(STM32_SPI_ERR_TIMEOUT, stm32_spi_transfer(&spi, tx, rx, 2u));
    TEST_ASSERT_EQUAL_UINT16(UINT16_MAX, spi.timeouts);
}

static void test_gpio_output(void)
{
    stm32_gpio_t c;
    memset((void *)&c, 0, sizeof c);
    c.MODER = 0x00000F00u;   /* PC4 in analogue mode (11), PC5 too */
    c.OSPEEDR = 0x00000F00u; /* both very high */
    stm32_gpio_set_output(&c, 4u, 0u);
    TEST_ASSERT_EQUAL_HEX32(0x00100000u, c.BSRR);  /* low: reset bit 20 */
    TEST_ASSERT_EQUAL_HEX32(0x00000D00u, c.MODER); /* PC4 01, PC5 kept */
    TEST_ASSERT_EQUAL_HEX32(0x00000E00u, c.OSPEEDR);
    stm32_gpio_set_output(&c, 15u, 1u);
    TEST_ASSERT_EQUAL_HEX32(0x00008000u, c.BSRR);
    TEST_ASSERT_EQUAL_HEX32(0x40000D00u, c.MODER);
    stm32_gpio_write(&c, 0u, 0u);
    TEST_ASSERT_EQUAL_HEX32(0x00010000u, c.BSRR);
    stm32_gpio_write(&c, 15u, 0u);
    TEST_ASSERT_EQUAL_HEX32(0x80000000u, c.BSRR);
    stm32_gpio_write(&c, 16u, 1u);      /* ignored */
    stm32_gpio_set_output(&c, 16u, 1u); /* ignored */
    TEST_ASSERT_EQUAL_HEX32(0x80000000u, c.BSRR);
    TEST_ASSERT_EQUAL_HEX32(0x40000D00u, c.MODER);
    stm32_gpio_write(NULL, 1u, 1u);
    stm32_gpio_set_output(NULL, 1u, 1u);
}

static void test_rcc_enable_spi1(void)
{
    stm32_rcc_t rcc;
    memset((void *)&rcc, 0, sizeof rcc);
    rcc.AHB1ENR = 0x2u;  /* GPIOB already on */
    rcc.APB2ENR = 0x10u; /* USART1 already on */
    stm32_rcc_enable_spi1(&rcc);
    TEST_ASSERT_EQUAL_HEX32(0x3u, rcc.AHB1ENR);
    TEST_ASSERT_EQUAL_HEX32(0x1010u, rcc.APB2ENR);
    stm32_rcc_enable_spi1(NULL);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_baud_field_edges);
    RUN_TEST(test_init_mode3_1mhz_from_hsi);
    RUN_TEST(test_init_other_clocks);
    RUN_TEST(test_init_refuses_without_writing);
    RUN_TEST(test_set_clock);
    RUN_TEST(test_select_deselect);
    RUN_TEST(test_transfer_loopback);
    RUN_TEST(test_transfer_times_out);
    RUN_TEST(test_gpio_output);
    RUN_TEST(test_rcc_enable_spi1);
    return UNITY_END();
}
