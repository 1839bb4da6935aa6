/*
 * stm32f4_flash.c - the embedded flash driver (see stm32f4_flash.h).
 */
#include "stm32f4_flash.h"

#ifdef STM32_FLASH_ACCESS_HOOKS
static uint32_t rd(const volatile uint32_t *a)
{
    return stm32_flash_hook_read(a);
}
static void wr(volatile uint32_t *a, uint32_t v)
{
    stm32_flash_hook_write(a, v);
}
#else
static inline uint32_t rd(const volatile uint32_t *a)
{
    return *a;
}
static inline void wr(volatile uint32_t *a, uint32_t v)
{
    *a = v;
}
#endif

/* RM0090 table 5: sectors 0-3 of 16 KiB, 4 of 64 KiB, 5-11 of 128 KiB. */
#define KIB16  0x4000u
#define KIB64  0x10000u
#define KIB128 0x20000u

static void count(uint16_t *c)
{
    if (*c != UINT16_MAX) {
        (*c)++;
    }
}

uint32_t stm32_flash_sector_offset(uint32_t sector)
{
    if (sector < 4u) {
        return sector * KIB16;
    }
    if (sector == 4u) {
        return 4u * KIB16;
    }
    if (sector < STM32_FLASH_SECTORS) {
        return KIB128 * (sector - 4u); /* sector 5 at 128 KiB = 4 x 16 + 64 */
    }
    return 0u;
}

uint32_t stm32_flash_sector_bytes(uint32_t sector)
{
    if (sector < 4u) {
        return KIB16;
    }
    if (sector == 4u) {
        return KIB64;
    }
    if (sector < STM32_FLASH_SECTORS) {
        return KIB128;
    }
    return 0u;
}

stm32_flash_status_t stm32_flash_init(stm32_flash_t *f, stm32_flash_regs_t *regs,
                                      volatile uint32_t *mem, uint32_t erase_spin_limit,
                                      uint32_t program_spin_limit)
{
    if (f == NULL || regs == NULL || mem == NULL) {
        return STM32_FLASH_ERR_NULL;
    }
    f->ready = 0u;
    if (erase_spin_limit == 0u || program_spin_limit == 0u) {
        return STM32_FLASH_ERR_RANGE;
    }
    f->regs = regs;
    f->mem = mem;
    f->erase_spin_limit = erase_spin_limit;
    f->program_spin_limit = program_spin_limit;
    f->last_errors = 0u;
    f->timeouts = 0u;
    f->errors = 0u;
    f->ready = 1u;
    return STM32_FLASH_OK;
}

/* BSY = 0 within spin_limit SR reads. */
static int wait_idle(stm32_flash_t *f, uint32_t spin_limit)
{
    for (uint32_t spins = 0u; spins < spin_limit; ++spins) {
        if ((rd(&f->regs->SR) & FLASH_SR_BSY) == 0u) {
            return 1;
        }
    }
    count(&f->timeouts);
    return 0;
}

/* RM0090 section 3.6.1: KEY1 then KEY2 into KEYR clears CR.LOCK. A wrong
 * sequence earlier (or a stray KEYR write) keeps CR locked until reset, so
 * the result is read back rather than assumed. */
static stm32_flash_status_t unlock(stm32_flash_t *f)
{
    if ((rd(&f->regs->CR) & FLASH_CR_LOCK) == 0u) {
        return STM32_FLASH_OK;
    }
    wr(&f->regs->KEYR, FLASH_KEY1);
    wr(&f->regs->KEYR, FLASH_KEY2);
    if ((rd(&f->regs->CR) & FLASH_CR_LOCK) != 0u) {
        return STM32_FLASH_ERR_LOCKED;
    }
    return STM32_FLASH_OK;
}

/* Flags left over from an earlier operation (or a stray write into flash)
 * would make the next one fail with PGSERR: clear them first (write 1 to
 * clear, RM0090 section 3.9.4). */
static void clear_flags(stm32_flash_t *f)
{
    wr(&f->regs->SR, FLASH_SR_EOP | FLASH_SR_ERRORS);
}

/* After BSY fell: an error flag fails the operation; it is kept, counted
 * and cleared so the next operation starts clean. */
static stm32_flash_status_t check_flags(stm32_flash_t *f)
{
    const uint32_t errors = rd(&f->regs->SR) & FLASH_SR_ERRORS;
    if (errors == 0u) {
        return STM32_FLASH_OK;
    }
    f->last_errors = errors;
    count(&f->errors);
    wr(&f->regs->SR, errors);
    return STM32_FLASH_ERR_PROGRAM;
}

/* The data cache (8 lines of 128 bits, RM0090 section 3.5.2) may hold lines
 * of what was just erased or programmed; reset it so the read-back sees the
 * array. DCRST may only be written while DCEN = 0 (FLASH_ACR, section 3.9.1). */
static void flush_dcache(stm32_flash_t *f)
{
    const uint32_t acr = rd(&f->regs->ACR);
    if ((acr & FLASH_ACR_DCEN) == 0u) {
        return;
    }
    const uint32_t off = acr & ~FLASH_ACR_DCEN;
    wr(&f->regs->ACR, off);
    wr(&f->regs->ACR, off | FLASH_ACR_DCRST);
    wr(&f->regs->ACR, off);
    wr(&f->regs->ACR, acr);
}

/* Every erase and program starts alike: the controller idle (no CR write
 * while BSY: it would stall the bus), unlocked, and the old flags cleared. */
static stm32_flash_status_t begin_operation(stm32_flash_t *f, uint32_t spin_limit)
{
    if (!wait_idle(f, spin_limit)) {
        return STM32_FLASH_ERR_TIMEOUT;
    }
    const stm32_flash_status_t u = unlock(f);
    if (u == STM32_FLASH_OK) {
        clear_flags(f);
    }
    return u;
}

stm32_flash_status_t stm32_flash_erase_sector(stm32_flash_t *f, uint32_t sector)
{
    if (f == NULL || !f->ready) {
        return STM32_FLASH_ERR_NULL;
    }
    if (sector >= STM32_FLASH_SECTORS) {
        return STM32_FLASH_ERR_RANGE;
    }
    const stm32_flash_status_t u = begin_operation(f, f->erase_spin_limit);
    if (u != STM32_FLASH_OK) {
        return u;
    }
    /* RM0090 section 3.6.3, sector erase: SER and SNB, then STRT. */
    const uint32_t snb = (sector << FLASH_CR_SNB_SHIFT) & FLASH_CR_SNB_MASK;
    const uint32_t cr = FLASH_CR_PSIZE_X32 | FLASH_CR_SER | snb;
    wr(&f->regs->CR, cr);
    wr(&f->regs->CR, cr | FLASH_CR_STRT);
    if (!wait_idle(f, f->erase_spin_limit)) {
        return STM32_FLASH_ERR_TIMEOUT; /* no CR write while BSY: it would stall the bus */
    }
    stm32_flash_status_t s = check_flags(f);
    wr(&f->regs->CR, FLASH_CR_LOCK); /* also clears SER, SNB and PSIZE */
    if (s != STM32_FLASH_OK) {
        return s;
    }
    flush_dcache(f);
    const uint32_t first = stm32_flash_sector_offset(sector) / 4u;
    const uint32_t words = stm32_flash_sector_bytes(sector) / 4u;
    for (uint32_t i = 0u; i < words; ++i) {
        if (rd(&f->mem[first + i]) != 0xFFFFFFFFu) {
            s = STM32_FLASH_ERR_VERIFY;
            break;
        }
    }
    return s;
}

static uint32_t word_le(const uint8_t *p)
{
    const uint32_t b0 = p[0];
    const uint32_t b1 = p[1];
    const uint32_t b2 = p[2];
    const uint32_t b3 = p[3];
    return b0 | (b1 << 8) | (b2 << 16) | (b3 << 24);
}

static int span_ok(uint32_t offset, uint32_t n)
{
    return offset <= STM32_FLASH_MEM_BYTES && n <= STM32_FLASH_MEM_BYTES - offset;
}

stm32_flash_status_t stm32_flash_program(stm32_flash_t *f, uint32_t offset, const uint8_t *data,
                                         uint32_t n)
{
    if (f == NULL || data == NULL || !f->ready) {
        return STM32_FLASH_ERR_NULL;
    }
    if ((offset & 3u) != 0u || (n & 3u) != 0u || !span_ok(offset, n)) {
        return STM32_FLASH_ERR_RANGE;
    }
    if (n == 0u) {
        return STM32_FLASH_OK;
    }
    const stm32_flash_status_t u = begin_operation(f, f->program_spin_limit);
    if (u != STM32_FLASH_OK) {
        return u;
    }
    /* RM0090 section 3.6.4: PG set, then word writes (x32: word accesses),
     * each followed by BSY = 0. */
    wr(&f->regs->CR, FLASH_CR_PSIZE_X32 | FLASH_CR_PG);
    const uint32_t first = offset / 4u;
    const uint32_t words = n / 4u;
    stm32_flash_status_t s = STM32_FLASH_OK;
    for (uint32_t i = 0u; i < words; ++i) {
        wr(&f->mem[first + i], word_le(&data[(size_t)4u * i]));
        if (!wait_idle(f, f->program_spin_limit)) {
            return STM32_FLASH_ERR_TIMEOUT; /* no CR write while BSY: it would stall the bus */
        }
        s = check_flags(f);
        if (s != STM32_FLASH_OK) {
            break;
        }
    }
    wr(&f->regs->CR, FLASH_CR_LOCK); /* also clears PG and PSIZE */
    if (s != STM32_FLASH_OK) {
        return s;
    }
    flush_dcache(f);
    for (uint32_t i = 0u; i < words; ++i) {
        if (rd(&f->mem[first + i]) != word_le(&data[(size_t)4u * i])) {
            s = STM32_FLASH_ERR_VERIFY;
            break;
        }
    }
    return s;
}

stm32_flash_status_t stm32_flash_read(const stm32_flash_t *f, uint32_t offset, uint8_t *out,
                                      uint32_t n)
{
    if (f == NULL || out == NULL || !f->ready) {
        return STM32_FLASH_ERR_NULL;
    }
    if (!span_ok(offset, n)) {
        return STM32_FLASH_ERR_RANGE;
    }
    /* Word reads only (the memory window is a word array), bytes taken out
     * little-endian as the Cortex-M4 stores them. */
    for (uint32_t i = 0u; i < n; ++i) {
        const uint32_t at = offset + i;
        const uint32_t word = rd(&f->mem[at / 4u]);
        const uint32_t shift = 8u * (at & 3u);
        out[i] = (uint8_t)((word >> shift) & 0xFFu);
    }
    return STM32_FLASH_OK;
}

stm32_flash_status_t stm32_flash_lock(stm32_flash_t *f)
{
    if (f == NULL || !f->ready) {
        return STM32_FLASH_ERR_NULL;
    }
    if (!wait_idle(f, f->program_spin_limit)) {
        return STM32_FLASH_ERR_TIMEOUT;
    }
    wr(&f->regs->CR, FLASH_CR_LOCK);
    return STM32_FLASH_OK;
}
