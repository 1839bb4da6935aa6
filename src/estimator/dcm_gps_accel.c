/*
 * dcm_gps_accel.c - the estimator's GPS acceleration reference: the
 * accelerometer in earth axes against the GPS velocity's change, over the
 * same time (src/estimator/dcm_gps_accel.h has why and how).
 *
 * Formats: the open interval's sum of R f in g, Q16 (per sample at most
 * 16 g * sqrt(3) = 1.8e6; an interval is at most imu_rate_hz samples, and
 * the sums saturate beyond 1 100 g*samples); closed intervals as velocity
 * changes in cm/s, Q12 (1 s at 28 g is 1.1e8; Q8 left 2e-5 of a 0.2 s
 * interval's change in its rounding); GPS velocities in cm/s clamped
 * to +/-655.35 m/s; the error in Q30 (sines of the tilt error).
 */
#include "estimator/dcm_gps_accel.h"

#include <stddef.h>

#include "helical/math/q14.h"
#include "math/q_inline.h"

/* GPS velocities are clamped before any difference. */
#define GA_V_MAX_CM_S 65535

void dcm_ga_reset(ht_dcm_ga_t *g)
{
    const ht_dcm_ga_t z = {0};
    *g = z;
}

/* The chain of consecutive intervals is broken: the window refills. */
/* sin^2(10 deg) in Q28 and its reciprocal (33.163) in Q24: the lean above
 * which the heading term is dropped whole */
#define H0_SQ_Q28     ((int32_t)8094319)
#define INV_H0_SQ_Q24 ((int32_t)556390154)

static void break_chain(ht_dcm_ga_t *g)
{
    g->count = 0u;
    g->err_valid = 0u;
}

/* The open interval closes: it becomes the candidate for the next solution. */
static void close_interval(const ht_dcm_t *d, ht_dcm_ga_t *g)
{
    for (unsigned i = 0u; i < 3u; i++) {
        /* Q16 g*samples * Q24 (cm/s per g*sample) / 2^28 = cm/s in Q12 */
        g->closed_q12[i] = qi_mul32(g->open_q16[i], d->g_dt_q24, 28u);
        g->open_q16[i] = 0;
    }
    g->closed_n = g->open_n;
    g->closed_ok = g->open_aligned;
    g->open_n = 0u;
    g->open_aligned = 1u;
    g->boundary_done = 1u;
}

/* Appends a solution's velocity (and, when with_interval, the interval that
 * ends at its epoch) to the window, oldest first. */
static void push(ht_dcm_ga_t *g, const ht_dcm_aiding_t *a, uint8_t with_interval)
{
    for (unsigned k = 0u; k < HT_DCM_GA_WINDOW; k++) {
        for (unsigned i = 0u; i < 3u; i++) {
            g->vel_cm_s[k][i] = g->vel_cm_s[k + 1u][i];
        }
    }
    for (unsigned i = 0u; i < 3u; i++) {
        g->vel_cm_s[HT_DCM_GA_WINDOW][i] =
            q_clamp32(a->vel_ned_cm_s[i], -GA_V_MAX_CM_S, GA_V_MAX_CM_S);
    }
    if (with_interval == 0u) {
        g->count = 0u;
        return;
    }
    for (unsigned k = 0u; (k + 1u) < HT_DCM_GA_WINDOW; k++) {
        for (unsigned i = 0u; i < 3u; i++) {
            g->dv_q12[k][i] = g->dv_q12[k + 1u][i];
        }
        g->n[k] = g->n[k + 1u];
    }
    for (unsigned i = 0u; i < 3u; i++) {
        g->dv_q12[HT_DCM_GA_WINDOW - 1u][i] = g->closed_q12[i];
    }
    g->n[HT_DCM_GA_WINDOW - 1u] = g->closed_n;
    if (g->count < HT_DCM_GA_WINDOW) {
        g->count++;
    }
}

/* |v| of a vector from its unit vector (Q28): v . u, in v's format. */
static int32_t vector_length(const int32_t v[3], const int32_t u[3])
{
    int32_t s = 0;
    for (unsigned i = 0u; i < 3u; i++) {
        s = qi_add_sat32(s, qi_mul32(v[i], u[i], 28u));
    }
    return s;
}

/*
 * The full window's error: u_imu x u_gps in earth axes (a rotation about it
 * turns the estimate's specific force toward the GPS's), the vertical
 * component dropped (a heading error: the course loop's job). No error when
 * the GPS's specific force is below half of gravity's (free fall: no
 * direction) or the two magnitudes differ by more than half (a glitch).
 */
static void window_error(const ht_dcm_t *d, ht_dcm_ga_t *g)
{
    int32_t f_imu[3] = {0, 0, 0};
    int32_t f_gps[3];
    int32_t n_total = 0;
    for (unsigned k = 0u; k < HT_DCM_GA_WINDOW; k++) {
        for (unsigned i = 0u; i < 3u; i++) {
            f_imu[i] = qi_add_sat32(f_imu[i], g->dv_q12[k][i]);
        }
        n_total += (int32_t)g->n[k]; /* <= 5 * 1000 */
    }
    /* gravity's share: g0 * T, cm/s in Q12 (<= 5000 samples at 50 Hz: 4e8) */
    const int32_t g0t_q12 = qi_mul32(n_total, d->g_dt_q24, 12u);
    for (unsigned i = 0u; i < 3u; i++) {
        /* |difference| <= 131070 cm/s: times 4096 fits */
        f_gps[i] = (g->vel_cm_s[HT_DCM_GA_WINDOW][i] - g->vel_cm_s[0][i]) * 4096;
    }
    /* the specific force's integral is dv - g T, g = +g0 down */
    f_gps[2] = qi_sub_sat32(f_gps[2], g0t_q12);
    int32_t u_imu[3];
    int32_t u_gps[3];
    g->err_valid = 0u;
    if (q_unit3_q28(f_imu, u_imu) == 0 || q_unit3_q28(f_gps, u_gps) == 0) {
        return;
    }
    const int32_t len_gps = vector_length(f_gps, u_gps);
    const int32_t len_imu = vector_length(f_imu, u_imu);
    const int32_t diff = (len_imu >= len_gps) ? (len_imu - len_gps) : (len_gps - len_imu);
    if (len_gps < (g0t_q12 / 2) || diff > (len_gps / 2)) {
        return;
    }
    /* Q28 * Q28 / 2^26 = Q30 */
    g->err_q30[0] = qi_mul32_fit(u_imu[1], u_gps[2], 26u) - qi_mul32_fit(u_imu[2], u_gps[1], 26u);
    g->err_q30[1] = qi_mul32_fit(u_imu[2], u_gps[0], 26u) - qi_mul32_fit(u_imu[0], u_gps[2], 26u);
    g->h_q28[0] = u_gps[0];
    g->h_q28[1] = u_gps[1];
    g->err_valid = 1u;
}

/* A new solution: extends the window when it is the one the last boundary
 * was placed for, else restarts the chain from it. */
static void on_solution(const ht_dcm_t *d, ht_dcm_ga_t *g, const ht_dcm_aiding_t *a)
{
    const int32_t since = (int32_t)g->since_fix;
    const int32_t period = (int32_t)g->period;
    const int32_t jitter = since - period;
    uint8_t consistent = 0u;
    if (period != 0 && g->boundary_done != 0u && jitter >= -1 && jitter <= 1) {
        consistent = 1u;
    }
    const uint8_t extend = (consistent != 0u && g->closed_ok != 0u) ? 1u : 0u;
    push(g, a, extend);
    if (consistent == 0u) {
        /* the open interval began at a boundary placed for another time */
        g->open_aligned = 0u;
    }
    /* the next boundary is placed from this period: at most one second */
    g->period = (since >= 2 && since <= (int32_t)d->p.imu_rate_hz) ? (uint16_t)since : 0u;
    g->since_fix = 0u;
    g->boundary_done = 0u;
    if (g->count >= HT_DCM_GA_WINDOW) {
        window_error(d, g);
    } else {
        g->err_valid = 0u;
    }
}

void dcm_ga_sample(const ht_dcm_t *d, ht_dcm_ga_t *g, const int32_t r[3][3], const int32_t acc[3],
                   uint8_t acc_saturated, const ht_dcm_aiding_t *a)
{
    if (d->p.centripetal != (uint8_t)HT_DCM_CF_AUTO || a->gps_fix == 0u) {
        dcm_ga_reset(g); /* no GPS: the chain restarts with the next fix */
        return;
    }
    /* R f in earth axes, g in Q16 (|R| <= 1.5, |f| <= 32 g: each product fits) */
    for (unsigned i = 0u; i < 3u; i++) {
        int32_t fe = 0;
        for (unsigned j = 0u; j < 3u; j++) {
            fe = qi_add_sat32(fe, qi_mul32(r[i][j], acc[j], 30u));
        }
        g->open_q16[i] = qi_add_sat32(g->open_q16[i], fe);
    }
    if (g->open_n < UINT16_MAX) {
        g->open_n++;
    }
    if (acc_saturated != 0u) {
        g->open_aligned = 0u;
    }
    if (g->since_fix < UINT16_MAX) {
        g->since_fix++;
    }
    const uint16_t lat = d->gps_latency_samples;
    if (g->period > lat && g->boundary_done == 0u && g->since_fix == (uint16_t)(g->period - lat)) {
        close_interval(d, g);
    }
    if (a->gps_fresh != 0u) {
        on_solution(d, g, a);
    } else if (g->period != 0u && (uint32_t)g->since_fix > ((uint32_t)g->period + 2u)) {
        /* a solution missed: the boundaries no longer line up */
        break_chain(g);
        g->period = 0u;
        g->open_aligned = 0u;
    } else {
        /* between solutions */
    }
}

/*
 * Without a trusted heading, the part of the error about h's direction,
 * weighted by min(1, |h|^2 / sin^2(10 deg)), is dropped. Why: in a turn the
 * specific force leans by phi toward the centre (|h| = sin phi), and a
 * heading error d turns h about the vertical; the error reads that as a
 * tilt about h's direction of d sin phi cos phi (9 degrees for a 22-degree
 * crab at 30 degrees of bank), beside the true tilt about it. The tilt
 * across h (the bank's error) carries no heading term and is kept.
 */
static void drop_heading_term(const ht_dcm_ga_t *g, int32_t err[2])
{
    int32_t hn;
    int32_t he;
    if (q_unit2_q28(g->h_q28[0], g->h_q28[1], &hn, &he) == 0) {
        return; /* no lean: nothing to drop */
    }
    const int32_t h2_q28 =
        qi_mul32(g->h_q28[0], g->h_q28[0], 28u) + qi_mul32(g->h_q28[1], g->h_q28[1], 28u);
    int32_t w_q30 = (int32_t)0x40000000; /* 1 in Q30 */
    if (h2_q28 < H0_SQ_Q28) {
        w_q30 = qi_mul32(h2_q28, INV_H0_SQ_Q24, 22u); /* < 2^30 */
    }
    const int32_t along =
        qi_mul32(qi_mul32(err[0], hn, 28u) + qi_mul32(err[1], he, 28u), w_q30, 30u);
    err[0] -= qi_mul32(along, hn, 28u);
    err[1] -= qi_mul32(along, he, 28u);
}

int dcm_ga_error(const ht_dcm_ga_t *g, const int32_t r[3][3], uint8_t heading_trusted, int32_t e[3])
{
    if (g->err_valid == 0u) {
        e[0] = 0;
        e[1] = 0;
        e[2] = 0;
        return 0;
    }
    int32_t err[2] = {g->err_q30[0], g->err_q30[1]};
    if (heading_trusted == 0u) {
        drop_heading_term(g, err);
    }
    /* earth to body: e_body = R^T e_earth, the vertical component 0 (see
     * window_error) */
    for (unsigned j = 0u; j < 3u; j++) {
        e[j] = qi_add_sat32(qi_mul32(r[0][j], err[0], 30u), qi_mul32(r[1][j], err[1], 30u));
    }
    return 1;
}
