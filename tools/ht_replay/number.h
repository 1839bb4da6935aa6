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
 * where blanks are spaces and tabs. Host tool code: floating point is fine.
 */
#ifndef HT_REPLAY_NUMBER_H
#define HT_REPLAY_NUMBER_H

#include <stddef.h>

/*
 * Parse text[0..len) (not NUL-terminated; may contain NUL bytes, which are
 * rejected). On success writes *out and returns NULL; on failure returns a
 * static message saying what is wrong ("empty field", "not a number",
 * "not finite", "too large") and leaves *out unchanged. Values too small to
 * represent become 0 or a subnormal, which is not an error (they round to 0
 * in every fixed-point format anyway).
 */
const char *ht_parse_number(const char *text, size_t len, double *out);

/*
 * Round v * scale to the nearest integer (halves away from zero, as the
 * Q*_FROM_REAL macros do) and store it in *out if it lies in [lo, hi].
 * Returns 0, or -1 with *out unchanged (also for a NaN or an overflow to
 * infinity). lo and hi must be exact in a double (|x| <= 2^53).
 */
int ht_scale_round(double v, double scale, long lo, long hi, long *out);

#endif /* HT_REPLAY_NUMBER_H */
