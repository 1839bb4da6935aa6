/*
 * fw_board_config.h - the one place a board may change the flight image's
 * configuration: fw_main.c calls fw_board_config after fw_config_default
 * and before board_init, so a board with a parameter store can put the
 * stored law and estimator parameters in (boards/matekf405wing). The
 * firmware step itself is untouched; fw_init still checks the result.
 *
 * fw_main.c defines it weak, doing nothing: boards without a store (the
 * netduinoplus2 image) fly the defaults as before.
 */
#ifndef HT_FW_BOARD_CONFIG_H
#define HT_FW_BOARD_CONFIG_H

#include "fw_step.h"

void fw_board_config(fw_config_t *cfg);

#endif /* HT_FW_BOARD_CONFIG_H */
