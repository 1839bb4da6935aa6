/*
 * stm32f4_param_flash.c - slots to sectors for the parameter store (see
 * stm32f4_param_flash.h).
 */
#include "stm32f4_param_flash.h"

_Static_assert(STM32_PARAM_A_ADDR == STM32_FLASH_MEM_BASE + 0x4000u, "sector 1 address");
_Static_assert(STM32_PARAM_B_ADDR == STM32_FLASH_MEM_BASE + 0x8000u, "sector 2 address");

static int result(stm32_flash_status_t s)
{
    const int code = (int)s;
    return -code;
}

/* The slot's sector, or STM32_FLASH_SECTORS for a bad slot. */
static uint32_t sector_of(uint32_t slot)
{
    if (slot == 0u) {
        return STM32_PARAM_SECTOR_A;
    }
    if (slot == 1u) {
        return STM32_PARAM_SECTOR_B;
    }
    return STM32_FLASH_SECTORS;
}

static int span_ok(uint32_t slot, uint32_t offset, uint32_t n)
{
    return sector_of(slot) < STM32_FLASH_SECTORS && offset <= STM32_PARAM_SECTOR_BYTES &&
           n <= STM32_PARAM_SECTOR_BYTES - offset;
}

int stm32_param_flash_erase(void *ctx, uint32_t slot)
{
    if (sector_of(slot) >= STM32_FLASH_SECTORS) {
        return result(STM32_FLASH_ERR_RANGE);
    }
    return result(stm32_flash_erase_sector(ctx, sector_of(slot)));
}

int stm32_param_flash_program(void *ctx, uint32_t slot, uint32_t offset, const uint8_t *bytes,
                              uint32_t n)
{
    if (!span_ok(slot, offset, n)) {
        return result(STM32_FLASH_ERR_RANGE);
    }
    const uint32_t at = stm32_flash_sector_offset(sector_of(slot)) + offset;
    return result(stm32_flash_program(ctx, at, bytes, n));
}

int stm32_param_flash_read(void *ctx, uint32_t slot, uint32_t offset, uint8_t *bytes, uint32_t n)
{
    if (!span_ok(slot, offset, n)) {
        return result(STM32_FLASH_ERR_RANGE);
    }
    const uint32_t at = stm32_flash_sector_offset(sector_of(slot)) + offset;
    return result(stm32_flash_read(ctx, at, bytes, n));
}

void stm32_param_flash_bind(stm32_flash_t *flash, param_flash_t *out)
{
    if (out == NULL) {
        return;
    }
    out->ctx = flash;
    out->slot_size = STM32_PARAM_SECTOR_BYTES;
    out->erase = stm32_param_flash_erase;
    out->program = stm32_param_flash_program;
    out->read = stm32_param_flash_read;
}
