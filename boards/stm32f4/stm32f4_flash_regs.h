/*
 * stm32f4_flash_regs.h - the STM32F405 embedded flash interface (FLASH
 * controller) register block, its bits and the sector map of the 1 MiB main
 * memory. Offsets, addresses, keys and bit positions are from RM0090
 * section 3 (Embedded flash memory interface): section 3.3, table 5 (flash
 * module organisation, STM32F40x/41x), section 3.6 (erase and program
 * operations: 3.6.1 unlocking the control register, 3.6.2 program/erase
 * parallelism, 3.6.3 erase, 3.6.4 programming) and section 3.9 (FLASH
 * registers: ACR, KEYR, OPTKEYR, SR, CR, OPTCR). Section numbers follow
 * RM0090 rev 19; older revisions number the same text 3.5.x/3.8.x. The FLASH block sits on
 * AHB1 at 0x40023C00 (RM0090 section 2.3, table 1, memory map).
 */
#ifndef HT_STM32F4_FLASH_REGS_H
#define HT_STM32F4_FLASH_REGS_H

#include <stddef.h>
#include <stdint.h>

typedef struct {
    volatile uint32_t ACR;     /* 0x00 access control: wait states, prefetch, caches */
    volatile uint32_t KEYR;    /* 0x04 key: KEY1 then KEY2 unlocks CR */
    volatile uint32_t OPTKEYR; /* 0x08 option key (not used: option bytes are never written) */
    volatile uint32_t SR;      /* 0x0C status: BSY, error flags (write 1 to clear) */
    volatile uint32_t CR;      /* 0x10 control: PG, SER, SNB, PSIZE, STRT, LOCK */
    volatile uint32_t OPTCR;   /* 0x14 option control (not used) */
} stm32_flash_regs_t;

_Static_assert((size_t)offsetof(stm32_flash_regs_t, KEYR) == 0x04u, "FLASH KEYR offset");
_Static_assert((size_t)offsetof(stm32_flash_regs_t, OPTKEYR) == 0x08u, "FLASH OPTKEYR offset");
_Static_assert((size_t)offsetof(stm32_flash_regs_t, SR) == 0x0Cu, "FLASH SR offset");
_Static_assert((size_t)offsetof(stm32_flash_regs_t, CR) == 0x10u, "FLASH CR offset");
_Static_assert((size_t)offsetof(stm32_flash_regs_t, OPTCR) == 0x14u, "FLASH OPTCR offset");

#define STM32_FLASH_REGS_BASE 0x40023C00u /* AHB1 */
#define STM32_FLASH_MEM_BASE  0x08000000u /* main memory, sector 0 */
#define STM32_FLASH_MEM_BYTES 0x00100000u /* 1 MiB: STM32F405xG */

/* FLASH_KEYR: writing KEY1 then KEY2 clears CR.LOCK; any other write or
 * order locks CR until the next reset (and raises a bus error). */
#define FLASH_KEY1 0x45670123u
#define FLASH_KEY2 0xCDEF89ABu

/* FLASH_ACR */
#define FLASH_ACR_DCEN  0x400u  /* bit 10: data cache enable */
#define FLASH_ACR_DCRST 0x1000u /* bit 12: data cache reset: writable only while DCEN = 0 */

/* FLASH_SR (reset value 0). EOP is set only while CR.EOPIE = 1, so the driver
 * never waits for it; BSY is what ends an operation. */
#define FLASH_SR_EOP    (1u << 0) /* end of operation (write 1 to clear) */
#define FLASH_SR_OPERR  (1u << 1) /* operation error (write 1 to clear) */
#define FLASH_SR_WRPERR (1u << 4) /* write protection error: the sector is protected */
#define FLASH_SR_PGAERR (1u << 5) /* programming alignment error: a write crossed a 128-bit row */
#define FLASH_SR_PGPERR (1u << 6) /* parallelism error: access size differs from PSIZE */
#define FLASH_SR_PGSERR (1u << 7) /* sequence error: a flash write without PG, or out of order */
#define FLASH_SR_BSY    0x10000u  /* bit 16: an erase or program is under way */
#define FLASH_SR_ERRORS                                                                            \
    (FLASH_SR_OPERR | FLASH_SR_WRPERR | FLASH_SR_PGAERR | FLASH_SR_PGPERR | FLASH_SR_PGSERR)

/* FLASH_CR (reset value 0x80000000: locked). CR must not be written while
 * SR.BSY = 1: the write would stall the AHB bus until the operation ends. */
#define FLASH_CR_PG          (1u << 0) /* programming */
#define FLASH_CR_SER         (1u << 1) /* sector erase */
#define FLASH_CR_MER         (1u << 2) /* mass erase (never used) */
#define FLASH_CR_SNB_SHIFT   3u        /* SNB[3:0] at bits 6:3: the sector to erase */
#define FLASH_CR_SNB_MASK    0x78u
#define FLASH_CR_PSIZE_SHIFT 8u /* PSIZE[1:0] at bits 9:8 */
#define FLASH_CR_PSIZE_X8    0x000u
#define FLASH_CR_PSIZE_X16   0x100u
#define FLASH_CR_PSIZE_X32   0x200u
#define FLASH_CR_PSIZE_X64   0x300u
#define FLASH_CR_PSIZE_MASK  0x300u
#define FLASH_CR_STRT        0x10000u    /* bit 16: start the erase selected by SER/MER */
#define FLASH_CR_EOPIE       0x1000000u  /* bit 24 */
#define FLASH_CR_ERRIE       0x2000000u  /* bit 25 */
#define FLASH_CR_LOCK        0x80000000u /* bit 31: write 1 to lock; cleared only by the keys */

/* The main memory's sectors (RM0090 table 5, STM32F40x/41x, one bank):
 * 0-3: 16 KiB each from 0x08000000, 4: 64 KiB at 0x08010000,
 * 5-11: 128 KiB each from 0x08020000. */
#define STM32_FLASH_SECTORS 12u

/* The parameter store's two slots: sectors 1 and 2 (16 KiB each, the
 * smallest sectors: a short erase, and the image loses only 32 KiB). The
 * vector table must stay in sector 0 (the boot address), so an image that
 * keeps these free continues from sector 3: see stm32f405_params.ld. */
#define STM32_PARAM_SECTOR_A     1u
#define STM32_PARAM_SECTOR_B     2u
#define STM32_PARAM_SECTOR_BYTES 0x4000u
#define STM32_PARAM_A_ADDR       0x08004000u
#define STM32_PARAM_B_ADDR       0x08008000u

#endif /* HT_STM32F4_FLASH_REGS_H */
