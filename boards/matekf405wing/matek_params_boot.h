/*
 * matek_params_boot.h - the parameter store of the Matek F405-WING image,
 * loaded before board_init (matek_params_boot.c, which also implements
 * fw_board_config).
 */
#ifndef HT_MATEK_PARAMS_BOOT_H
#define HT_MATEK_PARAMS_BOOT_H

#include "fw_step.h"
#include "link/fw_link.h"
#include "matek_param_blob.h"

const matek_params_report_t *matek_params_report(void);
/* The link's stored parameters when the boot load accepted a set, else NULL
 * (fw_board_link_init puts them into the link). */
const fw_link_params_t *matek_params_link(void);
/* fw_link_save_fn: every row the link exposes into the store (a flash sector
 * erase: the loop stalls). 0 = saved. */
int matek_params_save(void *ctx, const fw_config_t *cfg, const fw_link_params_t *link);

#endif /* HT_MATEK_PARAMS_BOOT_H */
