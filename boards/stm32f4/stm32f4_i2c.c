/*
 * stm32f4_i2c.c - the polled I2C master (see stm32f4_i2c.h). The event
 * sequences follow RM0090 section 27.3.3 (master transmitter, EV5..EV8_2;
 * master receiver, EV6/EV7 and the one-, two- and N-byte closing methods).
 */
#include "stm32f4_i2c.h"

static void count(uint16_t *c)
{
    if (*c != UINT16_MAX) {
        (*c)++;
    }
}

/* Write the saved timing and enable the block: CR1 first cleared (PE = 0 is
 * required while CCR and TRISE change, RM0090 27.6.8). */
static void apply_config(stm32_i2c_t *d)
{
    stm32_i2c_regs_t *r = d->regs;
    r->CR1 = 0u;
    r->CR2 = d->cr2; /* interrupts and DMA off: the driver polls */
    r->CCR = d->ccr;
    r->TRISE = d->trise;
    r->OAR1 = I2C_OAR1_BIT14;
    r->CR1 = I2C_CR1_PE;
}

i2c_bus_status_t stm32_i2c_init(stm32_i2c_t *d, stm32_i2c_regs_t *regs, uint32_t pclk1_hz,
                                stm32_i2c_speed_t speed, uint32_t spin_limit)
{
    if (d == NULL || regs == NULL) {
        return I2C_BUS_ERR_NULL;
    }
    d->ready = 0u;
    if ((pclk1_hz % 1000000u) != 0u) {
        return I2C_BUS_ERR_RANGE; /* FREQ is whole MHz: the timing would be off */
    }
    const uint32_t freq_mhz = pclk1_hz / 1000000u;
    uint32_t ccr;
    uint32_t trise;
    if (speed == STM32_I2C_STANDARD_100KHZ) {
        if (freq_mhz < I2C_CR2_FREQ_MIN_SM || freq_mhz > I2C_CR2_FREQ_MAX) {
            return I2C_BUS_ERR_RANGE;
        }
        const uint32_t div = 2u * STM32_I2C_SM_HZ; /* Thigh + Tlow = 2 CCR */
        ccr = (pclk1_hz + div - 1u) / div;         /* >= 10 from 2 MHz: above the minimum of 4 */
        trise = (freq_mhz * I2C_TRISE_SM_NS) / 1000u + 1u;
    } else if (speed == STM32_I2C_FAST_400KHZ) {
        if (freq_mhz < I2C_CR2_FREQ_MIN_FM || freq_mhz > I2C_CR2_FREQ_MAX) {
            return I2C_BUS_ERR_RANGE;
        }
        const uint32_t div = 3u * STM32_I2C_FM_HZ; /* Thigh + Tlow = 3 CCR (DUTY = 0) */
        ccr = (pclk1_hz + div - 1u) / div;         /* >= 4 from 4 MHz: above the minimum of 1 */
        trise = (freq_mhz * I2C_TRISE_FM_NS) / 1000u + 1u;
        ccr |= I2C_CCR_FS;
    } else {
        return I2C_BUS_ERR_RANGE;
    }
    d->regs = regs;
    d->spin_limit = (spin_limit == 0u) ? 1u : spin_limit;
    d->cr2 = freq_mhz & I2C_CR2_FREQ_MASK;
    d->ccr = ccr;
    d->trise = trise & I2C_TRISE_MASK;
    d->nacks = 0u;
    d->data_nacks = 0u;
    d->timeouts = 0u;
    d->bus_errors = 0u;
    d->arb_lost = 0u;
    d->busy = 0u;
    d->recoveries = 0u;
    /* A reset pulse first: the block may hold state from a previous run
     * (a boot loader, a watchdog reset in the middle of a transfer). */
    regs->CR1 = I2C_CR1_SWRST;
    apply_config(d);
    d->ready = 1u;
    return I2C_BUS_OK;
}

/* Wait for BUSY to drop: 1 when it did within the spin limit. */
static int wait_not_busy(const stm32_i2c_t *d)
{
    for (uint32_t spins = 0u; spins < d->spin_limit; ++spins) {
        if ((d->regs->SR2 & I2C_SR2_BUSY) == 0u) {
            return 1;
        }
    }
    return 0;
}

void stm32_i2c_recover(stm32_i2c_t *d)
{
    if (d == NULL || !d->ready) {
        return;
    }
    count(&d->recoveries);
    d->regs->CR1 |= I2C_CR1_STOP;
    (void)wait_not_busy(d); /* a slave holding SDA low keeps BUSY set: reset anyway */
    d->regs->CR1 = I2C_CR1_SWRST;
    apply_config(d); /* CR1 = 0 ends the reset, then the timing and PE */
}

/*
 * Wait for one SR1 event. Error flags are checked before the event, except
 * that a set ADDR proves the address was acknowledged whatever AF says (AF
 * then belongs to a later byte). nack_status says what AF means here.
 */
static i2c_bus_status_t wait_event(const stm32_i2c_t *d, uint32_t flag,
                                   i2c_bus_status_t nack_status)
{
    for (uint32_t spins = 0u; spins < d->spin_limit; ++spins) {
        const uint32_t sr1 = d->regs->SR1;
        if (flag == I2C_SR1_ADDR && (sr1 & I2C_SR1_ADDR) != 0u) {
            return I2C_BUS_OK;
        }
        if ((sr1 & I2C_SR1_BERR) != 0u) {
            return I2C_BUS_ERR_BUS;
        }
        if ((sr1 & I2C_SR1_ARLO) != 0u) {
            return I2C_BUS_ERR_ARLO;
        }
        if ((sr1 & I2C_SR1_AF) != 0u && nack_status != I2C_BUS_OK) {
            return nack_status;
        }
        if ((sr1 & flag) != 0u) {
            return I2C_BUS_OK;
        }
    }
    return I2C_BUS_ERR_TIMEOUT;
}

/* START (or repeated START), then the address byte; returns with ADDR seen
 * but not yet cleared (the receiver must set ACK/POS/STOP before clearing). */
static i2c_bus_status_t start_address(const stm32_i2c_t *d, uint8_t addr_byte)
{
    d->regs->CR1 |= I2C_CR1_START;
    i2c_bus_status_t st = wait_event(d, I2C_SR1_SB, I2C_BUS_OK); /* EV5 */
    if (st != I2C_BUS_OK) {
        return st;
    }
    d->regs->DR = addr_byte;                              /* SR1 read above + DR write clears SB */
    return wait_event(d, I2C_SR1_ADDR, I2C_BUS_ERR_NACK); /* EV6 */
}

/* ADDR is cleared by reading SR1 then SR2 (RM0090 27.6.6). */
static void clear_addr(const stm32_i2c_t *d)
{
    (void)d->regs->SR1;
    (void)d->regs->SR2;
}

static uint8_t read_dr(const stm32_i2c_t *d)
{
    const uint32_t dr = d->regs->DR;
    return (uint8_t)(dr & 0xFFu);
}

static i2c_bus_status_t transmit(const stm32_i2c_t *d, const uint8_t *tx, uint16_t ntx)
{
    if (ntx == 0u) {
        return I2C_BUS_OK; /* an address probe: no byte, so no BTF will come */
    }
    for (uint16_t i = 0u; i < ntx; ++i) {
        const i2c_bus_status_t st = wait_event(d, I2C_SR1_TXE, I2C_BUS_ERR_DATA_NACK); /* EV8 */
        if (st != I2C_BUS_OK) {
            return st;
        }
        d->regs->DR = tx[i];
    }
    /* EV8_2: TXE and BTF, the last byte is out and acknowledged */
    return wait_event(d, I2C_SR1_BTF, I2C_BUS_ERR_DATA_NACK);
}

/* The receiver after ADDR was seen (RM0090 27.3.3, "Closing the
 * communication"): the NACK and the STOP must be programmed while the bus is
 * stretched on the byte before the last, which is why 1, 2 and 3+ bytes end
 * differently. */
static i2c_bus_status_t receive(const stm32_i2c_t *d, uint8_t *rx, uint16_t nrx)
{
    stm32_i2c_regs_t *r = d->regs;
    i2c_bus_status_t st;
    if (nrx == 1u) {
        r->CR1 &= ~I2C_CR1_ACK; /* NACK the only byte: before ADDR is cleared */
        clear_addr(d);
        r->CR1 |= I2C_CR1_STOP;
        st = wait_event(d, I2C_SR1_RXNE, I2C_BUS_OK);
        if (st == I2C_BUS_OK) {
            rx[0] = read_dr(d);
        }
        return st;
    }
    if (nrx == 2u) {
        /* POS: the NACK applies to the second byte, not the one in flight */
        r->CR1 = (r->CR1 & ~I2C_CR1_ACK) | I2C_CR1_POS;
        clear_addr(d);
        st = wait_event(d, I2C_SR1_BTF, I2C_BUS_OK); /* byte 1 in DR, byte 2 in shift */
        if (st == I2C_BUS_OK) {
            r->CR1 |= I2C_CR1_STOP;
            rx[0] = read_dr(d);
            rx[1] = read_dr(d);
        }
        r->CR1 &= ~I2C_CR1_POS;
        return st;
    }
    clear_addr(d); /* ACK was set before the START */
    uint16_t i = 0u;
    for (; (uint16_t)(nrx - i) > 3u; ++i) {
        st = wait_event(d, I2C_SR1_RXNE, I2C_BUS_OK); /* EV7 */
        if (st != I2C_BUS_OK) {
            return st;
        }
        rx[i] = read_dr(d);
    }
    st = wait_event(d, I2C_SR1_BTF, I2C_BUS_OK); /* N-2 in DR, N-1 in shift */
    if (st != I2C_BUS_OK) {
        return st;
    }
    r->CR1 &= ~I2C_CR1_ACK; /* byte N will be NACKed */
    rx[i] = read_dr(d);
    st = wait_event(d, I2C_SR1_BTF, I2C_BUS_OK); /* N-1 in DR, N in shift */
    if (st != I2C_BUS_OK) {
        return st;
    }
    r->CR1 |= I2C_CR1_STOP;
    rx[i + 1u] = read_dr(d);
    st = wait_event(d, I2C_SR1_RXNE, I2C_BUS_OK);
    if (st == I2C_BUS_OK) {
        rx[i + 2u] = read_dr(d);
    }
    return st;
}

static i2c_bus_status_t transaction(const stm32_i2c_t *d, uint8_t addr7, const uint8_t *tx,
                                    uint16_t ntx, uint8_t *rx, uint16_t nrx)
{
    stm32_i2c_regs_t *r = d->regs;
    const uint8_t addr_w = (uint8_t)(addr7 << 1);
    const uint8_t addr_r = (uint8_t)(addr_w | 1u);
    i2c_bus_status_t st;
    if (ntx > 0u || nrx == 0u) {
        r->CR1 &= ~(I2C_CR1_ACK | I2C_CR1_POS);
        st = start_address(d, addr_w);
        if (st != I2C_BUS_OK) {
            return st;
        }
        clear_addr(d);
        st = transmit(d, tx, ntx);
        if (st != I2C_BUS_OK) {
            return st;
        }
        if (nrx == 0u) {
            r->CR1 |= I2C_CR1_STOP;
            return I2C_BUS_OK;
        }
    }
    /* ACK from the first byte on for 3+ bytes; the 1- and 2-byte closings
     * set their own ACK/POS after ADDR. */
    if (nrx > 2u) {
        r->CR1 |= I2C_CR1_ACK;
    } else {
        r->CR1 &= ~I2C_CR1_ACK;
    }
    st = start_address(d, addr_r); /* a repeated START after a write phase */
    if (st != I2C_BUS_OK) {
        return st;
    }
    return receive(d, rx, nrx);
}

i2c_bus_status_t stm32_i2c_write_read(void *ctx, uint8_t addr7, const uint8_t *tx, uint16_t ntx,
                                      uint8_t *rx, uint16_t nrx)
{
    // cppcheck-suppress misra-c2012-11.5 ; D-11.5-CTX: the seam's context is the stm32_i2c_t
    stm32_i2c_t *d = (stm32_i2c_t *)ctx;
    if (d == NULL) {
        return I2C_BUS_ERR_NULL;
    }
    if (!d->ready) {
        return I2C_BUS_ERR_NOT_READY;
    }
    if ((ntx > 0u && tx == NULL) || (nrx > 0u && rx == NULL)) {
        return I2C_BUS_ERR_NULL;
    }
    if (addr7 > 0x7Fu) {
        return I2C_BUS_ERR_RANGE;
    }
    if (!wait_not_busy(d)) {
        count(&d->busy);
        stm32_i2c_recover(d);
        return I2C_BUS_ERR_BUSY;
    }
    const i2c_bus_status_t st = transaction(d, addr7, tx, ntx, rx, nrx);
    switch (st) {
    case I2C_BUS_OK:
        break;
    case I2C_BUS_ERR_NACK:
    case I2C_BUS_ERR_DATA_NACK:
        /* A NACK leaves the master owning the bus: release it, clear AF. */
        if (st == I2C_BUS_ERR_NACK) {
            count(&d->nacks);
        } else {
            count(&d->data_nacks);
        }
        d->regs->CR1 |= I2C_CR1_STOP;
        d->regs->SR1 = I2C_SR1_RC_W0 & ~(uint32_t)I2C_SR1_AF;
        d->regs->CR1 &= ~(I2C_CR1_ACK | I2C_CR1_POS);
        break;
    case I2C_BUS_ERR_BUS:
        count(&d->bus_errors);
        stm32_i2c_recover(d);
        break;
    case I2C_BUS_ERR_ARLO:
        count(&d->arb_lost);
        stm32_i2c_recover(d);
        break;
    default: /* I2C_BUS_ERR_TIMEOUT */
        count(&d->timeouts);
        stm32_i2c_recover(d);
        break;
    }
    return st;
}

i2c_bus_t stm32_i2c_bus(stm32_i2c_t *d)
{
    i2c_bus_t bus;
    bus.ctx = d;
    bus.write_read = stm32_i2c_write_read;
    return bus;
}
