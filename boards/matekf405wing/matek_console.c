/*
 * matek_console.c - the console on USART1 (PA9 TX / PA10 RX, AF7, 115200
 * 8N1 from PCLK2): boot report, device status changes, a heartbeat. In QEMU's
 * netduinoplus2, -serial #0 is this USART.
 */
#include "matek_console.h"

#include "matek_hw.h"
#include "matek_txq.h"
#include "matekf405wing_pins.h"
#include "stm32f4_regs.h"

#define CONSOLE_BAUD 115200u

static stm32_usart_t console_usart;
static matek_txq_t console_q;

void matek_console_init(void)
{
    // cppcheck-suppress misra-c2012-11.4 ; D-11.4-REG: USART1 register block address
    stm32_usart_regs_t *const usart1 = (stm32_usart_regs_t *)STM32_USART1_BASE;
    matek_txq_init(&console_q, &console_usart);
    if (stm32_usart_init(&console_usart, usart1, matek_clocks()->pclk2_hz, CONSOLE_BAUD) !=
        STM32_USART_OK) {
        return;
    }
    matek_pin_af(0u, MATEK_USART1_TX_PIN, MATEK_AF_USART1_3, 0u);
    matek_pin_af(0u, MATEK_USART1_RX_PIN, MATEK_AF_USART1_3, 0u);
}

void matek_console_puts(const char *s)
{
    size_t n = 0u;
    while (s[n] != '\0' && n < 200u) {
        ++n;
    }
    (void)matek_txq_write(&console_q, (const uint8_t *)s, n);
}

void matek_console_put_u32(uint32_t v)
{
    char digits[11];
    uint32_t n = 0u;
    uint32_t x = v;
    do {
        digits[n] = (char)('0' + (char)(x % 10u));
        x /= 10u;
        ++n;
    } while (x != 0u && n < 10u);
    char out[11];
    for (uint32_t i = 0u; i < n; ++i) {
        out[i] = digits[n - 1u - i];
    }
    out[n] = '\0';
    matek_console_puts(out);
}

void matek_console_put_i32(int32_t v)
{
    if (v < 0) {
        matek_console_puts("-");
        matek_console_put_u32((uint32_t)(-(v + 1)) + 1u);
    } else {
        matek_console_put_u32((uint32_t)v);
    }
}

void matek_console_pump(void)
{
    matek_txq_pump(&console_q, 16u);
}

void matek_console_flush(void)
{
    matek_txq_drain(&console_q);
}
