/*
 * stm32f4_gpio.h - clock gating and alternate-function pin set-up for the
 * servo outputs, against RCC/GPIO blocks passed by pointer.
 */
#ifndef HT_STM32F4_GPIO_H
#define HT_STM32F4_GPIO_H

#include <stdint.h>

#include "stm32f4_regs.h"

/* Route one pin (0..15) to alternate function af (0..15): MODER = 10, AFR = af.
 * Other pins of the port are untouched. Out-of-range arguments do nothing. */
void stm32_gpio_set_af(stm32_gpio_t *port, uint8_t pin, uint8_t af);

/* Make one pin (0..15) a push-pull output at fast speed, driving high when
 * high != 0, else low. The level goes to BSRR before MODER turns the pin into
 * an output, so a chip select starts deselected without a glitch. Other pins
 * are untouched; an out-of-range pin does nothing. */
void stm32_gpio_set_output(stm32_gpio_t *port, uint8_t pin, uint8_t high);

/* Drive an output pin high (high != 0) or low with one BSRR write: atomic,
 * no read-modify-write of ODR that an interrupt could interleave with. */
void stm32_gpio_write(stm32_gpio_t *port, uint8_t pin, uint8_t high);

/* Clock GPIOA, GPIOB, TIM3 and TIM4 (read-modify-write: other enables kept). */
void stm32_rcc_enable_servo_clocks(stm32_rcc_t *rcc);

#endif /* HT_STM32F4_GPIO_H */
