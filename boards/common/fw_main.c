/*
 * fw_main.c - main() of every firmware image: bring the board up, then one
 * portable control tick per board tick. The one static instance of the
 * firmware state lives here (firmware, not library).
 */
#include "helical/board.h"

#include "fw_loop.h"

static fw_config_t config;
static fw_state_t state;

int main(void)
{
    const board_config_t board = BOARD_CONFIG_DEFAULT;
    fw_config_default(&config);
    if (board_init(&board) != BOARD_OK) {
        board_failsafe(BOARD_FS_CONFIG);
        for (;;) {
            /* no control without a board: stay here, outputs silenced */
        }
    }
    (void)fw_init(&state, &config); /* a refused config keeps the loop in failsafe */
    for (;;) {
        fw_tick(&state, board_wait_tick());
    }
}
