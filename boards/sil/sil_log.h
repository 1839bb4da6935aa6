/*
 * sil_log.h - the SIL host board's flight log: the firmware's log writer
 * (firmware/log/fw_log.h) into a host file, flight.bin, for every flight
 * the harness flies (sil/helical_sil/sim/lockstep.py). The same records a
 * board writes to its card; here the sink is a FILE and never stalls.
 *
 * Python calls it through ctypes: sil_log_size() bytes of its own buffer,
 * sil_log_open after sil_board_init, sil_log_close at the end of the flight.
 */
#ifndef HELICAL_SIL_LOG_H
#define HELICAL_SIL_LOG_H

#include <stddef.h>
#include <stdint.h>

#include "sil_board.h"

#ifdef __cplusplus
extern "C" {
#endif

size_t sil_log_size(void);

/* Start a log of board b (initialised) into the file at path, and attach it
 * to the board's steps. 0; -1 (NULL, a board not ready, or the file cannot
 * be opened: err says which). */
int sil_log_open(void *log, sil_board_t *b, const char *path, char *err, size_t err_len);

/* Detach, flush and close. Returns the records dropped (0 for a file that
 * took everything); -1 if the file could not be written completely. */
int32_t sil_log_close(void *log, sil_board_t *b);

/* Records written so far (put into the ring), for the harness's checks. */
uint32_t sil_log_records(const void *log);

#ifdef __cplusplus
}
#endif

#endif /* HELICAL_SIL_LOG_H */
