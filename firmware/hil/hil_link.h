/*
 * hil_link.h - the seam a HIL image's board file implements for the HIL
 * firmware (hil_fw.c): the byte link to the host and the servo read-back.
 *
 * Its own header, not part of hil_fw.h, so that a board's HIL file depends on
 * the seam only and the firmware on the board one way (hil_fw.c calls these;
 * the board file never needs the protocol): tools/arch/arch_check.py circles.
 */
#ifndef HT_HIL_LINK_H
#define HT_HIL_LINK_H

#include <stddef.h>
#include <stdint.h>

/* Bring the link up (after board_init); 0 if it did not come up. */
int hil_link_init(void);
/* One received byte, if any (never waits): 1 and *byte, or 0. */
int hil_link_poll(uint8_t *byte);
/* Send bytes on the link (blocking, bounded). */
void hil_link_send(const uint8_t *data, size_t n);
/* The pulse a servo output is producing, read back from the hardware (us). */
uint16_t hil_servo_readback_us(uint8_t channel);
/* The link's receive error count (overrun, framing, noise, parity). */
uint16_t hil_link_errors(void);

#endif /* HT_HIL_LINK_H */
