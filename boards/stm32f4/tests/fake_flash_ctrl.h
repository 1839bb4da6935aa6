/*
 * fake_flash_ctrl.h - a model of the STM32F405 flash controller for the
 * driver built with STM32_FLASH_ACCESS_HOOKS: it owns a FLASH register block
 * and the 1 MiB main memory, logs every write in order, and reacts as
 * RM0090 section 3.6 describes:
 *   KEYR: KEY1 then KEY2 clears CR.LOCK; anything else locks CR until
 *         "reset" (hard_locked) and counts a bus error.
 *   CR:   ignored while locked (LOCK can still be set); a write while BSY
 *         would stall the bus on silicon: counted (the driver must never).
 *         STRT with SER erases sector SNB (0xFF) unless write protected
 *         (WRPERR), then BSY reads busy_reads times.
 *   memory writes: need PG (else PGSERR), PSIZE x32 (else PGPERR); program
 *         by AND (bits only cleared); BSY for busy_reads reads.
 *   SR:   BSY as modelled; the error flags are write-1-to-clear.
 *   ACR:  DCRST written while DCEN = 1 is counted as a misuse.
 * Hooks for the test: inject_errors (raised by the next operation),
 * stuck_busy, busy_reads, write-protect mask.
 */
#ifndef HT_FAKE_FLASH_CTRL_H
#define HT_FAKE_FLASH_CTRL_H

#include <stdint.h>

#include "stm32f4_flash.h"

#define FAKE_LOG_MAX 64u

typedef enum {
    FAKE_ACR = 0,
    FAKE_KEYR = 1,
    FAKE_OPTKEYR = 2,
    FAKE_SR = 3,
    FAKE_CR = 4,
    FAKE_OPTCR = 5,
    FAKE_MEM = 6
} fake_target_t;

typedef struct {
    fake_target_t target;
    uint32_t word; /* FAKE_MEM: the word index from the memory base */
    uint32_t value;
} fake_write_t;

typedef struct {
    stm32_flash_regs_t regs;
    uint32_t *mem; /* STM32_FLASH_MEM_BYTES / 4 words */
    fake_write_t log[FAKE_LOG_MAX];
    uint32_t log_len; /* writes logged (the log keeps the first FAKE_LOG_MAX) */
    uint32_t writes;  /* all writes, logged or not */
    uint32_t sr_reads;
    uint32_t busy_reads; /* SR reads with BSY after each operation starts */
    uint32_t busy_left;
    uint8_t stuck_busy;  /* BSY never falls */
    uint8_t hard_locked; /* a wrong key sequence happened: CR locked until reset */
    uint8_t key_state;
    uint32_t wrp_sectors;   /* bit n: sector n write protected */
    uint32_t inject_errors; /* SR flags the next erase or program raises */
    uint32_t bus_errors, cr_writes_while_busy, dcrst_misuse, dcache_resets;
    uint32_t erased_sectors, programmed_words;
} fake_flash_ctrl_t;

extern fake_flash_ctrl_t fake;

/* Reset state: CR = LOCK (0x80000000), SR = 0, ACR = 0, memory filled with
 * fill (as words), log empty, BSY for busy_reads SR reads per operation. */
void fake_reset(uint32_t fill, uint32_t busy_reads);
/* The sector a memory word belongs to. */
uint32_t fake_sector_of_word(uint32_t word);

#endif /* HT_FAKE_FLASH_CTRL_H */
