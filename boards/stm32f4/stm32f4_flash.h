/*
 * stm32f4_flash.h - erase and program the STM32F405's embedded flash through
 * its controller (RM0090 section 3.6), against a register block and a
 * memory window passed by pointer, so host tests run it on fakes.
 *
 * Programming parallelism: x32 (PSIZE = 10b). RM0090 section 3.6.2 (table
 * "program/erase parallelism") allows x32 for a supply of 2.7 V to 3.6 V
 * without an external Vpp; the board runs at 3.3 V. x64 needs Vpp on the
 * BOOT0 pin, x16/x8 are for lower supplies and only slower. So programming
 * takes whole, 4-byte aligned words, and a sector erase runs at x32.
 *
 * Nothing waits without a bound: every BSY poll stops after a spin limit
 * given at init (status reads). A timeout leaves CR untouched (a CR write
 * while BSY = 1 would stall the bus until the operation ends) and reports
 * STM32_FLASH_ERR_TIMEOUT; the next call waits for BSY again first.
 *
 * While an erase or a program runs, a read of the flash (an instruction
 * fetch included) stalls the CPU until it ends (one bank on the F405), so
 * the spin count then stands for less time than it seems: the limits are
 * safety nets, not timers. A 16 KiB sector erase takes about 250 ms (up to
 * 500 ms) at x32, a word about 16 us (DS8626, memory characteristics, table
 * "Flash memory programming"; figures to re-check on the part's datasheet).
 */
#ifndef HT_STM32F4_FLASH_H
#define HT_STM32F4_FLASH_H

#include <stddef.h>
#include <stdint.h>

#include "stm32f4_flash_regs.h"

typedef enum {
    STM32_FLASH_OK = 0,
    STM32_FLASH_ERR_NULL = 1,    /* a NULL pointer, or not initialised */
    STM32_FLASH_ERR_RANGE = 2,   /* bad sector, unaligned or out-of-memory address: nothing done */
    STM32_FLASH_ERR_LOCKED = 3,  /* CR.LOCK still set after the keys (locked until reset) */
    STM32_FLASH_ERR_TIMEOUT = 4, /* BSY stayed set for the whole spin limit */
    STM32_FLASH_ERR_PROGRAM = 5, /* SR reported an error flag (kept in last_errors, then cleared) */
    STM32_FLASH_ERR_VERIFY = 6   /* the read-back differs from what was programmed or erased */
} stm32_flash_status_t;

/* Driver state, owned by the caller. */
typedef struct {
    stm32_flash_regs_t *regs;
    volatile uint32_t *mem;      /* the main memory window: sector 0's first word */
    uint32_t erase_spin_limit;   /* SR reads while an erase runs */
    uint32_t program_spin_limit; /* SR reads while a word is programmed */
    uint32_t last_errors;        /* the SR error flags of the last failed operation */
    uint16_t timeouts;           /* operations given up on BSY (saturates) */
    uint16_t errors;             /* operations that ended with an SR error flag (saturates) */
    uint8_t ready;               /* 1 after a successful init */
} stm32_flash_t;

/* The first byte of a sector as an offset from the main memory base and its
 * size (RM0090 table 5); both 0 for a sector number over 11. */
uint32_t stm32_flash_sector_offset(uint32_t sector);
uint32_t stm32_flash_sector_bytes(uint32_t sector);

/*
 * Bind the driver to the controller's registers and the memory window
 * (STM32_FLASH_MEM_BASE on the board). Writes no register. The spin limits
 * must be at least 1.
 */
stm32_flash_status_t stm32_flash_init(stm32_flash_t *f, stm32_flash_regs_t *regs,
                                      volatile uint32_t *mem, uint32_t erase_spin_limit,
                                      uint32_t program_spin_limit);

/*
 * Erase one sector (0..11): unlock, wait for BSY = 0, clear the SR flags,
 * CR = PSIZE x32 | SER | SNB, then CR |= STRT, wait for BSY = 0, check the
 * error flags, lock. Then flushes the data cache (if on) and checks that
 * every word of the sector reads 0xFFFFFFFF.
 */
stm32_flash_status_t stm32_flash_erase_sector(stm32_flash_t *f, uint32_t sector);

/*
 * Program n bytes at offset (from the main memory base), both multiples of
 * 4, one 32-bit word at a time (little-endian: data[0] is bits 7:0 of the
 * first word): unlock, wait for BSY = 0, clear the SR flags, CR = PSIZE x32
 * | PG, then per word: write it, wait for BSY = 0, check the error flags;
 * then lock, flush the data cache and compare the read-back. Programming
 * only clears bits (RM0090 section 3.6.4: a 1 needs an erase), so a target
 * not erased reads back wrong: STM32_FLASH_ERR_VERIFY.
 */
stm32_flash_status_t stm32_flash_program(stm32_flash_t *f, uint32_t offset, const uint8_t *data,
                                         uint32_t n);

/* Copy n bytes from offset (any alignment) into out. */
stm32_flash_status_t stm32_flash_read(const stm32_flash_t *f, uint32_t offset, uint8_t *out,
                                      uint32_t n);

/* Set CR.LOCK (after a timeout, once BSY has cleared). */
stm32_flash_status_t stm32_flash_lock(stm32_flash_t *f);

#ifdef STM32_FLASH_ACCESS_HOOKS
/* Host tests only: when the driver is built with STM32_FLASH_ACCESS_HOOKS,
 * every access to a register or to the memory window goes through these,
 * which the test defines to log the sequence and model the controller. */
uint32_t stm32_flash_hook_read(const volatile uint32_t *addr);
void stm32_flash_hook_write(volatile uint32_t *addr, uint32_t value);
#endif

#endif /* HT_STM32F4_FLASH_H */
