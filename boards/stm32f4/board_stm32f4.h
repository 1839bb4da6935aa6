/*
 * board_stm32f4.h - what the STM32F405 board file offers beyond board.h.
 */
#ifndef HT_BOARD_STM32F4_H
#define HT_BOARD_STM32F4_H

#include "stm32f4_pwm.h"

/* The servo PWM driver's state (read-only), e.g. to read the compare
 * registers back in the HIL image. */
const stm32_pwm_t *board_stm32f4_pwm(void);

#endif /* HT_BOARD_STM32F4_H */
