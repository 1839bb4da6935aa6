/*
 * sil_log.c - the flight log into a host file (sil_log.h). The ring is
 * large and the budget unbounded because a file takes every byte at once;
 * the board-side bounds (budget per tick, drops) are the writer's own and
 * tested in firmware/log/tests.
 */
#include "sil_log.h"

// cppcheck-suppress misra-c2012-21.6 ; D-SIL-HOST: the SIL host board writes flight.bin
#include <stdio.h>
#include <string.h>

#include "link/fw_link_param_table.h"
#include "log/fw_log.h"

#define SIL_LOG_RING 65536u

typedef struct {
    fw_log_t log;
    FILE *f;
    const sil_board_t *board;
    uint8_t write_failed;
    uint8_t ring[SIL_LOG_RING];
} sil_log_t;

size_t sil_log_size(void)
{
    return sizeof(sil_log_t);
}

static size_t file_write(void *ctx, const uint8_t *bytes, size_t n)
{
    // cppcheck-suppress misra-c2012-11.5 ; D-11.5-CTX: the sink\'s context is the sil_log_t
    sil_log_t *l = ctx;
    const size_t took = fwrite(bytes, 1u, n, l->f);
    if (took != n) {
        l->write_failed = 1u;
    }
    return took;
}

/* Every row as the ground station sees it: the MAVLink name and the value
 * in force. */
static int param_row(void *ctx, uint16_t index, char name[17], int32_t *raw, int32_t *scale)
{
    // cppcheck-suppress misra-c2012-11.5 ; D-11.5-CTX: the sink\'s context is the sil_log_t
    const sil_log_t *l = ctx;
    const ht_param_info_t *row = NULL;
    if ((index >= fw_link_param_count()) ||
        (fw_link_param_get(&l->board->link, index, raw, &row) != 0) || (row == NULL) ||
        (fw_link_param_id(index, name) != 0)) {
        return -1;
    }
    *scale = row->scale;
    return 0;
}

static void after_step(void *ctx, const fw_t *fw, const fw_inputs_t *in, const fw_output_t *out,
                       uint64_t us)
{
    // cppcheck-suppress misra-c2012-11.5 ; D-11.5-CTX: the sink\'s context is the sil_log_t
    sil_log_t *l = ctx;
    fw_log_step(&l->log, fw, us, in, out);
}

static void say(char *err, size_t err_len, const char *what)
{
    if ((err != NULL) && (err_len > 0u)) {
        (void)snprintf(err, err_len, "%s", what);
    }
}

int sil_log_open(void *log, sil_board_t *b, const char *path, char *err, size_t err_len)
{
    // cppcheck-suppress misra-c2012-11.5 ; D-11.5-CTX: the Python caller's handle is the sil_log_t
    sil_log_t *l = log;
    if ((l == NULL) || (b == NULL) || (path == NULL)) {
        say(err, err_len, "sil_log_open: NULL argument");
        return -1;
    }
    if (b->ready == 0u) {
        say(err, err_len, "sil_log_open: the board is not initialised");
        return -1;
    }
    (void)memset(l, 0, sizeof(*l));
    l->f = fopen(path, "wb");
    if (l->f == NULL) {
        say(err, err_len, "sil_log_open: cannot open the log file for writing");
        return -1;
    }
    l->board = b;
    const fw_log_config_t cfg = {l->ring, SIL_LOG_RING, SIL_LOG_RING, 1u, file_write, l, param_row,
                                 l};
    if (fw_log_init(&l->log, &cfg) != 0) {
        (void)fclose(l->f);
        l->f = NULL;
        say(err, err_len, "sil_log_open: the log writer refused its configuration");
        return -1;
    }
    b->after_step = after_step;
    b->after_step_ctx = l;
    return 0;
}

int32_t sil_log_close(void *log, sil_board_t *b)
{
    // cppcheck-suppress misra-c2012-11.5 ; D-11.5-CTX: the Python caller's handle is the sil_log_t
    sil_log_t *l = log;
    if ((l == NULL) || (l->f == NULL)) {
        return -1;
    }
    if ((b != NULL) && (b->after_step_ctx == l)) {
        b->after_step = NULL;
        b->after_step_ctx = NULL;
    }
    const uint32_t left = fw_log_flush(&l->log);
    const int closed = fclose(l->f);
    l->f = NULL;
    if ((left != 0u) || (closed != 0) || (l->write_failed != 0u)) {
        return -1;
    }
    return (int32_t)l->log.dropped;
}

uint32_t sil_log_records(const void *log)
{
    // cppcheck-suppress misra-c2012-11.5 ; D-11.5-CTX: the Python caller's handle is the sil_log_t
    const sil_log_t *l = log;
    return (l == NULL) ? 0u : l->log.records;
}
