/*
 * stm32f4_i2c_regs.h - the STM32F405 I2C register block and the bits the
 * polled master uses. Offsets, addresses and bit positions are from RM0090
 * (section 27.6, I2C registers; section 2.3, memory map; section 7.3.13,
 * RCC_APB1ENR) and the STM32F405 datasheet (DS8626: table 9, alternate
 * functions, I2C1/I2C2 on AF4; table 53, I2C characteristics).
 */
#ifndef HT_STM32F4_I2C_REGS_H
#define HT_STM32F4_I2C_REGS_H

#include <stddef.h>
#include <stdint.h>

typedef struct {
    volatile uint32_t CR1;   /* 0x00 control 1 */
    volatile uint32_t CR2;   /* 0x04 control 2: FREQ = PCLK1 in MHz */
    volatile uint32_t OAR1;  /* 0x08 own address 1 (slave mode; unused by a master) */
    volatile uint32_t OAR2;  /* 0x0C own address 2 (dual addressing) */
    volatile uint32_t DR;    /* 0x10 data (8 bits) */
    volatile uint32_t SR1;   /* 0x14 status 1: events and errors */
    volatile uint32_t SR2;   /* 0x18 status 2: MSL, BUSY, TRA */
    volatile uint32_t CCR;   /* 0x1C clock control: F/S, DUTY, CCR[11:0] */
    volatile uint32_t TRISE; /* 0x20 maximum rise time in PCLK1 periods + 1 */
    volatile uint32_t FLTR;  /* 0x24 noise filter: STM32F42x/43x only (RM0090 27.3.5);
                                reserved on the F405, so the driver never writes it */
} stm32_i2c_regs_t;

_Static_assert((size_t)offsetof(stm32_i2c_regs_t, CR2) == 0x04u, "I2C CR2 offset");
_Static_assert((size_t)offsetof(stm32_i2c_regs_t, OAR1) == 0x08u, "I2C OAR1 offset");
_Static_assert((size_t)offsetof(stm32_i2c_regs_t, OAR2) == 0x0Cu, "I2C OAR2 offset");
_Static_assert((size_t)offsetof(stm32_i2c_regs_t, DR) == 0x10u, "I2C DR offset");
_Static_assert((size_t)offsetof(stm32_i2c_regs_t, SR1) == 0x14u, "I2C SR1 offset");
_Static_assert((size_t)offsetof(stm32_i2c_regs_t, SR2) == 0x18u, "I2C SR2 offset");
_Static_assert((size_t)offsetof(stm32_i2c_regs_t, CCR) == 0x1Cu, "I2C CCR offset");
_Static_assert((size_t)offsetof(stm32_i2c_regs_t, TRISE) == 0x20u, "I2C TRISE offset");
_Static_assert((size_t)offsetof(stm32_i2c_regs_t, FLTR) == 0x24u, "I2C FLTR offset");

/* APB1 peripherals, clocked by PCLK1 (16 MHz from the HSI after reset,
 * at most 42 MHz). */
#define STM32_I2C1_BASE 0x40005400u
#define STM32_I2C2_BASE 0x40005800u
#define STM32_I2C3_BASE 0x40005C00u

/* I2C_CR1 */
#define I2C_CR1_PE    0x0001u /* peripheral enable */
#define I2C_CR1_START 0x0100u /* generate a (repeated) START; hardware clears it */
#define I2C_CR1_STOP  0x0200u /* generate a STOP after the current byte; hardware clears it */
#define I2C_CR1_ACK   0x0400u /* acknowledge received bytes */
#define I2C_CR1_POS   0x0800u /* ACK/NACK applies to the next byte (2-byte reception) */
#define I2C_CR1_SWRST 0x8000u /* software reset: every register back to its reset value */

/* I2C_CR2 */
#define I2C_CR2_FREQ_MASK   0x003Fu /* FREQ[5:0]: PCLK1 in MHz */
#define I2C_CR2_FREQ_MIN_SM 2u      /* RM0090 27.6.2 and DS8626 table 53 note 2 */
#define I2C_CR2_FREQ_MIN_FM 4u
#define I2C_CR2_FREQ_MAX    42u

/* I2C_OAR1: bit 14 "should always be kept at 1 by software" (RM0090 27.6.3) */
#define I2C_OAR1_BIT14 0x4000u

/* I2C_SR1 */
#define I2C_SR1_SB   0x0001u /* START sent (EV5); cleared by SR1 read + DR write */
#define I2C_SR1_ADDR 0x0002u /* address acknowledged (EV6); cleared by SR1 + SR2 reads */
#define I2C_SR1_BTF                                                                                \
    0x0004u                      /* byte transfer finished: DR and shift register both full        \
                                    (receive) or both empty (transmit) */
#define I2C_SR1_RXNE     0x0040u /* a byte waits in DR */
#define I2C_SR1_TXE      0x0080u /* DR is empty */
#define I2C_SR1_BERR     0x0100u /* bus error: misplaced START or STOP */
#define I2C_SR1_ARLO     0x0200u /* arbitration lost */
#define I2C_SR1_AF       0x0400u /* acknowledge failure (NACK) */
#define I2C_SR1_OVR      0x0800u /* overrun/underrun (slave mode only) */
#define I2C_SR1_PECERR   0x1000u
#define I2C_SR1_TIMEOUT  0x4000u /* SMBus timeout */
#define I2C_SR1_SMBALERT 0x8000u
/* The rc_w0 bits: cleared by writing 0, unchanged by writing 1. Writing this
 * mask without one bit clears that bit alone, with no read-modify-write race. */
#define I2C_SR1_RC_W0                                                                              \
    (I2C_SR1_BERR | I2C_SR1_ARLO | I2C_SR1_AF | I2C_SR1_OVR | I2C_SR1_PECERR | I2C_SR1_TIMEOUT |   \
     I2C_SR1_SMBALERT)

/* I2C_SR2 */
#define I2C_SR2_MSL  0x0001u /* master mode */
#define I2C_SR2_BUSY 0x0002u /* SDA or SCL low: a transfer is on the bus */

/* I2C_CCR */
#define I2C_CCR_FS      0x8000u /* fast mode (Fm, up to 400 kHz) */
#define I2C_CCR_DUTY    0x4000u /* Fm duty 16/9 (unused: the driver keeps Tlow/Thigh = 2) */
#define I2C_CCR_MASK    0x0FFFu
#define I2C_CCR_MIN_SM  4u /* RM0090 27.6.8: the minimum CCR in standard mode */
#define I2C_CCR_MIN_FM  1u
#define I2C_TRISE_MASK  0x003Fu
#define I2C_TRISE_SM_NS 1000u /* maximum SCL rise time, Sm (UM10204 table 10) */
#define I2C_TRISE_FM_NS 300u  /* the same, Fm */

/* RCC_APB1ENR (offset 0x40) and RCC_APB1RSTR (offset 0x20): same bit per block */
#define RCC_APB1ENR_I2C1EN 0x00200000u /* bit 21 */
#define RCC_APB1ENR_I2C2EN 0x00400000u /* bit 22 */

/* I2C1 on PB8 (SCL) / PB9 (SDA) and I2C2 on PB10 (SCL) / PB11 (SDA):
 * alternate function 4, open-drain outputs (DS8626 table 9). */
#define GPIO_AF4_I2C1_3 4u

#endif /* HT_STM32F4_I2C_REGS_H */
