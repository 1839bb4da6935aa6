/*
 * bench_common.c - the benchmark's configuration (see bench_common.h).
 *
 * Parameters: a realistic, fully-used law, so that every term costs what it
 * costs in flight: kp aileron/elevator/rudder = 2.0/2.5/1.0, kff = 0.5 each,
 * kd = 0.15/0.2/0.1, v_ref 15 m/s, v_min 5 m/s, airspeed schedule on,
 * max_tilt 4, earth-frame pitch. Output stage: a conventional airframe of
 * five channels (aileron, a second mirrored aileron, elevator, rudder,
 * throttle) with the default centres, travels and end points.
 */
#include "bench_common.h"

#include <stddef.h>

ht_controller_t bench_ctl;
ht_output_t bench_out;
uint16_t bench_pulses[8];
law_q14_ctl_t bench_q14_ctl;
law_q14_output_t bench_q14_out;

#define KP_A 2.0
#define KP_E 2.5
#define KP_R 1.0
#define KFF  0.5
#define KD_A 0.15
#define KD_E 0.2
#define KD_R 0.1

/* Body axis order: X = elevator, Y = aileron, Z = rudder gains. */
const law_params_f32_t bench_law_params_f32 = {{(float)KP_E, (float)KP_A, (float)KP_R},
                                               {(float)KFF, (float)KFF, (float)KFF},
                                               {(float)KD_E, (float)KD_A, (float)KD_R},
                                               15.0f,
                                               5.0f,
                                               4.0f,
                                               1};

const law_params_f64_t bench_law_params_f64 = {
    {KP_E, KP_A, KP_R}, {KFF, KFF, KFF}, {KD_E, KD_A, KD_R}, 15.0, 5.0, 4.0, 1, 0};

/* c172p scheduled, in the same body-axis order (elevator, aileron, rudder). */
const law_params_f64_t bench_law_params_f64_c172p = {
    {6.0, 3.0, 0.3}, {1.0, 0.0, 0.5}, {1.0, 0.5, 1.0}, 50.0, 10.0, 4.0, 1, 0};

#if BENCH_HAVE_OS
os_config_t bench_os_cfg;
#endif

int32_t bench_setup_c172p(ht_controller_t *ctl, law_q14_ctl_t *q14)
{
    ht_params_t p = HT_PARAMS_DEFAULT;
    p.kp_aileron = Q16_FROM_REAL(3.0);
    p.kp_elevator = Q16_FROM_REAL(6.0);
    p.kp_rudder = Q16_FROM_REAL(0.3);
    p.kff_aileron = 0;
    p.kff_elevator = Q16_FROM_REAL(1.0);
    p.kff_rudder = Q16_FROM_REAL(0.5);
    p.kd_aileron = Q16_FROM_REAL(0.5);
    p.kd_elevator = Q16_FROM_REAL(1.0);
    p.kd_rudder = Q16_FROM_REAL(1.0);
    p.v_ref_cm_s = 5000;
    p.v_min_cm_s = 1000;
    p.schedule = 1u;
    p.max_tilt = 4 * Q16_ONE;
    p.pitch_mode = (uint8_t)HT_PITCH_EARTH_FRAME;
    if (ht_init(ctl, &p, NULL) != HT_OK) {
        return 1;
    }
    return law_q14_init(q14, &p);
}

int32_t bench_setup(void)
{
    ht_params_t p = HT_PARAMS_DEFAULT;
    p.kp_aileron = Q16_FROM_REAL(KP_A);
    p.kp_elevator = Q16_FROM_REAL(KP_E);
    p.kp_rudder = Q16_FROM_REAL(KP_R);
    p.kff_aileron = Q16_FROM_REAL(KFF);
    p.kff_elevator = Q16_FROM_REAL(KFF);
    p.kff_rudder = Q16_FROM_REAL(KFF);
    p.kd_aileron = Q16_FROM_REAL(KD_A);
    p.kd_elevator = Q16_FROM_REAL(KD_E);
    p.kd_rudder = Q16_FROM_REAL(KD_R);
    p.v_ref_cm_s = 1500;
    p.v_min_cm_s = 500;
    p.schedule = 1u;
    p.max_tilt = 4 * Q16_ONE;
    p.pitch_mode = (uint8_t)HT_PITCH_EARTH_FRAME;
#if defined(BENCH_OPTIONS) && BENCH_OPTIONS
    /* bench.py --options: every option of docs/control-law.md "Extensions
     * beyond the seed" on, to measure what they cost */
    p.roll_in = 1u;
    p.roll_in_rate_max_rad_s = 2 * Q16_ONE;
    p.kp_sideslip = Q16_FROM_REAL(1.0);
    p.vertical_fade = Q16_FROM_REAL(0.1);
#endif
    if (ht_init(&bench_ctl, &p, NULL) != HT_OK) {
        return 1;
    }
    if (law_q14_init(&bench_q14_ctl, &p) != 0) {
        return 3;
    }
#if BENCH_HAVE_OS
    static const uint8_t functions[5] = {(uint8_t)OS_FN_AILERON, (uint8_t)OS_FN_AILERON2,
                                         (uint8_t)OS_FN_ELEVATOR, (uint8_t)OS_FN_RUDDER,
                                         (uint8_t)OS_FN_THROTTLE};
    bench_os_cfg.count = 5u;
    for (uint8_t i = 0; i < 5u; i++) {
        os_channel_default(&bench_os_cfg.ch[i], functions[i]);
    }
    bench_os_cfg.ch[1].reversed = 1u;
    if (os_config_check(&bench_os_cfg, NULL) != OS_OK) {
        return 2;
    }
#endif
    return 0;
}

void bench_step_output(const ht_input_t *in)
{
    ht_step(&bench_ctl, in, &bench_out);
#if BENCH_HAVE_OS
    const os_command_t cmd = {bench_out.aileron, bench_out.elevator, bench_out.rudder,
                              BENCH_THROTTLE_Q14};
    (void)os_compute(&bench_os_cfg, &cmd, bench_pulses);
#endif
}

void bench_step_output_q14(const ht_input_t *in)
{
    law_step_q14(&bench_q14_ctl, in, &bench_q14_out);
#if BENCH_HAVE_OS
    const os_command_t cmd = {bench_q14_out.aileron, bench_q14_out.elevator, bench_q14_out.rudder,
                              BENCH_THROTTLE_Q14};
    (void)os_compute(&bench_os_cfg, &cmd, bench_pulses);
#endif
}
