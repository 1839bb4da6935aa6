/*
 * stm32f4_usart_regs.h - the STM32F405 USART register block and the bits the
 * HIL link and the receiver/GPS links use. Offsets, addresses and bit
 * positions are from RM0090 (section 30.6, USART registers; section 2.3,
 * memory map; section 7.3.14, RCC_APB2ENR; table 61, vector table) and the
 * STM32F405 datasheet's alternate-function table (USART1 on PA9/PA10, AF7).
 */
#ifndef HT_STM32F4_USART_REGS_H
#define HT_STM32F4_USART_REGS_H

#include <stddef.h>
#include <stdint.h>

typedef struct {
    volatile uint32_t SR;   /* 0x00 status */
    volatile uint32_t DR;   /* 0x04 data (8 or 9 bits) */
    volatile uint32_t BRR;  /* 0x08 baud rate: mantissa 15:4, fraction 3:0 */
    volatile uint32_t CR1;  /* 0x0C control 1 */
    volatile uint32_t CR2;  /* 0x10 control 2 (stop bits) */
    volatile uint32_t CR3;  /* 0x14 control 3 (flow control, DMA) */
    volatile uint32_t GTPR; /* 0x18 guard time and prescaler (smartcard, IrDA) */
} stm32_usart_regs_t;

_Static_assert((size_t)offsetof(stm32_usart_regs_t, DR) == 0x04u, "USART DR offset");
_Static_assert((size_t)offsetof(stm32_usart_regs_t, BRR) == 0x08u, "USART BRR offset");
_Static_assert((size_t)offsetof(stm32_usart_regs_t, CR1) == 0x0Cu, "USART CR1 offset");
_Static_assert((size_t)offsetof(stm32_usart_regs_t, GTPR) == 0x18u, "USART GTPR offset");

#define STM32_USART1_BASE 0x40011000u /* APB2; clocked by PCLK2 (16 MHz after reset) */
#define STM32_USART6_BASE 0x40011400u /* APB2, PCLK2 */
#define STM32_USART2_BASE 0x40004400u /* APB1; clocked by PCLK1 */
#define STM32_USART3_BASE 0x40004800u /* APB1, PCLK1 */
#define STM32_UART4_BASE  0x40004C00u /* APB1, PCLK1 */
#define STM32_UART5_BASE  0x40005000u /* APB1, PCLK1 */

/* USART_SR */
#define USART_SR_PE  (1u << 0) /* parity error */
#define USART_SR_FE  (1u << 1) /* framing error */
#define USART_SR_NF  (1u << 2) /* noise detected */
#define USART_SR_ORE (1u << 3) /* overrun: a byte arrived while RXNE was set */
#define USART_SR_IDLE                                                                              \
    (1u << 4) /* a whole idle frame after the last byte (cleared by the SR-then-DR read) */
#define USART_SR_RXNE                                                                              \
    (1u << 5)                     /* a byte waits in DR; reading DR clears it (and PE/FE/NF/ORE    \
                                     after an SR read) */
#define USART_SR_TC     (1u << 6) /* transmission complete */
#define USART_SR_TXE    (1u << 7) /* DR may take the next byte */
#define USART_SR_ERRORS (USART_SR_PE | USART_SR_FE | USART_SR_NF | USART_SR_ORE)

/* USART_CR1 (section 30.6.4). OVER8 (bit 15) stays 0: 16x oversampling. */
#define USART_CR1_RE     (1u << 2)            /* receiver enable */
#define USART_CR1_TE     (1u << 3)            /* transmitter enable */
#define USART_CR1_RXNEIE (1u << 5)            /* interrupt while RXNE or ORE is set */
#define USART_CR1_TXEIE  (1u << 7)            /* interrupt while TXE is set */
#define USART_CR1_PS     (1u << 9)            /* parity selection: 0 even, 1 odd */
#define USART_CR1_PCE    0x0400u              /* bit 10, parity control: the word's MSB is parity */
#define USART_CR1_M      0x1000u              /* bit 12, word length: 0 = 8 bits, 1 = 9 bits */
#define USART_CR1_UE     ((uint32_t)1u << 13) /* USART enable */

/* USART_CR2 (section 30.6.5): STOP[1:0] at bits 13:12 - 00 one stop bit,
 * 01 half, 10 two, 11 one and a half (UART4/5 have no half or 1.5). */
#define USART_CR2_STOP_1  0x0000u
#define USART_CR2_STOP_2  0x2000u
#define USART_CR2_STOP_MS 0x3000u

/* USART1's interrupt line (RM0090 table 61, position 37) and the Cortex-M4
 * NVIC interrupt set-enable registers (ISER0..7 at 0xE000E100, one bit per
 * line). */
#define STM32_USART1_IRQN    37u
#define STM32_USART2_IRQN    38u
#define STM32_USART3_IRQN    39u
#define STM32_UART4_IRQN     52u /* the Matek's MAVLink link (boards/matekf405wing) */
#define STM32_UART5_IRQN     53u
#define STM32_USART6_IRQN    71u
#define STM32_NVIC_ISER_BASE 0xE000E100u

/* RCC_APB2ENR (offset 0x44) */
#define RCC_APB2ENR_USART1EN (1u << 4)

/* USART1_TX on PA9, USART1_RX on PA10: alternate function 7 */
#define GPIO_AF7_USART1_3 7u

#endif /* HT_STM32F4_USART_REGS_H */
