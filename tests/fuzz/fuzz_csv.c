/*
 * libFuzzer target: arbitrary bytes as ht_replay's standard input, read the
 * way the tool reads it (main.c's loop): ht_csv_read_header and
 * ht_csv_read_line on a FILE (so CRLF, a byte order mark, a missing final
 * newline, NUL bytes and the line limit are all reached), then
 * ht_csv_parse_row_fields and ht_replay_to_input. Checks:
 *
 *   - the lines the reader returns are those of a plain in-memory split
 *     (LF ends a line, one CR before it or before the end is dropped, a final
 *     LF starts no line), numbered from 1;
 *   - a failure names a line (>= 1) and formats as "line N..."; a bad field
 *     names a column;
 *   - a converted row is within one step of the double-precision rounding of
 *     the same number (the exact decimal rounding may differ from a double
 *     only at a tie), and its values are finite;
 *   - the same bytes give the same answer twice;
 *   - with a line limit of 80 bytes (the 1 MiB limit's code, reachable with
 *     short inputs) the run stops at the first line over 80 bytes and is
 *     otherwise the same.
 */
#define _GNU_SOURCE /* fmemopen */
#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "csv_reader.h"
#include "input_convert.h"

static void check(int ok)
{
    if (!ok) {
        abort();
    }
}

#define SMALL_LIMIT 80u

typedef struct {
    int rc;                      /* 0: every row converted */
    ht_csv_error_t err;          /* when rc != 0 */
    unsigned long rows;          /* rows converted */
    double sum;                  /* of the converted fixed-point values */
    unsigned long too_long_line; /* the line refused as too long, or 0 */
} result_t;

/* The next line of data[*pos..size) by the plain rule; returns 0 at the end. */
static int oracle_line(const uint8_t *data, size_t size, size_t *pos, size_t *start, size_t *len)
{
    if (*pos >= size) {
        return 0;
    }
    const uint8_t *nl = memchr(data + *pos, '\n', size - *pos);
    size_t end = nl != NULL ? (size_t)(nl - data) : size;
    *start = *pos;
    *len = end - *pos;
    if (*len > 0 && data[end - 1] == '\r') {
        (*len)--;
    }
    *pos = nl != NULL ? end + 1 : size;
    return 1;
}

/* One step of each format, for the double-rounding comparison. */
static void check_near(double v, double scale, long fixed)
{
    double r = round(v * scale);
    check(isfinite(v) && fabs(r - (double)fixed) <= 1.0);
}

static void run(const uint8_t *data, size_t size, size_t limit, result_t *res)
{
    memset(res, 0, sizeof *res);
    /* fmemopen needs a non-empty buffer; an empty input is a valid case */
    static const uint8_t nothing[1] = {0};
    FILE *f = fmemopen((void *)(size > 0 ? data : nothing), size > 0 ? size : 1, "rb");
    check(f != NULL);
    if (size == 0) {
        (void)fgetc(f); /* consume the placeholder byte: the stream is empty */
    }
    ht_csv_line_t line = HT_CSV_LINE_INIT;
    line.max_len = limit;
    ht_csv_header_t header = HT_CSV_HEADER_INIT;
    size_t opos = 0, ostart = 0, olen = 0;
    unsigned long lines = 0;

    if (ht_csv_read_header(f, &line, &header, &res->err) != 0) {
        res->rc = -1;
    } else {
        check(oracle_line(data, size, &opos, &ostart, &olen));
        check(line.number == 1 && line.len == olen && memcmp(line.text, data + ostart, olen) == 0);
        lines = 1;
        for (;;) {
            ht_csv_line_status_t s = ht_csv_read_line(f, &line, &header, &res->err);
            if (s == HT_CSV_LINE_EOF) {
                check(!oracle_line(data, size, &opos, &ostart, &olen));
                break;
            }
            check(oracle_line(data, size, &opos, &ostart, &olen));
            lines++;
            check(line.number == lines);
            if (s == HT_CSV_LINE_ERR) {
                res->rc = -1;
                check(olen > (limit != 0 ? limit : HT_CSV_MAX_LINE)); /* the only reason here */
                res->too_long_line = lines;
                break;
            }
            check(line.len == olen && memcmp(line.text, data + ostart, olen) == 0);
            double values[HT_COL_COUNT];
            ht_csv_field_t fields[HT_COL_COUNT];
            ht_input_t in;
            if (ht_csv_parse_row_fields(&header, line.text, line.len, line.number, values, fields,
                                        &res->err) != 0 ||
                ht_replay_to_input(fields, line.number, &in, &res->err) != 0) {
                res->rc = -1;
                break;
            }
            check_near(values[HT_COL_X], 16384.0, in.x);
            check_near(values[HT_COL_Y], 16384.0, in.y);
            check_near(values[HT_COL_Z], 16384.0, in.z);
            check_near(values[HT_COL_TURN_RATE], 2048.0, in.turn_rate_rad_s);
            check_near(values[HT_COL_PITCH], 65536.0, in.pitch_ratio);
            check_near(values[HT_COL_AIRSPEED], 100.0, in.airspeed_cm_s);
            check_near(values[HT_COL_GYRO_X], 2048.0, in.gyro_rad_s[0]);
            check_near(values[HT_COL_GYRO_Y], 2048.0, in.gyro_rad_s[1]);
            check_near(values[HT_COL_GYRO_Z], 2048.0, in.gyro_rad_s[2]);
            check(in.inverted <= 1u);
            res->sum += (double)in.x + in.y + in.z + in.turn_rate_rad_s + (double)in.pitch_ratio +
                        in.airspeed_cm_s + in.gyro_rad_s[0] + in.gyro_rad_s[1] + in.gyro_rad_s[2] +
                        in.inverted;
            res->rows++;
        }
    }
    if (res->rc != 0) {
        check(res->err.line >= 1u && res->err.message[0] != '\0');
        char buf[320];
        ht_csv_error_format(&res->err, buf, sizeof buf);
        check(strncmp(buf, "line ", 5) == 0);
    }
    ht_csv_header_free(&header);
    ht_csv_line_free(&line);
    (void)fclose(f);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static result_t a, b, small;
    run(data, size, 0, &a);
    run(data, size, 0, &b);
    check(a.rc == b.rc && a.rows == b.rows && a.sum == b.sum);
    if (a.rc != 0) {
        check(a.err.line == b.err.line && strcmp(a.err.column, b.err.column) == 0 &&
              strcmp(a.err.message, b.err.message) == 0);
    }
    run(data, size, SMALL_LIMIT, &small);
    if (small.too_long_line != 0) {
        /* stopped at the long line: the full run got at least that far */
        check(a.rc == 0 || a.err.line >= small.too_long_line);
        check(strstr(small.err.message, "line longer than 80 bytes") != NULL);
    } else if (small.rc == 0 || small.err.line > 1u ||
               strstr(small.err.message, "longer") == NULL) {
        /* no line over the limit (or only the header): the same answer */
        check(small.rc == a.rc && small.rows == a.rows && small.sum == a.sum);
    }
    return 0;
}
