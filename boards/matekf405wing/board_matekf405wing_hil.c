/*
 * board_matekf405wing_hil.c - the HIL/PIL link of the Matek F405-WING image
 * (docs/hil-protocol.md): USART1 PA9 TX / PA10 RX, AF7, 115200 8N1 from the
 * clock actually running (PCLK2: 84 MHz, or 16 MHz on HSI). Received bytes go
 * from the USART1 interrupt into a ring; the main loop sleeps (WFI) while it
 * is empty. Sending is polled (bounded per byte). The servo read-back is the
 * timers' compare registers.
 */
#include "hil/hil_link.h"
#include "matek_board.h"
#include "matek_hw.h"
#include "matekf405wing_pins.h"
#include "serial_rx_ring.h"
#include "stm32f4_regs.h"

#define HIL_BAUD    115200u
#define TX_SPIN_MAX 100000u
#define RX_RING     256u

static stm32_usart_t link;
static serial_rx_ring_t ring;
static volatile uint8_t ring_buf[RX_RING];

/* Named by the vector table (startup_stm32f405.c), which declares it weak. */
void USART1_IRQHandler(void);
void USART1_IRQHandler(void)
{
    (void)serial_rx_ring_isr(&link, &ring);
}

int hil_link_init(void)
{
    // cppcheck-suppress misra-c2012-11.4 ; D-11.4-REG: USART1 register block address
    stm32_usart_regs_t *const usart1 = (stm32_usart_regs_t *)STM32_USART1_BASE;
    (void)serial_rx_ring_init(&ring, ring_buf, RX_RING);
    if (stm32_usart_init(&link, usart1, matek_clocks()->pclk2_hz, HIL_BAUD) != STM32_USART_OK) {
        return 0;
    }
    matek_pin_af(0u, MATEK_USART1_TX_PIN, MATEK_AF_USART1_3, 0u);
    matek_pin_af(0u, MATEK_USART1_RX_PIN, MATEK_AF_USART1_3, 0u);
    stm32_usart_enable_rx_irq(&link);
    matek_nvic_enable(STM32_USART1_IRQN);
    return 1;
}

/* A byte from the ring; when empty, sleep until an interrupt and report none
 * (masked check + WFI: a byte arriving in between still ends the WFI). */
int hil_link_poll(uint8_t *byte)
{
    __asm__ volatile("cpsid i" ::: "memory");
    if (serial_rx_ring_count(&ring) == 0u) {
        __asm__ volatile("wfi");
        __asm__ volatile("cpsie i" ::: "memory");
        return 0;
    }
    __asm__ volatile("cpsie i" ::: "memory");
    return (serial_rx_ring_read(&ring, byte, 1u) == 1u) ? 1 : 0;
}

void hil_link_send(const uint8_t *data, size_t n)
{
    (void)stm32_usart_write(&link, data, n, TX_SPIN_MAX);
}

uint16_t hil_link_errors(void)
{
    const uint32_t sum = (uint32_t)link.overrun + link.framing + link.noise + link.parity +
                         link.tx_timeouts + ring.dropped_full + ring.dropped_error;
    return (sum > UINT16_MAX) ? (uint16_t)UINT16_MAX : (uint16_t)sum;
}

/* The timers count at 1 MHz, so a compare register holds the pulse in us. */
uint16_t hil_servo_readback_us(uint8_t channel)
{
    return matek_servo_readback_us(channel);
}
