/*
 * ht_replay - run the Q14 helical-turn core on a CSV of inputs.
 *
 *   ht_replay [--param NAME=VALUE]... < in.csv > out.csv
 *
 * This file does the arguments and the loop; the CSV reading, the unit
 * conversions and the printing live in their own files (see README.md).
 * Rows are independent steps, so each is converted, stepped and printed as it
 * is read: memory does not grow with the input, and a bad row stops the run
 * at once with everything before it already printed.
 */
#include <stdio.h>
#include <string.h>

#include "csv_reader.h"
#include "format.h"
#include "helical/law/helical_turn.h"
#include "input_convert.h"
#include "log_replay.h"
#include "param_parse.h"

/* Exit statuses (documented in --help and README.md). */
enum {
    EXIT_OK = 0,
    EXIT_BAD_INPUT = 1, /* the CSV: a bad field, row or header */
    EXIT_USAGE = 2,     /* the command line: an option or a parameter */
    EXIT_IO = 3         /* reading, writing or memory */
};

static void usage(FILE *out)
{
    static const ht_params_t defaults = HT_PARAMS_DEFAULT;
    (void)fputs("usage: ht_replay [--param NAME=VALUE]... < in.csv > out.csv\n"
                "       ht_replay --log FLIGHT.bin\n"
                "       ht_replay --help\n"
                "\n"
                "--log: replay a flight log (DataFlash .bin, docs/flight-log.md): each HTIN\n"
                "record's law inputs through ht_step, with the law parameters of its PARM\n"
                "records, compared with the logged HTO outputs bit for bit. Exit 0: all\n"
                "equal; 1: the first difference (or an unreadable log), named; 3: read error.\n"
                "\n"
                "Runs the Q14 helical-turn control law (docs/control-law.md) once per input row.\n"
                "Rows are independent steps; nothing is carried from one row to the next.\n"
                "\n"
                "Input: a header line, then one row per step. Columns in any order, other\n"
                "columns ignored, each of these exactly once (decimal numbers):\n"
                "  x, y, z      DCM bottom row, unitless   -> Q14, fits [-2, 1.99994]\n"
                "  turn_rate    rad/s, + = right turn      -> Q11, fits [-16, 15.9995]\n"
                "  pitch        climb ratio, + = climb     -> Q16, fits [-32768, 32767.99998]\n"
                "  airspeed     m/s                        -> int16 cm/s, fits [-327.68, 327.67]\n"
                "  gyro_x, gyro_y, gyro_z  rad/s           -> Q11, fits [-16, 15.9995]\n"
                "  inverted     0 or 1\n"
                "and optionally, for the law's options (0 when the column is absent):\n"
                "  turn_accel   rad/s^2, rate of change of the turn command (roll_in)\n"
                "                                          -> Q11, fits [-16, 15.9995]\n"
                "  accel_lat    g, lateral specific force, + = left wing (kp_sideslip)\n"
                "                                          -> Q14, fits [-2, 1.99994]\n"
                "Values are rounded to the nearest LSB from their decimal digits, exactly,\n"
                "halves away from zero. A value that does not fit its format\n"
                "is an error, not a clamp. A number is at most 400 characters. Lines end in\n"
                "LF or CRLF and are at most 1 MiB; a field may be quoted.\n"
                "\n"
                "Output: a header, then per row: turn_rate_used, tilt_x, tilt_y, tilt_z,\n"
                "rate_x, rate_y, rate_z, roll_dot, roll_cross, roll_error, pitch_error,\n"
                "pitch_body_x, pitch_body_z, aileron, elevator, rudder (units as above;\n"
                "surfaces in [-1, 1]), tilt_ratio and flags (HT_F_* bits: 1 airspeed floored,\n"
                "2 tilt limited, 4 roll beyond 90, 8 pitch beyond 90, 16 fuselage vertical,\n"
                "32 surface saturated), six decimals each.\n"
                "\n"
                "Parameters (--param NAME=VALUE or --param=NAME=VALUE; repeatable, last wins).\n"
                "Names, units and defaults (the table include/helical/params.def):\n",
                out);
    ht_param_print_table(out, &defaults);
    (void)fputs("ht_init decides the allowed ranges: each field's own (the same table),\n"
                "and v_min <= v_ref <= 32 v_min, per axis kff * v_ref / v_min + kd * s_p,max\n"
                "<= 512 (docs/control-law.md):\n",
                out);
    ht_param_print_ranges(out);
    (void)fputs("\n"
                "Errors go to stderr as \"ht_replay: line N, column NAME: what\" (the header\n"
                "is line 1); rows before the bad one have already been printed.\n"
                "Exit status: 0 success, 1 bad input (empty input, missing or duplicate\n"
                "column, empty/non-numeric/non-finite/out-of-range field, short or long row,\n"
                "line over 1 MiB), 2 bad command line or parameter, 3 read/write/memory error.\n",
                out);
}

static int fail_csv(const ht_csv_error_t *err)
{
    char buf[320];
    ht_csv_error_format(err, buf, sizeof buf);
    (void)fprintf(stderr, "ht_replay: %s\n", buf);
    /* Errors without a column are the reader's own (read error, memory). */
    return err->column[0] != '\0' ? EXIT_BAD_INPUT : EXIT_IO;
}

/* Parse the command line into *params, keeping the text of each value given
 * (the last one wins) in given[]; returns EXIT_OK, or the exit status (with
 * *stop set for --help, which succeeds without running). */
static int parse_args(int argc, char **argv, ht_params_t *params, const char *given[HT_P_COUNT],
                      int *stop)
{
    *stop = 0;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        const char *spec = NULL;
        if (strcmp(a, "--help") == 0 || strcmp(a, "-h") == 0) {
            usage(stdout);
            *stop = 1;
            /* A help text that did not reach its reader is a failure
             * (`ht_replay --help > /dev/full`), like any other output. */
            if (fflush(stdout) != 0 || ferror(stdout)) {
                (void)fprintf(stderr, "ht_replay: error writing the help text\n");
                return EXIT_IO;
            }
            return EXIT_OK;
        } else if (strcmp(a, "--param") == 0) {
            if (i + 1 >= argc) {
                (void)fprintf(stderr, "ht_replay: --param needs NAME=VALUE\n");
                return EXIT_USAGE;
            }
            spec = argv[++i];
        } else if (strncmp(a, "--param=", 8) == 0) {
            spec = a + 8;
        } else {
            (void)fprintf(stderr,
                          "ht_replay: unknown argument \"%s\" (input is read from standard "
                          "input; see --help)\n",
                          a);
            return EXIT_USAGE;
        }
        char msg[256];
        ht_param_id_t id = HT_P_NONE;
        if (ht_param_parse(params, spec, &id, msg, sizeof msg) != 0) {
            (void)fprintf(stderr, "ht_replay: %s\n", msg);
            return EXIT_USAGE;
        }
        given[id] = strchr(spec, '=') + 1; /* parsed: the '=' is there */
    }
    return EXIT_OK;
}

static int run(const ht_controller_t *ctl)
{
    ht_csv_line_t line = HT_CSV_LINE_INIT;
    ht_csv_header_t header = HT_CSV_HEADER_INIT;
    ht_csv_error_t err;
    int status = EXIT_OK;

    if (ht_csv_read_header(stdin, &line, &header, &err) != 0) {
        ht_csv_line_free(&line);
        return fail_csv(&err);
    }
    ht_format_header(stdout);
    for (;;) {
        ht_csv_line_status_t s = ht_csv_read_line(stdin, &line, &header, &err);
        if (s == HT_CSV_LINE_EOF) {
            break;
        }
        double values[HT_COL_COUNT];
        ht_csv_field_t fields[HT_COL_COUNT];
        ht_input_t in;
        if (s == HT_CSV_LINE_ERR ||
            ht_csv_parse_row_fields(&header, line.text, line.len, line.number, values, fields,
                                    &err) != 0 ||
            ht_replay_to_input(fields, line.number, &in, &err) != 0) {
            status = fail_csv(&err);
            break;
        }
        ht_output_t out;
        ht_step(ctl, &in, &out);
        ht_format_row(stdout, &out);
        if (ferror(stdout)) {
            break; /* reported below */
        }
    }
    ht_csv_header_free(&header);
    ht_csv_line_free(&line);
    return status;
}

int main(int argc, char **argv)
{
    if ((argc == 3) && (strcmp(argv[1], "--log") == 0)) {
        return ht_log_replay(argv[2], stdout, stderr);
    }
    ht_params_t params = HT_PARAMS_DEFAULT;
    const char *given[HT_P_COUNT] = {NULL};
    int stop = 0;
    int status = parse_args(argc, argv, &params, given, &stop);
    if (status != EXIT_OK || stop) {
        return status;
    }

    ht_controller_t ctl;
    ht_param_id_t bad = HT_P_NONE;
    ht_status_t st = ht_init(&ctl, &params, &bad);
    if (st != HT_OK) {
        /* The core is the one authority on ranges; the tool reports its verdict
         * with the value in --param units, and says when it was a default. */
        const char *name = ht_param_name(bad);
        int known = (int)bad > (int)HT_P_NONE && (int)bad < (int)HT_P_COUNT;
        const char *as_given = known ? given[bad] : NULL;
        /* The value as the user wrote it (64.00001 is refused, and "64" would
         * not say why); a default in --param units. */
        char value[HT_PARAM_SHOWN_MAX];
        if (as_given != NULL) {
            ht_param_show_text(as_given, value, sizeof value);
        } else {
            (void)ht_param_format_value(&params, bad, value, sizeof value);
        }
        char range[96];
        (void)ht_param_format_range(bad, range, sizeof range);
        (void)fprintf(stderr,
                      "ht_replay: parameter %s=%s%s: refused by ht_init (outside the range the "
                      "law allows: %s, and the joint limits; see --help)\n",
                      name[0] != '\0' ? name : "(unknown)", value,
                      known && as_given == NULL ? " (the default)" : "", range);
        return EXIT_USAGE;
    }

    status = run(&ctl);
    if (fflush(stdout) != 0 || ferror(stdout)) {
        (void)fprintf(stderr, "ht_replay: error writing the output\n");
        return EXIT_IO;
    }
    return status;
}
