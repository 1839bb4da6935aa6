/*
 * sim_bus.h - the host tests' side of imu_spi_bus_t: each xfer is one
 * chip-select frame handed to a simulated chip, set_clock records the SCK the
 * chip then checks against its datasheet limit, delay_us advances a
 * simulated clock (nothing sleeps). A stuck MISO (0x00 or 0xFF, no chip) and
 * a failing transfer can be injected.
 */
#ifndef HT_SIM_BUS_H
#define HT_SIM_BUS_H

#include <stdint.h>

#include "imu_spi.h"

/* One frame at sck_hz at time now_us; returns 0. */
typedef int (*sim_frame_fn)(void *chip, const uint8_t *tx, uint8_t *rx, uint16_t n, uint32_t sck_hz,
                            uint64_t now_us);

typedef struct {
    imu_spi_bus_t bus; /* ctx = this sim_bus_t */
    void *chip;        /* NULL: nothing on the bus (MISO reads stuck_miso) */
    sim_frame_fn frame;
    int stuck_miso;      /* -1: the chip drives MISO; 0x00 or 0xFF: every rx byte */
    uint32_t sck_hz;     /* last set_clock (0: never set) */
    uint64_t now_us;     /* advanced by delay_us only */
    uint32_t frames;     /* xfer calls */
    uint32_t delays;     /* delay_us calls */
    uint32_t fail_frame; /* 1-based xfer number that fails (returns -1); 0: none */
    int fail_clock;      /* nonzero: set_clock fails */
} sim_bus_t;

void sim_bus_init(sim_bus_t *b, void *chip, sim_frame_fn frame);

#endif /* HT_SIM_BUS_H */
