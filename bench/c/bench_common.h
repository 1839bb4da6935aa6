/*
 * bench_common.h - what the emulator harness (ARM) and the host timing
 * program share: the benchmark's controller, output-stage configuration and
 * the float/double law's parameters, all set to the same physical values.
 */
#ifndef BENCH_COMMON_H
#define BENCH_COMMON_H

#include <stdint.h>

#include "helical/law/helical_turn.h"
#include "law_q14.h"
#include "law_real.h"

#ifndef BENCH_HAVE_OS
#define BENCH_HAVE_OS 0
#endif

#if BENCH_HAVE_OS
#include "helical/output/output_stage.h"
extern os_config_t bench_os_cfg;
#endif

/* The throttle command of every step + output-stage call: 0.6 in Q14. */
#define BENCH_THROTTLE_Q14 ((q14_t)9830)

extern ht_controller_t bench_ctl;
extern ht_output_t bench_out;
extern uint16_t bench_pulses[8];
extern const law_params_f32_t bench_law_params_f32;
extern const law_params_f64_t bench_law_params_f64;

/* The 16-bit law (law_q14.c) on the same parameters, and its output. */
extern law_q14_ctl_t bench_q14_ctl;
extern law_q14_output_t bench_q14_out;

/* The high-gain set "c172p scheduled" (accuracy only, host): kp
 * aileron/elevator/rudder 3/6/0.3, kff 0/1/0.5, kd 0.5/1/1, v_ref 50 m/s,
 * v_min 10 m/s, schedule on, max_tilt 4: effective gains up to 6 * 50/10. */
extern const law_params_f64_t bench_law_params_f64_c172p;

/* ht_init with the bench parameters (+ the output-stage channels, + the
 * 16-bit law's controller). Returns 0 on success, a nonzero code naming what
 * failed. */
int32_t bench_setup(void);

/* ht_init and law_q14_init with the c172p set. Returns 0 on success. */
int32_t bench_setup_c172p(ht_controller_t *ctl, law_q14_ctl_t *q14);

/* ht_step on bench_ctl, then (when the output stage builds) mix + pulses of
 * bench_os_cfg into bench_pulses. */
void bench_step_output(const ht_input_t *in);

/* The same with the 16-bit law in place of ht_step: law_step_q14 on
 * bench_q14_ctl into bench_q14_out, then the same output stage. */
void bench_step_output_q14(const ht_input_t *in);

#endif /* BENCH_COMMON_H */
