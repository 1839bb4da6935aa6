/*
 * log_replay.h - `ht_replay --log FILE`: the law's inputs of a DataFlash
 * flight log (firmware/log, docs/flight-log.md) through ht_step again, with
 * the law's parameters of the log's PARM records, and every output compared
 * with the logged HTO record, bit for bit.
 */
#ifndef HT_LOG_REPLAY_H
#define HT_LOG_REPLAY_H

#include <stdio.h>

/* Replay path; the summary to out, a problem to err. 0: every step equal;
 * 1: a mismatch (the first is named) or a log that cannot be read as one
 * (the byte offset and what); 3: a read error. */
int ht_log_replay(const char *path, FILE *out, FILE *err);

#endif /* HT_LOG_REPLAY_H */
