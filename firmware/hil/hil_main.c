/*
 * hil_main.c - main() of the HIL firmware image: bring the board up, enable
 * the link, send the ready banner, then act on each frame as it arrives. The
 * loop is driven by the frames (one control step per SENSORS frame), not by
 * the board's control tick: the simulator is the clock (docs/hil-protocol.md).
 */
#include "helical/board.h"

#include "hil/hil_fw.h"

// cppcheck-suppress misra-c2012-8.6 ; FP: one main per image, fw_main.c is another program
int main(void)
{
    static hil_fw_t hil; /* static: not on the stack (same storage as at file scope) */
    const board_config_t board = BOARD_CONFIG_DEFAULT;
    if (board_init(&board) != BOARD_OK) {
        board_failsafe(BOARD_FS_CONFIG);
        for (;;) {
            /* no board: stay here, outputs silenced */
        }
    }
    hil_fw_init(&hil);
    if (hil_link_init() == 0) {
        for (;;) {
            /* no link: nothing to fly; outputs keep "no pulses" */
        }
    }
    /* Bytes sent before the USART was enabled are lost: the host waits for
     * this frame (or asks again with HELLO) before it sends anything else. */
    hil_fw_send_ready(&hil);
    for (;;) {
        uint8_t byte = 0u;
        if (hil_link_poll(&byte) != 0) {
            hil_fw_on_byte(&hil, byte);
        }
    }
}
