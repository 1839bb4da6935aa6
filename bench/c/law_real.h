/*
 * law_real.h - the helical-turn law of docs/control-law.md written the way a
 * user with a floating-point toolchain would write it, for the benchmark's
 * float/fixed comparison only (never part of the library). Generic in the
 * real type: law_f32.c and law_f64.c include it with LAW_REAL = float or
 * double. Straight from the spec: sqrt, divisions, no tricks.
 */
#ifndef BENCH_LAW_REAL_H
#define BENCH_LAW_REAL_H

#include <stdint.h>

typedef struct {
    float kp[3], kff[3], kd[3]; /* body X (elevator), Y (aileron), Z (rudder) */
    float v_ref, v_min, max_tilt;
    int32_t schedule;
} law_params_f32_t;

typedef struct {
    float x, y, z;      /* DCM bottom row */
    float turn_rate;    /* rad/s */
    float pitch;        /* vertical / horizontal airspeed */
    float airspeed;     /* m/s */
    float gyro[3];      /* rad/s */
    int32_t inverted;
} law_input_f32_t;

typedef struct {
    float aileron, elevator, rudder;
} law_output_f32_t;

typedef struct {
    double kp[3], kff[3], kd[3];
    double v_ref, v_min, max_tilt;
    int32_t schedule;
    int32_t pad_;
} law_params_f64_t;

typedef struct {
    double x, y, z;
    double turn_rate;
    double pitch;
    double airspeed;
    double gyro[3];
    int32_t inverted;
    int32_t pad_;
} law_input_f64_t;

typedef struct {
    double aileron, elevator, rudder;
} law_output_f64_t;

void law_step_f32(const law_params_f32_t *p, const law_input_f32_t *in, law_output_f32_t *out);
void law_step_f64(const law_params_f64_t *p, const law_input_f64_t *in, law_output_f64_t *out);

#endif /* BENCH_LAW_REAL_H */
