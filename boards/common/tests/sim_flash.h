/*
 * sim_flash.h - a simulated NOR flash for the parameter store's host tests,
 * with a power-cut injector.
 *
 * NOR semantics: erase sets every byte of a slot to 0xFF; program can only
 * clear bits. A program that would need a bit to go 0 -> 1 is reported:
 * the call fails, the byte keeps old & new (what real cells do) and
 * nor_violations counts it. Program offsets and lengths must be multiples
 * of align (the STM32 driver's x32 words); others fail and are counted.
 *
 * Power cuts (one armed at a time; after it fires every call fails until
 * sim_flash_power_on, like a board that lost its supply and rebooted):
 *   program cut: bytes are programmed one at a time in address order; the
 *     cut comes after `after` bytes (counted across calls since arming).
 *     Byte number `after` is then left torn: of the bits it should clear,
 *     only those in torn_mask are cleared (0x00: untouched, 0xFF: complete).
 *   erase cut, during the erase of a slot, one of three models:
 *     PREFIX: bytes 0 .. at-1 erased (0xFF), the rest keep old data;
 *     SUFFIX: the last `at` bytes erased, the rest keep old data;
 *     NOISE:  every byte becomes old | r, r from a xorshift32 seeded with
 *             at (nonzero): an interrupted erase only moves cells towards 1,
 *             by an amount that differs from cell to cell.
 * Real silicon may also leave marginal cells that read differently from
 * one read to the next; no model here covers that (see the doc).
 */
#ifndef HT_SIM_FLASH_H
#define HT_SIM_FLASH_H

#include <stdint.h>

#include "param_store.h"

typedef enum { SIM_ERASE_PREFIX = 0, SIM_ERASE_SUFFIX = 1, SIM_ERASE_NOISE = 2 } sim_erase_model_t;

typedef enum { SIM_CUT_NONE = 0, SIM_CUT_PROGRAM = 1, SIM_CUT_ERASE = 2 } sim_cut_t;

typedef struct {
    uint8_t *mem; /* slots x slot_size bytes, owned by the test */
    uint32_t slot_size;
    uint32_t slots;
    uint32_t align;
    sim_cut_t cut;
    uint32_t cut_at;
    uint8_t torn_mask;
    sim_erase_model_t erase_model;
    uint8_t powered;
    uint32_t programmed; /* bytes programmed since the last power-on */
    uint32_t erases, program_calls, read_calls;
    uint32_t nor_violations, align_violations, range_violations;
} sim_flash_t;

/* Bind to mem (slots x slot_size bytes, all set to 0xFF), powered, no cut. */
void sim_flash_init(sim_flash_t *s, uint8_t *mem, uint32_t slot_size, uint32_t slots,
                    uint32_t align);
/* Arm a cut after `after` more programmed bytes (torn byte as above). */
void sim_flash_cut_program(sim_flash_t *s, uint32_t after, uint8_t torn_mask);
/* Arm a cut during the next erase. */
void sim_flash_cut_erase(sim_flash_t *s, sim_erase_model_t model, uint32_t at);
/* Power back: any armed cut is dropped, the byte count restarts. */
void sim_flash_power_on(sim_flash_t *s);
/* The param_flash_t over this sim. */
void sim_flash_bind(sim_flash_t *s, param_flash_t *out);

int sim_flash_erase(void *ctx, uint32_t slot);
int sim_flash_program(void *ctx, uint32_t slot, uint32_t offset, const uint8_t *bytes, uint32_t n);
int sim_flash_read(void *ctx, uint32_t slot, uint32_t offset, uint8_t *bytes, uint32_t n);

/* Failure codes of the three calls. */
#define SIM_FLASH_ERR_POWER -1 /* no power (a cut fired) */
#define SIM_FLASH_ERR_RANGE -2 /* bad slot or span */
#define SIM_FLASH_ERR_ALIGN -3 /* program offset or length not a multiple of align */
#define SIM_FLASH_ERR_NOR   -4 /* program needed a 0 -> 1 */

#endif /* HT_SIM_FLASH_H */
