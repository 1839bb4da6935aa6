/*
 * sim_bus.c - see sim_bus.h.
 */
#include "sim_bus.h"

#include <stddef.h>
#include <string.h>

static int sim_xfer(void *ctx, const uint8_t *tx, uint8_t *rx, uint16_t n)
{
    sim_bus_t *b = (sim_bus_t *)ctx;
    b->frames++;
    if (b->fail_frame != 0u && b->frames == b->fail_frame) {
        return -1;
    }
    if (b->chip == NULL || b->stuck_miso >= 0) {
        memset(rx, b->stuck_miso >= 0 ? b->stuck_miso : 0xFF, n);
        return 0;
    }
    return b->frame(b->chip, tx, rx, n, b->sck_hz, b->now_us);
}

static int sim_set_clock(void *ctx, uint32_t max_hz)
{
    sim_bus_t *b = (sim_bus_t *)ctx;
    if (b->fail_clock) {
        return -1;
    }
    b->sck_hz = max_hz;
    return 0;
}

static void sim_delay_us(void *ctx, uint32_t us)
{
    sim_bus_t *b = (sim_bus_t *)ctx;
    b->delays++;
    b->now_us += us;
}

void sim_bus_init(sim_bus_t *b, void *chip, sim_frame_fn frame)
{
    memset(b, 0, sizeof *b);
    b->chip = chip;
    b->frame = frame;
    b->stuck_miso = -1;
    b->bus.ctx = b;
    b->bus.xfer = sim_xfer;
    b->bus.set_clock = sim_set_clock;
    b->bus.delay_us = sim_delay_us;
}
