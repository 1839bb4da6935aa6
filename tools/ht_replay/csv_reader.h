/*
 * csv_reader.h - the input side of ht_replay: reading lines, mapping the
 * header to the ten input columns, and splitting a row into numbers, with an
 * error that names the line and the column of the first problem.
 *
 * Kept free of the control law (no helical types) so that a fuzz target can
 * link this library alone.
 *
 * Format: fields separated by ',', lines ended by "\n" or "\r\n" (the last
 * line may lack it). A field may be double-quoted ("a,b" with "" for a quote)
 * so that text columns of a log, which are ignored, cannot shift the numbers;
 * a quoted field may not span lines. A UTF-8 byte order mark before the
 * header is skipped. Column names are compared exactly (case-sensitive) after
 * trimming spaces and tabs; numbers may also carry surrounding blanks.
 */
#ifndef HT_REPLAY_CSV_READER_H
#define HT_REPLAY_CSV_READER_H

#include <stddef.h>
#include <stdio.h>

/* The input columns, in the order of docs/control-law.md. */
typedef enum {
    HT_COL_X = 0,
    HT_COL_Y,
    HT_COL_Z,
    HT_COL_TURN_RATE,
    HT_COL_PITCH,
    HT_COL_AIRSPEED,
    HT_COL_GYRO_X,
    HT_COL_GYRO_Y,
    HT_COL_GYRO_Z,
    HT_COL_INVERTED,
    /* optional (the law's options, docs/control-law.md "Extensions beyond the
     * seed"): a file without them reads as 0, which an option off ignores */
    HT_COL_TURN_ACCEL,
    HT_COL_ACCEL_LAT,
    HT_COL_COUNT
} ht_csv_col_t;

/* The columns every file must have: x .. inverted. */
#define HT_COL_REQUIRED ((int)HT_COL_INVERTED + 1)

/* index[] of an optional column the header does not have. */
#define HT_CSV_ABSENT ((size_t)-1)

/* "x", "y", ..., "inverted", "turn_accel", "accel_lat"; "" for an out-of-range value. */
const char *ht_csv_col_name(ht_csv_col_t col);

/*
 * Longest line accepted, in bytes without the line ending. A longer line is an
 * error ("line longer than ..."), never cut short. 1 MiB holds about 40 000
 * numeric columns, which no log has, and bounds the memory a bad file can take.
 */
#define HT_CSV_MAX_LINE ((size_t)1 << 20)

/* Room for a column name in a message; longer names are shown cut, ending in
 * "...". Only the message is affected, never the data. */
#define HT_CSV_NAME_MAX 48

/* The first problem found. Printed as "line N, column NAME: MESSAGE", or
 * "line N: MESSAGE" when no column applies (a read error, out of memory). */
typedef struct {
    unsigned long line;           /* 1-based; the header is line 1 */
    char column[HT_CSV_NAME_MAX]; /* the header's name, "#k" (1-based), or "" */
    char message[160];
} ht_csv_error_t;

/* Format e as above into buf (always NUL-terminated when size > 0). */
void ht_csv_error_format(const ht_csv_error_t *e, char *buf, size_t size);

/* --- header --------------------------------------------------------------- */

/* The mapped header line. Initialise with HT_CSV_HEADER_INIT; free with
 * ht_csv_header_free. */
typedef struct {
    size_t nfields;             /* fields in the header line (at least 1) */
    size_t index[HT_COL_COUNT]; /* field position (0-based) of each input column, or
                                   HT_CSV_ABSENT (an optional column the file lacks) */
    int *column_of;             /* per field: its ht_csv_col_t, or -1 if ignored */
    char **names;               /* per field: its name (unquoted, trimmed), for messages */
    char *name_text;            /* storage of the names */
} ht_csv_header_t;

#define HT_CSV_HEADER_INIT                                                                         \
    {                                                                                              \
        0, {0}, NULL, NULL, NULL                                                                   \
    }

void ht_csv_header_free(ht_csv_header_t *h);

/*
 * Map a header line (line 1). Every required input column must appear
 * exactly once, an optional one at most once; other columns are allowed and
 * ignored. Returns 0, or -1 with err filled:
 * a missing column names that column; a duplicate or a broken quote names
 * the field. On failure h is left empty (nothing to free).
 */
int ht_csv_parse_header(const char *text, size_t len, ht_csv_header_t *h, ht_csv_error_t *err);

/* --- lines ---------------------------------------------------------------- */

/* A growable line buffer. Initialise with HT_CSV_LINE_INIT; free with
 * ht_csv_line_free. */
typedef struct {
    char *text;           /* the line without its ending, NUL-terminated */
    size_t len;           /* bytes in text (may include NUL bytes) */
    size_t cap;           /* allocated bytes */
    unsigned long number; /* 1-based number of the line last read */
    size_t max_len;       /* longest line accepted; 0: HT_CSV_MAX_LINE (a fuzz target sets it
                             lower to reach the limit with short inputs; never above it) */
} ht_csv_line_t;

#define HT_CSV_LINE_INIT                                                                           \
    {                                                                                              \
        NULL, 0, 0, 0, 0                                                                           \
    }

void ht_csv_line_free(ht_csv_line_t *line);

typedef enum {
    HT_CSV_LINE_OK = 0,  /* a line was read */
    HT_CSV_LINE_EOF = 1, /* no more lines (a final "\n" does not start an empty line) */
    HT_CSV_LINE_ERR = 2  /* too long, out of memory, or a read error: see err */
} ht_csv_line_status_t;

/*
 * Read the next line of f into line, dropping "\n" or "\r\n" (a "\r" just
 * before the end of the file is dropped too). header (may be NULL) supplies
 * the column name in the message for a too-long line.
 */
ht_csv_line_status_t ht_csv_read_line(FILE *f, ht_csv_line_t *line, const ht_csv_header_t *header,
                                      ht_csv_error_t *err);

/*
 * Read line 1 of f and map it (ht_csv_parse_header). An empty input is an
 * error ("line 1, column x: empty input, no header line"); so is a too-long
 * header. Skips a UTF-8 byte order mark. Returns 0 or -1 with err filled.
 */
int ht_csv_read_header(FILE *f, ht_csv_line_t *line, ht_csv_header_t *h, ht_csv_error_t *err);

/* --- rows ----------------------------------------------------------------- */

/*
 * Split one data line and parse the ten input columns into values[] (indexed
 * by ht_csv_col_t; ignored columns are not parsed; an optional column the
 * header lacks is 0, its text "0"). The row must have exactly
 * h->nfields fields. Returns 0, or -1 with err naming line_number and the
 * column of the first problem, from left to right; the messages are those of
 * ht_parse_number ("empty field", "not a number", "not finite", "too large")
 * and "empty line", "missing field (...)", "too many fields (...)",
 * "unterminated quote", "text after the closing quote".
 */
int ht_csv_parse_row(const ht_csv_header_t *h, const char *text, size_t len,
                     unsigned long line_number, double values[HT_COL_COUNT], ht_csv_error_t *err);

/* A field's text inside the line (quotes removed, blanks kept; valid while the
 * line is). The exact conversions (ht_decimal_round) work on the text. */
typedef struct {
    const char *text;
    size_t len;
} ht_csv_field_t;

/* ht_csv_parse_row, also giving each input column's text in fields[]. */
int ht_csv_parse_row_fields(const ht_csv_header_t *h, const char *text, size_t len,
                            unsigned long line_number, double values[HT_COL_COUNT],
                            ht_csv_field_t fields[HT_COL_COUNT], ht_csv_error_t *err);

#endif /* HT_REPLAY_CSV_READER_H */
