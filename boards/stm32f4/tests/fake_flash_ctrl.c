/*
 * fake_flash_ctrl.c - the flash controller model (see fake_flash_ctrl.h).
 */
#include "fake_flash_ctrl.h"

#include <stddef.h>
#include <string.h>

fake_flash_ctrl_t fake;
static uint32_t memory[STM32_FLASH_MEM_BYTES / 4u];

void fake_reset(uint32_t fill, uint32_t busy_reads)
{
    memset(&fake, 0, sizeof fake);
    fake.mem = memory;
    fake.regs.CR = FLASH_CR_LOCK;
    fake.busy_reads = busy_reads;
    for (uint32_t i = 0u; i < STM32_FLASH_MEM_BYTES / 4u; ++i) {
        memory[i] = fill;
    }
}

uint32_t fake_sector_of_word(uint32_t word)
{
    const uint32_t byte = word * 4u;
    for (uint32_t s = 0u; s < STM32_FLASH_SECTORS; ++s) {
        const uint32_t first = stm32_flash_sector_offset(s);
        if (byte >= first && byte - first < stm32_flash_sector_bytes(s)) {
            return s;
        }
    }
    return STM32_FLASH_SECTORS;
}

static void log_write(fake_target_t t, uint32_t word, uint32_t v)
{
    if (fake.log_len < FAKE_LOG_MAX) {
        fake.log[fake.log_len].target = t;
        fake.log[fake.log_len].word = word;
        fake.log[fake.log_len].value = v;
        fake.log_len++;
    }
    fake.writes++;
}

static int busy(void)
{
    return fake.stuck_busy || fake.busy_left > 0u;
}

static void start_op(void)
{
    fake.busy_left = fake.busy_reads;
}

static uint32_t reg_index(const volatile uint32_t *a)
{
    const uintptr_t base = (uintptr_t)&fake.regs;
    const uintptr_t at = (uintptr_t)a;
    if (at >= base && at < base + sizeof fake.regs) {
        return (uint32_t)((at - base) / 4u);
    }
    return 0xFFFFFFFFu;
}

static uint32_t mem_word(const volatile uint32_t *a)
{
    const uintptr_t base = (uintptr_t)memory;
    const uintptr_t at = (uintptr_t)a;
    if (at >= base && at < base + sizeof memory) {
        return (uint32_t)((at - base) / 4u);
    }
    return 0xFFFFFFFFu;
}

uint32_t stm32_flash_hook_read(const volatile uint32_t *addr)
{
    const uint32_t r = reg_index(addr);
    if (r == FAKE_SR) {
        fake.sr_reads++;
        if (fake.stuck_busy) {
            return fake.regs.SR | FLASH_SR_BSY;
        }
        if (fake.busy_left > 0u) {
            fake.busy_left--;
            return fake.regs.SR | FLASH_SR_BSY;
        }
        return fake.regs.SR;
    }
    if (r != 0xFFFFFFFFu) {
        return *addr;
    }
    const uint32_t w = mem_word(addr);
    return (w != 0xFFFFFFFFu) ? memory[w] : 0xDEADBEEFu;
}

static void write_cr(uint32_t v)
{
    if (busy()) {
        fake.cr_writes_while_busy++;
    }
    if ((fake.regs.CR & FLASH_CR_LOCK) != 0u) {
        return; /* locked: only the keys open it */
    }
    if ((v & FLASH_CR_LOCK) != 0u) {
        fake.regs.CR = FLASH_CR_LOCK;
        fake.key_state = 0u;
        return;
    }
    fake.regs.CR = v & ~FLASH_CR_STRT;
    if ((v & FLASH_CR_STRT) != 0u && (v & FLASH_CR_SER) != 0u) {
        const uint32_t sector = (v & FLASH_CR_SNB_MASK) >> FLASH_CR_SNB_SHIFT;
        start_op();
        if (fake.inject_errors != 0u) {
            fake.regs.SR |= fake.inject_errors;
            fake.inject_errors = 0u;
            return;
        }
        if ((fake.wrp_sectors >> sector) & 1u) {
            fake.regs.SR |= FLASH_SR_WRPERR;
            return;
        }
        const uint32_t first = stm32_flash_sector_offset(sector) / 4u;
        const uint32_t words = stm32_flash_sector_bytes(sector) / 4u;
        for (uint32_t i = 0u; i < words; ++i) {
            memory[first + i] = 0xFFFFFFFFu;
        }
        fake.erased_sectors |= 1u << sector;
    }
}

static void write_mem(uint32_t w, uint32_t v)
{
    const uint32_t cr = fake.regs.CR;
    start_op();
    if ((cr & FLASH_CR_LOCK) != 0u || (cr & FLASH_CR_PG) == 0u) {
        fake.regs.SR |= FLASH_SR_PGSERR;
        return;
    }
    if ((cr & FLASH_CR_PSIZE_MASK) != FLASH_CR_PSIZE_X32) {
        fake.regs.SR |= FLASH_SR_PGPERR;
        return;
    }
    if (fake.inject_errors != 0u) {
        fake.regs.SR |= fake.inject_errors;
        fake.inject_errors = 0u;
        return;
    }
    if ((fake.wrp_sectors >> fake_sector_of_word(w)) & 1u) {
        fake.regs.SR |= FLASH_SR_WRPERR;
        return;
    }
    memory[w] &= v;
    fake.programmed_words++;
}

void stm32_flash_hook_write(volatile uint32_t *addr, uint32_t value)
{
    const uint32_t r = reg_index(addr);
    if (r == 0xFFFFFFFFu) {
        const uint32_t w = mem_word(addr);
        log_write(FAKE_MEM, w, value);
        if (w != 0xFFFFFFFFu) {
            write_mem(w, value);
        }
        return;
    }
    log_write((fake_target_t)r, 0u, value);
    switch (r) {
    case FAKE_ACR:
        if ((value & FLASH_ACR_DCRST) != 0u) {
            if ((fake.regs.ACR & FLASH_ACR_DCEN) != 0u || (value & FLASH_ACR_DCEN) != 0u) {
                fake.dcrst_misuse++;
            } else {
                fake.dcache_resets++;
            }
        }
        fake.regs.ACR = value;
        break;
    case FAKE_KEYR:
        if (fake.hard_locked) {
            fake.bus_errors++;
        } else if (fake.key_state == 0u && value == FLASH_KEY1) {
            fake.key_state = 1u;
        } else if (fake.key_state == 1u && value == FLASH_KEY2) {
            fake.key_state = 0u;
            fake.regs.CR &= ~FLASH_CR_LOCK;
        } else {
            fake.hard_locked = 1u;
            fake.bus_errors++;
        }
        break;
    case FAKE_SR:
        fake.regs.SR &= ~(value & (FLASH_SR_EOP | FLASH_SR_ERRORS));
        break;
    case FAKE_CR:
        write_cr(value);
        break;
    default:
        *addr = value;
        break;
    }
}
