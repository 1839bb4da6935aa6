/*
 * dcm_harness.c - the estimator's side of the emulator benchmark
 * (bench/py/bench_dcm.py; Cortex-M ELFs only, no startup code).
 *
 * The driver calls dcm_bench_setup once, then per sample k
 * dcm_bench_prepare(k) (not counted: it synthesises the sample) and
 * dcm_bench_update() (counted: one ht_dcm_update), and every fifth sample
 * dcm_bench_output() (counted: one ht_dcm_output, the law's 40 Hz read at
 * 200 Hz). The flight is a deterministic, integer-only synthetic one:
 * rates that change every 0.5 s (+/-0.5 rad/s), a gravity reading with
 * +/-0.05 g of noise and, every other second, a 1.3 g pull (weight 0.4),
 * a GPS fix at 20 m/s whose course wanders, airspeed valid, and the
 * magnetometer valid while the GPS is slow - so every branch of the step
 * is taken in its flight proportion.
 *
 * Built for the host too (with dcm_host_main.c): the driver compares the
 * state after the flight with the emulated cores' bit for bit.
 */
#include <stddef.h>
#include <stdint.h>

#include "helical/estimator/dcm.h"

#ifdef __arm__
__attribute__((naked, used, section(".text.bench_stop"))) void bench_stop(void)
{
    __asm__ volatile("bkpt #0\n\tb .\n");
}
#endif

ht_dcm_t dcm_bench_d;
ht_dcm_state_t dcm_bench_s;
ht_imu_sample_t dcm_bench_imu;
ht_dcm_aiding_t dcm_bench_aid;
ht_dcm_output_t dcm_bench_out;
uint32_t dcm_bench_rng;

static int32_t rnd(int32_t half_range)
{
    dcm_bench_rng = dcm_bench_rng * 1664525u + 1013904223u;
    const uint32_t r = dcm_bench_rng >> 8; /* 24 bits */
    const int64_t span = (int64_t)half_range * 2 + 1;
    return (int32_t)(((int64_t)r * span) >> 24) - half_range;
}

int dcm_bench_setup(void)
{
    ht_dcm_params_t p;
    ht_dcm_params_default(&p);
    if (ht_dcm_init(&dcm_bench_d, &p, NULL) != 0) {
        return 1;
    }
    ht_dcm_reset(&dcm_bench_s);
    const q16_t down[3] = {0, 0, -Q16_ONE};
    dcm_bench_rng = 6u;
    return ht_dcm_align(&dcm_bench_d, &dcm_bench_s, down, 1u, 4500u);
}

void dcm_bench_prepare(uint32_t k)
{
    if (k % 100u == 0u) {
        for (unsigned i = 0u; i < 3u; i++) {
            dcm_bench_imu.gyro_rad_s[i] = rnd(Q16_ONE / 2);
        }
    }
    const int32_t pull = ((k / 200u) % 2u == 1u) ? (Q16_ONE * 3 / 10) : 0;
    dcm_bench_imu.accel_g[0] = rnd(Q16_ONE / 20);
    dcm_bench_imu.accel_g[1] = rnd(Q16_ONE / 20);
    dcm_bench_imu.accel_g[2] = -Q16_ONE - pull + rnd(Q16_ONE / 20);
    dcm_bench_aid.gps_fix = 1u;
    dcm_bench_aid.gps_fresh = (k % 40u == 0u) ? 1u : 0u;
    const int32_t slow = ((k / 200u) % 5u == 4u) ? 1 : 0; /* 1 s in 5 below min speed */
    dcm_bench_aid.vel_ned_cm_s[0] = slow ? 100 : 1400 + rnd(300);
    dcm_bench_aid.vel_ned_cm_s[1] = slow ? 50 : 1400 + rnd(300);
    dcm_bench_aid.vel_ned_cm_s[2] = rnd(100);
    dcm_bench_aid.airspeed_valid = 1u;
    dcm_bench_aid.airspeed_cm_s = 2000;
    dcm_bench_aid.mag_valid = (uint8_t)slow;
    dcm_bench_aid.mag[0] = 200;
    dcm_bench_aid.mag[1] = 150;
    dcm_bench_aid.mag[2] = 400;
    dcm_bench_aid.mag_declination_cdeg = 300;
}

void dcm_bench_update(void)
{
    ht_dcm_update(&dcm_bench_d, &dcm_bench_s, &dcm_bench_imu, &dcm_bench_aid);
}

void dcm_bench_output(void)
{
    ht_dcm_output(&dcm_bench_s, &dcm_bench_out);
}

typedef void (*dcm_bench_fn_t)(void);
__attribute__((used)) const dcm_bench_fn_t bench_dcm_keep[] = {(dcm_bench_fn_t)dcm_bench_setup,
                                                               (dcm_bench_fn_t)dcm_bench_prepare,
                                                               dcm_bench_update, dcm_bench_output};
