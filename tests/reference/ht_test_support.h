/*
 * ht_test_support.h - what the control-law tests share: a seeded RNG, the
 * gain sets the sweeps run, conversions to fixed point, and an error tracker
 * that reports the worst error of an output in LSB.
 */
#ifndef HT_TEST_SUPPORT_H
#define HT_TEST_SUPPORT_H

#include <stdint.h>

#include "helical/law/helical_turn.h"
#include "ht_reference.h"

/* splitmix64: small, fast, and the same sequence on every platform. */
uint64_t ts_rng_next(uint64_t *state);
double ts_uniform(uint64_t *state, double lo, double hi);
double ts_gaussian(uint64_t *state);

/* Round a real to a fixed-point format with 2^frac_bits = 1.0, clamped to int16. */
int16_t ts_fix16(double v, int frac_bits);
int32_t ts_fix32(double v, int frac_bits);

/* Distance (real units) under which a branch decision of the spec is a tie
 * that may go either way; the core's branch quantities are exact to a few
 * Q28 LSB. */
#define TS_BRANCH_EPS 1e-4

/* 1 when a step lies within TS_BRANCH_EPS of a branch boundary of the spec
 * (tilt limit, roll beyond 90 degrees and its sign, pitch beyond 90 degrees
 * and its sign): the one skip rule of every comparison with the reference. */
int ts_on_branch_boundary(const ht_ref_output_t *r, const ht_ref_params_t *p);

/* A named parameter set. */
typedef struct {
    const char *name;
    ht_params_t params;
} ts_gain_set_t;

extern const ts_gain_set_t ts_gain_sets[];
extern const int ts_gain_set_count;

/* The worst error of one output over a sweep, in LSB of its format. */
typedef struct {
    const char *name;
    double lsb;   /* the value of one LSB in real units */
    double worst; /* worst |core - reference| in LSB */
    long samples;
} ts_err_t;

void ts_err_add(ts_err_t *e, double core_real, double ref_real);

/* Every output of one step, core vs reference: index order of ts_output_names. */
enum { TS_N_OUTPUTS = 16 };
extern const char *const ts_output_names[TS_N_OUTPUTS];
void ts_errs_init(ts_err_t errs[TS_N_OUTPUTS]);
void ts_errs_add_step(ts_err_t errs[TS_N_OUTPUTS], const ht_output_t *core,
                      const ht_ref_output_t *ref);
void ts_errs_print(const char *title, const ts_err_t errs[TS_N_OUTPUTS]);

/* The defaults with the same kp, kff and kd (Q16) on every axis and the
 * given airspeeds, schedule, tilt limit and pitch method: the sweeps' sets. */
ht_params_t ts_gains3(q16_t kp, q16_t kff, q16_t kd, int32_t v_ref, int32_t v_min, uint8_t schedule,
                      q16_t max_tilt, uint8_t pitch_mode);

#endif
