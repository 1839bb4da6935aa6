/*
 * log_df.h - the ArduPilot DataFlash (.bin) record layout the log writes
 * (log_df.c): every record is 0xA3 0x95, a type byte, then its fields
 * little-endian and packed, as its FMT record declares them. The formats
 * and their units are docs/flight-log.md's table.
 */
#ifndef HT_LOG_DF_H
#define HT_LOG_DF_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#define FW_LOG_HEAD1    0xA3u
#define FW_LOG_HEAD2    0x95u
#define FW_LOG_TYPE_FMT 0x80u
#define FW_LOG_FMT_LEN  89u /* 3 + type, length, name[4], format[16], labels[64] */
#define FW_LOG_REC_MAX  89u /* the longest record (FMT) */

/* The record types (the FMT records are written in this order). */
typedef enum {
    FW_LOG_PARM = 0,
    FW_LOG_MSG,
    FW_LOG_IMU,
    FW_LOG_GPS,
    FW_LOG_BARO,
    FW_LOG_ARSP,
    FW_LOG_ATT,
    FW_LOG_HTIN,
    FW_LOG_HTO,
    FW_LOG_CTRL,
    FW_LOG_RCOU,
    FW_LOG_MODE,
    FW_LOG_EV,
    FW_LOG_KIND_COUNT
} fw_log_kind_t;

/* One record type: its type byte, DataFlash name, format characters and
 * comma-separated labels, and its length in bytes (header included). */
typedef struct {
    uint8_t type;
    uint8_t length;
    const char *name;   /* at most 4 characters */
    const char *format; /* at most 16 characters */
    const char *labels; /* at most 64 characters */
} fw_log_format_t;

/* The table's row of a kind, NULL out of range. */
const fw_log_format_t *fw_log_format(fw_log_kind_t kind);

/* A record being built in a caller's buffer (at least FW_LOG_REC_MAX
 * bytes): fw_log_rec_begin writes the header, each put appends one field. */
typedef struct {
    uint8_t *p;
    size_t n;
} fw_log_rec_t;

void fw_log_rec_begin(fw_log_rec_t *r, uint8_t *buf, uint8_t type);
void fw_log_put_u8(fw_log_rec_t *r, uint8_t v);
void fw_log_put_u16(fw_log_rec_t *r, uint16_t v);
void fw_log_put_i16(fw_log_rec_t *r, int16_t v);
void fw_log_put_u32(fw_log_rec_t *r, uint32_t v);
void fw_log_put_i32(fw_log_rec_t *r, int32_t v);
void fw_log_put_u64(fw_log_rec_t *r, uint64_t v);
/* A text field of width bytes: s copied, cut at width, NUL-padded. */
void fw_log_put_text(fw_log_rec_t *r, const char *s, size_t width);

/* The FMT record of a kind into buf (FW_LOG_FMT_LEN bytes). 0, or -1 out of
 * range. */
int fw_log_fmt_record(fw_log_kind_t kind, uint8_t buf[FW_LOG_FMT_LEN]);

#ifdef __cplusplus
}
#endif

#endif /* HT_LOG_DF_H */
