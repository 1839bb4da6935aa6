/*
 * Unit tests of ht_replay's CSV reader (tools/ht_replay/csv_reader.c) and
 * number parser (number.c): header mapping, row splitting, the line reader,
 * and the line/column of every error.
 */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "csv_reader.h"
#include "number.h"
#include "unity.h"

/* Unity 2.4 has no size_t assertion. */
#define ASSERT_SIZE(expected, actual)                                                              \
    TEST_ASSERT_EQUAL_UINT64((uint64_t)(expected), (uint64_t)(actual))

#define CANON "x,y,z,turn_rate,pitch,airspeed,gyro_x,gyro_y,gyro_z,inverted"

static ht_csv_header_t hdr;
static ht_csv_error_t err;

void setUp(void)
{
    static const ht_csv_header_t empty = HT_CSV_HEADER_INIT;
    hdr = empty;
    memset(&err, 0, sizeof err);
}

void tearDown(void)
{
    ht_csv_header_free(&hdr);
}

static int parse_header(const char *text)
{
    return ht_csv_parse_header(text, strlen(text), &hdr, &err);
}

static int parse_row(const char *text, double v[HT_COL_COUNT])
{
    return ht_csv_parse_row(&hdr, text, strlen(text), 7, v, &err);
}

/* Assert the error is at (line, column) and its message contains what. */
static void assert_error(unsigned long line, const char *column, const char *what)
{
    TEST_ASSERT_EQUAL_UINT32(line, err.line);
    TEST_ASSERT_EQUAL_STRING(column, err.column);
    if (strstr(err.message, what) == NULL) {
        TEST_FAIL_MESSAGE(err.message);
    }
}

/* A FILE holding exactly the n bytes of data, rewound. */
static FILE *file_with(const char *data, size_t n)
{
    FILE *f = tmpfile();
    TEST_ASSERT_NOT_NULL(f);
    ASSERT_SIZE(n, fwrite(data, 1, n, f));
    rewind(f);
    return f;
}

/* --- numbers ----------------------------------------------------------------- */

static const char *num(const char *s, double *v)
{
    return ht_parse_number(s, strlen(s), v);
}

static void test_number_accepts_decimal_forms(void)
{
    double v = -99.0;
    TEST_ASSERT_NULL(num("0.5", &v));
    TEST_ASSERT_EQUAL_DOUBLE(0.5, v);
    TEST_ASSERT_NULL(num("-12", &v));
    TEST_ASSERT_EQUAL_DOUBLE(-12.0, v);
    TEST_ASSERT_NULL(num("+.25", &v));
    TEST_ASSERT_EQUAL_DOUBLE(0.25, v);
    TEST_ASSERT_NULL(num("5.", &v));
    TEST_ASSERT_EQUAL_DOUBLE(5.0, v);
    TEST_ASSERT_NULL(num("1.5e-3", &v));
    TEST_ASSERT_EQUAL_DOUBLE(0.0015, v);
    TEST_ASSERT_NULL(num("2E+2", &v));
    TEST_ASSERT_EQUAL_DOUBLE(200.0, v);
    TEST_ASSERT_NULL(num(" \t-0.75\t ", &v));
    TEST_ASSERT_EQUAL_DOUBLE(-0.75, v);
    TEST_ASSERT_NULL(num("1e-400", &v)); /* underflow is harmless: rounds to 0 anyway */
    TEST_ASSERT_DOUBLE_WITHIN(1e-300, 0.0, v);
}

static void test_number_rejects_everything_else(void)
{
    double v = 42.0;
    TEST_ASSERT_EQUAL_STRING("empty field", num("", &v));
    TEST_ASSERT_EQUAL_STRING("empty field", num("  \t ", &v));
    TEST_ASSERT_EQUAL_STRING("not finite", num("nan", &v));
    TEST_ASSERT_EQUAL_STRING("not finite", num("-NaN", &v));
    TEST_ASSERT_EQUAL_STRING("not finite", num("inf", &v));
    TEST_ASSERT_EQUAL_STRING("not finite", num("+Infinity", &v));
    TEST_ASSERT_EQUAL_STRING("too large", num("1e999", &v));
    TEST_ASSERT_EQUAL_STRING("too large", num("-1e400", &v));
    static const char *const junk[] = {"abc", "0x10", "1.2.3", "1e",  "1e+", ".",   "-",
                                       "--1", "0.5x", "1 2",   "1,5", "e5",  "+-1", "0.5;"};
    for (size_t i = 0; i < sizeof junk / sizeof junk[0]; i++) {
        TEST_ASSERT_EQUAL_STRING_MESSAGE("not a number", num(junk[i], &v), junk[i]);
    }
    /* An embedded NUL is not the end of the field. */
    TEST_ASSERT_EQUAL_STRING("not a number", ht_parse_number("1\0002", 3, &v));
    TEST_ASSERT_EQUAL_DOUBLE(42.0, v); /* untouched by every failure */
}

static void test_number_too_long_text_is_refused_not_cut(void)
{
    char buf[500];
    memset(buf, '1', sizeof buf);
    double v = 0.0;
    TEST_ASSERT_EQUAL_STRING("number text longer than 400 characters",
                             ht_parse_number(buf, sizeof buf, &v));
    /* the limit itself, blanks around not counted; one more is refused */
    char edge[412];
    memset(edge, ' ', sizeof edge);
    memset(edge + 5, '0', HT_NUMBER_MAX_TEXT);
    TEST_ASSERT_NULL(ht_parse_number(edge, sizeof edge, &v));
    TEST_ASSERT_EQUAL_DOUBLE(0.0, v);
    edge[5 + HT_NUMBER_MAX_TEXT] = '1';
    TEST_ASSERT_EQUAL_STRING("number text longer than 400 characters",
                             ht_parse_number(edge, sizeof edge, &v));
}

static long dround(const char *text, unsigned long scale, long lo, long hi)
{
    long r = 123456789;
    if (ht_decimal_round(text, strlen(text), scale, lo, hi, &r) != 0) {
        TEST_ASSERT_EQUAL_INT32(123456789, r); /* untouched */
        return -999999999;
    }
    return r;
}
#define NOFIT (-999999999)

static void test_decimal_round_halves_away_and_bounds(void)
{
    /* half a Q14 step, exactly, both signs */
    TEST_ASSERT_EQUAL_INT32(1, dround("0.000030517578125", 16384, -32768, 32767));
    TEST_ASSERT_EQUAL_INT32(-1, dround("-0.000030517578125", 16384, -32768, 32767));
    TEST_ASSERT_EQUAL_INT32(0, dround("0.000030517578124999", 16384, -32768, 32767));
    TEST_ASSERT_EQUAL_INT32(-32768, dround("-2.0", 16384, -32768, 32767));
    TEST_ASSERT_EQUAL_INT32(32767, dround("1.99996", 16384, -32768, 32767));
    /* 1.99997 * 16384 = 32767.508 rounds to 32768: does not fit */
    TEST_ASSERT_EQUAL_INT32(NOFIT, dround("1.99997", 16384, -32768, 32767));
    /* the last value that fits, and the first tie that does not */
    TEST_ASSERT_EQUAL_INT32(32767, dround("1.999969482421874999999", 16384, -32768, 32767));
    TEST_ASSERT_EQUAL_INT32(NOFIT, dround("1.999969482421875", 16384, -32768, 32767));
    TEST_ASSERT_EQUAL_INT32(NOFIT, dround("-2.0001", 16384, -32768, 32767));
    TEST_ASSERT_EQUAL_INT32(NOFIT, dround("1e308", 65536, INT32_MIN, INT32_MAX));
    TEST_ASSERT_EQUAL_INT32(NOFIT, dround("1e99999999999999999999", 65536, INT32_MIN, INT32_MAX));
    TEST_ASSERT_EQUAL_INT32(0, dround("1e-99999999999999999999", 65536, INT32_MIN, INT32_MAX));
    TEST_ASSERT_EQUAL_INT32(0, dround("-0.0e5", 65536, INT32_MIN, INT32_MAX));
    /* decimal ties that a double misses (1.005 is 1.00499999999999989... in
     * binary): README, "halves away from zero" */
    TEST_ASSERT_EQUAL_INT32(101, dround("1.005", 100, INT16_MIN, INT16_MAX));
    TEST_ASSERT_EQUAL_INT32(-101, dround("-1.005", 100, INT16_MIN, INT16_MAX));
    TEST_ASSERT_EQUAL_INT32(100, dround("1.00499999999999999999999999", 100, INT16_MIN, INT16_MAX));
    TEST_ASSERT_EQUAL_INT32(32767, dround("327.674999", 100, INT16_MIN, INT16_MAX));
    TEST_ASSERT_EQUAL_INT32(NOFIT, dround("327.675", 100, INT16_MIN, INT16_MAX));
    TEST_ASSERT_EQUAL_INT32(-32768, dround("-327.68499", 100, INT16_MIN, INT16_MAX));
    TEST_ASSERT_EQUAL_INT32(NOFIT, dround("-327.685", 100, INT16_MIN, INT16_MAX));
    /* spellings: exponent, leading zeros, signs, blanks */
    TEST_ASSERT_EQUAL_INT32(101, dround(" +0.1005e1\t", 100, INT16_MIN, INT16_MAX));
    TEST_ASSERT_EQUAL_INT32(101, dround("000100.5E-2", 100, INT16_MIN, INT16_MAX));
    TEST_ASSERT_EQUAL_INT32(101, dround("10050e-4", 100, INT16_MIN, INT16_MAX));
    TEST_ASSERT_EQUAL_INT32(1500, dround("15.", 100, INT16_MIN, INT16_MAX));
    TEST_ASSERT_EQUAL_INT32(25, dround(".25", 100, INT16_MIN, INT16_MAX));
    TEST_ASSERT_EQUAL_INT32(NOFIT, dround("abc", 100, INT16_MIN, INT16_MAX));
    TEST_ASSERT_EQUAL_INT32(NOFIT, dround("", 100, INT16_MIN, INT16_MAX));
}

/* Every tie n + 1/2 of a seeded sweep, written as a decimal, and one digit
 * either side of it far down (where a double cannot see): exact answers from
 * integer arithmetic. Q14, Q11, Q16 and cm/s. */
static void test_decimal_round_seeded_ties(void)
{
    const unsigned long scales[4] = {16384, 2048, 65536, 100};
    uint64_t rng = 0x1005;
    for (int k = 0; k < 20000; k++) {
        rng = rng * 6364136223846793005u + 1442695040888963407u;
        unsigned long scale = scales[k % 4];
        long n = (long)((rng >> 33) % 60000u) - 30000; /* the tie (n + 1/2) / scale */
        /* |2n + 1| / (2 scale) by long division: 2 scale (2^a, or 200)
         * divides 10^21, so 21 decimals are exact. */
        int neg = 2 * n + 1 < 0;
        unsigned long long a = (unsigned long long)(neg ? -(2 * n + 1) : 2 * n + 1);
        unsigned long long den = 2ull * scale;
        long long ip = (long long)(a / den);
        unsigned long long r = a % den;
        const unsigned j = 21;
        char frac[32], text[64], lo[96], hi[96];
        for (unsigned i = 0; i < j; i++) {
            r *= 10u;
            frac[i] = (char)('0' + (int)(r / den));
            r %= den;
        }
        TEST_ASSERT_EQUAL_UINT64(0, r);
        frac[j] = '\0';
        (void)snprintf(text, sizeof text, "%s%lld.%s", neg ? "-" : "", ip, frac);
        (void)snprintf(lo, sizeof lo, "%s%lld.%s%s", neg ? "-" : "", ip, frac, "0000001");
        long want = neg ? n : n + 1; /* away from zero: |tie| rounds up */
        long got = 0;
        TEST_ASSERT_EQUAL_INT(0, ht_decimal_round(text, strlen(text), scale, -40000, 40000, &got));
        TEST_ASSERT_EQUAL_INT32_MESSAGE(want, got, text);
        /* a hair further from zero: same; a hair closer: the other way */
        TEST_ASSERT_EQUAL_INT(0, ht_decimal_round(lo, strlen(lo), scale, -40000, 40000, &got));
        TEST_ASSERT_EQUAL_INT32_MESSAGE(want, got, lo);
        /* the tie minus 10^-30 in magnitude: ...(digits - 1)999999999 */
        (void)snprintf(hi, sizeof hi, "%s", text);
        size_t m = strlen(hi);
        size_t p = m - 1;
        while (hi[p] == '0' || hi[p] == '.') { /* borrow */
            if (hi[p] == '0') {
                hi[p] = '9';
            }
            p--;
        }
        hi[p] = (char)(hi[p] - 1);
        (void)snprintf(hi + m, sizeof hi - m, "%s", "999999999");
        TEST_ASSERT_EQUAL_INT(0, ht_decimal_round(hi, strlen(hi), scale, -40000, 40000, &got));
        TEST_ASSERT_EQUAL_INT32_MESSAGE(neg ? n + 1 : n, got, hi);
    }
}

/* --- header ----------------------------------------------------------------- */

static void test_header_canonical_order(void)
{
    TEST_ASSERT_EQUAL_INT(0, parse_header(CANON));
    ASSERT_SIZE(10, hdr.nfields);
    for (int c = 0; c < HT_COL_REQUIRED; c++) {
        ASSERT_SIZE((size_t)c, hdr.index[c]);
        TEST_ASSERT_EQUAL_INT(c, hdr.column_of[c]);
    }
    /* the optional columns of the law's options: absent, and read as 0 */
    for (int c = HT_COL_REQUIRED; c < (int)HT_COL_COUNT; c++) {
        ASSERT_SIZE(HT_CSV_ABSENT, hdr.index[c]);
    }
    double v[HT_COL_COUNT];
    v[HT_COL_TURN_ACCEL] = v[HT_COL_ACCEL_LAT] = 7.0;
    TEST_ASSERT_EQUAL_INT(0, parse_row("0,0,1,0.5,0,15,0,0,0,0", v));
    TEST_ASSERT_EQUAL_DOUBLE(0.0, v[HT_COL_TURN_ACCEL]);
    TEST_ASSERT_EQUAL_DOUBLE(0.0, v[HT_COL_ACCEL_LAT]);
    TEST_ASSERT_EQUAL_STRING("turn_rate", hdr.names[3]);
}

/* The optional columns, in any place, once each; their fields are parsed and
 * their errors named like any column's. */
static void test_header_optional_columns(void)
{
    TEST_ASSERT_EQUAL_INT(0, parse_header("accel_lat," CANON ",turn_accel"));
    ASSERT_SIZE(0, hdr.index[HT_COL_ACCEL_LAT]);
    ASSERT_SIZE(11, hdr.index[HT_COL_TURN_ACCEL]);
    double v[HT_COL_COUNT];
    TEST_ASSERT_EQUAL_INT(0, parse_row("-0.25,0,0,1,0.5,0,15,0,0,0,0,1.5", v));
    TEST_ASSERT_EQUAL_DOUBLE(-0.25, v[HT_COL_ACCEL_LAT]);
    TEST_ASSERT_EQUAL_DOUBLE(1.5, v[HT_COL_TURN_ACCEL]);
    TEST_ASSERT_EQUAL_INT(-1, parse_row("-0.25,0,0,1,0.5,0,15,0,0,0,0,fast", v));
    assert_error(7, "turn_accel", "not a number: \"fast\"");
    ht_csv_header_free(&hdr);
    TEST_ASSERT_EQUAL_INT(-1, parse_header(CANON ",accel_lat,accel_lat"));
    assert_error(1, "accel_lat", "appears twice (fields 11 and 12)");
    /* an optional column does not stand in for a required one */
    TEST_ASSERT_EQUAL_INT(-1, parse_header("x,y,z,turn_rate,pitch,airspeed,gyro_x,gyro_y,gyro_z,"
                                           "turn_accel,accel_lat"));
    assert_error(1, "inverted", "missing from the header");
}

static void test_header_any_order_extra_columns_blanks_and_quotes(void)
{
    TEST_ASSERT_EQUAL_INT(0, parse_header("time, inverted ,gyro_z,gyro_y,gyro_x,\"airspeed\","
                                          "\"note, with comma\",pitch,turn_rate,z,y,x,"));
    ASSERT_SIZE(13, hdr.nfields);
    ASSERT_SIZE(11, hdr.index[HT_COL_X]);
    ASSERT_SIZE(1, hdr.index[HT_COL_INVERTED]);
    ASSERT_SIZE(5, hdr.index[HT_COL_AIRSPEED]);
    ASSERT_SIZE(7, hdr.index[HT_COL_PITCH]);
    TEST_ASSERT_EQUAL_INT(-1, hdr.column_of[0]);
    TEST_ASSERT_EQUAL_INT(-1, hdr.column_of[6]);
    TEST_ASSERT_EQUAL_INT(-1, hdr.column_of[12]);
    TEST_ASSERT_EQUAL_STRING("note, with comma", hdr.names[6]);
    TEST_ASSERT_EQUAL_STRING("", hdr.names[12]);
}

static void test_header_unprintable_name_in_message(void)
{
    TEST_ASSERT_EQUAL_INT(-1, parse_header(CANON ",h\xc3\xb6he\x1b,h\xc3\xb6he\x1b,x"));
    assert_error(1, "x", "appears twice (fields 1 and 13)");
    TEST_ASSERT_EQUAL_INT(0, parse_header(CANON ",\"h\xc3\xb6he\x1b\""));
    double v[HT_COL_COUNT];
    TEST_ASSERT_EQUAL_INT(-1, ht_csv_parse_row(&hdr, "0,0,1,0,0,15,0,0,0,0", 20, 2, v, &err));
    assert_error(2, "h??he?", "missing field");
}

static void test_header_names_are_case_sensitive(void)
{
    TEST_ASSERT_EQUAL_INT(-1, parse_header("X,y,z,turn_rate,pitch,airspeed,gyro_x,gyro_y,gyro_z,"
                                           "inverted"));
    assert_error(1, "x", "missing from the header");
    TEST_ASSERT_NULL(hdr.names); /* nothing left to free */
}

static void test_header_missing_column_named(void)
{
    TEST_ASSERT_EQUAL_INT(-1,
                          parse_header("x,y,z,turn_rate,pitch,airspeed,gyro_x,gyro_z,inverted"));
    assert_error(1, "gyro_y", "missing from the header");
}

static void test_header_duplicate_column_named(void)
{
    TEST_ASSERT_EQUAL_INT(-1, parse_header(CANON ",pitch"));
    assert_error(1, "pitch", "appears twice (fields 5 and 11)");
}

static void test_header_broken_quote(void)
{
    TEST_ASSERT_EQUAL_INT(-1, parse_header("x,y,\"z,turn_rate"));
    assert_error(1, "#3", "unterminated quote");
    TEST_ASSERT_EQUAL_INT(-1, parse_header("x,\"y\"z,z"));
    assert_error(1, "#2", "text after the closing quote");
}

static void test_header_cr_only_line_endings(void)
{
    TEST_ASSERT_EQUAL_INT(-1, parse_header(CANON "\r0,0,1,0.5,0,15,0,0,0,0\r"));
    assert_error(1, "#10", "carriage return inside the line");
}

static void test_header_empty_line_misses_x(void)
{
    TEST_ASSERT_EQUAL_INT(-1, parse_header(""));
    assert_error(1, "x", "missing from the header");
}

/* --- rows ------------------------------------------------------------------- */

static void test_row_values_land_in_their_columns(void)
{
    TEST_ASSERT_EQUAL_INT(0, parse_header("t,inverted,gyro_z,gyro_y,gyro_x,airspeed,pitch,"
                                          "turn_rate,z,y,x,comment"));
    double v[HT_COL_COUNT];
    TEST_ASSERT_EQUAL_INT(0, parse_row("12:00:01,1,-0.3,0.2,0.1,15.5,0.25,-0.5, 0.995 ,\"0.1\",0,"
                                       "\"any text, even \"\"quoted\"\"\"",
                                       v));
    TEST_ASSERT_EQUAL_DOUBLE(0.0, v[HT_COL_X]);
    TEST_ASSERT_EQUAL_DOUBLE(0.1, v[HT_COL_Y]);
    TEST_ASSERT_EQUAL_DOUBLE(0.995, v[HT_COL_Z]);
    TEST_ASSERT_EQUAL_DOUBLE(-0.5, v[HT_COL_TURN_RATE]);
    TEST_ASSERT_EQUAL_DOUBLE(0.25, v[HT_COL_PITCH]);
    TEST_ASSERT_EQUAL_DOUBLE(15.5, v[HT_COL_AIRSPEED]);
    TEST_ASSERT_EQUAL_DOUBLE(0.1, v[HT_COL_GYRO_X]);
    TEST_ASSERT_EQUAL_DOUBLE(0.2, v[HT_COL_GYRO_Y]);
    TEST_ASSERT_EQUAL_DOUBLE(-0.3, v[HT_COL_GYRO_Z]);
    TEST_ASSERT_EQUAL_DOUBLE(1.0, v[HT_COL_INVERTED]);
}

static void test_row_short_names_first_missing_column(void)
{
    TEST_ASSERT_EQUAL_INT(0, parse_header(CANON));
    double v[HT_COL_COUNT];
    TEST_ASSERT_EQUAL_INT(-1, parse_row("0,0,1,0.5,0,15,0", v));
    assert_error(7, "gyro_y", "missing field (the row has 7 fields, the header 10)");
}

static void test_row_too_many_fields(void)
{
    TEST_ASSERT_EQUAL_INT(0, parse_header(CANON));
    double v[HT_COL_COUNT];
    TEST_ASSERT_EQUAL_INT(-1, parse_row("0,0,1,0.5,0,15,0,0,0,0,9", v));
    assert_error(7, "#11", "too many fields (the header has 10)");
    /* A trailing comma is an eleventh, empty field. */
    TEST_ASSERT_EQUAL_INT(-1, parse_row("0,0,1,0.5,0,15,0,0,0,0,", v));
    assert_error(7, "#11", "too many fields");
}

static void test_row_bad_fields_name_their_column(void)
{
    TEST_ASSERT_EQUAL_INT(0, parse_header(CANON));
    double v[HT_COL_COUNT];
    TEST_ASSERT_EQUAL_INT(-1, parse_row("0,0,1,0.5,0,15,,0,0,0", v));
    assert_error(7, "gyro_x", "empty field");
    TEST_ASSERT_EQUAL_INT(-1, parse_row("0,0,1,0.5,NaN,15,0,0,0,0", v));
    assert_error(7, "pitch", "not finite: \"NaN\"");
    TEST_ASSERT_EQUAL_INT(-1, parse_row("0,0,1,inf,0,15,0,0,0,0", v));
    assert_error(7, "turn_rate", "not finite");
    TEST_ASSERT_EQUAL_INT(-1, parse_row("0,0,1,0.5,0,fast,0,0,0,0", v));
    assert_error(7, "airspeed", "not a number: \"fast\"");
    TEST_ASSERT_EQUAL_INT(-1, parse_row("0,0,1,0.5,0,15,0,0,0,1e999", v));
    assert_error(7, "inverted", "too large");
    /* The first problem from the left wins. */
    TEST_ASSERT_EQUAL_INT(-1, parse_row("a,0,1,0.5,0,15,0,0,0", v));
    assert_error(7, "x", "not a number");
}

static void test_row_field_text_is_cleaned_and_cut_in_messages(void)
{
    TEST_ASSERT_EQUAL_INT(0, parse_header(CANON));
    double v[HT_COL_COUNT];
    const char row[] = "0,\x1b[31m,1,0.5,0,15,0,0,0,0";
    TEST_ASSERT_EQUAL_INT(-1, parse_row(row, v));
    assert_error(7, "y", "not a number: \"?[31m\"");
    /* Bytes outside printable ASCII (here UTF-8 "é") are shown as '?'. */
    TEST_ASSERT_EQUAL_INT(-1, parse_row("0,0,\xc3\xa9,0.5,0,15,0,0,0,0", v));
    assert_error(7, "z", "not a number: \"??\"");
    char big[200];
    memset(big, 'q', sizeof big);
    memcpy(big, "0,0,1,", 6);
    big[sizeof big - 1] = '\0';
    TEST_ASSERT_EQUAL_INT(-1, parse_row(big, v));
    assert_error(7, "turn_rate", "qqq...\"");
    TEST_ASSERT_TRUE(strlen(err.message) < sizeof err.message - 1);
}

static void test_row_embedded_nul_is_an_error(void)
{
    TEST_ASSERT_EQUAL_INT(0, parse_header(CANON));
    double v[HT_COL_COUNT];
    static const char row[] = "0,0,1,0.5\0001,0,15,0,0,0,0";
    TEST_ASSERT_EQUAL_INT(-1, ht_csv_parse_row(&hdr, row, sizeof row - 1, 3, v, &err));
    assert_error(3, "turn_rate", "not a number");
}

static void test_row_empty_line(void)
{
    TEST_ASSERT_EQUAL_INT(0, parse_header("id," CANON));
    double v[HT_COL_COUNT];
    TEST_ASSERT_EQUAL_INT(-1, parse_row("", v));
    assert_error(7, "id", "empty line (the header has 11 fields)");
    TEST_ASSERT_EQUAL_INT(-1, parse_row(" \t", v));
    assert_error(7, "id", "empty line");
}

static void test_row_unnamed_extra_column_gets_its_number(void)
{
    TEST_ASSERT_EQUAL_INT(0, parse_header(CANON ","));
    double v[HT_COL_COUNT];
    TEST_ASSERT_EQUAL_INT(-1, parse_row("0,0,1,0.5,0,15,0,0,0,0,\"open", v));
    assert_error(7, "#11", "unterminated quote");
    TEST_ASSERT_EQUAL_INT(0, parse_row("0,0,1,0.5,0,15,0,0,0,0,anything", v));
}

/* --- lines ------------------------------------------------------------------ */

static void test_lines_lf_crlf_and_no_final_newline(void)
{
    static const char data[] = "a,b\r\n\nc\r\nlast";
    FILE *f = file_with(data, sizeof data - 1);
    ht_csv_line_t line = HT_CSV_LINE_INIT;
    TEST_ASSERT_EQUAL_INT(HT_CSV_LINE_OK, ht_csv_read_line(f, &line, NULL, &err));
    TEST_ASSERT_EQUAL_STRING("a,b", line.text);
    ASSERT_SIZE(3, line.len);
    TEST_ASSERT_EQUAL_UINT32(1, line.number);
    TEST_ASSERT_EQUAL_INT(HT_CSV_LINE_OK, ht_csv_read_line(f, &line, NULL, &err));
    ASSERT_SIZE(0, line.len);
    TEST_ASSERT_EQUAL_STRING("", line.text);
    TEST_ASSERT_EQUAL_INT(HT_CSV_LINE_OK, ht_csv_read_line(f, &line, NULL, &err));
    TEST_ASSERT_EQUAL_STRING("c", line.text);
    TEST_ASSERT_EQUAL_INT(HT_CSV_LINE_OK, ht_csv_read_line(f, &line, NULL, &err));
    TEST_ASSERT_EQUAL_STRING("last", line.text);
    TEST_ASSERT_EQUAL_UINT32(4, line.number);
    TEST_ASSERT_EQUAL_INT(HT_CSV_LINE_EOF, ht_csv_read_line(f, &line, NULL, &err));
    TEST_ASSERT_EQUAL_INT(HT_CSV_LINE_EOF, ht_csv_read_line(f, &line, NULL, &err));
    ht_csv_line_free(&line);
    (void)fclose(f);
}

static void test_lines_final_newline_adds_no_line(void)
{
    FILE *f = file_with("one\n", 4);
    ht_csv_line_t line = HT_CSV_LINE_INIT;
    TEST_ASSERT_EQUAL_INT(HT_CSV_LINE_OK, ht_csv_read_line(f, &line, NULL, &err));
    TEST_ASSERT_EQUAL_INT(HT_CSV_LINE_EOF, ht_csv_read_line(f, &line, NULL, &err));
    TEST_ASSERT_EQUAL_UINT32(1, line.number);
    ht_csv_line_free(&line);
    (void)fclose(f);
}

static void test_lines_limit_is_exact_and_errors_name_the_column(void)
{
    /* Exactly the limit, ended by CRLF: accepted whole. */
    size_t n = HT_CSV_MAX_LINE;
    char *data = malloc(n + 64);
    TEST_ASSERT_NOT_NULL(data);
    memset(data, '7', n);
    memcpy(data + n, "\r\n", 2);
    FILE *f = file_with(data, n + 2);
    ht_csv_line_t line = HT_CSV_LINE_INIT;
    TEST_ASSERT_EQUAL_INT(HT_CSV_LINE_OK, ht_csv_read_line(f, &line, NULL, &err));
    ASSERT_SIZE(n, line.len);
    TEST_ASSERT_EQUAL_INT(HT_CSV_LINE_EOF, ht_csv_read_line(f, &line, NULL, &err));
    (void)fclose(f);

    /* One byte more (no line ending): refused, with the field in progress. */
    TEST_ASSERT_EQUAL_INT(0, parse_header(CANON));
    memcpy(data, "0,0,", 4);
    data[n] = '8';
    f = file_with(data, n + 1);
    line.number = 4;
    TEST_ASSERT_EQUAL_INT(HT_CSV_LINE_ERR, ht_csv_read_line(f, &line, &hdr, &err));
    assert_error(5, "z", "line longer than 1048576 bytes");
    (void)fclose(f);
    ht_csv_line_free(&line);
    free(data);
}

static void test_read_header_empty_input_and_bom(void)
{
    ht_csv_line_t line = HT_CSV_LINE_INIT;
    FILE *f = file_with("", 0);
    TEST_ASSERT_EQUAL_INT(-1, ht_csv_read_header(f, &line, &hdr, &err));
    assert_error(1, "x", "empty input, no header line");
    (void)fclose(f);

    static const char bom[] = "\xEF\xBB\xBF" CANON "\r\n";
    f = file_with(bom, sizeof bom - 1);
    TEST_ASSERT_EQUAL_INT(0, ht_csv_read_header(f, &line, &hdr, &err));
    ASSERT_SIZE(0, hdr.index[HT_COL_X]);
    TEST_ASSERT_EQUAL_STRING("x", hdr.names[0]);
    (void)fclose(f);
    ht_csv_line_free(&line);
}

static void test_error_format(void)
{
    ht_csv_error_t e = {12, "gyro_z", "not finite: \"nan\""};
    char buf[100];
    ht_csv_error_format(&e, buf, sizeof buf);
    TEST_ASSERT_EQUAL_STRING("line 12, column gyro_z: not finite: \"nan\"", buf);
    ht_csv_error_t io = {3, "", "read error"};
    ht_csv_error_format(&io, buf, sizeof buf);
    TEST_ASSERT_EQUAL_STRING("line 3: read error", buf);
    ht_csv_error_format(&e, buf, 8);
    TEST_ASSERT_EQUAL_STRING("line 12", buf);
}

static void test_column_names(void)
{
    TEST_ASSERT_EQUAL_STRING("x", ht_csv_col_name(HT_COL_X));
    TEST_ASSERT_EQUAL_STRING("turn_rate", ht_csv_col_name(HT_COL_TURN_RATE));
    TEST_ASSERT_EQUAL_STRING("inverted", ht_csv_col_name(HT_COL_INVERTED));
    TEST_ASSERT_EQUAL_STRING("turn_accel", ht_csv_col_name(HT_COL_TURN_ACCEL));
    TEST_ASSERT_EQUAL_STRING("accel_lat", ht_csv_col_name(HT_COL_ACCEL_LAT));
    TEST_ASSERT_EQUAL_STRING("", ht_csv_col_name(HT_COL_COUNT));
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_number_accepts_decimal_forms);
    RUN_TEST(test_number_rejects_everything_else);
    RUN_TEST(test_number_too_long_text_is_refused_not_cut);
    RUN_TEST(test_decimal_round_halves_away_and_bounds);
    RUN_TEST(test_decimal_round_seeded_ties);
    RUN_TEST(test_header_canonical_order);
    RUN_TEST(test_header_optional_columns);
    RUN_TEST(test_header_any_order_extra_columns_blanks_and_quotes);
    RUN_TEST(test_header_unprintable_name_in_message);
    RUN_TEST(test_header_names_are_case_sensitive);
    RUN_TEST(test_header_missing_column_named);
    RUN_TEST(test_header_duplicate_column_named);
    RUN_TEST(test_header_broken_quote);
    RUN_TEST(test_header_empty_line_misses_x);
    RUN_TEST(test_header_cr_only_line_endings);
    RUN_TEST(test_row_values_land_in_their_columns);
    RUN_TEST(test_row_short_names_first_missing_column);
    RUN_TEST(test_row_too_many_fields);
    RUN_TEST(test_row_bad_fields_name_their_column);
    RUN_TEST(test_row_field_text_is_cleaned_and_cut_in_messages);
    RUN_TEST(test_row_embedded_nul_is_an_error);
    RUN_TEST(test_row_empty_line);
    RUN_TEST(test_row_unnamed_extra_column_gets_its_number);
    RUN_TEST(test_lines_lf_crlf_and_no_final_newline);
    RUN_TEST(test_lines_final_newline_adds_no_line);
    RUN_TEST(test_lines_limit_is_exact_and_errors_name_the_column);
    RUN_TEST(test_read_header_empty_input_and_bom);
    RUN_TEST(test_error_format);
    RUN_TEST(test_column_names);
    return UNITY_END();
}
