/*
 * matek_console_none.c - the HIL image's console: USART1 carries the HIL
 * frames (board_matekf405wing_hil.c), so status text would corrupt them.
 */
#include "matek_console.h"

void matek_console_init(void) {}

void matek_console_puts(const char *s)
{
    (void)s;
}

void matek_console_put_u32(uint32_t v)
{
    (void)v;
}

void matek_console_put_i32(int32_t v)
{
    (void)v;
}

void matek_console_pump(void) {}

void matek_console_flush(void) {}
