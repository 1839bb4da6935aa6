/*
 * stm32f4_param_flash.h - the parameter store's flash (param_flash_t) on the
 * STM32F405: slot 0 is sector 1 (0x08004000), slot 1 is sector 2
 * (0x08008000), 16 KiB each (RM0090 table 5). The image must leave both
 * sectors free: see stm32f405_params.ld.
 */
#ifndef HT_STM32F4_PARAM_FLASH_H
#define HT_STM32F4_PARAM_FLASH_H

#include "param_store.h"
#include "stm32f4_flash.h"

/* Fill out so the store erases, programs and reads through flash (an
 * initialised driver, owned by the caller and outliving out). */
void stm32_param_flash_bind(stm32_flash_t *flash, param_flash_t *out);

/* The three calls (0 on success, else minus the stm32_flash_status_t, or
 * -STM32_FLASH_ERR_RANGE for a slot over 1 or a span outside the slot). */
int stm32_param_flash_erase(void *ctx, uint32_t slot);
int stm32_param_flash_program(void *ctx, uint32_t slot, uint32_t offset, const uint8_t *bytes,
                              uint32_t n);
int stm32_param_flash_read(void *ctx, uint32_t slot, uint32_t offset, uint8_t *bytes, uint32_t n);

#endif /* HT_STM32F4_PARAM_FLASH_H */
