/*
 * bench_common.h - what the emulator harness (ARM) and the host timing
 * program share: the benchmark's controller, output-stage configuration and
 * the float/double law's parameters, all set to the same physical values.
 */
#ifndef BENCH_COMMON_H
#define BENCH_COMMON_H

#include <stdint.h>

#include "helical/helical_turn.h"
#include "law_real.h"

#ifndef BENCH_HAVE_OS
#define BENCH_HAVE_OS 0
#endif

#if BENCH_HAVE_OS
#include "helical/output_stage.h"
extern os_config_t bench_os_cfg;
#endif

/* The throttle command of every step + output-stage call: 0.6 in Q14. */
#define BENCH_THROTTLE_Q14 ((q14_t)9830)

extern ht_controller_t bench_ctl;
extern ht_output_t bench_out;
extern uint16_t bench_pulses[8];
extern const law_params_f32_t bench_law_params_f32;
extern const law_params_f64_t bench_law_params_f64;

/* ht_init with the bench parameters (+ the output-stage channels).
 * Returns 0 on success, a nonzero code naming what failed. */
int32_t bench_setup(void);

/* ht_step on bench_ctl, then (when the output stage builds) mix + pulses of
 * bench_os_cfg into bench_pulses. */
void bench_step_output(const ht_input_t *in);

#endif /* BENCH_COMMON_H */
