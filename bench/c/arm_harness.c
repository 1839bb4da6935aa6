/*
 * arm_harness.c - the emulator side of the benchmark (Cortex-M ELFs only).
 *
 * No startup code: the Python driver loads the ELF, zeroes .bss, calls
 * bench_setup once, then calls the measured functions (ht_step, the
 * primitives, bench_step_output, law_step_f32/f64, law_step_q14,
 * bench_step_output_q14) directly with their arguments in r0-r3 and
 * LR = bench_stop | 1. bench_stop is where the
 * emulation ends: a mapped address, never executed (the driver stops there),
 * a breakpoint and a branch-to-self in case it is.
 */
#include <stddef.h>
#include <stdint.h>

#include "bench_common.h"
#include "helical/math/q14.h"

__attribute__((naked, used, section(".text.bench_stop"))) void bench_stop(void)
{
    __asm__ volatile("bkpt #0\n\tb .\n");
}

/* The measured calls' memory: the driver writes the input here. */
ht_input_t bench_in;
law_input_f32_t bench_in_f32;
law_output_f32_t bench_out_f32;
law_input_f64_t bench_in_f64;
law_output_f64_t bench_out_f64;
int32_t bench_vec_in[3];
int32_t bench_vec_out[3];
q14_t bench_q14_vec[3];

/* Layout checks: the driver packs these structs itself. */
_Static_assert(sizeof(ht_input_t) == 28u, "ht_input_t layout");
_Static_assert(offsetof(ht_input_t, pitch_ratio) == 8u, "ht_input_t layout");
_Static_assert(offsetof(ht_input_t, airspeed_cm_s) == 12u, "ht_input_t layout");
_Static_assert(offsetof(ht_input_t, gyro_rad_s) == 14u, "ht_input_t layout");
_Static_assert(offsetof(ht_input_t, inverted) == 20u, "ht_input_t layout");
_Static_assert(offsetof(ht_input_t, turn_accel_rad_s2) == 22u, "ht_input_t layout");
_Static_assert(offsetof(ht_input_t, accel_lat_g) == 24u, "ht_input_t layout");
_Static_assert(sizeof(law_input_f32_t) == 40u, "law_input_f32_t layout");
_Static_assert(sizeof(law_input_f64_t) == 80u, "law_input_f64_t layout");

/* Keeps every measured library function in the link (-gc-sections). */
typedef void (*bench_fn_t)(void);
__attribute__((used))
const bench_fn_t bench_keep[] = {(bench_fn_t)ht_step,           (bench_fn_t)q14_mul,
                                 (bench_fn_t)q_mul32,           (bench_fn_t)q_mul32_fit,
                                 (bench_fn_t)q_rsqrt_norm_q28,  (bench_fn_t)q_recip_q30,
                                 (bench_fn_t)q_isqrt32,         (bench_fn_t)q_unit2_q28,
                                 (bench_fn_t)q_unit3_q28,       (bench_fn_t)q14_normalize3,
                                 (bench_fn_t)law_step_f32,      (bench_fn_t)law_step_f64,
                                 (bench_fn_t)bench_step_output, (bench_fn_t)bench_setup,
                                 (bench_fn_t)law_step_q14,      (bench_fn_t)bench_step_output_q14};

_Static_assert(offsetof(ht_output_t, tilt_ratio) == 4u, "ht_output_t layout");
_Static_assert(offsetof(ht_output_t, aileron) == 32u, "ht_output_t layout");
_Static_assert(offsetof(ht_output_t, flags) == 38u, "ht_output_t layout");
_Static_assert(offsetof(ht_output_t, roll_in_rate_rad_s) == 40u, "ht_output_t layout");
_Static_assert(sizeof(ht_output_t) == 48u, "ht_output_t layout");
_Static_assert(sizeof(law_q14_output_t) == 12u, "law_q14_output_t layout");
