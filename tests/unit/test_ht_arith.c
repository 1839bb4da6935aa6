/*
 * The control law's own arithmetic (src/math/q_inline.h, used by helical_turn.c):
 * - qi_dot3 / qi_dot3_portable: three products summed exactly and rounded
 *   once (each surface's demand), against an exact __int128 reference and bit
 *   for bit against each other, for every shift in [1, 62];
 * - qi_rsqrt_norm_q30: the target tilt's and the projection's 1/sqrt, within
 *   1.5e-9 relative over every input (1 to 2^32 - 1);
 * - the whole law compiled here with HT_PORTABLE_ONLY=1 (the int32-only code
 *   of the dsPIC and the Cortex-M0: 16x16 partial products, no 64-bit
 *   multiply) gives the same bits as the library's ht_step on this host.
 */
#define HT_PORTABLE_ONLY 1

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

/* The law again, portable, under another name. */
#define ht_step ht_step_portable
#include "../../src/law/helical_turn.c"
#undef ht_step
void ht_step(const ht_controller_t *ctl, const ht_input_t *in, ht_output_t *out);

#include "ht_test_support.h"
#include "unity.h"

__extension__ typedef __int128 arith_i128;

/* The library's own build of q_inline.h (MUL64 on this host): the non-portable
 * qi_dot3 is compiled in a TU without HT_PORTABLE_ONLY, so it is tested
 * through ht_step below; here the exact reference checks the portable form,
 * and the MUL64 form is written out the same way it is in q_inline.h. */
static int32_t dot3_mul64(int32_t a0, int32_t b0, int32_t a1, int32_t b1, int32_t a2, int32_t b2,
                          unsigned shift)
{
    const int64_t half = (int64_t)((uint64_t)1u << (shift - 1u));
    int64_t p = ((int64_t)a0 * b0) + ((int64_t)a1 * b1) + ((int64_t)a2 * b2) + half;
    p >>= shift;
    return (p > INT32_MAX) ? INT32_MAX : ((p < INT32_MIN) ? INT32_MIN : (int32_t)p);
}

static int32_t dot3_exact(int32_t a0, int32_t b0, int32_t a1, int32_t b1, int32_t a2, int32_t b2,
                          unsigned shift)
{
    const arith_i128 s = (arith_i128)a0 * b0 + (arith_i128)a1 * b1 + (arith_i128)a2 * b2 +
                         ((arith_i128)1 << (shift - 1u));
    const arith_i128 d = (arith_i128)1 << shift;
    arith_i128 q = s / d; /* floor, by C division plus a correction */
    if ((s % d) != 0 && s < 0) {
        q -= 1;
    }
    return (q > INT32_MAX) ? INT32_MAX : ((q < INT32_MIN) ? INT32_MIN : (int32_t)q);
}

void setUp(void) {}
void tearDown(void) {}

/* A value of every magnitude: a random bit length, sign, and now and then an
 * edge (0, +-1, INT32_MIN, INT32_MAX, a power of two). */
static int32_t any_i32(uint64_t *rng)
{
    const uint64_t r = ts_rng_next(rng);
    switch (r & 15u) {
    case 0:
        return 0;
    case 1:
        return ((r >> 4) & 1u) ? 1 : -1;
    case 2:
        return ((r >> 4) & 1u) ? INT32_MAX : INT32_MIN;
    case 3:
        return (int32_t)((uint32_t)1u << ((r >> 4) % 31u)) * (((r >> 9) & 1u) ? 1 : -1);
    default: {
        const unsigned bits = (unsigned)((r >> 4) % 32u);
        const uint32_t mag = (uint32_t)(r >> 32) >> (31u - bits);
        return ((r >> 9) & 1u) ? -(int32_t)mag : (int32_t)mag;
    }
    }
}

static void test_dot3_exact_and_portable_same_bits(void)
{
    uint64_t rng = 0xD073u;
    long checked = 0;
    for (unsigned shift = 1u; shift <= 62u; shift++) {
        for (int k = 0; k < 40000; k++) {
            int32_t v[6];
            for (int i = 0; i < 6; i++) {
                v[i] = any_i32(&rng);
            }
            const arith_i128 sum =
                (arith_i128)v[0] * v[1] + (arith_i128)v[2] * v[3] + (arith_i128)v[4] * v[5];
            const arith_i128 lim = (arith_i128)1 << 62; /* the contract */
            if (sum > lim || sum < -lim) {
                continue;
            }
            const int32_t want = dot3_exact(v[0], v[1], v[2], v[3], v[4], v[5], shift);
            const int32_t port = qi_dot3_portable(v[0], v[1], v[2], v[3], v[4], v[5], shift);
            const int32_t wide = dot3_mul64(v[0], v[1], v[2], v[3], v[4], v[5], shift);
            if (port != want || wide != want) {
                printf("dot3 shift %u: %d*%d + %d*%d + %d*%d: exact %d portable %d mul64 %d\n",
                       shift, v[0], v[1], v[2], v[3], v[4], v[5], want, port, wide);
            }
            TEST_ASSERT_EQUAL_INT32(want, port);
            TEST_ASSERT_EQUAL_INT32(want, wide);
            checked++;
        }
        /* exact ties sgn * odd * 2^(shift-1) + d, d in {-1, 0, 1}: as
         * (sgn * odd * 2^u) * 2^v with u + v = shift - 1, v <= 30, and the
         * largest shifts as one or two products 2^30 * 2^30 */
        for (int k = 0; k < 2000; k++) {
            const int32_t sgn = (k & 1) ? -1 : 1;
            const unsigned v = (shift - 1u > 30u) ? 30u : (shift - 1u);
            const unsigned u = shift - 1u - v;
            int32_t a0, b0, a1 = 0, b1 = 0;
            if (u <= 29u) {
                const uint32_t odd = ((uint32_t)ts_rng_next(&rng) & ((1u << (30u - u)) - 1u)) | 1u;
                a0 = sgn * (int32_t)(odd << u); /* below 2^30 */
                b0 = (int32_t)(1u << v);
            } else { /* shift 61: 2^60; shift 62: 2^61 = 2 * 2^60 */
                a0 = sgn * (1 << 30);
                b0 = 1 << 30;
                a1 = (u == 31u) ? a0 : 0;
                b1 = (u == 31u) ? b0 : 0;
            }
            for (int32_t d = -1; d <= 1; d++) {
                const int32_t want = dot3_exact(a0, b0, a1, b1, d, 1, shift);
                TEST_ASSERT_EQUAL_INT32(want, qi_dot3_portable(a0, b0, a1, b1, d, 1, shift));
                TEST_ASSERT_EQUAL_INT32(want, dot3_mul64(a0, b0, a1, b1, d, 1, shift));
            }
        }
    }
    printf("qi_dot3: %ld random triples over shifts 1..62, exact\n", checked);
}

/* |y * 2^exp2 - 1/sqrt(x / 2^28)| relative, for one x. */
static double rsqrt30_rel_err(uint32_t x)
{
    const qi_rsqrt30_t r = qi_rsqrt_norm_q30(x);
    const double exact = 1.0 / sqrt((double)x / 268435456.0);
    const double y = ldexp((double)r.y_q30, r.exp2 - 30);
    TEST_ASSERT_TRUE(r.y_q30 >= (1 << 29) && r.y_q30 <= (1 << 30));
    return fabs(y - exact) / exact;
}

static void test_rsqrt_q30_accuracy(void)
{
    double worst = 0.0;
    /* [1, 4) in Q28, densely: every table cell at many points */
    for (uint32_t x = 1u << 28; x < (1u << 30); x += 997u) {
        const double e = rsqrt30_rel_err(x);
        worst = (e > worst) ? e : worst;
    }
    /* every other magnitude, 1 to 2^32 - 1 (bits dropped above 2^30) */
    uint64_t rng = 0x5A12u;
    for (int k = 0; k < 1000000; k++) {
        const unsigned bits = (unsigned)(ts_rng_next(&rng) % 32u);
        uint32_t x = (uint32_t)(ts_rng_next(&rng) >> 32) >> (31u - bits);
        x = (x == 0u) ? 1u : x;
        const double e = rsqrt30_rel_err(x);
        worst = (e > worst) ? e : worst;
    }
    printf("qi_rsqrt_norm_q30: worst relative error %.3g (2^%.2f)\n", worst, log2(worst));
    TEST_ASSERT_TRUE(worst < 1.5e-9);
}

/* Random legal parameters: the legal corners often (kp 64, the rate gain at
 * 512, scale 32), and anything legal otherwise. */
static ht_params_t arith_params(uint64_t *rng)
{
    for (;;) {
        ht_params_t p = HT_PARAMS_DEFAULT;
        q16_t *g[9] = {&p.kp_aileron,  &p.kp_elevator,  &p.kp_rudder,
                       &p.kff_aileron, &p.kff_elevator, &p.kff_rudder,
                       &p.kd_aileron,  &p.kd_elevator,  &p.kd_rudder};
        const int corner = (ts_rng_next(rng) & 1u) != 0u;
        p.v_min_cm_s = 100 + (int32_t)(ts_rng_next(rng) % 3000u);
        p.v_ref_cm_s =
            corner ? p.v_min_cm_s * 32 : p.v_min_cm_s + (int32_t)(ts_rng_next(rng) % 3000u);
        p.v_ref_cm_s = (p.v_ref_cm_s > 32767) ? 32767 : p.v_ref_cm_s;
        p.schedule = (uint8_t)(ts_rng_next(rng) & 1u);
        p.pitch_mode = (uint8_t)(ts_rng_next(rng) & 1u);
        p.max_tilt = (ts_rng_next(rng) & 1u) ? HT_MAX_TILT_LIMIT_Q16
                                             : 1 + (q16_t)(ts_rng_next(rng) % 524288u);
        const double s_max = (double)p.v_ref_cm_s / p.v_min_cm_s;
        for (int i = 0; i < 3; i++) {
            const double f = ts_uniform(rng, 0.0, 1.0);
            const double kff = 511.9 * f / s_max;
            const double kd = 511.9 * (1.0 - f) / (p.schedule ? s_max : 1.0);
            *g[i] = corner ? HT_GAIN_MAX_Q16 : (q16_t)(ts_rng_next(rng) % 4194305u);
            *g[3 + i] = (q16_t)(65536.0 * (kff > 64.0 ? 64.0 : kff));
            *g[6 + i] = (q16_t)(65536.0 * (kd > 64.0 ? 64.0 : kd));
        }
        ht_controller_t c;
        if (ht_init(&c, &p, NULL) == HT_OK) {
            return p;
        }
    }
}

static int16_t any_i16(uint64_t *rng)
{
    const uint64_t r = ts_rng_next(rng);
    switch (r & 7u) {
    case 0:
        return (int16_t)(int32_t)((r >> 8) % 41u) - 20; /* near zero */
    case 1:
        return ((r >> 8) & 1u) ? INT16_MAX : INT16_MIN;
    default:
        return (int16_t)(uint16_t)(r >> 16);
    }
}

static void test_portable_law_same_bits(void)
{
    uint64_t rng = 0x9027AB1Eu;
    long steps = 0;
    for (int set = 0; set < 400; set++) {
        const ht_params_t p = arith_params(&rng);
        ht_controller_t ctl;
        TEST_ASSERT_EQUAL_INT(HT_OK, ht_init(&ctl, &p, NULL));
        for (int k = 0; k < 1000; k++) {
            ht_input_t in;
            in.x = any_i16(&rng);
            in.y = any_i16(&rng);
            in.z = any_i16(&rng);
            in.turn_rate_rad_s = any_i16(&rng);
            const uint64_t r = ts_rng_next(&rng);
            in.pitch_ratio =
                (r & 1u) ? (int32_t)(r >> 32) : (int32_t)((r >> 32) % 1048577u) - 524288;
            in.airspeed_cm_s = any_i16(&rng);
            for (int i = 0; i < 3; i++) {
                in.gyro_rad_s[i] = any_i16(&rng);
            }
            in.inverted = (uint8_t)(ts_rng_next(&rng) & 1u);
            ht_output_t a, b;
            ht_step(&ctl, &in, &a);
            ht_step_portable(&ctl, &in, &b);
            const int16_t va[] = {
                a.turn_rate_used_rad_s, a.tilt_x,       a.tilt_y,       a.tilt_z,
                a.rate_x_rad_s,         a.rate_y_rad_s, a.rate_z_rad_s, a.roll_dot,
                a.roll_cross,           a.roll_error,   a.pitch_error,  a.pitch_body_x,
                a.pitch_body_z,         a.aileron,      a.elevator,     a.rudder};
            const int16_t vb[] = {
                b.turn_rate_used_rad_s, b.tilt_x,       b.tilt_y,       b.tilt_z,
                b.rate_x_rad_s,         b.rate_y_rad_s, b.rate_z_rad_s, b.roll_dot,
                b.roll_cross,           b.roll_error,   b.pitch_error,  b.pitch_body_x,
                b.pitch_body_z,         b.aileron,      b.elevator,     b.rudder};
            TEST_ASSERT_EQUAL_INT16_ARRAY(va, vb, sizeof va / sizeof va[0]);
            TEST_ASSERT_EQUAL_INT32(a.tilt_ratio, b.tilt_ratio);
            TEST_ASSERT_EQUAL_UINT8(a.flags, b.flags);
            steps++;
        }
    }
    printf("portable law: %ld steps, the same bits as ht_step\n", steps);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_dot3_exact_and_portable_same_bits);
    RUN_TEST(test_rsqrt_q30_accuracy);
    RUN_TEST(test_portable_law_same_bits);
    return UNITY_END();
}
