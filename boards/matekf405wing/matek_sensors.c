/*
 * matek_sensors.c - board_sensors_read for the Matek F405-WING:
 *   IMU   MPU-6000 or ICM-42688-P (WHO_AM_I) on SPI1, data-ready PC4 -> EXTI4
 *         at 1 kHz; each sample read in the tick loop, the samples of one
 *         tick averaged (imu_decimate.h: 5 at 200 Hz).
 *   baro  BMP280 on I2C1 at 0x76, read every 4th tick (50 Hz at 200 Hz:
 *         its own rate is 43-50 Hz).
 *   pitot MS4525DO on I2C2 at 0x28, every 8th tick (25 Hz), optional.
 *   GPS   u-blox on USART3, configured by gps_ubx_link, bytes through an
 *         interrupt-fed ring, taken every tick.
 * A device that is missing at start-up is reported on the console and
 * tried again (IMU, baro every 1 s; pitot by its driver's back-off; GPS by
 * its link's probe cycle); the estimator runs without baro and pitot, and
 * the firmware's failsafe handles a missing IMU.
 *
 * Assumed sensor alignment (UNVERIFIED on hardware): IMU_ALIGN_YAW180 for
 * both chips - the chip top up, its +Y toward the tail, +X toward the left
 * wing - derived from ArduPilot's MatekF405-Wing ROTATION_YAW_180 with its
 * Invensense axis mapping. docs/boards/matek_f405_wing.md says how to check.
 */
#include "helical/board.h"

#include "airspeed_ms4525.h"
#include "baro_bmp280.h"
#include "gps_ubx_link.h"
#include "imu_decimate.h"
#include "imu_spi.h"
#include "matek_console.h"
#include "matek_hw.h"
#include "matek_sensors.h"
#include "matek_txq.h"
#include "matekf405wing_pins.h"
#include "serial_rx_ring.h"
#include "stm32f4_exti.h"
#include "stm32f4_i2c.h"
#include "stm32f4_spi.h"

#include <stddef.h>

#define RETRY_TICKS      200u /* 1 s at 200 Hz */
#define BARO_EVERY       4u
#define PITOT_EVERY      8u
#define GPS_RING_BYTES   512u /* 115200 baud: 58 bytes per 5 ms tick */
#define GPS_MISSING_MS   3000u
#define IMU_SCK_START_HZ 1000000u

static stm32_spi_t spi1;
static imu_spi_bus_t imu_bus;
static imu_spi_t imu;
static const imu_spi_config_t imu_cfg = {(uint8_t)IMU_ALIGN_YAW180, (uint8_t)IMU_ALIGN_YAW180,
                                         (uint8_t)IMU_LPF_MEDIUM};
static imu_decimate_t decim;
static volatile uint32_t drdy_count; /* written by EXTI4_IRQHandler only */
static uint32_t drdy_seen, imu_samples, imu_missed;
static uint8_t imu_reported;

static stm32_i2c_t i2c1, i2c2;
static i2c_bus_t bus1, bus2;
static bmp280_t baro;
static ms4525_t pitot;
static uint8_t pitot_state; /* 0 unknown, 1 absent, 2 present */

static stm32_usart_t gps_usart;
static serial_rx_ring_t gps_ring;
static volatile uint8_t gps_ring_buf[GPS_RING_BYTES];
static matek_txq_t gps_q;
static gps_ubx_link_t gps;
static uint8_t gps_state; /* 0 waiting, 1 reported missing, 2 solutions */

static uint32_t reads;

/* Named by the vector table (startup_stm32f405.c), which declares it weak. */
void EXTI4_IRQHandler(void);
void EXTI4_IRQHandler(void)
{
    // cppcheck-suppress misra-c2012-11.4 ; D-11.4-REG: EXTI register block address
    stm32_exti_t *const exti = (stm32_exti_t *)STM32_EXTI_BASE;
    if (stm32_exti_take(exti, MATEK_IMU_DRDY_PIN) != 0) {
        drdy_count = drdy_count + 1u;
    }
}

void USART3_IRQHandler(void);
void USART3_IRQHandler(void)
{
    (void)serial_rx_ring_isr(&gps_usart, &gps_ring);
}

static void imu_start(void)
{
    // cppcheck-suppress misra-c2012-11.4 ; D-11.4-REG: SYSCFG register block address
    stm32_syscfg_t *const syscfg = (stm32_syscfg_t *)STM32_SYSCFG_BASE;
    // cppcheck-suppress misra-c2012-11.4 ; D-11.4-REG: EXTI register block address
    stm32_exti_t *const exti = (stm32_exti_t *)STM32_EXTI_BASE;
    const imu_status_t st = imu_spi_init(&imu, &imu_bus, &imu_cfg);
    if (st != IMU_OK) {
        if (imu_reported == 0u) {
            matek_console_puts("imu: missing on SPI1 (status ");
            matek_console_put_u32((uint32_t)st);
            matek_console_puts(st == IMU_ERR_NO_DEVICE ? ": no answer)\r\n" : ")\r\n");
            imu_reported = 1u;
        }
        return;
    }
    matek_console_puts((imu.chip == (uint8_t)IMU_CHIP_MPU6000) ? "imu: MPU-6000"
                                                               : "imu: ICM-42688-P");
    matek_console_puts(" on SPI1, 1 kHz data-ready on PC4, SCK ");
    matek_console_put_u32(spi1.sck_hz);
    matek_console_puts(" Hz\r\n");
    imu_reported = 0u;
    drdy_seen = drdy_count;
    (void)stm32_exti_route(syscfg, exti, STM32_EXTI_PORT_C, MATEK_IMU_DRDY_PIN, STM32_EXTI_RISING);
    matek_nvic_enable(STM32_EXTI4_IRQN);
}

static void baro_start(void)
{
    const bmp280_status_t st = bmp280_init(&baro, &bus1, BMP280_ADDR_SDO_LOW);
    if (st == BMP280_OK) {
        matek_console_puts("baro: BMP280 on I2C1 at 0x76\r\n");
    } else if (reads == 0u) {
        matek_console_puts("baro: missing on I2C1 (status ");
        matek_console_put_u32((uint32_t)st);
        matek_console_puts(")\r\n");
    } else {
        /* still missing: said once at start-up */
    }
}

static size_t gps_write(void *ctx, const uint8_t *bytes, size_t n)
{
    (void)ctx;
    return matek_txq_write(&gps_q, bytes, n);
}

static void gps_set_baud(void *ctx, uint32_t baud)
{
    // cppcheck-suppress misra-c2012-11.4 ; D-11.4-REG: USART3 register block address
    stm32_usart_regs_t *const usart3 = (stm32_usart_regs_t *)STM32_USART3_BASE;
    (void)ctx;
    matek_txq_drain(&gps_q); /* what is queued leaves at the old rate */
    if (stm32_usart_init(&gps_usart, usart3, matek_clocks()->pclk1_hz, baud) == STM32_USART_OK) {
        stm32_usart_enable_rx_irq(&gps_usart);
    }
}

static void gps_start(void)
{
    static const gps_ubx_config_t cfg = GPS_UBX_CONFIG_DEFAULT;
    const gps_ubx_io_t io = {NULL, gps_write, gps_set_baud};
    (void)serial_rx_ring_init(&gps_ring, gps_ring_buf, GPS_RING_BYTES);
    matek_txq_init(&gps_q, &gps_usart);
    gps_set_baud(NULL, cfg.baud);
    matek_pin_af(2u, MATEK_USART3_TX_PIN, MATEK_AF_USART1_3, 0u);
    matek_pin_af(2u, MATEK_USART3_RX_PIN, MATEK_AF_USART1_3, 0u);
    matek_nvic_enable(STM32_USART3_IRQN);
    (void)gps_ubx_link_init(&gps, &cfg, &io, matek_time_ms());
    matek_console_puts("gps: configuring a u-blox receiver on USART3 (UBX NAV-PVT, 5 Hz)\r\n");
}

void matek_sensors_init(void)
{
    // cppcheck-suppress misra-c2012-11.4 ; D-11.4-REG: SPI1 register block address
    stm32_spi_regs_t *const spi_regs = (stm32_spi_regs_t *)STM32_SPI1_BASE;
    // cppcheck-suppress misra-c2012-11.4 ; D-11.4-REG: I2C1 register block address
    stm32_i2c_regs_t *const i2c1_regs = (stm32_i2c_regs_t *)STM32_I2C1_BASE;
    // cppcheck-suppress misra-c2012-11.4 ; D-11.4-REG: I2C2 register block address
    stm32_i2c_regs_t *const i2c2_regs = (stm32_i2c_regs_t *)STM32_I2C2_BASE;
    const stm32_clocks_t *clk = matek_clocks();
    imu_decimate_reset(&decim);
    /* IMU: SPI1 from PCLK2, register accesses at 1 MHz at most. */
    if (stm32_spi_init(&spi1, spi_regs, matek_gpio(0u), MATEK_IMU_CS_PIN, clk->pclk2_hz,
                       IMU_SCK_START_HZ, MATEK_SPI_SPINS) == STM32_SPI_OK) {
        matek_pin_af(0u, MATEK_SPI1_SCK_PIN, GPIO_AF5_SPI1_2, 0u);
        matek_pin_af(0u, MATEK_SPI1_MISO_PIN, GPIO_AF5_SPI1_2, 0u);
        matek_pin_af(0u, MATEK_SPI1_MOSI_PIN, GPIO_AF5_SPI1_2, 0u);
        imu_bus.ctx = &spi1;
        imu_bus.xfer = stm32_spi_bus_xfer;
        imu_bus.set_clock = stm32_spi_bus_set_clock;
        imu_bus.delay_us = matek_delay_us;
        imu_start();
    } else {
        matek_console_puts("imu: SPI1 set-up refused\r\n");
    }
    /* I2C: 400 kHz from PCLK1 (42 MHz, or 16 MHz on HSI). */
    matek_pin_af(1u, MATEK_I2C1_SCL_PIN, MATEK_AF_I2C, 1u);
    matek_pin_af(1u, MATEK_I2C1_SDA_PIN, MATEK_AF_I2C, 1u);
    matek_pin_af(1u, MATEK_I2C2_SCL_PIN, MATEK_AF_I2C, 1u);
    matek_pin_af(1u, MATEK_I2C2_SDA_PIN, MATEK_AF_I2C, 1u);
    (void)stm32_i2c_init(&i2c1, i2c1_regs, clk->pclk1_hz, STM32_I2C_FAST_400KHZ, MATEK_I2C_SPINS);
    (void)stm32_i2c_init(&i2c2, i2c2_regs, clk->pclk1_hz, STM32_I2C_FAST_400KHZ, MATEK_I2C_SPINS);
    bus1 = stm32_i2c_bus(&i2c1);
    bus2 = stm32_i2c_bus(&i2c2);
    baro_start();
    (void)ms4525_init(&pitot, &bus2, MS4525_ADDR_I);
    const ms4525_status_t ps = ms4525_update(&pitot); /* the first probe */
    if (ps == MS4525_ABSENT || ps == MS4525_ERR_BUS) {
        matek_console_puts("pitot: missing on I2C2 (no airspeed: the estimator's fallback)\r\n");
        pitot_state = 1u;
    } else {
        matek_console_puts("pitot: MS4525DO on I2C2 at 0x28, zeroing\r\n");
        pitot_state = 2u;
    }
    gps_start();
}

void matek_sensors_poll(void)
{
    if (imu.ready == 0u) {
        return;
    }
    const uint32_t now = drdy_count;
    if (now == drdy_seen) {
        return;
    }
    imu_missed += now - drdy_seen - 1u; /* the chip overwrote samples not yet read */
    drdy_seen = now;
    ht_imu_sample_t s;
    if (imu_spi_read(&imu, &s) == IMU_OK) {
        imu_decimate_add(&decim, &s);
        ++imu_samples;
    }
}

uint32_t matek_sensors_imu_samples(void)
{
    return imu_samples;
}

static void gps_poll(void)
{
    uint8_t buf[128];
    const uint32_t now = matek_time_ms();
    size_t n = serial_rx_ring_read(&gps_ring, buf, sizeof buf);
    gps_ubx_link_poll(&gps, buf, n, now);
    matek_txq_pump(&gps_q, 4u);
    if (gps.solution_seq != 0u && gps_state != 2u) {
        matek_console_puts("gps: u-blox answering on USART3\r\n");
        gps_state = 2u;
    } else if (gps.solution_seq == 0u && gps_state == 0u && now > GPS_MISSING_MS) {
        matek_console_puts("gps: missing on USART3 (no NAV-PVT yet; still probing)\r\n");
        gps_state = 1u;
    } else {
        /* no change to report */
    }
}

board_status_t board_sensors_read(board_sensors_t *out)
{
    if (out == NULL) {
        return BOARD_ERR_NULL;
    }
    matek_budget_mark(MATEK_MARK_SENSORS_IN);
    out->imu_fresh = (uint8_t)((imu_decimate_take(&decim, &out->imu) != 0u) ? 1u : 0u);
    if (imu.ready == 0u && (reads % RETRY_TICKS) == (RETRY_TICKS - 1u)) {
        imu_start();
    }
    gps_poll();
    (void)gps_ubx_link_read(&gps, &out->gps);
    out->baro_fresh = 0u;
    if ((reads % BARO_EVERY) == 0u) {
        if (baro.ready != 0u) {
            if (bmp280_read(&baro) == BMP280_OK) {
                out->baro_fresh = 1u;
                out->baro_alt_cm = baro.alt_cm;
                /* the static temperature: the step's pitot density (air_data.h) */
                out->baro_temp_valid = 1u;
                out->baro_temp_cdeg = (int16_t)baro.reading.temp_cdeg;
            }
        } else if ((reads % RETRY_TICKS) == 0u && reads != 0u) {
            baro_start();
        } else {
            /* absent: waiting for the next retry */
        }
    }
    out->airspeed_fresh = 0u;
    if ((reads % PITOT_EVERY) == 1u) {
        const ms4525_status_t ps = ms4525_update(&pitot);
        if (ps == MS4525_OK) {
            out->airspeed_fresh = 1u;
            out->airspeed_cm_s = pitot.airspeed_cm_s;
            if (pitot_state != 2u) {
                matek_console_puts("pitot: MS4525DO found on I2C2\r\n");
                pitot_state = 2u;
            }
        }
    }
    ++reads;
    matek_budget_mark(MATEK_MARK_SENSORS_OUT);
    const int any = (out->imu_fresh | out->gps.fresh | out->baro_fresh | out->airspeed_fresh) != 0u;
    return any ? BOARD_OK : BOARD_ERR_NO_DATA;
}
