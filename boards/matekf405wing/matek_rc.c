/*
 * matek_rc.c - the receiver of the Matek F405-WING image, chosen at build
 * time (CMake HT_MATEK_RX: SBUS, CRSF or PPM -> MATEK_RX_*):
 *   SBUS  USART2 RX on PA3 (the board's "SBUS" pad: RX2 through its inverter),
 *         100000 baud 8E2 from PCLK1;
 *   CRSF  USART6 RX on PC7 (uninverted), 420000 baud 8N1 from PCLK2 (84 MHz:
 *         BRR 200 exactly);
 *   PPM   TIM5 channel 4 input capture on PA3, 1 us counts from the APB1
 *         timer clock.
 * The serial receivers' bytes go from the USART interrupt into a ring; the
 * tick loop polls the link at every wake (<= 1 ms apart: SBUS's inter-frame
 * gap detection needs <= 3 ms). board_rc_read_us hands the pulses on with
 * freshness; the firmware's RC-loss policy (modes.h) acts on the freshness.
 */
#include "helical/board.h"

#include "matek_console.h"
#include "matek_hw.h"
#include "matek_rc.h"
#include "matekf405wing_pins.h"
#include "rc_serial_link.h"
#include "serial_rx_ring.h"
#include "stm32f4_ppm.h"

#include <stddef.h>

#if !defined(MATEK_RX_SBUS) && !defined(MATEK_RX_CRSF) && !defined(MATEK_RX_PPM)
#define MATEK_RX_SBUS 1
#endif

#define RC_RING_BYTES 256u /* CRSF at 420 kbaud: 42 bytes per ms */
#define RC_REPORT_MS  1000u

static uint8_t rc_up;          /* a frame seen since the last report of "lost" */
static uint32_t last_frame_ms; /* for the console's up / lost lines */
static uint8_t reported_none;

#if defined(MATEK_RX_PPM)
static stm32_ppm_t ppm;

void TIM5_IRQHandler(void);
void TIM5_IRQHandler(void)
{
    stm32_ppm_isr(&ppm);
}

void matek_rc_init(void)
{
    // cppcheck-suppress misra-c2012-11.4 ; D-11.4-REG: TIM5 register block address
    stm32_tim_t *const tim5 = (stm32_tim_t *)STM32_TIM5_BASE;
    if (stm32_ppm_init(&ppm, tim5, MATEK_PPM_CHANNEL, matek_clocks()->tim_apb1_hz,
                       STM32_PPM_RISING) != STM32_PPM_OK) {
        matek_console_puts("rc: PPM timer set-up refused\r\n");
        return;
    }
    matek_pin_af(0u, MATEK_PPM_PIN, MATEK_AF_TIM5, 0u);
    matek_nvic_enable(STM32_TIM5_IRQN);
    matek_console_puts("rc: PPM on PA3 (TIM5 CH4)\r\n");
}

void matek_rc_poll(void) {}

static board_status_t rc_read(uint16_t pulse_us[], uint8_t count)
{
    return (stm32_ppm_read_us(&ppm, pulse_us, count) == STM32_PPM_OK) ? BOARD_OK
                                                                      : BOARD_ERR_NO_DATA;
}
#else
static stm32_usart_t rc_usart;
static serial_rx_ring_t rc_ring;
static volatile uint8_t rc_ring_buf[RC_RING_BYTES];
static rc_serial_link_t rc_link;

#if defined(MATEK_RX_CRSF)
void USART6_IRQHandler(void);
void USART6_IRQHandler(void)
{
    (void)serial_rx_ring_isr(&rc_usart, &rc_ring);
}
#else
void USART2_IRQHandler(void);
void USART2_IRQHandler(void)
{
    (void)serial_rx_ring_isr(&rc_usart, &rc_ring);
}
#endif

void matek_rc_init(void)
{
    (void)serial_rx_ring_init(&rc_ring, rc_ring_buf, RC_RING_BYTES);
#if defined(MATEK_RX_CRSF)
    // cppcheck-suppress misra-c2012-11.4 ; D-11.4-REG: USART6 register block address
    stm32_usart_regs_t *const regs = (stm32_usart_regs_t *)STM32_USART6_BASE;
    const stm32_usart_status_t st = stm32_usart_init_format(
        &rc_usart, regs, matek_clocks()->pclk2_hz, 420000u, STM32_USART_8N1);
    matek_pin_af(2u, MATEK_USART6_TX_PIN, MATEK_AF_USART6, 0u);
    matek_pin_af(2u, MATEK_USART6_RX_PIN, MATEK_AF_USART6, 0u);
    const uint32_t irqn = STM32_USART6_IRQN;
    const rc_serial_protocol_t proto = RC_SERIAL_CRSF;
    const char *what = "rc: CRSF on USART6 (PC7), 420000 baud\r\n";
#else
    // cppcheck-suppress misra-c2012-11.4 ; D-11.4-REG: USART2 register block address
    stm32_usart_regs_t *const regs = (stm32_usart_regs_t *)STM32_USART2_BASE;
    const stm32_usart_status_t st = stm32_usart_init_format(
        &rc_usart, regs, matek_clocks()->pclk1_hz, 100000u, STM32_USART_8E2);
    matek_pin_af(0u, MATEK_USART2_RX_PIN, MATEK_AF_USART1_3, 0u);
    const uint32_t irqn = STM32_USART2_IRQN;
    const rc_serial_protocol_t proto = RC_SERIAL_SBUS;
    const char *what = "rc: SBUS on USART2 (PA3, the inverted SBUS pad), 100000 8E2\r\n";
#endif
    if (st != STM32_USART_OK) {
        matek_console_puts("rc: USART set-up refused\r\n");
        return;
    }
    (void)rc_serial_link_init(&rc_link, proto, RC_SERIAL_TIMEOUT_US_DEFAULT, matek_time_us());
    stm32_usart_enable_rx_irq(&rc_usart);
    matek_nvic_enable(irqn);
    matek_console_puts(what);
}

void matek_rc_poll(void)
{
    uint8_t buf[64];
    const size_t n = serial_rx_ring_read(&rc_ring, buf, sizeof buf);
    rc_serial_link_poll(&rc_link, buf, n, matek_time_us());
}

static board_status_t rc_read(uint16_t pulse_us[], uint8_t count)
{
    return rc_serial_link_read_us(&rc_link, pulse_us, count);
}
#endif

uint8_t board_rc_count(void)
{
    return (uint8_t)BOARD_MAX_RC_INPUTS;
}

board_status_t board_rc_read_us(uint16_t pulse_us[], uint8_t count)
{
    if (pulse_us == NULL) {
        return BOARD_ERR_NULL;
    }
    if (count > BOARD_MAX_RC_INPUTS) {
        return BOARD_ERR_RANGE;
    }
    matek_budget_mark(MATEK_MARK_RC_IN);
    const board_status_t st = rc_read(pulse_us, count);
    const uint32_t now = matek_time_ms();
    if (st == BOARD_OK) {
        last_frame_ms = now;
        if (rc_up == 0u) {
            matek_console_puts("rc: receiver frames arriving\r\n");
            rc_up = 1u;
        }
    } else if (rc_up != 0u && (now - last_frame_ms) > RC_REPORT_MS) {
        matek_console_puts("rc: receiver lost (no frame for 1 s)\r\n");
        rc_up = 0u;
    } else if (rc_up == 0u && reported_none == 0u && now > RC_REPORT_MS) {
        matek_console_puts("rc: receiver missing (no frame yet)\r\n");
        reported_none = 1u;
    } else {
        /* no change to report */
    }
    matek_budget_mark(MATEK_MARK_RC_OUT);
    return st;
}
