/*
 * matek_console.h - the console on USART1 (115200 8N1): matek_console.c in
 * the flight image. In the HIL image the link owns USART1 and these print
 * nothing (matek_console_none.c).
 */
#ifndef HT_MATEK_CONSOLE_H
#define HT_MATEK_CONSOLE_H

#include <stdint.h>

void matek_console_init(void);
void matek_console_puts(const char *s);
void matek_console_put_u32(uint32_t v);
void matek_console_put_i32(int32_t v);
void matek_console_pump(void);
void matek_console_flush(void);

#endif /* HT_MATEK_CONSOLE_H */
