/*
 * matek_params_boot.c - the stored parameters, loaded before board_init
 * (firmware/fw_board_config.h): the store's two slots are flash sectors 1
 * and 2 (stm32f4_param_flash.h; the image is linked with
 * stm32f405_params.ld so nothing else lives there). Reading needs no
 * register access (the flash is memory mapped), so this runs before the
 * clocks are raised; board_init prints the result on the console.
 */
#include "fw_board_config.h"
#include "matek_params_boot.h"
#include "stm32f4_flash.h"
#include "stm32f4_param_flash.h"

/* Generous: a sector erase is 250-500 ms (and a save is not done at boot). */
#define ERASE_SPINS   50000000u
#define PROGRAM_SPINS 100000u

static stm32_flash_t flash;
static param_flash_t pflash;
static uint8_t flash_ok;
static matek_params_report_t report = {
    (uint8_t)MATEK_PARAMS_CORRUPT, 0u, 0u, 0u, 0u, 0, -1, "", ""};
static fw_link_params_t stored_link; /* the link's rows of the stored set */
static uint8_t link_loaded;

void fw_board_config(fw_config_t *cfg)
{
    // cppcheck-suppress misra-c2012-11.4 ; D-11.4-REG: flash interface register block address
    stm32_flash_regs_t *const regs = (stm32_flash_regs_t *)STM32_FLASH_REGS_BASE;
    // cppcheck-suppress misra-c2012-11.4 ; D-11.4-REG: the main flash memory window
    volatile uint32_t *const mem = (volatile uint32_t *)STM32_FLASH_MEM_BASE;
    if (stm32_flash_init(&flash, regs, mem, ERASE_SPINS, PROGRAM_SPINS) != STM32_FLASH_OK) {
        return;
    }
    stm32_param_flash_bind(&flash, &pflash);
    flash_ok = 1u;
    ht_link_params_default(&stored_link);
    matek_params_load(&pflash, cfg, &stored_link, &report);
    link_loaded = ((report.result == (uint8_t)MATEK_PARAMS_LOADED) ||
                   (report.result == (uint8_t)MATEK_PARAMS_LOADED_OTHER_CORRUPT))
                      ? 1u
                      : 0u;
}

const fw_link_params_t *matek_params_link(void)
{
    return (link_loaded != 0u) ? &stored_link : NULL;
}

int matek_params_save(void *ctx, const fw_config_t *cfg, const fw_link_params_t *link)
{
    static uint8_t blob[MATEK_PARAM_BLOB_MAX_BYTES];
    (void)ctx;
    if ((flash_ok == 0u) || (matek_param_blob_encode(cfg, link, blob) != 0)) {
        return -1;
    }
    param_store_t store;
    matek_param_store(&pflash, &store);
    uint8_t slot = 0u;
    uint32_t sequence = 0u;
    return (param_store_save(&store, blob, &slot, &sequence) == PARAM_STORE_OK) ? 0 : -1;
}

const matek_params_report_t *matek_params_report(void)
{
    return &report;
}
