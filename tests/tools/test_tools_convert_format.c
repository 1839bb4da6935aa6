/*
 * Unit tests of ht_replay's unit conversions: a CSV row's real values to
 * ht_input_t (tools/ht_replay/input_convert.c), with the out-of-range errors,
 * and ht_output_t back to text (format.c).
 */
#include <string.h>

#include "format.h"
#include "input_convert.h"
#include "unity.h"

static ht_csv_error_t err;

void setUp(void)
{
    memset(&err, 0, sizeof err);
}

void tearDown(void) {}

static void set(ht_csv_field_t v[HT_COL_COUNT], ht_csv_col_t c, const char *text)
{
    v[c].text = text;
    v[c].len = strlen(text);
}

/* A typical row: the fields' texts indexed by ht_csv_col_t. */
static void typical(ht_csv_field_t v[HT_COL_COUNT])
{
    set(v, HT_COL_X, "0.1");
    set(v, HT_COL_Y, "-0.25");
    set(v, HT_COL_Z, "0.995");
    set(v, HT_COL_TURN_RATE, "0.5");
    set(v, HT_COL_PITCH, "0.2");
    set(v, HT_COL_AIRSPEED, "15");
    set(v, HT_COL_GYRO_X, "-1.0");
    set(v, HT_COL_GYRO_Y, "0.001");
    set(v, HT_COL_GYRO_Z, "15.9995");
    set(v, HT_COL_INVERTED, "1");
    /* the optional columns as the reader gives them when a file lacks them */
    set(v, HT_COL_TURN_ACCEL, "0");
    set(v, HT_COL_ACCEL_LAT, "0");
}

static void test_row_to_input_exact_integers(void)
{
    ht_csv_field_t v[HT_COL_COUNT];
    typical(v);
    ht_input_t in;
    TEST_ASSERT_EQUAL_INT(0, ht_replay_to_input(v, 2, &in, &err));
    TEST_ASSERT_EQUAL_INT16(1638, in.x); /* 1638.4 */
    TEST_ASSERT_EQUAL_INT16(-4096, in.y);
    TEST_ASSERT_EQUAL_INT16(16302, in.z); /* 16302.08 */
    TEST_ASSERT_EQUAL_INT16(1024, in.turn_rate_rad_s);
    TEST_ASSERT_EQUAL_INT32(13107, in.pitch_ratio); /* 13107.2 */
    TEST_ASSERT_EQUAL_INT16(1500, in.airspeed_cm_s);
    TEST_ASSERT_EQUAL_INT16(-2048, in.gyro_rad_s[0]);
    TEST_ASSERT_EQUAL_INT16(2, in.gyro_rad_s[1]); /* 2.048 */
    TEST_ASSERT_EQUAL_INT16(32767, in.gyro_rad_s[2]);
    TEST_ASSERT_EQUAL_UINT8(1, in.inverted);
    TEST_ASSERT_EQUAL_INT16(0, in.turn_accel_rad_s2);
    TEST_ASSERT_EQUAL_INT16(0, in.accel_lat_g);
    /* the optional columns of the law's options */
    set(v, HT_COL_TURN_ACCEL, "-1.25");
    set(v, HT_COL_ACCEL_LAT, "0.1");
    TEST_ASSERT_EQUAL_INT(0, ht_replay_to_input(v, 2, &in, &err));
    TEST_ASSERT_EQUAL_INT16(-2560, in.turn_accel_rad_s2);
    TEST_ASSERT_EQUAL_INT16(1638, in.accel_lat_g); /* 1638.4 */
}

static void expect_out_of_range(ht_csv_col_t col, const char *value, const char *what)
{
    ht_csv_field_t v[HT_COL_COUNT];
    typical(v);
    set(v, col, value);
    ht_input_t in;
    setUp();
    TEST_ASSERT_EQUAL_INT(-1, ht_replay_to_input(v, 9, &in, &err));
    TEST_ASSERT_EQUAL_UINT32(9, err.line);
    TEST_ASSERT_EQUAL_STRING(ht_csv_col_name(col), err.column);
    if (strstr(err.message, what) == NULL) {
        TEST_FAIL_MESSAGE(err.message);
    }
}

static void test_values_that_do_not_fit_are_errors(void)
{
    expect_out_of_range(HT_COL_X, "3.0", "3 does not fit the core's format (Q14");
    expect_out_of_range(HT_COL_Y, "-2.0001", "Q14");
    expect_out_of_range(HT_COL_Z, "1.99997", "Q14"); /* rounds to 32768 */
    expect_out_of_range(HT_COL_TURN_RATE, "20.0", "20 does not fit the core's format (Q11");
    expect_out_of_range(HT_COL_TURN_ACCEL, "16", "16 does not fit the core's format (Q11 rad/s^2");
    expect_out_of_range(HT_COL_ACCEL_LAT, "-2.5", "-2.5 does not fit the core's format (Q14 g");
    expect_out_of_range(HT_COL_PITCH, "40000.0", "Q16");
    expect_out_of_range(HT_COL_AIRSPEED, "400.0", "int16 cm/s");
    expect_out_of_range(HT_COL_AIRSPEED, "-327.69", "int16 cm/s");
    expect_out_of_range(HT_COL_GYRO_X, "-16.001", "Q11");
    expect_out_of_range(HT_COL_GYRO_Y, "1e300", "Q11");
    expect_out_of_range(HT_COL_GYRO_Z, "16.0", "Q11");
    expect_out_of_range(HT_COL_INVERTED, "0.5", "0.5 is not 0 or 1");
    expect_out_of_range(HT_COL_INVERTED, "-1.0", "is not 0 or 1");
}

static void test_edges_that_fit(void)
{
    ht_csv_field_t v[HT_COL_COUNT];
    typical(v);
    set(v, HT_COL_X, "-2.0");
    set(v, HT_COL_AIRSPEED, "-327.68"); /* a pitot can read below zero; the core floors it */
    set(v, HT_COL_TURN_RATE, "-16.0");
    set(v, HT_COL_PITCH, "-32768.0");
    set(v, HT_COL_INVERTED, "0.0");
    ht_input_t in;
    TEST_ASSERT_EQUAL_INT(0, ht_replay_to_input(v, 2, &in, &err));
    TEST_ASSERT_EQUAL_INT16(-32768, in.x);
    TEST_ASSERT_EQUAL_INT16(-32768, in.airspeed_cm_s);
    TEST_ASSERT_EQUAL_INT16(-32768, in.turn_rate_rad_s);
    TEST_ASSERT_EQUAL_INT32(-2147483647L - 1, in.pitch_ratio);
    TEST_ASSERT_EQUAL_UINT8(0, in.inverted);
}

/* Ties in the decimal text round away from zero, exactly (README): 1.005 m/s
 * is 100.5 cm/s, not the 100.4999... a double holds. */
static void test_decimal_ties_round_away_from_zero(void)
{
    ht_csv_field_t v[HT_COL_COUNT];
    typical(v);
    set(v, HT_COL_AIRSPEED, "1.005");
    set(v, HT_COL_X, "-0.000030517578125");        /* half a Q14 step */
    set(v, HT_COL_TURN_RATE, "0.000244140625");    /* half a Q11 step */
    set(v, HT_COL_PITCH, "1.0000076293945312500"); /* 65536.5 / 65536 */
    ht_input_t in;
    TEST_ASSERT_EQUAL_INT(0, ht_replay_to_input(v, 2, &in, &err));
    TEST_ASSERT_EQUAL_INT16(101, in.airspeed_cm_s);
    TEST_ASSERT_EQUAL_INT16(-1, in.x);
    TEST_ASSERT_EQUAL_INT16(1, in.turn_rate_rad_s);
    TEST_ASSERT_EQUAL_INT32(65537, in.pitch_ratio);
    set(v, HT_COL_AIRSPEED, "-1.00499999999999999999");
    TEST_ASSERT_EQUAL_INT(0, ht_replay_to_input(v, 2, &in, &err));
    TEST_ASSERT_EQUAL_INT16(-100, in.airspeed_cm_s);
}

static void test_fixed_to_real(void)
{
    TEST_ASSERT_EQUAL_DOUBLE(1.0, ht_q14_to_real(16384));
    TEST_ASSERT_EQUAL_DOUBLE(-2.0, ht_q14_to_real(-32768));
    TEST_ASSERT_EQUAL_DOUBLE(1.0 / 16384.0, ht_q14_to_real(1));
    TEST_ASSERT_EQUAL_DOUBLE(0.5, ht_q11_to_real(1024));
    TEST_ASSERT_EQUAL_DOUBLE(-16.0, ht_q11_to_real(-32768));
    TEST_ASSERT_EQUAL_DOUBLE(4.0, ht_q16_to_real(262144));
}

static void read_back(FILE *f, char *text, size_t size)
{
    rewind(f);
    size_t n = fread(text, 1, size - 1, f);
    text[n] = '\0';
    (void)fclose(f);
}

static void test_header_and_row_text(void)
{
    FILE *f = tmpfile();
    TEST_ASSERT_NOT_NULL(f);
    ht_format_header(f);
    char text[1024];
    read_back(f, text, sizeof text);
    TEST_ASSERT_EQUAL_STRING("turn_rate_used,tilt_x,tilt_y,tilt_z,rate_x,rate_y,rate_z,roll_dot,"
                             "roll_cross,roll_error,pitch_error,pitch_body_x,pitch_body_z,aileron,"
                             "elevator,rudder,tilt_ratio,flags\n",
                             text);

    ht_output_t o;
    memset(&o, 0, sizeof o);
    o.turn_rate_used_rad_s = 1024; /* 0.5 */
    o.tilt_x = -9953;              /* -0.60748291015625 */
    o.tilt_y = 1;                  /* one LSB: 0.00006103515625 */
    o.tilt_z = 16384;
    o.rate_x_rad_s = -1; /* -0.00048828125 */
    o.rate_y_rad_s = 32767;
    o.rate_z_rad_s = -32768;
    o.roll_dot = 13014;
    o.roll_cross = -9953;
    o.roll_error = -16384;
    o.pitch_error = -3213;
    o.pitch_body_x = 3213;
    o.pitch_body_z = -1;
    o.aileron = 16384;
    o.elevator = -16384;
    o.rudder = 0;
    o.tilt_ratio = 50121; /* 0.7647857666015625 */
    o.flags = 0x25;
    f = tmpfile();
    TEST_ASSERT_NOT_NULL(f);
    ht_format_row(f, &o);
    read_back(f, text, sizeof text);
    TEST_ASSERT_EQUAL_STRING("0.500000,-0.607483,0.000061,1.000000,-0.000488,15.999512,-16.000000,"
                             "0.794312,-0.607483,-1.000000,-0.196106,0.196106,-0.000061,1.000000,"
                             "-1.000000,0.000000,0.764786,37\n",
                             text);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_row_to_input_exact_integers);
    RUN_TEST(test_values_that_do_not_fit_are_errors);
    RUN_TEST(test_edges_that_fit);
    RUN_TEST(test_decimal_ties_round_away_from_zero);
    RUN_TEST(test_fixed_to_real);
    RUN_TEST(test_header_and_row_text);
    return UNITY_END();
}
