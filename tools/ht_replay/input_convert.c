/* input_convert.c - real CSV values to ht_input_t; see input_convert.h. */
#include "input_convert.h"

#include <stdint.h>
#include <string.h>

#include "number.h"

/* How one column is stored in ht_input_t. */
typedef struct {
    unsigned long scale;
    long lo, hi;
    const char *format; /* for the message */
} col_format_t;

static const col_format_t q14_fmt = {16384u, INT16_MIN, INT16_MAX, "Q14, [-2, 1.99994]"};
static const col_format_t q11_fmt = {2048u, INT16_MIN, INT16_MAX, "Q11 rad/s, [-16, 15.9995]"};
static const col_format_t q16_fmt = {65536u, INT32_MIN, INT32_MAX, "Q16, [-32768, 32767.99998]"};
static const col_format_t q11_accel_fmt = {2048u, INT16_MIN, INT16_MAX,
                                           "Q11 rad/s^2, [-16, 15.9995]"};
static const col_format_t q14_g_fmt = {16384u, INT16_MIN, INT16_MAX, "Q14 g, [-2, 1.99994]"};
static const col_format_t cm_fmt = {100u, INT16_MIN, INT16_MAX,
                                    "int16 cm/s, [-327.68, 327.67] m/s"};

static void set_column(ht_csv_error_t *err, unsigned long line, ht_csv_col_t c)
{
    err->line = line;
    (void)snprintf(err->column, sizeof err->column, "%s", ht_csv_col_name(c));
}

int ht_replay_to_input(const ht_csv_field_t fields[HT_COL_COUNT], unsigned long line_number,
                       ht_input_t *in, ht_csv_error_t *err)
{
    /* The real values, for the messages and the flag (the CSV reader has
     * already checked the grammar; this is not the conversion). */
    double values[HT_COL_COUNT];
    for (int c = 0; c < (int)HT_COL_COUNT; c++) {
        const char *why = ht_parse_number(fields[c].text, fields[c].len, &values[c]);
        if (why != NULL) {
            set_column(err, line_number, (ht_csv_col_t)c);
            (void)snprintf(err->message, sizeof err->message, "%s", why);
            return -1;
        }
    }
    static const struct {
        ht_csv_col_t col;
        const col_format_t *fmt;
    } plan[] = {
        {HT_COL_X, &q14_fmt},           {HT_COL_Y, &q14_fmt},
        {HT_COL_Z, &q14_fmt},           {HT_COL_TURN_RATE, &q11_fmt},
        {HT_COL_PITCH, &q16_fmt},       {HT_COL_AIRSPEED, &cm_fmt},
        {HT_COL_GYRO_X, &q11_fmt},      {HT_COL_GYRO_Y, &q11_fmt},
        {HT_COL_GYRO_Z, &q11_fmt},      {HT_COL_TURN_ACCEL, &q11_accel_fmt},
        {HT_COL_ACCEL_LAT, &q14_g_fmt},
    };
    long fixed[HT_COL_COUNT] = {0};
    for (size_t i = 0; i < sizeof plan / sizeof plan[0]; i++) {
        ht_csv_col_t c = plan[i].col;
        const col_format_t *f = plan[i].fmt;
        if (ht_decimal_round(fields[c].text, fields[c].len, f->scale, f->lo, f->hi, &fixed[c]) !=
            0) {
            set_column(err, line_number, c);
            (void)snprintf(err->message, sizeof err->message,
                           "%.10g does not fit the core's format (%s)", values[c], f->format);
            return -1;
        }
    }
    /* A flag, not a quantity: 0.4 or 2 is more likely a wrong column than a
     * value to round. */
    double inv = values[HT_COL_INVERTED];
    if (inv != 0.0 && inv != 1.0) {
        set_column(err, line_number, HT_COL_INVERTED);
        (void)snprintf(err->message, sizeof err->message, "%.10g is not 0 or 1", inv);
        return -1;
    }

    memset(in, 0, sizeof *in);
    in->x = (q14_t)fixed[HT_COL_X];
    in->y = (q14_t)fixed[HT_COL_Y];
    in->z = (q14_t)fixed[HT_COL_Z];
    in->turn_rate_rad_s = (q11_t)fixed[HT_COL_TURN_RATE];
    in->pitch_ratio = (q16_t)fixed[HT_COL_PITCH];
    in->airspeed_cm_s = (int16_t)fixed[HT_COL_AIRSPEED];
    in->gyro_rad_s[0] = (q11_t)fixed[HT_COL_GYRO_X];
    in->gyro_rad_s[1] = (q11_t)fixed[HT_COL_GYRO_Y];
    in->gyro_rad_s[2] = (q11_t)fixed[HT_COL_GYRO_Z];
    in->inverted = inv != 0.0 ? 1u : 0u;
    in->turn_accel_rad_s2 = (q11_t)fixed[HT_COL_TURN_ACCEL];
    in->accel_lat_g = (q14_t)fixed[HT_COL_ACCEL_LAT];
    return 0;
}
