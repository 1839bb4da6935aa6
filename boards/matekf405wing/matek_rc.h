/*
 * matek_rc.h - the Matek F405-WING's receiver (matek_rc.c, which also
 * implements board_rc_count and board_rc_read_us): SBUS (USART2), CRSF
 * (USART6) or PPM (TIM5).
 */
#ifndef HT_MATEK_RC_H
#define HT_MATEK_RC_H

void matek_rc_init(void);
/* Every wake of the tick loop (<= 1 ms apart: SBUS needs <= 3 ms). */
void matek_rc_poll(void);

#endif /* HT_MATEK_RC_H */
