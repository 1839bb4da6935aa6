/*
 * libFuzzer target: arbitrary bytes as ht_replay's input. The header parser
 * and the row parser must either accept or fail with a message that names a
 * line (>= 1) and a column; an accepted row's values are finite; the same
 * bytes give the same answer twice; nothing crashes or leaks.
 */
#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "csv_reader.h"

static void check(int ok)
{
    if (!ok) {
        abort();
    }
}

/* Parse text (header line, then rows split at '\n'); 0 if all rows parse. */
static int parse_all(const char *text, size_t len, double *sum, ht_csv_error_t *err)
{
    const char *nl = memchr(text, '\n', len);
    size_t hlen = nl ? (size_t)(nl - text) : len;
    ht_csv_header_t h = HT_CSV_HEADER_INIT;
    if (ht_csv_parse_header(text, hlen, &h, err) != 0) {
        return -1;
    }
    int rc = 0;
    unsigned long line = 1;
    size_t pos = nl ? hlen + 1 : len;
    while (pos < len && rc == 0) {
        const char *start = text + pos;
        const char *end = memchr(start, '\n', len - pos);
        size_t rlen = end ? (size_t)(end - start) : len - pos;
        double values[HT_COL_COUNT];
        line++;
        if (ht_csv_parse_row(&h, start, rlen, line, values, err) != 0) {
            rc = -1;
        } else {
            for (int i = 0; i < HT_COL_COUNT; i++) {
                check(isfinite(values[i]));
                *sum += values[i];
            }
        }
        pos += rlen + 1;
    }
    ht_csv_header_free(&h);
    return rc;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    const char *text = (const char *)data;
    double s1 = 0, s2 = 0;
    ht_csv_error_t e1, e2;
    memset(&e1, 0, sizeof e1);
    memset(&e2, 0, sizeof e2);
    int r1 = parse_all(text, size, &s1, &e1);
    int r2 = parse_all(text, size, &s2, &e2);
    check(r1 == r2);
    if (r1 != 0) {
        check(e1.line >= 1u && e1.message[0] != '\0');
        check(e1.line == e2.line && strcmp(e1.column, e2.column) == 0);
        char buf[256];
        ht_csv_error_format(&e1, buf, sizeof buf);
        check(strstr(buf, "line ") != NULL);
    } else {
        check(s1 == s2 || (isnan(s1) && isnan(s2)));
    }
    return 0;
}
