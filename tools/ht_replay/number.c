/* number.c - strict decimal number parsing; see number.h. */
#include "number.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Longest number text handed to strtod. Longer fields are refused rather than
 * cut: 400 characters is far beyond any value a log writes (a double has 17
 * significant digits), and the fixed buffer keeps this function free of
 * allocation. */
#define HT_NUMBER_MAX_TEXT 400

static int is_blank(char c)
{
    return c == ' ' || c == '\t';
}

static int is_digit(char c)
{
    return c >= '0' && c <= '9';
}

/* Case-insensitive compare of text[0..len) with a lower-case word. */
static int equals_word(const char *text, size_t len, const char *word)
{
    size_t n = strlen(word);
    if (len != n) {
        return 0;
    }
    for (size_t i = 0; i < n; i++) {
        char c = text[i];
        if (c >= 'A' && c <= 'Z') {
            c = (char)(c - 'A' + 'a');
        }
        if (c != word[i]) {
            return 0;
        }
    }
    return 1;
}

/* The spellings of NaN and infinity that strtod and printf produce, so that
 * they get the precise message rather than "not a number". */
static int is_non_finite_word(const char *text, size_t len)
{
    if (len > 0 && (text[0] == '+' || text[0] == '-')) {
        text++;
        len--;
    }
    return equals_word(text, len, "nan") || equals_word(text, len, "inf") ||
           equals_word(text, len, "infinity");
}

/* Length of the longest prefix of text[0..len) matching the grammar of
 * number.h (without blanks), or 0 if there is none. */
static size_t match_decimal(const char *text, size_t len)
{
    size_t i = 0;
    size_t int_digits = 0;
    size_t frac_digits = 0;
    if (i < len && (text[i] == '+' || text[i] == '-')) {
        i++;
    }
    while (i < len && is_digit(text[i])) {
        i++;
        int_digits++;
    }
    if (i < len && text[i] == '.') {
        i++;
        while (i < len && is_digit(text[i])) {
            i++;
            frac_digits++;
        }
    }
    if (int_digits == 0 && frac_digits == 0) {
        return 0;
    }
    if (i < len && (text[i] == 'e' || text[i] == 'E')) {
        size_t j = i + 1;
        size_t exp_digits = 0;
        if (j < len && (text[j] == '+' || text[j] == '-')) {
            j++;
        }
        while (j < len && is_digit(text[j])) {
            j++;
            exp_digits++;
        }
        if (exp_digits == 0) {
            return 0; /* "1e" or "1e+": a broken exponent is not a number */
        }
        i = j;
    }
    return i;
}

const char *ht_parse_number(const char *text, size_t len, double *out)
{
    while (len > 0 && is_blank(text[0])) {
        text++;
        len--;
    }
    while (len > 0 && is_blank(text[len - 1])) {
        len--;
    }
    if (len == 0) {
        return "empty field";
    }
    if (is_non_finite_word(text, len)) {
        return "not finite";
    }
    if (match_decimal(text, len) != len) {
        return "not a number";
    }
    if (len > HT_NUMBER_MAX_TEXT) {
        return "number text too long";
    }

    char buf[HT_NUMBER_MAX_TEXT + 1];
    memcpy(buf, text, len);
    buf[len] = '\0';
    errno = 0;
    char *end = NULL;
    double v = strtod(buf, &end);
    if (end != buf + len) {
        return "not a number"; /* unreachable after match_decimal; kept as a guard */
    }
    if (!isfinite(v) || (errno == ERANGE && fabs(v) > 1.0)) {
        return "too large";
    }
    *out = v;
    return NULL;
}

int ht_scale_round(double v, double scale, long lo, long hi, long *out)
{
    double r = round(v * scale);
    /* Written so that a NaN fails the test and is refused. */
    if (!(r >= (double)lo && r <= (double)hi)) {
        return -1;
    }
    *out = (long)r;
    return 0;
}
