/*
 * stm32f4_gpio.c - see stm32f4_gpio.h.
 */
#include "stm32f4_gpio.h"

#include <stddef.h>

void stm32_gpio_set_af(stm32_gpio_t *port, uint8_t pin, uint8_t af)
{
    if (port == NULL || pin > 15u || af > 15u) {
        return;
    }
    /* AFR first, so the pin never drives a wrong function once in AF mode. */
    const uint32_t pin32 = pin;
    const uint32_t reg = pin32 / 8u;
    const uint32_t af_shift = 4u * (pin32 % 8u);
    port->AFR[reg] = (port->AFR[reg] & ~((uint32_t)0xFu << af_shift)) | ((uint32_t)af << af_shift);
    const uint32_t mode_shift = 2u * pin32;
    port->MODER =
        (port->MODER & ~((uint32_t)3u << mode_shift)) | ((uint32_t)GPIO_MODER_AF << mode_shift);
}

void stm32_gpio_write(stm32_gpio_t *port, uint8_t pin, uint8_t high)
{
    if (port == NULL || pin > 15u) {
        return;
    }
    const uint32_t shift = (high != 0u) ? (uint32_t)pin : (uint32_t)pin + GPIO_BSRR_RESET_SHIFT;
    port->BSRR = (uint32_t)1u << shift;
}

void stm32_gpio_set_output(stm32_gpio_t *port, uint8_t pin, uint8_t high)
{
    if (port == NULL || pin > 15u) {
        return;
    }
    stm32_gpio_write(port, pin, high);
    const uint32_t pin32 = pin;
    port->OTYPER &= ~((uint32_t)1u << pin32); /* push-pull */
    const uint32_t shift2 = 2u * pin32;
    port->OSPEEDR =
        (port->OSPEEDR & ~((uint32_t)3u << shift2)) | ((uint32_t)GPIO_OSPEEDR_FAST << shift2);
    port->MODER =
        (port->MODER & ~((uint32_t)3u << shift2)) | ((uint32_t)GPIO_MODER_OUTPUT << shift2);
}

void stm32_rcc_enable_servo_clocks(stm32_rcc_t *rcc)
{
    if (rcc == NULL) {
        return;
    }
    rcc->AHB1ENR |= RCC_AHB1ENR_GPIOAEN | RCC_AHB1ENR_GPIOBEN;
    rcc->APB1ENR |= RCC_APB1ENR_TIM3EN | RCC_APB1ENR_TIM4EN;
    /* RM0090: a peripheral must not be accessed in the two clock cycles after
     * its enable; reading the enable register back provides that delay. */
    (void)rcc->APB1ENR;
}
