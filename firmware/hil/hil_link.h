/*
 * hil_link.h - the HIL/PIL link's byte transport and servo read-back,
 * provided by the HIL image's board file (board_stm32f4_hil.c,
 * board_matekf405wing_hil.c) for the firmware side (hil_fw.c, hil_main.c).
 * A board file implements these and needs nothing else of the HIL code.
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
