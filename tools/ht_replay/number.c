/* number.c - strict decimal number parsing; see number.h. */
#include "number.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

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
        return "number text longer than 400 characters";
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

/* Strip blanks from both ends of text[0..*len). */
static const char *trim_blanks(const char *text, size_t *len)
{
    while (*len > 0 && is_blank(text[0])) {
        text++;
        (*len)--;
    }
    while (*len > 0 && is_blank(text[*len - 1])) {
        (*len)--;
    }
    return text;
}

int ht_decimal_round(const char *text, size_t len, unsigned long scale, long lo, long hi, long *out)
{
    text = trim_blanks(text, &len);
    if (len == 0 || len > HT_NUMBER_MAX_TEXT || match_decimal(text, len) != len || scale == 0 ||
        scale > (1ul << 20)) {
        return -1;
    }
    /* The value is 0.d[0]d[1]...d[n-1] * 10^point, d[0] != 0 (or n == 0). */
    unsigned char d[HT_NUMBER_MAX_TEXT];
    size_t n = 0, i = 0;
    long point = 0;
    int negative = 0;
    if (text[i] == '+' || text[i] == '-') {
        negative = text[i] == '-';
        i++;
    }
    int in_fraction = 0;
    for (; i < len && (is_digit(text[i]) || text[i] == '.'); i++) {
        if (text[i] == '.') {
            in_fraction = 1;
        } else if (n == 0 && text[i] == '0') {
            point -= in_fraction; /* a leading zero: only a fraction's moves the point */
        } else {
            d[n++] = (unsigned char)(text[i] - '0');
            point += !in_fraction;
        }
    }
    if (i < len) { /* the exponent, saturated: beyond +-100000 the answer is clear */
        i++;
        int exp_negative = text[i] == '-';
        i += (text[i] == '+' || text[i] == '-') ? 1u : 0u;
        long e = 0;
        for (; i < len; i++) {
            e = e > 100000 ? e : e * 10 + (text[i] - '0');
        }
        point += exp_negative ? -e : e;
    }

    /* floor(|v| * 2 * scale), then (that + 1) / 2 = |v| * scale rounded with
     * halves up: floor((x + 1) / 2) == floor((floor(x) + 1) / 2). */
    const unsigned long long twice = 2ull * scale;
    unsigned long long whole = 0; /* floor(|v| * twice) */
    if (n > 0 && point > 12) {
        return -1; /* |v| >= 10^12: beyond any long range asked for here */
    }
    if (n > 0 && point >= -12) { /* else |v| * twice < 10^-12 * 2^21 < 1 */
        unsigned long long int_part = 0;
        for (long k = 0; k < point; k++) {
            int_part = int_part * 10u + ((size_t)k < n ? (unsigned long long)d[k] : 0u);
        }
        /* The fraction's digits times twice, from the last digit up: the
         * carry out of the first is floor(fraction * twice), exactly. */
        unsigned long long carry = 0;
        size_t first = point > 0 ? (size_t)point : 0u;
        for (size_t k = n; k > first; k--) {
            carry = ((unsigned long long)d[k - 1] * twice + carry) / 10u;
        }
        for (long z = point; z < 0; z++) { /* the fraction's leading zeros */
            carry /= 10u;
        }
        whole = int_part * twice + carry;
    }
    long long magnitude = (long long)((whole + 1u) / 2u);
    long long q = negative ? -magnitude : magnitude;
    if (q < lo || q > hi) {
        return -1;
    }
    *out = (long)q;
    return 0;
}
