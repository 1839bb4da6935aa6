/*
 * host_bench.c - the x86-64 side of the benchmark: runs the library's step
 * over the bench's input file (packed ht_input_t records written by
 * bench/py/bench.py).
 *
 *   host_bench INPUTS dump            one line per input: every ht_output_t
 *                                     field, the pulses, the double law's
 *                                     surfaces, the 16-bit law's outputs and
 *                                     pulses (the emulator runs are checked
 *                                     against these), then the c172p set's
 *                                     surfaces of ht_step, the 16-bit and the
 *                                     double law (the accuracy table)
 *   host_bench INPUTS time step|step_os REPEATS RUNS
 *                                     RUNS lines: nanoseconds per step of one
 *                                     run of REPEATS passes over the inputs
 *   host_bench INPUTS once step|step_os
 *                                     one pass (for valgrind --tool=callgrind
 *                                     --toggle-collect)
 */
#define _POSIX_C_SOURCE 199309L
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "bench_common.h"

static int die(const char *msg, const char *arg)
{
    fprintf(stderr, "host_bench: %s%s%s\n", msg, arg ? ": " : "", arg ? arg : "");
    return 2;
}

static ht_input_t *read_inputs(const char *path, size_t *count)
{
    FILE *f = fopen(path, "rb");
    if (f == NULL) {
        return NULL;
    }
    size_t cap = 1024u, n = 0u;
    ht_input_t *v = malloc(cap * sizeof *v);
    unsigned char rec[28];
    while (v != NULL && fread(rec, 1u, sizeof rec, f) == sizeof rec) {
        if (n == cap) {
            cap *= 2u;
            ht_input_t *w = realloc(v, cap * sizeof *v);
            if (w == NULL) {
                free(v);
                v = NULL;
                break;
            }
            v = w;
        }
        /* Same little-endian packed layout as the ARM EABI struct. */
        ht_input_t in;
        memset(&in, 0, sizeof in);
        memcpy(&in.x, rec + 0, 2u);
        memcpy(&in.y, rec + 2, 2u);
        memcpy(&in.z, rec + 4, 2u);
        memcpy(&in.turn_rate_rad_s, rec + 6, 2u);
        memcpy(&in.pitch_ratio, rec + 8, 4u);
        memcpy(&in.airspeed_cm_s, rec + 12, 2u);
        memcpy(&in.gyro_rad_s[0], rec + 14, 6u);
        in.inverted = rec[20];
        memcpy(&in.turn_accel_rad_s2, rec + 22, 2u);
        memcpy(&in.accel_lat_g, rec + 24, 2u);
        v[n++] = in;
    }
    fclose(f);
    *count = n;
    return v;
}

static double now_ns(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec * 1e9 + (double)ts.tv_nsec;
}

/* The two measured workloads; noinline keeps callgrind's toggle point. */
__attribute__((noinline)) static void run_step(const ht_input_t *in)
{
    ht_step(&bench_ctl, in, &bench_out);
}

static void run_pass(const ht_input_t *v, size_t n, int with_os, unsigned *sink)
{
    for (size_t i = 0; i < n; i++) {
        if (with_os) {
            bench_step_output(&v[i]);
        } else {
            run_step(&v[i]);
        }
        *sink += (unsigned)(uint16_t)bench_out.aileron + bench_pulses[0];
    }
}

static law_input_f64_t to_f64(const ht_input_t *in)
{
    law_input_f64_t fin;
    memset(&fin, 0, sizeof fin);
    fin.x = in->x / 16384.0;
    fin.y = in->y / 16384.0;
    fin.z = in->z / 16384.0;
    fin.turn_rate = in->turn_rate_rad_s / 2048.0;
    fin.pitch = in->pitch_ratio / 65536.0;
    fin.airspeed = in->airspeed_cm_s / 100.0;
    for (unsigned k = 0; k < 3u; k++) {
        fin.gyro[k] = in->gyro_rad_s[k] / 2048.0;
    }
    fin.inverted = in->inverted ? 1 : 0;
    return fin;
}

static int dump(const ht_input_t *v, size_t n)
{
    static ht_controller_t ctl_c172p;
    static law_q14_ctl_t q14_c172p;
    if (bench_setup_c172p(&ctl_c172p, &q14_c172p) != 0) {
        return die("bench_setup_c172p failed", NULL);
    }
    for (size_t i = 0; i < n; i++) {
        bench_step_output(&v[i]);
        const ht_output_t *o = &bench_out;
        printf("%d %ld %d %d %d %d %d %d %d %d %d %d %d %d %d %d %d %u", o->turn_rate_used_rad_s,
               (long)o->tilt_ratio, o->tilt_x, o->tilt_y, o->tilt_z, o->rate_x_rad_s,
               o->rate_y_rad_s, o->rate_z_rad_s, o->roll_dot, o->roll_cross, o->roll_error,
               o->pitch_error, o->pitch_body_x, o->pitch_body_z, o->aileron, o->elevator, o->rudder,
               (unsigned)o->flags);
        for (unsigned c = 0; c < 5u; c++) {
            printf(" %u", (unsigned)bench_pulses[c]);
        }
        const law_input_f64_t fin = to_f64(&v[i]);
        law_output_f64_t fo;
        law_step_f64(&bench_law_params_f64, &fin, &fo);
        printf(" %.9f %.9f %.9f", fo.aileron, fo.elevator, fo.rudder);
        /* The 16-bit law: its outputs, then its pulses through the same
         * output stage (the emulator runs are checked against both). */
        bench_step_output_q14(&v[i]);
        const law_q14_output_t *q = &bench_q14_out;
        printf(" %d %d %d %d %d %d", q->aileron, q->elevator, q->rudder, q->tilt_x, q->tilt_y,
               q->tilt_z);
        for (unsigned c = 0; c < 5u; c++) {
            printf(" %u", (unsigned)bench_pulses[c]);
        }
        /* The c172p set: ht_step, the 16-bit law and the double law's
         * surfaces (accuracy only). */
        ht_output_t oc;
        ht_step(&ctl_c172p, &v[i], &oc);
        law_q14_output_t qc;
        law_step_q14(&q14_c172p, &v[i], &qc);
        law_step_f64(&bench_law_params_f64_c172p, &fin, &fo);
        printf(" %d %d %d %d %d %d %.9f %.9f %.9f\n", oc.aileron, oc.elevator, oc.rudder,
               qc.aileron, qc.elevator, qc.rudder, fo.aileron, fo.elevator, fo.rudder);
    }
    return 0;
}

int main(int argc, char **argv)
{
    if (argc < 3) {
        return die("usage: host_bench INPUTS dump | time step|step_os REPEATS RUNS | once "
                   "step|step_os",
                   NULL);
    }
    size_t n = 0u;
    ht_input_t *v = read_inputs(argv[1], &n);
    if (v == NULL || n == 0u) {
        return die("cannot read inputs", argv[1]);
    }
    if (bench_setup() != 0) {
        return die("bench_setup failed", NULL);
    }
    int rc = 0;
    unsigned sink = 0u;
    if (strcmp(argv[2], "dump") == 0) {
        rc = dump(v, n);
    } else if ((strcmp(argv[2], "time") == 0 && argc == 6) ||
               (strcmp(argv[2], "once") == 0 && argc == 4)) {
        int with_os = strcmp(argv[3], "step_os") == 0;
        if (!with_os && strcmp(argv[3], "step") != 0) {
            rc = die("unknown workload", argv[3]);
        } else if (argv[2][0] == 'o') {
            run_pass(v, n, with_os, &sink);
        } else {
            long repeats = strtol(argv[4], NULL, 10), runs = strtol(argv[5], NULL, 10);
            if (repeats <= 0 || runs <= 0) {
                rc = die("REPEATS and RUNS must be positive", NULL);
            }
            run_pass(v, n, with_os, &sink); /* warm-up */
            for (long r = 0; rc == 0 && r < runs; r++) {
                double t0 = now_ns();
                for (long k = 0; k < repeats; k++) {
                    run_pass(v, n, with_os, &sink);
                }
                double t1 = now_ns();
                printf("%.3f\n", (t1 - t0) / ((double)repeats * (double)n));
            }
        }
    } else {
        rc = die("bad arguments", argv[2]);
    }
    free(v);
    fprintf(stderr, "host_bench: checksum %u\n", sink);
    return rc;
}
