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

#include "link/fw_link.h"
#include "fw_step.h"

void fw_board_config(fw_config_t *cfg);

/*
 * The MAVLink ground-station link (fw_link.h) on a board's UART. fw_main.c
 * calls fw_board_link_init once after fw_link_init (the board sets up its
 * UART and may set link->save; 1 = the board has a link), then, every tick,
 * fw_board_link_poll (the board gives the received bytes to fw_link_rx and
 * takes fw_link_tx's bytes for its UART), and fw_link_after_step after each
 * control step with fw_board_time_ms. fw_main.c defines them weak: no link
 * (0), nothing polled, time 0 (boards/matekf405wing/matek_mavlink.c has them).
 */
int fw_board_link_init(fw_link_t *link);
void fw_board_link_poll(fw_link_t *link);
uint32_t fw_board_time_ms(void);

#endif /* HT_FW_BOARD_CONFIG_H */
