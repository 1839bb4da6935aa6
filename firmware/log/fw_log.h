/*
 * fw_log.h - THE flight log writer: ArduPilot DataFlash (.bin) records of
 * what the step saw, estimated, commanded and output (docs/flight-log.md),
 * into a caller's byte sink.
 *
 * How it is fed: after each control step (fw_output_t.control_ran), the
 * host calls fw_log_step with the step's state, inputs and outputs and its
 * clock.
 * The writer builds whole records into a caller-owned ring and hands at most
 * budget_bytes of the ring to the sink's write per call: the time a tick
 * spends logging is bounded whatever the sink (an SD card, a file, a
 * MAVLink download buffer). A record that does not fit the ring is dropped
 * whole and counted (fw_log_t.dropped): the step keeps flying, the log has a
 * gap a reader sees, never a torn record.
 *
 * The start of the log: one FMT per record type, a MSG, then one PARM per
 * parameter row (from the caller's row source, so the names are the ones a
 * ground station sees). Step records wait until the header is in the ring.
 *
 * Integer only, no allocation, no globals: all state in fw_log_t.
 */
#ifndef HT_FW_LOG_H
#define HT_FW_LOG_H

#include <stddef.h>
#include <stdint.h>

#include "fw_step.h"
#include "log/log_df.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The sink: accepts up to n bytes, returns how many it took (0: busy, full
 * or gone; the bytes stay in the ring). */
typedef size_t (*fw_log_write_fn)(void *ctx, const uint8_t *bytes, size_t n);

/* A parameter row for PARM: index from 0; fills name (NUL-terminated, at
 * most 16 characters), the stored value and its scale (stored = value *
 * scale, ht_param_info_t.scale). 0, or -1 past the last row. */
typedef int (*fw_log_param_fn)(void *ctx, uint16_t index, char name[17], int32_t *raw,
                               int32_t *scale);

typedef struct {
    uint8_t *ring;         /* the caller's buffer */
    uint32_t ring_size;    /* bytes, >= 2 * FW_LOG_REC_MAX */
    uint32_t budget_bytes; /* to the sink per fw_log_step, >= 1 */
    uint16_t decimation;   /* log the per-step records every n-th control step, >= 1 */
    fw_log_write_fn write;
    void *write_ctx;
    fw_log_param_fn param; /* may be NULL: no PARM records */
    void *param_ctx;
} fw_log_config_t;

/* Event ids of the EV record. */
// cppcheck-suppress misra-c2012-5.7 ; D-ANON-ENUM: an anonymous enum has no tag to repeat
enum {
    FW_LOG_EV_IMU_FAILSAFE_ON = 1,
    FW_LOG_EV_IMU_FAILSAFE_OFF = 2,
    FW_LOG_EV_RC_FAILSAFE_ON = 3,
    FW_LOG_EV_RC_FAILSAFE_OFF = 4,
    FW_LOG_EV_GUARD_ON = 5,
    FW_LOG_EV_GUARD_OFF = 6
};
/* The MODE record's mode number for the guided path (a scenario or a
 * companion computer); the flight modes log their ht_mode_t. */
#define FW_LOG_MODE_GUIDED 15u

typedef struct {
    fw_log_config_t cfg;
    uint32_t head, tail, used; /* ring indices and fill, bytes */
    uint16_t fmt_next;         /* header cursor: FMT records, then the MSG */
    uint16_t parm_next;        /* PARM rows written */
    uint8_t header_done;
    uint8_t ready;
    uint16_t decim_count;
    uint8_t last_mode, last_imu_fs, last_rc_fs, last_guard; /* for the events */
    uint32_t written;                                       /* bytes the sink took */
    uint32_t records;                                       /* records put into the ring */
    uint32_t dropped;                                       /* records dropped: the ring was full */
    uint32_t stalls; /* calls in which the sink took less than offered */
} fw_log_t;

/* Check the configuration and start a log. 0; -1 for NULL or a bad field
 * (nothing is written until it is fixed: every later call does nothing). */
int fw_log_init(fw_log_t *log, const fw_log_config_t *cfg);

/* After a control step: queue the header (first calls), the step's records
 * and its events, then give the sink at most budget_bytes. fw is the step's
 * state (its configuration says which pitch method the modes fly). NULL fw,
 * in or out: only the sink is served. */
void fw_log_step(fw_log_t *log, const fw_t *fw, uint64_t time_us, const fw_inputs_t *in,
                 const fw_output_t *out);

/* Give the sink whatever it takes of the ring, without a budget (the end of
 * a flight on a host). Returns the bytes still in the ring. */
uint32_t fw_log_flush(fw_log_t *log);

#ifdef __cplusplus
}
#endif

#endif /* HT_FW_LOG_H */
