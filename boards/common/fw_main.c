/*
 * fw_main.c - main() of every firmware image: bring the board up, then one
 * portable control tick per board tick. The one static instance of the
 * firmware state lives here (firmware, not library).
 */
#include "helical/board.h"

#include "fw_loop.h"

// cppcheck-suppress misra-c2012-8.6 ; FP: one main per image, hil_main.c is another program
int main(void)
{
    /* static: the firmware state is not on the stack (same storage as at file scope) */
    static fw_config_t config;
    static fw_state_t state;
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
