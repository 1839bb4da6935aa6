/*
 * number.h - strict parsing of one decimal number for ht_replay.
 *
 * strtod alone accepts far more than a log column should contain ("nan",
 * "inf", hex floats, trailing junk after the number); a replay that silently
 * turned "0.5x" into 0.5 would be silently wrong. This accepts exactly:
 *
 *   [blanks] [+|-] digits [. [digits]] [(e|E) [+|-] digits] [blanks]
 *   [blanks] [+|-] . digits [(e|E) [+|-] digits] [blanks]
 *
 * where blanks are spaces and tabs, and at most HT_NUMBER_MAX_TEXT characters
 * without the blanks. Host tool code: floating point is fine.
 */
#ifndef HT_REPLAY_NUMBER_H
#define HT_REPLAY_NUMBER_H

#include <stddef.h>

/* Longest number text accepted, blanks around it not counted. A longer field
 * is refused ("number text longer than 400 characters"), never cut: 400 is far
 * beyond what a log writes (a double needs 17 significant digits), and the
 * fixed bound keeps the parsing free of allocation. */
#define HT_NUMBER_MAX_TEXT 400

/*
 * Parse text[0..len) (not NUL-terminated; may contain NUL bytes, which are
 * rejected). On success writes *out and returns NULL; on failure returns a
 * static message saying what is wrong ("empty field", "not a number",
 * "not finite", "too large", "number text longer than 400 characters") and
 * leaves *out unchanged. Values too small to
 * represent become 0 or a subnormal, which is not an error (they round to 0
 * in every fixed-point format anyway).
 */
const char *ht_parse_number(const char *text, size_t len, double *out);

/*
 * Round the decimal text[0..len) (a number ht_parse_number accepts) times
 * scale (1 <= scale <= 2^20) to the nearest integer, halves away from zero,
 * exactly: the digits are used as written, never through a double, so
 * 1.005 m/s is 100.5 cm/s and rounds to 101, and 0.00006103515625 (half a Q14
 * step) to 1. Stores the result in *out if it lies in [lo, hi] and returns 0;
 * returns -1 with *out unchanged when it does not, or when text is not such a
 * number.
 */
int ht_decimal_round(const char *text, size_t len, unsigned long scale, long lo, long hi,
                     long *out);

#endif /* HT_REPLAY_NUMBER_H */
