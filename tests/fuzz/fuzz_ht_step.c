/*
 * libFuzzer target: arbitrary bytes -> a parameter set and one step's input.
 * Every parameter set that ht_init accepts and every input must give
 * surfaces in [-1, 1], a unit target tilt, the same output twice, and agree
 * with the double reference away from the spec's branch boundaries (the
 * sweep's skip rule, ts_on_branch_boundary): every angle within 1 LSB and
 * every surface within 2 LSB, the documented bounds (docs/control-law.md).
 */
#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "helical/law/helical_turn.h"
#include "ht_reference.h"
#include "ht_test_support.h"

typedef struct {
    const uint8_t *p;
    size_t n;
} bytes_t;

static uint32_t take(bytes_t *b, unsigned count)
{
    uint32_t v = 0;
    for (unsigned i = 0; i < count; i++) {
        v = (v << 8) | (b->n ? (b->n--, *b->p++) : 0u);
    }
    return v;
}

static int32_t take_i32(bytes_t *b)
{
    return (int32_t)take(b, 4);
}

static int16_t take_i16(bytes_t *b)
{
    return (int16_t)(uint16_t)take(b, 2);
}

/* A gain in [0, 64] most of the time, anything now and then; small gains
 * often, so that the rate-gain limit of ht_init passes at large scales. */
static q16_t take_gain(bytes_t *b)
{
    uint32_t raw = take(b, 4);
    if (raw & 0x80000000u) {
        return (int32_t)raw;
    }
    const uint32_t top = (raw & 0x40000000u) ? (64u * 65536u) : (16u * 65536u);
    return (q16_t)(raw % (top + 1u));
}

static void check(int ok)
{
    if (!ok) {
        abort();
    }
}

static void fuzz_params(bytes_t *b, ht_params_t *p)
{
    q16_t *gains[9] = {&p->kp_aileron,  &p->kp_elevator,  &p->kp_rudder,
                       &p->kff_aileron, &p->kff_elevator, &p->kff_rudder,
                       &p->kd_aileron,  &p->kd_elevator,  &p->kd_rudder};
    for (int i = 0; i < 9; i++) {
        *gains[i] = take_gain(b);
    }
    p->v_min_cm_s = (int32_t)(take(b, 2) % 40000u) - 1000;
    /* v_ref from v_min up to beyond the scale limit (32 v_min) */
    const int32_t span = (p->v_min_cm_s > 0) ? 33 * p->v_min_cm_s : 1000;
    p->v_ref_cm_s = p->v_min_cm_s + (int32_t)(take(b, 3) % (uint32_t)span) - 500;
    p->schedule = (uint8_t)(take(b, 1) % 3u);
    p->max_tilt = (q16_t)(take(b, 3) % (9u * 65536u)) - 1000;
    p->pitch_mode = (uint8_t)(take(b, 1) % 3u);
}

/* |core - reference| in Q14 LSB, the reference clamped to the Q14 range the
 * core documents (an unnormalized row can make a cross product exceed 2). */
static double err_q14(q14_t core, double ref)
{
    double r = ref > 32767.0 / 16384.0 ? 32767.0 / 16384.0 : (ref < -2.0 ? -2.0 : ref);
    return fabs(core / 16384.0 - r) * 16384.0;
}

/* The law's options (docs/control-law.md "Extensions beyond the seed"),
 * their parameters and inputs from the bytes after the step's (a corpus file
 * from before them keeps its meaning and flies them off). */
static void fuzz_options(bytes_t *b, ht_params_t *p, ht_input_t *in)
{
    p->roll_in = (uint8_t)(take(b, 1) % 3u);
    p->roll_in_rate_max_rad_s = (q16_t)(take(b, 3) % (9u * 65536u)) - 1000;
    p->kp_sideslip = take_gain(b);
    p->vertical_fade = (q16_t)(take(b, 3) % (2u * 65536u)) - 1000;
    in->turn_accel_rad_s2 = take_i16(b);
    in->accel_lat_g = take_i16(b);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    bytes_t b = {data, size};
    ht_params_t params = HT_PARAMS_DEFAULT;
    fuzz_params(&b, &params);
    ht_input_t in;
    memset(&in, 0, sizeof in);
    in.x = take_i16(&b);
    in.y = take_i16(&b);
    in.z = take_i16(&b);
    in.turn_rate_rad_s = take_i16(&b);
    in.pitch_ratio = take_i32(&b);
    in.airspeed_cm_s = take_i16(&b);
    for (int i = 0; i < 3; i++) {
        in.gyro_rad_s[i] = take_i16(&b);
    }
    in.inverted = (uint8_t)take(&b, 1);
    fuzz_options(&b, &params, &in);

    ht_controller_t ctl;
    ht_param_id_t bad = HT_P_NONE;
    ht_status_t st = ht_init(&ctl, &params, &bad);
    if (st != HT_OK) {
        /* a refusal always names a field, and the controller gives zeros */
        check(st == HT_ERR_PARAM && bad != HT_P_NONE && ht_param_name(bad)[0] != '\0');
        check(ctl.ready == 0u);
        return 0;
    }

    ht_output_t o1, o2;
    ht_step(&ctl, &in, &o1);
    ht_step(&ctl, &in, &o2);
    check(o1.aileron == o2.aileron && o1.elevator == o2.elevator && o1.rudder == o2.rudder &&
          o1.flags == o2.flags && o1.pitch_error == o2.pitch_error);
    check(o1.aileron >= -16384 && o1.aileron <= 16384);
    check(o1.elevator >= -16384 && o1.elevator <= 16384);
    check(o1.rudder >= -16384 && o1.rudder <= 16384);
    double n = sqrt((double)o1.tilt_x * o1.tilt_x + (double)o1.tilt_y * o1.tilt_y +
                    (double)o1.tilt_z * o1.tilt_z);
    check(fabs(n - 16384.0) <= 3.0);

    /* Against the reference, for every legal parameter set: the bounds the
     * sweep holds the core to (angles 1 LSB, surfaces 2 LSB). */
    ht_ref_params_t rp;
    ht_ref_input_t ri;
    ht_ref_output_t ro;
    ht_ref_params_from_controller(&ctl, &rp);
    ht_ref_input_from_fixed(&in, &ri);
    ht_ref_step(&rp, &ri, &ro);
    if (!ts_on_branch_boundary(&ro, &rp)) {
        check(err_q14(o1.aileron, ro.aileron) <= 2.0);
        check(err_q14(o1.elevator, ro.elevator) <= 2.0);
        check(err_q14(o1.rudder, ro.rudder) <= 2.0);
        check(err_q14(o1.roll_dot, ro.roll_dot) <= 1.0);
        check(err_q14(o1.roll_cross, ro.roll_cross) <= 1.0);
        check(err_q14(o1.pitch_error, ro.pitch_error) <= 1.0);
        check(err_q14(o1.roll_error, ro.roll_error) <= 1.0);
        check(err_q14(o1.pitch_body_x, ro.pitch_body_x) <= 1.0);
        check(err_q14(o1.pitch_body_z, ro.pitch_body_z) <= 1.0);
        check(err_q14(o1.tilt_x, ro.tilt[0]) <= 1.0);
        check(err_q14(o1.tilt_y, ro.tilt[1]) <= 1.0);
        check(err_q14(o1.tilt_z, ro.tilt[2]) <= 1.0);
        check(err_q14(o1.roll_fade, ro.roll_fade) <= 1.0);
        check(fabs(o1.roll_in_rate_rad_s / 2048.0 - ro.roll_in_rate) * 2048.0 <= 0.51);
    }
    return 0;
}
