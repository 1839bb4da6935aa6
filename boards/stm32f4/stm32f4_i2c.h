/*
 * stm32f4_i2c.h - a polled I2C master for the STM32F4 I2C peripheral
 * (RM0090 section 27) against a register block passed by pointer, so host
 * tests run it on a fake block. It implements the chip drivers' bus seam
 * (boards/devices/i2c_bus.h): stm32_i2c_bus() hands it to baro_bmp280.c and
 * airspeed_ms4525.c.
 *
 * Nothing here waits without a bound: every event (SB, ADDR, TXE, BTF, RXNE,
 * BUSY released) is awaited for at most spin_limit status reads. An address
 * NACK is the normal answer of an absent chip and only ends the transaction
 * (STOP); a bus error, lost arbitration, a stuck BUSY or a timeout also
 * resets the peripheral (STOP, then SWRST, then the saved configuration).
 */
#ifndef HT_STM32F4_I2C_H
#define HT_STM32F4_I2C_H

#include <stddef.h>
#include <stdint.h>

#include "i2c_bus.h"
#include "stm32f4_i2c_regs.h"

typedef enum {
    STM32_I2C_STANDARD_100KHZ = 0, /* Sm: Thigh = Tlow = CCR * Tpclk1 */
    STM32_I2C_FAST_400KHZ = 1      /* Fm, DUTY = 0: Thigh = CCR * Tpclk1, Tlow = 2 Thigh */
} stm32_i2c_speed_t;

#define STM32_I2C_SM_HZ 100000u
#define STM32_I2C_FM_HZ 400000u

/* Driver state, owned by the caller. The counters saturate at UINT16_MAX. */
typedef struct {
    stm32_i2c_regs_t *regs;
    uint32_t spin_limit;      /* status reads per awaited event */
    uint32_t cr2, ccr, trise; /* the configuration, re-applied after a SWRST */
    uint16_t nacks;           /* address not acknowledged (absent chip) */
    uint16_t data_nacks;      /* a written byte not acknowledged */
    uint16_t timeouts;        /* an event never came */
    uint16_t bus_errors;      /* BERR */
    uint16_t arb_lost;        /* ARLO */
    uint16_t busy;            /* BUSY stayed set before a START */
    uint16_t recoveries;      /* STOP + SWRST + reconfiguration runs */
    uint8_t ready;            /* 1 after a successful init */
} stm32_i2c_t;

/*
 * Configure the master from PCLK1 (a whole number of MHz: FREQ holds it in
 * MHz; 2..42 MHz for 100 kHz, 4..42 MHz for 400 kHz) and enable it:
 *   CR2.FREQ = pclk1 / 1 MHz
 *   100 kHz: CCR = ceil(pclk1 / 200 kHz);  TRISE = FREQ + 1
 *            (1000 ns maximum rise time)
 *   400 kHz: CCR = F/S | ceil(pclk1 / 1.2 MHz);
 *            TRISE = floor(FREQ * 300 / 1000) + 1 (300 ns)
 * Rounding CCR up keeps SCL at or below the nominal rate (RM0090 27.6.8,
 * 27.6.9); the FREQ ranges keep CCR above its minimum (4 in Sm, 1 in Fm). A bad clock or speed
 * returns I2C_BUS_ERR_RANGE and writes nothing. spin_limit 0 is read as 1.
 */
i2c_bus_status_t stm32_i2c_init(stm32_i2c_t *d, stm32_i2c_regs_t *regs, uint32_t pclk1_hz,
                                stm32_i2c_speed_t speed, uint32_t spin_limit);

/*
 * One transaction (the shapes are listed in i2c_bus.h); ctx is the
 * stm32_i2c_t. Returns I2C_BUS_OK or the first failure; a failure always
 * leaves the bus released (STOP) and, for anything but a NACK, the
 * peripheral reset and reconfigured.
 */
i2c_bus_status_t stm32_i2c_write_read(void *ctx, uint8_t addr7, const uint8_t *tx, uint16_t ntx,
                                      uint8_t *rx, uint16_t nrx);

/* The bus seam for the chip drivers. */
i2c_bus_t stm32_i2c_bus(stm32_i2c_t *d);

/*
 * Release and reset: request a STOP, wait (bounded) for BUSY to drop, pulse
 * SWRST and write the saved configuration back (RM0090 27.6.1, SWRST: "can be
 * used to reinitialize the peripheral after an error or a locked state").
 * A bus held low by a slave needs SCL toggled as GPIO, which this driver
 * cannot do (the board owns the pins).
 */
void stm32_i2c_recover(stm32_i2c_t *d);

#endif /* HT_STM32F4_I2C_H */
