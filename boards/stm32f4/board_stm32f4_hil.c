/*
 * board_stm32f4_hil.c - the HIL link of the STM32F405 image: USART1 on PA9
 * (TX) / PA10 (RX), AF7, 115200 8N1 from the reset clock (PCLK2 = HSI =
 * 16 MHz); received bytes go from the USART1 interrupt into a ring buffer,
 * the main loop sleeps (WFI) while it is empty, so the image is driven by the
 * frames' arrival. Sending is polled. And the servo read-back from the
 * timers' compare registers. In QEMU's netduinoplus2, -serial #0 is this USART.
 */
#include "board_stm32f4.h"
#include "hil/hil_link.h"
#include "stm32f4_gpio.h"
#include "stm32f4_regs.h"
#include "stm32f4_usart.h"

#define HIL_BAUD    115200u
#define PCLK2_HZ    STM32_HSI_HZ /* APB2 prescaler 1 after reset */
#define TX_SPIN_MAX 100000u      /* ~100 byte times at 115200 baud: a stuck TXE is reported */

#define RX_RING 256u /* a power of two; indices are uint8_t, wrapping by themselves */

static stm32_usart_t link;
static volatile uint8_t rx_ring[RX_RING];
static volatile uint8_t rx_head; /* written by the interrupt only */
static volatile uint8_t rx_tail; /* written by the main loop only */
static volatile uint16_t rx_dropped;

/* Named by the vector table (startup_stm32f405.c), which declares it weak. */
void USART1_IRQHandler(void);
void USART1_IRQHandler(void)
{
    uint8_t byte = 0u;
    while (stm32_usart_read(&link, &byte) != 0) {
        const uint8_t next = (uint8_t)(rx_head + 1u);
        if (next == rx_tail) {
            if (rx_dropped != UINT16_MAX) {
                rx_dropped = (uint16_t)(rx_dropped + 1u);
            }
        } else {
            rx_ring[rx_head] = byte;
            rx_head = next;
        }
    }
}

int hil_link_init(void)
{
    /* The register blocks at their fixed addresses (RM0090 memory map, the
     * Cortex-M4 NVIC): docs/static-analysis.md, D-11.4-REG. */
    // cppcheck-suppress misra-c2012-11.4 ; D-11.4-REG: RCC register block address
    stm32_rcc_t *const rcc = (stm32_rcc_t *)STM32_RCC_BASE;
    // cppcheck-suppress misra-c2012-11.4 ; D-11.4-REG: GPIOA register block address
    stm32_gpio_t *const gpioa = (stm32_gpio_t *)STM32_GPIOA_BASE;
    // cppcheck-suppress misra-c2012-11.4 ; D-11.4-REG: USART1 register block address
    stm32_usart_regs_t *const usart1 = (stm32_usart_regs_t *)STM32_USART1_BASE;
    // cppcheck-suppress misra-c2012-11.4 ; D-11.4-REG: NVIC ISER0..7 register address
    volatile uint32_t *const iser = (volatile uint32_t *)STM32_NVIC_ISER_BASE;
    rcc->AHB1ENR |= RCC_AHB1ENR_GPIOAEN;
    rcc->APB2ENR |= RCC_APB2ENR_USART1EN;
    if (stm32_usart_init(&link, usart1, PCLK2_HZ, HIL_BAUD) != STM32_USART_OK) {
        return 0;
    }
    stm32_gpio_set_af(gpioa, 9u, GPIO_AF7_USART1_3);
    stm32_gpio_set_af(gpioa, 10u, GPIO_AF7_USART1_3);
    stm32_usart_enable_rx_irq(&link);
    iser[STM32_USART1_IRQN / 32u] = 1u << (STM32_USART1_IRQN % 32u);
    return 1;
}

/* A byte from the ring; when it is empty, sleep until an interrupt (a byte,
 * or SysTick) and report none. The check and the WFI run with interrupts
 * masked, so a byte arriving between them still ends the WFI. */
int hil_link_poll(uint8_t *byte)
{
    __asm__ volatile("cpsid i" ::: "memory");
    if (rx_tail == rx_head) {
        __asm__ volatile("wfi");
        __asm__ volatile("cpsie i" ::: "memory");
        return 0;
    }
    __asm__ volatile("cpsie i" ::: "memory");
    const uint8_t t = rx_tail;
    *byte = rx_ring[t];
    rx_tail = (uint8_t)(t + 1u);
    return 1;
}

void hil_link_send(const uint8_t *data, size_t n)
{
    (void)stm32_usart_write(&link, data, n, TX_SPIN_MAX);
}

uint16_t hil_link_errors(void)
{
    const uint32_t sum = (uint32_t)link.overrun + link.framing + link.noise + link.parity +
                         link.tx_timeouts + rx_dropped;
    return (sum > UINT16_MAX) ? (uint16_t)UINT16_MAX : (uint16_t)sum;
}

/* The timers count at 1 MHz, so a compare register holds the pulse in us. */
uint16_t hil_servo_readback_us(uint8_t channel)
{
    const stm32_pwm_t *pwm = board_stm32f4_pwm();
    if (channel >= STM32_PWM_CHANNELS || !pwm->ready) {
        return 0u;
    }
    return (uint16_t)(pwm->tim[channel / 4u]->CCR[channel % 4u] & 0xFFFFu);
}
