/*
 * i2c_bus.h - the seam between an I2C chip driver and the bus it sits on.
 *
 * A chip driver (baro_bmp280.c, airspeed_ms4525.c) sees only this struct: one
 * blocking transaction "write ntx bytes, then (repeated START) read nrx bytes"
 * to a 7-bit address. The STM32F4 board passes its register-level master
 * (boards/stm32f4/stm32f4_i2c.c); the host tests pass a simulated chip
 * (boards/devices/tests/sim_*.c). The chip drivers therefore never touch a
 * register and run unchanged on both.
 *
 * Transaction shapes (the I2C-bus specification UM10204, section 3.1):
 *   ntx > 0, nrx = 0: S addr+W tx... P                      (register write)
 *   ntx > 0, nrx > 0: S addr+W tx... Sr addr+R rx... P       (register read)
 *   ntx = 0, nrx > 0: S addr+R rx... P                       (a plain read)
 *   ntx = 0, nrx = 0: S addr+W P                             (an address probe)
 */
#ifndef HT_I2C_BUS_H
#define HT_I2C_BUS_H

#include <stddef.h>
#include <stdint.h>

typedef enum {
    I2C_BUS_OK = 0,
    I2C_BUS_ERR_NULL = 1,      /* a NULL pointer (or NULL buffer with a length) */
    I2C_BUS_ERR_RANGE = 2,     /* an address above 0x7F or a bad configuration */
    I2C_BUS_ERR_NACK = 3,      /* the address was not acknowledged: the chip is absent */
    I2C_BUS_ERR_DATA_NACK = 4, /* a written byte was not acknowledged */
    I2C_BUS_ERR_TIMEOUT = 5,   /* an event did not come within the spin limit */
    I2C_BUS_ERR_BUS = 6,       /* a misplaced START/STOP was seen (bus error) */
    I2C_BUS_ERR_ARLO = 7,      /* arbitration lost to another master or a glitch */
    I2C_BUS_ERR_BUSY = 8,      /* the bus stayed busy before our START */
    I2C_BUS_ERR_NOT_READY = 9  /* the master was never initialised */
} i2c_bus_status_t;

/* One blocking transaction; see the shapes above. rx may be NULL when
 * nrx == 0, tx when ntx == 0. */
typedef i2c_bus_status_t (*i2c_write_read_fn)(void *ctx, uint8_t addr7, const uint8_t *tx,
                                              uint16_t ntx, uint8_t *rx, uint16_t nrx);

typedef struct {
    void *ctx; /* the master's (or the simulated chip's) state */
    i2c_write_read_fn write_read;
} i2c_bus_t;

/* The bus call with the NULL checks every chip driver needs. */
static inline i2c_bus_status_t i2c_bus_write_read(const i2c_bus_t *bus, uint8_t addr7,
                                                  const uint8_t *tx, uint16_t ntx, uint8_t *rx,
                                                  uint16_t nrx)
{
    if (bus == NULL || bus->write_read == NULL) {
        return I2C_BUS_ERR_NULL;
    }
    return bus->write_read(bus->ctx, addr7, tx, ntx, rx, nrx);
}

#endif /* HT_I2C_BUS_H */
