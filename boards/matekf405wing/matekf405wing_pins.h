/*
 * matekf405wing_pins.h - the Matek F405-WING's pin map (STM32F405RGT6), as
 * this image uses it. Sources (facts only, no code; docs/boards/
 * matek_f405_wing.md has the table and what is unverified):
 *   [INAV]  iNavFlight/inav src/main/target/MATEKF405SE/target.h, target.c
 *   [AP]    ArduPilot libraries/AP_HAL_ChibiOS/hwdef/MatekF405-Wing/hwdef.dat
 *   [DS]    STM32F405xx datasheet DS8626, table 9 "alternate function mapping"
 * Port letters: A = 0, B = 1, C = 2 (the EXTI port code, RM0090 9.2.3).
 */
#ifndef HT_MATEKF405WING_PINS_H
#define HT_MATEKF405WING_PINS_H

/* Servo / motor outputs S1..S8 [INAV target.c, AP hwdef PWM(1..8)]. S7/S8
 * use TIM12 (AF9) as INAV's older target did; AP uses TIM1_CH2N/CH3N on the
 * same pins (complementary outputs, which this driver does not set up). S9
 * (PA8, TIM1_CH1) is not used: board.h has at most 8 servos. */
#define MATEK_S1_PIN    7u  /* PB7  TIM4_CH2  AF2 */
#define MATEK_S2_PIN    6u  /* PB6  TIM4_CH1  AF2 */
#define MATEK_S3_PIN    0u  /* PB0  TIM3_CH3  AF2 */
#define MATEK_S4_PIN    1u  /* PB1  TIM3_CH4  AF2 */
#define MATEK_S5_PIN    8u  /* PC8  TIM8_CH3  AF3 */
#define MATEK_S6_PIN    9u  /* PC9  TIM8_CH4  AF3 */
#define MATEK_S7_PIN    14u /* PB14 TIM12_CH1 AF9 */
#define MATEK_S8_PIN    15u /* PB15 TIM12_CH2 AF9 */
#define MATEK_AF_TIM3_4 2u
#define MATEK_AF_TIM8   3u
#define MATEK_AF_TIM12  9u
#define MATEK_SERVOS    8u

/* Timers not in stm32f4_regs.h (RM0090 table 1, memory map). */
#define MATEK_TIM8_BASE  0x40010400u /* APB2 */
#define MATEK_TIM12_BASE 0x40001800u /* APB1 */

/* IMU: SPI1 SCK PA5, MISO PA6, MOSI PA7 (AF5), CS PA4, data-ready PC4
 * (EXTI4) [INAV target.h: SPI1_*, MPU6000_CS_PIN, GYRO_INT_EXTI; AP hwdef]. */
#define MATEK_SPI1_SCK_PIN  5u
#define MATEK_SPI1_MISO_PIN 6u
#define MATEK_SPI1_MOSI_PIN 7u
#define MATEK_IMU_CS_PIN    4u /* PA4 */
#define MATEK_IMU_DRDY_PIN  4u /* PC4 */

/* Baro BMP280 on I2C1 PB8 SCL / PB9 SDA at 0x76 [INAV I2C1_*, BARO_I2C_BUS;
 * AP HAL_BARO_BMP280_I2C_ADDR 0x76]. External I2C2 PB10 SCL / PB11 SDA:
 * pitot, compass [INAV PITOT_I2C_BUS BUS_I2C2]. AF4 [DS]. */
#define MATEK_I2C1_SCL_PIN 8u
#define MATEK_I2C1_SDA_PIN 9u
#define MATEK_I2C2_SCL_PIN 10u
#define MATEK_I2C2_SDA_PIN 11u
#define MATEK_AF_I2C       4u

/* UARTs [INAV target.h UARTn_*_PIN; AP hwdef]:
 *   USART1 PA9 TX / PA10 RX  AF7: console, and the HIL/PIL link in the HIL image
 *   USART2 PA3 RX (the "SBUS" pad: RX2 through the board's inverter) AF7: SBUS
 *          (PA2 TX2: unused here)
 *   USART3 PC10 TX / PC11 RX AF7: GPS (u-blox)
 *   UART4  PA0 TX4 / PA1 RX4 AF8: the MAVLink ground-station link (matek_mavlink.c)
 *   UART5  PC12 / PD2: free
 *   USART6 PC6 TX / PC7 RX   AF8: CRSF receiver (uninverted)
 * PPM: PA3 (the same RX2 pad) as TIM5_CH4, AF2 [DS; INAV uses TIM9_CH2, AP
 * once TIM2_CH4: any of the three fits the pin]. */
#define MATEK_USART1_TX_PIN 9u
#define MATEK_USART1_RX_PIN 10u
#define MATEK_USART2_RX_PIN 3u
#define MATEK_USART3_TX_PIN 10u
#define MATEK_USART3_RX_PIN 11u
#define MATEK_USART6_TX_PIN 6u
#define MATEK_USART6_RX_PIN 7u
#define MATEK_AF_USART1_3   7u
#define MATEK_AF_USART6     8u
#define MATEK_UART4_TX_PIN  0u /* PA0 */
#define MATEK_UART4_RX_PIN  1u /* PA1 */
#define MATEK_AF_UART4      8u
#define MATEK_PPM_PIN       3u /* PA3 */
#define MATEK_PPM_CHANNEL   4u /* TIM5_CH4 */
#define MATEK_AF_TIM5       2u

/* LED0 (blue) PA14, LED1 (green) PA13, beeper PC15 driven high to sound
 * [INAV LED0/LED1/BEEPER; AP LED_BLUE, LED_GREEN, BUZZER with HAL_BUZZER_ON 1].
 * PA13/PA14 are also SWDIO/SWCLK: the image uses only PA14 (blue), after
 * boot, so SWD is lost once the image runs (flash by USB DFU / BOOT pad). */
#define MATEK_LED_PIN    14u /* PA14 */
#define MATEK_BEEPER_PIN 15u /* PC15 */

#endif /* HT_MATEKF405WING_PINS_H */
