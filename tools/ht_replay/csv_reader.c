/* csv_reader.c - header mapping and row parsing for ht_replay; see csv_reader.h. */
#include "csv_reader.h"

#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

#include "number.h"

static const char *const col_names[HT_COL_COUNT] = {
    "x",      "y",      "z",      "turn_rate", "pitch",      "airspeed",
    "gyro_x", "gyro_y", "gyro_z", "inverted",  "turn_accel", "accel_lat",
};

const char *ht_csv_col_name(ht_csv_col_t col)
{
    if ((int)col < 0 || col >= HT_COL_COUNT) {
        return "";
    }
    return col_names[col];
}

/* --- errors ---------------------------------------------------------------- */

/* Copy a column name into the error, every byte outside printable ASCII as
 * '?' (a terminal could take it as a control code, and a cut could split a
 * UTF-8 sequence), cutting a long name with "..." (messages only). */
static void set_column_text(ht_csv_error_t *err, const char *name, size_t len)
{
    const size_t room = sizeof err->column - 1;
    size_t n = len;
    int cut = 0;
    if (n > room) {
        n = room - 3;
        cut = 1;
    }
    for (size_t i = 0; i < n; i++) {
        unsigned char c = (unsigned char)name[i];
        err->column[i] = (c < 0x20 || c > 0x7e) ? '?' : (char)c;
    }
    if (cut) {
        memcpy(err->column + n, "...", 3);
        n += 3;
    }
    err->column[n] = '\0';
}

/* Name of field k (0-based) for a message: the header's name if it has one,
 * else "#k+1". */
static void set_column_field(ht_csv_error_t *err, const ht_csv_header_t *h, size_t k)
{
    if (h != NULL && h->names != NULL && k < h->nfields && h->names[k][0] != '\0') {
        set_column_text(err, h->names[k], strlen(h->names[k]));
    } else {
        (void)snprintf(err->column, sizeof err->column, "#%lu", (unsigned long)k + 1);
    }
}

/* The compiler checks every message's format against its arguments. */
#if defined(__GNUC__)
#define HT_PRINTF_LIKE(f, a) __attribute__((format(printf, f, a)))
#else
#define HT_PRINTF_LIKE(f, a)
#endif
static void set_error(ht_csv_error_t *err, unsigned long line, const char *fmt, ...)
    HT_PRINTF_LIKE(3, 4);

static void set_error(ht_csv_error_t *err, unsigned long line, const char *fmt, ...)
{
    va_list ap;
    err->line = line;
    va_start(ap, fmt);
    (void)vsnprintf(err->message, sizeof err->message, fmt, ap);
    va_end(ap);
}

void ht_csv_error_format(const ht_csv_error_t *e, char *buf, size_t size)
{
    if (size == 0) {
        return;
    }
    if (e->column[0] != '\0') {
        (void)snprintf(buf, size, "line %lu, column %s: %s", e->line, e->column, e->message);
    } else {
        (void)snprintf(buf, size, "line %lu: %s", e->line, e->message);
    }
}

/* --- field splitting --------------------------------------------------------- */

typedef struct {
    const char *start; /* content: inside the quotes for a quoted field */
    size_t len;
    int quoted;
} field_t;

typedef enum { SPLIT_OK = 0, SPLIT_END, SPLIT_UNTERMINATED, SPLIT_AFTER_QUOTE } split_t;

static int is_blank(char c)
{
    return c == ' ' || c == '\t';
}

/*
 * Take the field starting at *pos. *pos == len + 1 marks that the line is
 * used up (a line of n commas has n + 1 fields, the last possibly empty).
 * On SPLIT_OK *pos moves past the field's separator.
 */
static split_t next_field(const char *text, size_t len, size_t *pos, field_t *f)
{
    size_t i = *pos;
    if (i > len) {
        return SPLIT_END;
    }
    size_t j = i;
    while (j < len && is_blank(text[j])) {
        j++;
    }
    if (j < len && text[j] == '"') {
        /* Quoted: runs to a quote that is not doubled. */
        size_t k = j + 1;
        for (;;) {
            if (k >= len) {
                return SPLIT_UNTERMINATED;
            }
            if (text[k] == '"') {
                if (k + 1 < len && text[k + 1] == '"') {
                    k += 2;
                    continue;
                }
                break;
            }
            k++;
        }
        f->start = text + j + 1;
        f->len = k - (j + 1);
        f->quoted = 1;
        k++;
        while (k < len && is_blank(text[k])) {
            k++;
        }
        if (k < len && text[k] != ',') {
            return SPLIT_AFTER_QUOTE;
        }
        *pos = k + 1; /* past the comma, or len + 1 at the end */
        return SPLIT_OK;
    }
    const char *comma = i < len ? memchr(text + i, ',', len - i) : NULL;
    size_t end = comma != NULL ? (size_t)(comma - text) : len;
    f->start = text + i;
    f->len = end - i;
    f->quoted = 0;
    *pos = end + 1;
    return SPLIT_OK;
}

static void set_split_error(ht_csv_error_t *err, unsigned long line, split_t s)
{
    set_error(err, line, "%s",
              s == SPLIT_UNTERMINATED ? "unterminated quote (a quoted field must end on its line)"
                                      : "text after the closing quote");
}

/* --- header ---------------------------------------------------------------- */

void ht_csv_header_free(ht_csv_header_t *h)
{
    free(h->column_of);
    free(h->names);
    free(h->name_text);
    h->column_of = NULL;
    h->names = NULL;
    h->name_text = NULL;
    h->nfields = 0;
}

static void trim(const char **s, size_t *len)
{
    while (*len > 0 && is_blank((*s)[0])) {
        (*s)++;
        (*len)--;
    }
    while (*len > 0 && is_blank((*s)[*len - 1])) {
        (*len)--;
    }
}

/* Copy a field's name into dst, undoubling quotes of a quoted field; returns
 * the bytes written (without the terminating NUL, which is added). */
static size_t copy_name(const field_t *f, char *dst)
{
    const char *s = f->start;
    size_t len = f->len;
    trim(&s, &len);
    size_t n = 0;
    for (size_t i = 0; i < len; i++) {
        dst[n++] = s[i];
        if (f->quoted && s[i] == '"') {
            i++; /* the second quote of a doubled pair */
        }
    }
    dst[n] = '\0';
    return n;
}

int ht_csv_parse_header(const char *text, size_t len, ht_csv_header_t *h, ht_csv_error_t *err)
{
    static const ht_csv_header_t empty = HT_CSV_HEADER_INIT;
    *h = empty;
    err->column[0] = '\0';
    if (text == NULL) { /* a fuzz driver may pass (NULL, 0) for an empty line */
        text = "";
        len = 0;
    }

    /* A carriage return left inside the line means CR-only line endings (old
     * Mac files): the whole file reads as one line, and "missing column"
     * would be a puzzling answer. */
    const char *cr = memchr(text, '\r', len);
    if (cr != NULL) {
        size_t k = 0;
        for (const char *q = text; q < cr; q++) {
            k += *q == ',' ? 1u : 0u;
        }
        set_column_field(err, NULL, k);
        set_error(err, 1, "carriage return inside the line (lines must end in LF or CRLF)");
        return -1;
    }

    /* Pass 1: count the fields and check the quoting. */
    size_t nfields = 0;
    size_t pos = 0;
    field_t f;
    for (;;) {
        split_t s = next_field(text, len, &pos, &f);
        if (s == SPLIT_END) {
            break;
        }
        if (s != SPLIT_OK) {
            set_column_field(err, NULL, nfields);
            set_split_error(err, 1, s);
            return -1;
        }
        nfields++;
    }

    /* Pass 2: copy the names. Each name is no longer than the line, and the
     * NULs take one byte per field. */
    h->nfields = nfields;
    h->column_of = malloc(nfields * sizeof *h->column_of);
    h->names = malloc(nfields * sizeof *h->names);
    h->name_text = malloc(len + nfields);
    if (h->column_of == NULL || h->names == NULL || h->name_text == NULL) {
        ht_csv_header_free(h);
        set_error(err, 1, "out of memory");
        return -1;
    }
    int seen[HT_COL_COUNT] = {0};
    for (int c = 0; c < (int)HT_COL_COUNT; c++) {
        h->index[c] = HT_CSV_ABSENT;
    }
    char *out = h->name_text;
    pos = 0;
    for (size_t k = 0; k < nfields; k++) {
        (void)next_field(text, len, &pos, &f);
        size_t n = copy_name(&f, out);
        h->names[k] = out;
        h->column_of[k] = -1;
        for (int c = 0; c < (int)HT_COL_COUNT; c++) {
            if (strlen(col_names[c]) == n && memcmp(col_names[c], out, n) == 0) {
                if (seen[c]) {
                    set_column_text(err, out, n);
                    set_error(err, 1, "appears twice (fields %lu and %lu)",
                              (unsigned long)h->index[c] + 1, (unsigned long)k + 1);
                    ht_csv_header_free(h);
                    return -1;
                }
                seen[c] = 1;
                h->index[c] = k;
                h->column_of[k] = c;
            }
        }
        out += n + 1;
    }
    for (int c = 0; c < HT_COL_REQUIRED; c++) {
        if (!seen[c]) {
            set_column_text(err, col_names[c], strlen(col_names[c]));
            set_error(err, 1, "missing from the header (needed: %s)",
                      "x,y,z,turn_rate,pitch,airspeed,gyro_x,gyro_y,gyro_z,inverted");
            ht_csv_header_free(h);
            return -1;
        }
    }
    return 0;
}

/* --- lines ------------------------------------------------------------------ */

void ht_csv_line_free(ht_csv_line_t *line)
{
    free(line->text);
    line->text = NULL;
    line->len = 0;
    line->cap = 0;
}

/* Make room for one more byte plus the terminating NUL. */
static int line_reserve(ht_csv_line_t *line)
{
    if (line->len + 2 <= line->cap) {
        return 0;
    }
    size_t cap = line->cap == 0 ? 256 : line->cap * 2;
    char *p = realloc(line->text, cap);
    if (p == NULL) {
        return -1;
    }
    line->text = p;
    line->cap = cap;
    return 0;
}

/* The field in progress at the length limit, for the too-long message. */
static size_t field_at_limit(const ht_csv_line_t *line)
{
    size_t k = 0;
    for (size_t i = 0; i < line->len; i++) {
        if (line->text[i] == ',') {
            k++;
        }
    }
    return k;
}

ht_csv_line_status_t ht_csv_read_line(FILE *f, ht_csv_line_t *line, const ht_csv_header_t *header,
                                      ht_csv_error_t *err)
{
    line->len = 0;
    int c = getc(f);
    if (c == EOF) {
        if (ferror(f)) {
            line->number++;
            err->column[0] = '\0';
            set_error(err, line->number, "read error");
            return HT_CSV_LINE_ERR;
        }
        return HT_CSV_LINE_EOF;
    }
    line->number++;
    const size_t max_len =
        line->max_len != 0 && line->max_len < HT_CSV_MAX_LINE ? line->max_len : HT_CSV_MAX_LINE;
    /* One byte more than the limit is kept so that the '\r' of a "\r\n"
     * ending a line of exactly the limit still fits. */
    while (c != EOF && c != '\n') {
        if (line->len > max_len) {
            set_column_field(err, header, field_at_limit(line));
            set_error(err, line->number, "line longer than %lu bytes", (unsigned long)max_len);
            return HT_CSV_LINE_ERR;
        }
        if (line_reserve(line) != 0) {
            err->column[0] = '\0';
            set_error(err, line->number, "out of memory");
            return HT_CSV_LINE_ERR;
        }
        line->text[line->len++] = (char)c;
        c = getc(f);
    }
    if (c == EOF && ferror(f)) {
        err->column[0] = '\0';
        set_error(err, line->number, "read error");
        return HT_CSV_LINE_ERR;
    }
    if (line->len > 0 && line->text[line->len - 1] == '\r') {
        line->len--;
    }
    if (line->len > max_len) {
        set_column_field(err, header, field_at_limit(line));
        set_error(err, line->number, "line longer than %lu bytes", (unsigned long)max_len);
        return HT_CSV_LINE_ERR;
    }
    if (line_reserve(line) != 0) { /* an empty line has no buffer yet */
        err->column[0] = '\0';
        set_error(err, line->number, "out of memory");
        return HT_CSV_LINE_ERR;
    }
    line->text[line->len] = '\0';
    return HT_CSV_LINE_OK;
}

int ht_csv_read_header(FILE *f, ht_csv_line_t *line, ht_csv_header_t *h, ht_csv_error_t *err)
{
    static const ht_csv_header_t empty = HT_CSV_HEADER_INIT;
    *h = empty;
    ht_csv_line_status_t s = ht_csv_read_line(f, line, NULL, err);
    if (s == HT_CSV_LINE_ERR) {
        return -1;
    }
    if (s == HT_CSV_LINE_EOF) {
        set_column_text(err, col_names[0], strlen(col_names[0]));
        set_error(err, 1, "empty input, no header line");
        return -1;
    }
    const char *text = line->text;
    size_t len = line->len;
    if (len >= 3 && memcmp(text, "\xEF\xBB\xBF", 3) == 0) {
        text += 3;
        len -= 3;
    }
    return ht_csv_parse_header(text, len, h, err);
}

/* --- rows ------------------------------------------------------------------ */

/* A field's text for a message: bytes outside printable ASCII as '?', cut
 * with "..." to fit. */
static void show_text(const char *s, size_t len, char *buf, size_t size)
{
    size_t n = len < size - 1 ? len : size - 4;
    for (size_t i = 0; i < n; i++) {
        unsigned char c = (unsigned char)s[i];
        buf[i] = (c < 0x20 || c > 0x7e) ? '?' : (char)c;
    }
    if (n < len) {
        memcpy(buf + n, "...", 3);
        n += 3;
    }
    buf[n] = '\0';
}

int ht_csv_parse_row(const ht_csv_header_t *h, const char *text, size_t len,
                     unsigned long line_number, double values[HT_COL_COUNT], ht_csv_error_t *err)
{
    ht_csv_field_t fields[HT_COL_COUNT];
    return ht_csv_parse_row_fields(h, text, len, line_number, values, fields, err);
}

int ht_csv_parse_row_fields(const ht_csv_header_t *h, const char *text, size_t len,
                            unsigned long line_number, double values[HT_COL_COUNT],
                            ht_csv_field_t fields[HT_COL_COUNT], ht_csv_error_t *err)
{
    if (text == NULL) {
        text = "";
        len = 0;
    }
    for (int c = HT_COL_REQUIRED; c < (int)HT_COL_COUNT; c++) {
        fields[c].text = "0"; /* an optional column the header lacks */
        fields[c].len = 1;
        values[c] = 0.0;
    }
    const char *t = text;
    size_t tl = len;
    trim(&t, &tl);
    if (tl == 0 && h->nfields > 1) {
        set_column_field(err, h, 0);
        set_error(err, line_number, "empty line (the header has %lu fields)",
                  (unsigned long)h->nfields);
        return -1;
    }

    size_t pos = 0;
    size_t k = 0;
    field_t f;
    for (;;) {
        split_t s = next_field(text, len, &pos, &f);
        if (s == SPLIT_END) {
            break;
        }
        if (k >= h->nfields) {
            set_column_field(err, h, k);
            set_error(err, line_number, "too many fields (the header has %lu)",
                      (unsigned long)h->nfields);
            return -1;
        }
        if (s != SPLIT_OK) {
            set_column_field(err, h, k);
            set_split_error(err, line_number, s);
            return -1;
        }
        int c = h->column_of[k];
        if (c >= 0) {
            fields[c].text = f.start;
            fields[c].len = f.len;
            const char *why = ht_parse_number(f.start, f.len, &values[c]);
            if (why != NULL) {
                char shown[40];
                show_text(f.start, f.len, shown, sizeof shown);
                set_column_field(err, h, k);
                if (strcmp(why, "empty field") == 0) {
                    set_error(err, line_number, "%s", why);
                } else {
                    set_error(err, line_number, "%s: \"%s\"", why, shown);
                }
                return -1;
            }
        }
        k++;
    }
    if (k < h->nfields) {
        set_column_field(err, h, k);
        set_error(err, line_number, "missing field (the row has %lu fields, the header %lu)",
                  (unsigned long)k, (unsigned long)h->nfields);
        return -1;
    }
    return 0;
}
