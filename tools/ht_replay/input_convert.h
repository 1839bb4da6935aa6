/*
 * input_convert.h - one parsed CSV row (real units) to the core's ht_input_t.
 *
 * Each value is scaled to its fixed-point format and rounded to the nearest
 * LSB (halves away from zero, as Q14_FROM_REAL does). A value whose rounded
 * result does not fit the format is an error naming the line and column, not
 * a clamp: a replay that quietly fed the core a different number than the log
 * holds would be silently wrong.
 *
 *   column     unit   format           range of the format (the value is
 *                                       checked after rounding to its LSB)
 *   x, y, z    1      Q14 (16384 = 1)  [-2, 1.99994]
 *   turn_rate  rad/s  Q11 (2048 = 1)   [-16, 15.9995]
 *   pitch      1      Q16 (65536 = 1)  [-32768, 32767.99998]
 *   airspeed   m/s    int16 cm/s       [-327.68, 327.67]
 *   gyro_*     rad/s  Q11 (2048 = 1)   [-16, 15.9995]
 *   inverted   0/1    uint8            exactly 0 or 1
 * and the optional columns of the law's options (0 when absent):
 *   turn_accel rad/s^2 Q11 (2048 = 1)  [-16, 15.9995]  (roll_in)
 *   accel_lat  g       Q14 (16384 = 1) [-2, 1.99994]   (kp_sideslip; + = left wing)
 */
#ifndef HT_REPLAY_INPUT_CONVERT_H
#define HT_REPLAY_INPUT_CONVERT_H

#include "csv_reader.h"
#include "helical/law/helical_turn.h"

/*
 * Convert the fields' texts (indexed by ht_csv_col_t, as
 * ht_csv_parse_row_fields gives them) into *in, each rounded exactly from its
 * decimal digits to the nearest step of its format, halves away from zero
 * (ht_decimal_round). Returns 0, or -1 with err naming line_number and the
 * first column, in the order of ht_csv_col_t, that is not a number or does
 * not fit.
 */
int ht_replay_to_input(const ht_csv_field_t fields[HT_COL_COUNT], unsigned long line_number,
                       ht_input_t *in, ht_csv_error_t *err);

#endif /* HT_REPLAY_INPUT_CONVERT_H */
