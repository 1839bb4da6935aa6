/*
 * dcm.c - the attitude estimator's sample step (include/helical/estimator/dcm.h):
 * propagation of the direction cosine matrix, renormalization, and the PI
 * drift correction from gravity, GPS course and magnetometer.
 *
 * Formats (docs/estimator.md has the precision argument and the measured
 * drift):
 *   R            Q30 in int32 (2^30 = 1.0): a rounding is 9.3e-10, so 10^6
 *                samples of rounding cannot move the attitude by 1e-5 rad.
 *   theta = w dt Q30 rad per sample, clamped to +/-0.5 rad per axis.
 *   bias         Q30 rad/s (bound <= 1 rad/s).
 *   errors       Q30 (sines of the attitude errors), weights Q16.
 *   rates, accel Q16 rad/s and g, as the caller gives them.
 */
#include <stddef.h>

#include "estimator/dcm_gps_accel.h"
#include "estimator/dcm_wind.h"
#include "estimator/dcm_trig.h"
#include "helical/estimator/dcm.h"
#include "math/q_inline.h"

#define Q30_ONE HT_DCM_Q30_ONE
/* The largest rotation of one sample about each axis: 0.5 rad keeps every
 * element of R + R x theta below 2 (Q30's limit) for unit rows, and is
 * 100 rad/s at 200 Hz: beyond, the first-order step is meaningless anyway. */
#define THETA_MAX_Q30 ((int32_t)0x20000000)
/* A row's squared norm outside [0.25, 2.25] (Q29) is a failure. */
#define NORM2_MIN_Q29    ((int32_t)0x08000000)
#define NORM2_MAX_Q29    ((int32_t)1207959552)
#define THREE_HALVES_Q30 ((int32_t)0x60000000) /* 3 * 2^29: (3 - n) / 2 in Q30 */
/* Velocities are clamped to +/-655 m/s before any product. */
#define V_MAX_CM_S 65535
/* 2^16 / 980.665 (cm/s^2 per g) in Q16: cm/s^2 -> g in Q16 */
#define CM_S2_TO_G_Q16_Q16 ((int32_t)4379707)
/* (65536 / 980.665) * 2^24: cm/s in Q8 to g*s in Q16 with a shift of 32. */
#define CM_S_Q8_TO_GS_Q16_Q24 ((int32_t)1121189833)
/* Alignment refuses a gravity reference below 0.5 g. */
#define ALIGN_MIN_G_Q16 ((int32_t)32768)
/* Flags that survive from one sample to the next. */
/* The integral (the bias estimate) learns only while every measured body
 * rate is within 20 deg/s (0.349 rad/s, Q16): in a roll reversal or a pull the
 * gravity reference misses the body-axis accelerations of the sideslip and
 * the angle of attack building up, and a bias is slow enough to wait for
 * the next quasi-steady second (a steady turn is 3-15 deg/s) */
#define BIAS_LEARN_RATE_MAX_Q16 ((int32_t)22876)
/* sin(10 deg) in Q30: the yaw integral learns below this heading error */
#define YAW_LEARN_MAX_Q30 ((int32_t)186453311)
/* sin(60 deg) in Q30: the wind learns while |R[2][1]| (sin pitch) is below */
#define NOSE_WIND_MAX_Q30 ((int32_t)929887697)
/* 2^31 / pi in Q30 / 2^31 = 2 / pi in Q30: rad (Q30) to a binary angle */
#define RAD_Q30_TO_BAM_Q30 ((int32_t)683565276)
#define FLAGS_KEPT         ((uint32_t)HT_DCM_F_ALIGNED | (uint32_t)HT_DCM_F_RENORM_FAILED)

static int32_t clamp32(int32_t x, int32_t lim)
{
    if (x > lim) {
        return lim;
    }
    if (x < -lim) {
        return -lim;
    }
    return x;
}

/* a x b of Q30 vectors, each component saturated. */
static void cross_q30(const int32_t a[3], const int32_t b[3], int32_t out[3])
{
    out[0] = qi_sub_sat32(qi_mul32(a[1], b[2], 30u), qi_mul32(a[2], b[1], 30u));
    out[1] = qi_sub_sat32(qi_mul32(a[2], b[0], 30u), qi_mul32(a[0], b[2], 30u));
    out[2] = qi_sub_sat32(qi_mul32(a[0], b[1], 30u), qi_mul32(a[1], b[0], 30u));
}

/* Sum of a_i * b_i / 2^shift, saturated. */
static int32_t dot_sat(const int32_t a[3], const int32_t b[3], unsigned shift)
{
    int32_t s = qi_mul32(a[0], b[0], shift);
    s = qi_add_sat32(s, qi_mul32(a[1], b[1], shift));
    return qi_add_sat32(s, qi_mul32(a[2], b[2], shift));
}

/*
 * R from a specific-force vector (gravity reference: earth-down is -f / |f|)
 * and the nose's horizontal direction (cos psi, sin psi) in Q30. Returns 1
 * without touching r when |f| < 0.5 g. Any attitude: the horizontal
 * reference is the nose, or the right wing when the nose is within 7 degrees
 * of vertical (its azimuth is then psi + 90 degrees).
 */
static int align_rows(int32_t r[3][3], const q16_t f_g[3], int32_t c_q30, int32_t s_q30)
{
    int32_t u[3];
    if (q_unit3_q28(f_g, u) == 0) {
        return 1;
    }
    const int32_t mag_q16 = dot_sat(f_g, u, 28u);
    if (mag_q16 < ALIGN_MIN_G_Q16) {
        return 1;
    }
    int32_t dn[3]; /* earth-down in body axes, Q30 */
    for (unsigned i = 0u; i < 3u; i++) {
        dn[i] = -(u[i] * 4); /* |u| <= 2^28 */
    }
    int32_t h[3];
    int32_t c = c_q30;
    int32_t s = s_q30;
    /* |horizontal nose|^2 = 1 - d1^2 < 1/64: use the right wing (-X) */
    const int32_t d1sq = qi_mul32_fit(dn[1], dn[1], 30u);
    if (Q30_ONE - d1sq < (Q30_ONE / 64)) {
        /* -X - (-X . d) d = [-1 + d0^2, d0 d1, d0 d2] */
        h[0] = qi_mul32_fit(dn[0], dn[0], 30u) - Q30_ONE;
        h[1] = qi_mul32_fit(dn[0], dn[1], 30u);
        h[2] = qi_mul32_fit(dn[0], dn[2], 30u);
        c = -s_q30; /* cos(psi + 90), sin(psi + 90) */
        s = c_q30;
    } else {
        /* Y - (Y . d) d = [-d1 d0, 1 - d1^2, -d1 d2] */
        h[0] = -qi_mul32_fit(dn[1], dn[0], 30u);
        h[1] = Q30_ONE - d1sq;
        h[2] = -qi_mul32_fit(dn[1], dn[2], 30u);
    }
    int32_t hu[3];
    (void)q_unit3_q28(h, hu); /* |h|^2 >= 1/64: never zero */
    for (unsigned i = 0u; i < 3u; i++) {
        hu[i] *= 4;
    }
    int32_t k[3];
    cross_q30(dn, hu, k); /* d x h: 90 degrees clockwise of h seen from above */
    /* north = c h - s k, east = s h + c k */
    for (unsigned i = 0u; i < 3u; i++) {
        r[0][i] = qi_mul32_fit(c, hu[i], 30u) - qi_mul32_fit(s, k[i], 30u);
        r[1][i] = qi_mul32_fit(s, hu[i], 30u) + qi_mul32_fit(c, k[i], 30u);
        r[2][i] = dn[i];
    }
    return 0;
}

static void zero3(int32_t v[3])
{
    v[0] = 0;
    v[1] = 0;
    v[2] = 0;
}

void ht_dcm_reset(ht_dcm_state_t *s)
{
    if (s == NULL) {
        return;
    }
    const ht_dcm_state_t z = {0};
    *s = z;
    s->r[0][0] = Q30_ONE;
    s->r[1][1] = Q30_ONE;
    s->r[2][2] = Q30_ONE;
}

int ht_dcm_align(const ht_dcm_t *d, ht_dcm_state_t *s, const q16_t accel_g[3],
                 uint8_t heading_valid, uint16_t heading_cdeg)
{
    if (d == NULL || s == NULL || accel_g == NULL || d->ready == 0u) {
        return 2;
    }
    const uint32_t hd = (uint32_t)heading_cdeg % 36000u;
    int32_t cd = (heading_valid != 0u) ? (int32_t)hd : 0;
    if (cd > 18000) {
        cd -= 36000;
    }
    int32_t c;
    int32_t sn;
    ht_dcm_sincos_q30(ht_dcm_cdeg_to_bam(cd), &c, &sn);
    if (align_rows(s->r, accel_g, c, sn) != 0) {
        return 1;
    }
    zero3(s->bias);
    zero3(s->omega_corr);
    s->g_filt_valid = 0u; /* the filters restart from the new attitude */
    dcm_ga_reset(&s->ga); /* its intervals were summed with the old matrix */
    const uint32_t kept = (uint32_t)s->flags & (uint32_t)HT_DCM_F_RENORM_FAILED;
    s->flags = (uint16_t)(kept | (uint32_t)HT_DCM_F_ALIGNED);
    return 0;
}

int ht_dcm_align_to(const ht_dcm_t *d, ht_dcm_state_t *s, const q14_t down_q14[3],
                    q14_t nose_north_q14, q14_t nose_east_q14)
{
    if (down_q14 == NULL) {
        return 2;
    }
    /* the specific force at rest is minus earth-down: Q14 -> Q16 */
    const q16_t f[3] = {-4 * (int32_t)down_q14[0], -4 * (int32_t)down_q14[1],
                        -4 * (int32_t)down_q14[2]};
    const uint8_t valid = (nose_north_q14 != 0 || nose_east_q14 != 0) ? 1u : 0u;
    int32_t cd = 0;
    if (valid != 0u) {
        cd = ht_dcm_bam_to_cdeg(ht_dcm_atan2_bam(nose_east_q14, nose_north_q14, NULL));
        cd = (cd < 0) ? (cd + 36000) : cd;
    }
    return ht_dcm_align(d, s, f, valid, (uint16_t)((cd >= 36000) ? 0 : cd));
}

/* Clamp a sample to the sensors' full scales, flagging an axis at its limit. */
static uint16_t clamp_sample(const ht_dcm_t *d, const ht_imu_sample_t *imu, q16_t gyro[3],
                             q16_t acc[3])
{
    uint16_t f = 0u;
    const int32_t gl = d->p.gyro_limit_rad_s;
    const int32_t al = d->p.accel_limit_g;
    for (unsigned i = 0u; i < 3u; i++) {
        const int32_t g = imu->gyro_rad_s[i];
        const int32_t a = imu->accel_g[i];
        if (g >= gl || g <= -gl) {
            f |= (uint16_t)HT_DCM_F_GYRO_SATURATED;
        }
        if (a >= al || a <= -al) {
            f |= (uint16_t)HT_DCM_F_ACCEL_SATURATED;
        }
        gyro[i] = clamp32(g, gl);
        acc[i] = clamp32(a, al);
    }
    return f;
}

/* |v_gps|^2 / 4 in (cm/s)^2: each component halved (|.| <= 32767) so that
 * the sum of the three squares stays below 2^32. */
static uint32_t gps_speed2_q2(const ht_dcm_aiding_t *a)
{
    uint32_t sum = 0u;
    for (unsigned i = 0u; i < 3u; i++) {
        const int32_t h = clamp32(a->vel_ned_cm_s[i], V_MAX_CM_S) / 2;
        const int32_t h2 = h * h; /* <= 32767^2 */
        sum += (uint32_t)h2;
    }
    return sum;
}

/*
 * The velocity through the air in body axes from the airspeed V: in the
 * plane of symmetry (no sideslip), [0, vy, vz], its angle of attack from the
 * climb rate c (GPS, 0 without a fix): v . R[2] = -c gives
 * vz = (-c - V R[2][1]) / R[2][2], and vy = V - vz^2 / (2 V). Along the
 * fuselage alone (vz = 0) a steep turn's angle of attack (10 deg at 60 deg of
 * bank) is missed and w x v is 0.2 g off. |vz| is held to V/2, and 0 when the
 * wings are near vertical (|R[2][2]| < 1/4) where the climb says nothing.
 */
static void air_velocity(const int32_t r[3][3], int32_t v, int32_t climb, int32_t v_q8[3])
{
    /* v in (0, 32767] cm/s, climb in [-32767, 32767] cm/s */
    /* R[2][2] in Q15 (|.| in [8192, 49152] where used): the quotient is
     * formed in two integer steps so that vz keeps its Q8 fraction */
    const int32_t r22_q15 = qi_rshift_round(r[2][2], 15u);
    int32_t vz_q8 = 0;
    if (r22_q15 >= 8192 || r22_q15 <= -8192) {
        /* V R[2][1] kept in Q8: rounded to cm/s it moved vz by up to 0.5 cm/s */
        const int32_t num_q8 =
            clamp32((-climb * 256) - qi_mul32(v, r[2][1], 22u), (int32_t)65535 * 256);
        const int32_t quot = num_q8 / r22_q15; /* |.| <= 2^24 / 2^13 */
        const int32_t rem = num_q8 % r22_q15;  /* |.| < 49152: times 2^15 fits */
        vz_q8 = clamp32((quot * 32768) + ((rem * 32768) / r22_q15), v * 128);
    }
    /* vy = V - vz^2 / (2 V): (vz / V) in Q15 first, |vz| <= V/2 */
    const int32_t ratio_q15 = (vz_q8 * 128) / v;
    v_q8[0] = 0;
    v_q8[1] = (v * 256) - qi_mul32(vz_q8, ratio_q15, 16u);
    v_q8[2] = vz_q8;
}

/*
 * The air velocity in body axes, cm/s in Q8 (0 when none), computed once per
 * sample for the centripetal term and the GPS course: the airspeed, else (no
 * airspeed, a dead pitot) the GPS speed; the climb from the GPS. With
 * CF_AIRSPEED the GPS is not used. Returns 1 when the GPS was used.
 */
static uint8_t body_velocity(const ht_dcm_t *d, const int32_t r[3][3], const ht_dcm_aiding_t *a,
                             int32_t v_q8[3])
{
    zero3(v_q8);
    const uint8_t gps =
        (d->p.centripetal != (uint8_t)HT_DCM_CF_AIRSPEED && a->gps_fix != 0u) ? 1u : 0u;
    const int32_t climb = (gps != 0u) ? -clamp32(a->vel_ned_cm_s[2], 32767) : 0;
    if (a->airspeed_valid != 0u && a->airspeed_cm_s > 0) {
        air_velocity(r, a->airspeed_cm_s, climb, v_q8);
        return gps;
    }
    if (gps != 0u) {
        /* the GPS speed in the airspeed's place, not the GPS velocity rotated
         * into the body, whose heading error would tilt the reference (a
         * 3-degree yaw error is a 0.06 g side force at 1 g) */
        const uint32_t sq = gps_speed2_q2(a);
        const int32_t v = clamp32((int32_t)q_isqrt32(sq) * 2, 32767);
        if (v > 0) {
            air_velocity(r, v, climb, v_q8);
        }
    }
    return gps;
}

/*
 * The acceleration along the fuselage from the airspeed's rate of change,
 * g in Q16, low-passed over 32 samples (0.16 s at 200 Hz): the pitot's
 * steps between its updates and its noise are smoothed, a turn entry's or a
 * dive's speed change is kept. No valid airspeed: the term decays to 0.
 */
static void forward_acceleration(const ht_dcm_t *d, ht_dcm_state_t *s, const ht_dcm_aiding_t *a)
{
    int32_t raw = 0;
    if (a->airspeed_valid != 0u && s->speed_prev_valid != 0u) {
        /* dv in cm/s per sample, clamped to +/-20 m/s (200 g at 1 kHz); times
         * the rate and 2^16 / 980.665 cm/s^2 (66.83, Q16): at most 1.4e8 */
        int32_t dv = (int32_t)a->airspeed_cm_s - (int32_t)s->speed_prev_cm_s;
        dv = clamp32(dv, 2000);
        raw = qi_mul32(dv * (int32_t)d->p.imu_rate_hz, CM_S2_TO_G_Q16_Q16, 16u);
    }
    s->accel_fwd_g = qi_add_sat32(s->accel_fwd_g, (raw - s->accel_fwd_g) / 32);
    s->speed_prev_valid = (a->airspeed_valid != 0u) ? 1u : 0u;
    s->speed_prev_cm_s = a->airspeed_cm_s;
}

/* One step of the 8-sample low-pass y += (x - y) / 8 (y = x when the filter
 * restarts); returns the new y. */
static int32_t lowpass8(int32_t *y, int32_t x, uint8_t running)
{
    *y = (running == 0u) ? x : qi_add_sat32(*y, qi_rshift_round(qi_sub_sat32(x, *y), 3u));
    return *y;
}

/* The gravity reference's weight in Q16 for a magnitude in g (Q16). */
static int32_t accel_weight_q16(const ht_dcm_t *d, int32_t mag_q16)
{
    const int32_t dev = (mag_q16 >= Q16_ONE) ? (mag_q16 - Q16_ONE) : (Q16_ONE - mag_q16);
    const int32_t band = d->p.accel_band_g;
    if (dev >= band) {
        return 0;
    }
    if (dev == 0) {
        return Q16_ONE;
    }
    /* (band - dev) / band: the reciprocal's 1e-6 can overshoot 1 by 0.07 LSB */
    const int32_t w = qi_mul32(band - dev, d->inv_band_q30, d->inv_band_shift);
    return (w > Q16_ONE) ? Q16_ONE : w;
}

/*
 * Roll/pitch error (Q30, already weighted): the measured earth-down
 * dm = (w x v - f) / |w x v - f| against R's bottom row, e = dm x R[2]: a
 * rotation about e turns R[2] toward dm. Returns the flags it sets.
 */
static uint16_t rollpitch_error(const ht_dcm_t *d, ht_dcm_state_t *s, const int32_t v_q8[3],
                                uint8_t v_gps, const q16_t acc[3], uint16_t flags, int32_t e[3])
{
    zero3(e);
    /* the centripetal term's velocity: none with CF_OFF */
    const uint8_t cf = (d->p.centripetal != (uint8_t)HT_DCM_CF_OFF) ? 1u : 0u;
    uint16_t f = (cf != 0u && v_gps != 0u) ? (uint16_t)HT_DCM_F_CF_GPS : 0u;
    int32_t v_gs[3] = {0, 0, 0}; /* g*s, Q16 */
    if (cf != 0u) {
        for (unsigned i = 0u; i < 3u; i++) {
            v_gs[i] = qi_mul32(v_q8[i], CM_S_Q8_TO_GS_Q16_Q24, 32u);
        }
    }
    /* w x v in g (Q16): |w| <= 65 rad/s, |v| <= 117 g*s: fits */
    const int32_t *w = s->rate_rad_s;
    int32_t g[3];
    g[0] = qi_sub_sat32(qi_mul32(w[1], v_gs[2], 16u), qi_mul32(w[2], v_gs[1], 16u));
    g[1] = qi_sub_sat32(qi_mul32(w[2], v_gs[0], 16u), qi_mul32(w[0], v_gs[2], 16u));
    g[2] = qi_sub_sat32(qi_mul32(w[0], v_gs[1], 16u), qi_mul32(w[1], v_gs[0], 16u));
    /* the acceleration along the path: the aircraft speeding up reads as a
     * nose-up tilt of the apparent vertical (0.07 g is 4 degrees) */
    if (d->p.centripetal != (uint8_t)HT_DCM_CF_OFF) {
        g[1] = qi_add_sat32(g[1], s->accel_fwd_g);
    }
    for (unsigned i = 0u; i < 3u; i++) {
        g[i] = qi_sub_sat32(g[i], acc[i]);
    }
    /* Vibration: a propeller's 0.2 g reaches the samples (aliased below the
     * IMU rate) and the weight below is not linear in it, so an unfiltered
     * reference is biased (3.4 deg in the c172p SIL). The reference is
     * low-passed over 8 samples (40 ms at 200 Hz: a 40 Hz alias at 120 Hz is
     * cut 13 times) before its direction and its weight are taken. */
    /* The filter's state is Q24: in Q16 an eighth of a small difference
     * would round to nothing and leave the reference a few LSB off. */
    for (unsigned i = 0u; i < 3u; i++) {
        const int32_t g_q24 = clamp32(g[i], 0x7FFFFF) * 256; /* within +/-128 g */
        g[i] = qi_rshift_round(lowpass8(&s->g_filt_q24[i], g_q24, s->g_filt_valid), 8u);
        (void)lowpass8(&s->r2_filt_q30[i], s->r[2][i], s->g_filt_valid);
    }
    s->g_filt_valid = 1u;
    int32_t u[3];
    int32_t wt = 0;
    if (q_unit3_q28(g, u) != 0 && (flags & (uint16_t)HT_DCM_F_ACCEL_SATURATED) == 0u) {
        wt = accel_weight_q16(d, dot_sat(g, u, 28u));
    }
    if (wt == 0) {
        return (uint16_t)((uint32_t)f | (uint32_t)HT_DCM_F_ACCEL_IGNORED);
    }
    int32_t dm[3];
    for (unsigned i = 0u; i < 3u; i++) {
        dm[i] = u[i] * 4; /* Q28 -> Q30, |u| <= 2^28 */
    }
    /* R[2] through the same low-pass, so that the pair compared is of the
     * same instant: against the unfiltered row, a roll at 60 deg/s would read
     * as a 4-degree error of the estimate (the filter's 8 samples at 120 Hz)
     * and teach the integral a false roll bias at every reversal */
    int32_t c[3];
    cross_q30(dm, s->r2_filt_q30, c);
    for (unsigned i = 0u; i < 3u; i++) {
        e[i] = qi_mul32(c[i], wt, 16u);
    }
    return f;
}

/*
 * Yaw error (Q30) between a current and a wanted horizontal direction, both
 * unit in Q28: the vertical component of their cross product (the sine of
 * the angle to turn, + = clockwise from above), or +/-1 beyond 90 degrees
 * so that the pull never fades at a large error.
 */
static int32_t yaw_between(int32_t an, int32_t ae, int32_t bn, int32_t be)
{
    const int32_t cr = qi_mul32_fit(an, be, 26u) - qi_mul32_fit(ae, bn, 26u);
    const int32_t dt = qi_mul32_fit(an, bn, 26u) + qi_mul32_fit(ae, be, 26u);
    if (dt < 0) {
        return (cr >= 0) ? Q30_ONE : -Q30_ONE;
    }
    return cr;
}

/*
 * The horizontal part of the body air velocity v (Q8 cm/s) in earth axes,
 * north and east, cm/s Q8: 0 when no speed is known.
 */
static void air_earth(const int32_t r[3][3], const int32_t v_q8[3], int32_t air_q8[2])
{
    /* v = [0, vy, vz], |R| <= 1.5 and |v| < 2^23: each product and the sums fit */
    air_q8[0] = qi_mul32(r[0][1], v_q8[1], 30u) + qi_mul32(r[0][2], v_q8[2], 30u);
    air_q8[1] = qi_mul32(r[1][1], v_q8[1], 30u) + qi_mul32(r[1][2], v_q8[2], 30u);
}

/*
 * The heading's turn since the GPS velocity's epoch: the velocity is
 * gps_latency_ms old when it arrives and held since, so in a turn its
 * direction trails the heading by the turn rate times its age (1.6 degrees
 * at 8 deg/s, 0.1 s of latency and half of a 5 Hz period). The angle is the
 * heading rate about the earth vertical (R[2] . w) times that age, clamped
 * to 0.5 rad; cos and sin in Q30 (the CORDIC).
 */
static void gps_age_turn(const ht_dcm_t *d, const ht_dcm_state_t *s, int32_t *c, int32_t *sn)
{
    uint32_t age = (uint32_t)s->gps_age_samples + (uint32_t)d->gps_latency_samples;
    if (age > (uint32_t)d->p.imu_rate_hz) {
        age = d->p.imu_rate_hz; /* a stale velocity: at most one second ahead */
    }
    int32_t psi_dot_q16 = 0; /* rad/s about the earth vertical, clockwise from above */
    for (unsigned j = 0u; j < 3u; j++) {
        psi_dot_q16 = qi_add_sat32(psi_dot_q16, qi_mul32(s->r[2][j], s->rate_rad_s[j], 30u));
    }
    /* the turn of one sample, Q30 rad (<= 64 rad/s / 50 Hz), times the age
     * (a Q16 time would be 6e-5 off at 0.1 s) */
    const int32_t per_sample = qi_mul32(psi_dot_q16, d->dt_q30, 16u);
    const int32_t n = (age > 0u) ? (int32_t)age : 1;
    const int32_t a = clamp32(per_sample, THETA_MAX_Q30 / n) * (int32_t)age; /* Q30 rad */
    ht_dcm_sincos_q30(qi_mul32(a, RAD_Q30_TO_BAM_Q30, 30u), c, sn);
}

/* The GPS aiding of one sample: the air-relative course carried to now. */
typedef struct {
    int32_t turn_c, turn_s; /* the heading's turn over the GPS velocity's age, Q30 */
    int32_t air_q8[2];      /* the air velocity's horizontal part, earth axes */
    uint8_t course;         /* 1: the course aided the heading */
} gps_course_t;

/*
 * The yaw error in Q30 from the GPS course or the magnetometer, 0 without.
 * The course is that of the GPS velocity through the air (v_gps - wind), the
 * direction the air velocity R v should have; turned by the heading's turn
 * since its epoch.
 */
static int32_t yaw_error(const ht_dcm_t *d, const ht_dcm_state_t *s, const ht_dcm_aiding_t *a,
                         gps_course_t *g, uint16_t *flags)
{
    const int32_t(*r)[3] = s->r;
    int32_t nn;
    int32_t ne;
    g->course = 0u;
    if (q_unit2_q28(r[0][1], r[1][1], &nn, &ne) == 0) {
        return 0; /* nose vertical: no heading */
    }
    if (a->gps_fix != 0u) {
        const int32_t gps_cm_s[2] = {a->vel_ned_cm_s[0], a->vel_ned_cm_s[1]};
        int32_t through_air_q8[2];
        dcm_wind_through_air(&s->wind, gps_cm_s, through_air_q8);
        int32_t cn;
        int32_t ce;
        if (q_unit2_q28(through_air_q8[0], through_air_q8[1], &cn, &ce) != 0) {
            const int32_t speed_q8 = qi_add_sat32(qi_mul32(through_air_q8[0], cn, 28u),
                                                  qi_mul32(through_air_q8[1], ce, 28u));
            if (speed_q8 > ((int32_t)d->p.gps_min_speed_cm_s * 256)) {
                *flags |= (uint16_t)HT_DCM_F_YAW_AIDED;
                g->course = 1u;
                /* scaled by the nose's horizontal length (cos pitch): the
                 * course says nothing about the heading of a vertical nose,
                 * and its direction is ill-conditioned there */
                const int32_t nh_q30 =
                    qi_add_sat32(qi_mul32(r[0][1], nn, 28u), qi_mul32(r[1][1], ne, 28u));
                /* the course is the velocity's direction, not the nose's: in
                 * a banked turn the angle of attack points the nose inside
                 * the path by alpha sin(phi) (1.3 deg at 2.3 deg and 35 deg in
                 * the c172p SIL), which the nose would take for a yaw error */
                int32_t un;
                int32_t ue;
                if (q_unit2_q28(g->air_q8[0], g->air_q8[1], &un, &ue) != 0) {
                    nn = un;
                    ne = ue;
                }
                gps_age_turn(d, s, &g->turn_c, &g->turn_s);
                const int32_t n0 = cn;
                cn = qi_mul32_fit(n0, g->turn_c, 30u) - qi_mul32_fit(ce, g->turn_s, 30u);
                ce = qi_mul32_fit(ce, g->turn_c, 30u) + qi_mul32_fit(n0, g->turn_s, 30u);
                return qi_mul32(yaw_between(nn, ne, cn, ce), nh_q30, 30u);
            }
        }
    }
    if (a->mag_valid != 0u) {
        /* the field in earth axes; its horizontal part should point to
         * magnetic north, declination east of true north */
        int32_t mh[2] = {0, 0};
        for (unsigned i = 0u; i < 2u; i++) {
            for (unsigned j = 0u; j < 3u; j++) {
                mh[i] = qi_add_sat32(mh[i], qi_mul32(r[i][j], a->mag[j], 16u));
            }
        }
        int32_t mn;
        int32_t me;
        if (q_unit2_q28(mh[0], mh[1], &mn, &me) != 0) {
            int32_t decl = (int32_t)a->mag_declination_cdeg % 36000;
            decl = (decl > 18000) ? (decl - 36000) : decl;
            decl = (decl <= -18000) ? (decl + 36000) : decl;
            int32_t c;
            int32_t sn;
            ht_dcm_sincos_q30(ht_dcm_cdeg_to_bam(decl), &c, &sn);
            *flags |= (uint16_t)HT_DCM_F_YAW_AIDED;
            return yaw_between(mn, me, qi_rshift_round(c, 2u), qi_rshift_round(sn, 2u));
        }
    }
    return 0;
}

/*
 * The wind learns (dcm_wind.h) at a new GPS solution that aided the course,
 * with a live pitot (the air velocity's length is measured, not the GPS
 * speed put in its place), every body rate within 20 deg/s (the air
 * velocity's model has no sideslip, wrong in a roll or a snap) and the nose
 * within 60 degrees of the horizon.
 */
static void wind_step(const ht_dcm_t *d, ht_dcm_state_t *s, const ht_dcm_aiding_t *a,
                      const gps_course_t *g, uint32_t period)
{
    if (g->course == 0u || a->gps_fresh == 0u || a->airspeed_valid == 0u || a->airspeed_cm_s <= 0) {
        return;
    }
    for (unsigned i = 0u; i < 3u; i++) {
        const int32_t w = s->rate_rad_s[i];
        if (w > BIAS_LEARN_RATE_MAX_Q16 || w < -BIAS_LEARN_RATE_MAX_Q16) {
            return;
        }
    }
    if (s->r[2][1] > NOSE_WIND_MAX_Q30 || s->r[2][1] < -NOSE_WIND_MAX_Q30) {
        return;
    }
    const int32_t gps_cm_s[2] = {a->vel_ned_cm_s[0], a->vel_ned_cm_s[1]};
    dcm_wind_learn(d, &s->wind, g->air_q8, gps_cm_s, g->turn_c, g->turn_s, period);
}

/*
 * R <- R (I + [theta]x + [theta]x^2 / 2): each row r becomes
 * r + c + (c x theta) / 2 with c = r x theta. The second-order term is what
 * makes I + ... a rotation to O(theta^4): with the first-order step alone the
 * rows are stretched by theta^2 / 2 across the axis, and the row-wise
 * renormalization turns that stretch into a rotation error of about
 * theta^2 / 2 per sample (5e-3 rad per turn at 1 rad/s and 200 Hz; 1.5
 * degrees in one 5 rad/s roll). With it the error is the angle's own
 * truncation, theta^3 / 6 per sample (2.6e-5 rad per turn at 1 rad/s).
 */
static void cross_theta(const int32_t a[3], const int32_t th[3], unsigned shift, int32_t c[3])
{
    /* |a_i| < 2 and |theta| <= 0.5: each product fits */
    c[0] = qi_sub_sat32(qi_mul32_fit(a[1], th[2], shift), qi_mul32_fit(a[2], th[1], shift));
    c[1] = qi_sub_sat32(qi_mul32_fit(a[2], th[0], shift), qi_mul32_fit(a[0], th[2], shift));
    c[2] = qi_sub_sat32(qi_mul32_fit(a[0], th[1], shift), qi_mul32_fit(a[1], th[0], shift));
}

static void propagate(int32_t r[3][3], const int32_t th[3])
{
    for (unsigned k = 0u; k < 3u; k++) {
        int32_t c[3];
        int32_t c2[3];
        cross_theta(r[k], th, 30u, c);
        cross_theta(c, th, 31u, c2); /* (c x theta) / 2 */
        for (unsigned i = 0u; i < 3u; i++) {
            r[k][i] = qi_add_sat32(r[k][i], qi_add_sat32(c[i], c2[i]));
        }
    }
}

/*
 * Renormalization: the orthogonality error of rows 0 and 1 shared half and
 * half, row 2 = row 0 x row 1, each row scaled by (3 - |r|^2) / 2 (which is
 * exact in Q30 from |r|^2 in Q29). Returns nonzero when a row's squared norm
 * is outside [0.25, 2.25] (R is then not usable).
 */
static int renormalize(int32_t r[3][3])
{
    const int32_t err = dot_sat(r[0], r[1], 30u);
    int32_t a[3];
    int32_t b[3];
    for (unsigned i = 0u; i < 3u; i++) {
        a[i] = qi_sub_sat32(r[0][i], qi_mul32(err, r[1][i], 31u));
        b[i] = qi_sub_sat32(r[1][i], qi_mul32(err, r[0][i], 31u));
    }
    for (unsigned i = 0u; i < 3u; i++) {
        r[0][i] = a[i];
        r[1][i] = b[i];
    }
    cross_q30(a, b, r[2]);
    int fail = 0;
    for (unsigned k = 0u; k < 3u; k++) {
        const int32_t n_q29 = dot_sat(r[k], r[k], 31u);
        if (n_q29 < NORM2_MIN_Q29 || n_q29 > NORM2_MAX_Q29) {
            fail = 1;
        } else {
            const int32_t scale_q30 = THREE_HALVES_Q30 - n_q29;
            for (unsigned i = 0u; i < 3u; i++) {
                /* |r| <= 1.5, scale <= 1.375: fits */
                r[k][i] = qi_mul32_fit(r[k][i], scale_q30, 30u);
            }
        }
    }
    return fail;
}

/* After a renormalization failure: R from this sample's gravity reference
 * with the last good heading (level if the accelerometer cannot tell). */
static void recover(int32_t r[3][3], const q16_t acc[3], int32_t nose_n, int32_t nose_e)
{
    int32_t c = Q30_ONE;
    int32_t s = 0;
    int32_t cn;
    int32_t sn;
    if (q_unit2_q28(nose_n, nose_e, &cn, &sn) != 0) {
        c = cn * 4;
        s = sn * 4;
    }
    if (align_rows(r, acc, c, s) != 0) {
        const q16_t level[3] = {0, 0, -Q16_ONE};
        (void)align_rows(r, level, c, s);
    }
}

/* The PI step: bias integral (clamped), proportional correction, and the
 * rotation of this sample. Returns HT_DCM_F_BIAS_LIMITED or 0. */
static uint16_t pi_step(const ht_dcm_t *d, ht_dcm_state_t *s, const q16_t gyro[3],
                        const int32_t e_rp[3], const int32_t e_yaw[3], uint8_t rate_gate,
                        uint8_t yaw_learn, int32_t theta[3])
{
    uint16_t f = 0u;
    const int32_t bmax = d->bias_max_q30;
    /* After the gyro saturated the attitude is off by what the clipped rate
     * missed: the roll/pitch correction is 5 times stronger for a second
     * and the integral learns nothing from that error (it is not a bias). */
    const uint8_t boost = (s->recover_samples > 0u) ? 1u : 0u;
    const int32_t rp_gain = (boost != 0u) ? (int32_t)5 : (int32_t)1;
    uint32_t learn = 1u;
    if (boost != 0u) {
        learn = 0u;
    }
    for (unsigned i = 0u; i < 3u; i++) {
        /* the measured rate: the gate does not depend on the estimate */
        const int32_t w = gyro[i];
        if (rate_gate != 0u && (w > BIAS_LEARN_RATE_MAX_Q16 || w < -BIAS_LEARN_RATE_MAX_Q16)) {
            learn = 0u;
        }
    }
    for (unsigned i = 0u; i < 3u; i++) {
        /* the integral of ki * e is minus the bias */
        int32_t inc = 0;
        if (learn != 0u) {
            inc = qi_mul32(d->ki_rp_dt_q34, e_rp[i], 34u);
            if (yaw_learn != 0u) {
                inc = qi_add_sat32(inc, qi_mul32(d->ki_yaw_dt_q34, e_yaw[i], 34u));
            }
        }
        const int32_t b = clamp32(qi_sub_sat32(s->bias[i], inc), bmax);
        if (b == bmax || b == -bmax) {
            f = (uint16_t)HT_DCM_F_BIAS_LIMITED;
        }
        s->bias[i] = b;
        s->omega_corr[i] = qi_add_sat32(qi_mul32(d->p.kp_rollpitch, e_rp[i], 30u),
                                        qi_mul32(d->p.kp_yaw, e_yaw[i], 30u));
        /* (gyro - bias) dt + kp dt e, Q30 rad */
        int32_t t = qi_mul32(gyro[i], d->dt_q30, 16u);
        t = qi_sub_sat32(t, qi_mul32(b, d->dt_q30, 30u));
        t = qi_add_sat32(t,
                         qi_mul32(d->kp_rp_dt_q32, e_rp[i], 32u) * rp_gain); /* <= 5 x 0.32 rad */
        t = qi_add_sat32(t, qi_mul32(d->kp_yaw_dt_q32, e_yaw[i], 32u));
        theta[i] = clamp32(t, THETA_MAX_Q30);
    }
    return f;
}

void ht_dcm_update(const ht_dcm_t *d, ht_dcm_state_t *s, const ht_imu_sample_t *imu,
                   const ht_dcm_aiding_t *aid)
{
    static const ht_dcm_aiding_t no_aiding = {0};
    if (d == NULL || s == NULL || imu == NULL || d->ready == 0u) {
        return;
    }
    const ht_dcm_aiding_t *a = (aid != NULL) ? aid : &no_aiding;
    q16_t gyro[3];
    q16_t acc[3];
    const uint32_t sample_flags = clamp_sample(d, imu, gyro, acc);
    const uint32_t kept = (uint32_t)s->flags & FLAGS_KEPT;
    uint16_t flags = (uint16_t)(kept | sample_flags);
    if ((flags & (uint16_t)HT_DCM_F_ALIGNED) == 0u) {
        /* the first usable sample aligns roll and pitch (heading north) */
        if (align_rows(s->r, acc, Q30_ONE, 0) == 0) {
            flags |= (uint16_t)HT_DCM_F_ALIGNED;
            zero3(s->bias);
        }
    }
    for (unsigned i = 0u; i < 3u; i++) {
        s->rate_rad_s[i] = qi_sub_sat32(gyro[i], qi_rshift_round(s->bias[i], 14u));
    }
    forward_acceleration(d, s, a);
    /* samples since the previous solution: the weight of a new one in the
     * wind's low pass (dcm_wind.c) */
    const uint32_t gps_period = (uint32_t)s->gps_age_samples + 1u;
    if (a->gps_fresh != 0u) {
        s->gps_age_samples = 0u;
    } else if (s->gps_age_samples < UINT16_MAX) {
        s->gps_age_samples++;
    } else {
        /* saturated: course_now clamps the age anyway */
    }
    int32_t e_rp[3];
    if ((sample_flags & (uint32_t)HT_DCM_F_GYRO_SATURATED) != 0u) {
        s->recover_samples = d->p.imu_rate_hz;
    } else if (s->recover_samples > 0u) {
        s->recover_samples--;
    } else {
        /* no saturation in the last second */
    }
    int32_t v_q8[3];
    const ht_dcm_state_t *cs = s; /* the matrix is read only there */
    const uint8_t v_gps = body_velocity(d, cs->r, a, v_q8);
    const uint8_t acc_sat = ((sample_flags & (uint32_t)HT_DCM_F_ACCEL_SATURATED) != 0u) ? 1u : 0u;
    dcm_ga_sample(d, &s->ga, cs->r, acc, acc_sat, a);
    uint8_t rate_gate = 1u;
    /* a heading is trusted once a turn has taught the wind, or with a
     * magnetometer (dcm_gps_accel.c drop_heading_term) */
    const uint8_t heading_trusted = (s->wind.solved != 0u || a->mag_valid != 0u) ? 1u : 0u;
    if (heading_trusted != 0u) {
        flags |= (uint16_t)HT_DCM_F_HEADING_KNOWN;
    }
    if (dcm_ga_error(&s->ga, cs->r, heading_trusted, e_rp) != 0) {
        /* the GPS acceleration: the w x v model and its filters rest (they
         * restart from this sample's reference when the GPS goes) */
        flags |= (uint16_t)HT_DCM_F_GPS_ACCEL;
        s->g_filt_valid = 0u;
        rate_gate = 0u; /* no model error in a roll or a pull to keep out */
    } else {
        flags |= rollpitch_error(d, s, v_q8, v_gps, acc, flags, e_rp);
        /* the w x v model's reference carries its model's errors (the
         * airspeed, the angle of attack, the gyro bias through w): its loop
         * runs at half the gains, those of a MatrixPilot-like DCM (kp 0.2,
         * ki 0.02 at the defaults), which the GPS acceleration's doubles */
        for (unsigned i = 0u; i < 3u; i++) {
            e_rp[i] = qi_rshift_round(e_rp[i], 1u);
        }
    }
    gps_course_t g = {Q30_ONE, 0, {0, 0}, 0u};
    air_earth(cs->r, v_q8, g.air_q8);
    const int32_t ey = yaw_error(d, s, a, &g, &flags);
    wind_step(d, s, a, &g, gps_period);
    int32_t e_yaw[3]; /* about the earth vertical: along R[2] in body axes */
    for (unsigned i = 0u; i < 3u; i++) {
        e_yaw[i] = qi_mul32(ey, s->r[2][i], 30u);
    }
    int32_t theta[3];
    /* a large heading error (a start 180 degrees off) is not a bias: the
     * yaw integral learns only within 10 degrees, or it winds up while the
     * proportional term turns the heading and overshoots after it */
    const uint8_t yaw_learn = (ey <= YAW_LEARN_MAX_Q30 && ey >= -YAW_LEARN_MAX_Q30) ? 1u : 0u;
    flags |= pi_step(d, s, gyro, e_rp, e_yaw, rate_gate, yaw_learn, theta);
    const int32_t nose_n = s->r[0][1];
    const int32_t nose_e = s->r[1][1];
    propagate(s->r, theta);
    if (renormalize(s->r) != 0) {
        recover(s->r, acc, nose_n, nose_e);
        s->g_filt_valid = 0u;
        dcm_ga_reset(&s->ga);
        flags |= (uint16_t)HT_DCM_F_RENORM_FAILED;
    }
    s->flags = flags;
    s->samples++; /* wraps after 2^32 samples (248 days at 200 Hz): a counter only */
}

void ht_dcm_output(const ht_dcm_state_t *s, ht_dcm_output_t *out)
{
    if (out == NULL) {
        return;
    }
    const ht_dcm_output_t z = {0};
    *out = z;
    if (s == NULL) {
        return;
    }
    for (unsigned i = 0u; i < 3u; i++) {
        for (unsigned j = 0u; j < 3u; j++) {
            out->r[i][j] = qi_sat16(qi_rshift_round(s->r[i][j], 16u));
        }
        out->gyro_bias_rad_s[i] = qi_rshift_round(s->bias[i], 14u);
        out->gyro_rad_s[i] = s->rate_rad_s[i];
    }
    /* roll = atan2(-R20, R22); pitch = atan2(-R21, |(R20, R22)|), the
     * CORDIC's magnitude carrying its gain, so -R21 is scaled by it too */
    int32_t mag_k;
    const int32_t roll = ht_dcm_atan2_bam(qi_sub_sat32(0, s->r[2][0]), s->r[2][2], &mag_k);
    const int32_t pitch =
        ht_dcm_atan2_bam(qi_mul32(s->r[2][1], -HT_CORDIC_GAIN_Q30, 30u), mag_k, NULL);
    int32_t yaw = ht_dcm_bam_to_cdeg(ht_dcm_atan2_bam(s->r[1][1], s->r[0][1], NULL));
    if (yaw < 0) {
        yaw += 36000;
    }
    out->roll_cdeg = (int16_t)ht_dcm_bam_to_cdeg(roll);
    out->pitch_cdeg = (int16_t)ht_dcm_bam_to_cdeg(pitch);
    out->yaw_cdeg = (uint16_t)((yaw >= 36000) ? 0 : yaw);
    out->flags = s->flags;
}
