/*
 * matek_mavlink.c - the MAVLink ground-station link (firmware/link/fw_link.h) of
 * the Matek F405-WING image on UART4: TX4 PA0, RX4 PA1 (AF8), 57600 8N1,
 * the rate of the common telemetry radios (docs/boards/matek_f405_wing.md).
 *
 * Bytes in: the receive interrupt puts each byte into a ring; every tick
 * (fw_board_link_poll) the main loop hands what arrived to fw_link_rx.
 * Bytes out: fw_link_tx's bytes go into a transmit ring that the UART's TXE
 * interrupt empties at the line rate (one writer, the main loop; one reader,
 * the interrupt: head and tail are each written by one side only). The
 * interrupt is enabled when there is something to send and disables itself
 * when the ring is empty. (QEMU's USART model raises no TXE interrupt: under
 * QEMU the link receives but does not send.)
 *
 * MAV_CMD_PREFLIGHT_STORAGE (param1 = 1) saves every row the link exposes
 * (all of params.def, LINK included) in the parameter store
 * (matek_params_save; the boot load gives the LINK rows back here): a
 * flash sector erase that stalls the loop for up to half a second - on the
 * ground only (docs/mavlink.md).
 */
#include "fw_board_config.h"
#include "matek_console.h"
#include "matek_hw.h"
#include "matek_params_boot.h"
#include "matekf405wing_pins.h"
#include "serial_rx_ring.h"
#include "stm32f4_regs.h"

#define LINK_BAUD     57600u
#define RX_RING_BYTES 512u  /* 89 ms at 57600 baud: several ticks of slack */
#define TX_RING_BYTES 1024u /* a power of two */
#define TX_MASK       (TX_RING_BYTES - 1u)

static stm32_usart_t link_usart;
static serial_rx_ring_t rx_ring;
static volatile uint8_t rx_buf[RX_RING_BYTES];
static volatile uint8_t tx_buf[TX_RING_BYTES];
static volatile uint32_t tx_head; /* written by the main loop only */
static volatile uint32_t tx_tail; /* written by the interrupt only */

void UART4_IRQHandler(void);
void UART4_IRQHandler(void)
{
    stm32_usart_regs_t *const r = link_usart.regs;
    if ((r->SR & (USART_SR_RXNE | USART_SR_ORE)) != 0u) {
        (void)serial_rx_ring_isr(&link_usart, &rx_ring);
    }
    if (((r->CR1 & USART_CR1_TXEIE) != 0u) && ((r->SR & USART_SR_TXE) != 0u)) {
        const uint32_t tail = tx_tail;
        if (tail == tx_head) {
            r->CR1 &= ~USART_CR1_TXEIE; /* empty: the main loop enables it again */
        } else {
            r->DR = tx_buf[tail & TX_MASK];
            tx_tail = tail + 1u;
        }
    }
}

int fw_board_link_init(fw_link_t *link)
{
    // cppcheck-suppress misra-c2012-11.4 ; D-11.4-REG: UART4 register block address
    stm32_usart_regs_t *const uart4 = (stm32_usart_regs_t *)STM32_UART4_BASE;
    (void)serial_rx_ring_init(&rx_ring, rx_buf, RX_RING_BYTES);
    tx_head = 0u;
    tx_tail = 0u;
    if (stm32_usart_init(&link_usart, uart4, matek_clocks()->pclk1_hz, LINK_BAUD) !=
        STM32_USART_OK) {
        matek_console_puts("mavlink: UART4 set-up refused (no ground-station link)\r\n");
        return 0;
    }
    matek_pin_af(0u, MATEK_UART4_TX_PIN, MATEK_AF_UART4, 0u);
    matek_pin_af(0u, MATEK_UART4_RX_PIN, MATEK_AF_UART4, 0u);
    stm32_usart_enable_rx_irq(&link_usart);
    matek_nvic_enable(STM32_UART4_IRQN);
    const fw_link_params_t *stored = matek_params_link();
    if (stored != NULL) {
        link->params = *stored; /* the stored set's LINK rows (fw_link_init set the defaults) */
    }
    link->save = matek_params_save;
    link->save_ctx = NULL;
    matek_console_puts("mavlink: MAVLink 2 on UART4 (TX4 PA0, RX4 PA1), 57600 8N1\r\n");
    return 1;
}

void fw_board_link_poll(fw_link_t *link)
{
    uint8_t buf[64];
    size_t n;
    while ((n = serial_rx_ring_read(&rx_ring, buf, sizeof buf)) > 0u) {
        fw_link_rx(link, buf, n);
    }
    /* as much as the transmit ring takes; the rest waits in the link's queue */
    const uint32_t head = tx_head;
    const uint32_t room = TX_RING_BYTES - (head - tx_tail);
    const size_t got = fw_link_tx(link, buf, (room < sizeof buf) ? (size_t)room : sizeof buf);
    for (size_t i = 0u; i < got; ++i) {
        tx_buf[(head + (uint32_t)i) & TX_MASK] = buf[i];
    }
    if (got > 0u) {
        tx_head = head + (uint32_t)got;
        link_usart.regs->CR1 |= USART_CR1_TXEIE;
    }
}

uint32_t fw_board_time_ms(void)
{
    return matek_time_ms();
}
