/*
 * dcm_reference_gps_accel.c - the estimator's GPS acceleration reference in
 * double (dcm_reference.h), from docs/estimator.md: the same sample counting
 * (it is integer by nature), the sums and the error in real numbers.
 */
#include <math.h>
#include <string.h>

#include "dcm_reference.h"

#define G_CM_S2 980.665

static double clampv(double x, double lim)
{
    return x > lim ? lim : (x < -lim ? -lim : x);
}

static void unit(const double v[3], double u[3], double *len)
{
    *len = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    for (int i = 0; i < 3; i++) {
        u[i] = *len > 0.0 ? v[i] / *len : 0.0;
    }
}

static void window_error(dcmr_ga_t *g)
{
    double fi[3] = {0, 0, 0}, fg[3], t = 0.0;
    for (int k = 0; k < DCMR_GA_W; k++) {
        for (int i = 0; i < 3; i++) {
            fi[i] += g->dv[k][i];
        }
        t += g->t[k];
    }
    for (int i = 0; i < 3; i++) {
        fg[i] = (g->vel[DCMR_GA_W][i] - g->vel[0][i]) / G_CM_S2; /* g*s */
    }
    fg[2] -= t;
    double ui[3], ug[3], li, lg;
    unit(fi, ui, &li);
    unit(fg, ug, &lg);
    g->err_valid = 0;
    if (li == 0.0 || lg == 0.0 || lg < t / 2 || fabs(li - lg) > lg / 2) {
        return;
    }
    g->err[0] = ui[1] * ug[2] - ui[2] * ug[1];
    g->err[1] = ui[2] * ug[0] - ui[0] * ug[2];
    g->h[0] = ug[0];
    g->h[1] = ug[1];
    g->err_valid = 1;
}

static void push(dcmr_ga_t *g, const ht_dcm_aiding_t *a, int with_interval)
{
    memmove(g->vel[0], g->vel[1], sizeof g->vel[0] * DCMR_GA_W);
    for (int i = 0; i < 3; i++) {
        g->vel[DCMR_GA_W][i] = clampv(a->vel_ned_cm_s[i], 65535.0);
    }
    if (!with_interval) {
        g->count = 0;
        return;
    }
    memmove(g->dv[0], g->dv[1], sizeof g->dv[0] * (DCMR_GA_W - 1));
    memmove(&g->t[0], &g->t[1], sizeof g->t[0] * (DCMR_GA_W - 1));
    memcpy(g->dv[DCMR_GA_W - 1], g->closed, sizeof g->closed);
    g->t[DCMR_GA_W - 1] = g->closed_t;
    g->count = g->count < DCMR_GA_W ? g->count + 1 : DCMR_GA_W;
}

void dcmr_ga_sample(const dcmr_params_t *p, dcmr_ga_t *g, double r[3][3], const double acc[3],
                    int acc_sat, const ht_dcm_aiding_t *a)
{
    if (p->centripetal != HT_DCM_CF_AUTO || !a->gps_fix) {
        memset(g, 0, sizeof *g);
        return;
    }
    for (int i = 0; i < 3; i++) {
        g->open[i] += (r[i][0] * acc[0] + r[i][1] * acc[1] + r[i][2] * acc[2]) * p->dt;
    }
    g->open_t += p->dt;
    if (acc_sat) {
        g->open_aligned = 0;
    }
    g->since_fix++;
    if (g->period > p->lat_samples && !g->boundary_done &&
        g->since_fix == g->period - p->lat_samples) {
        memcpy(g->closed, g->open, sizeof g->open);
        g->closed_t = g->open_t;
        g->closed_ok = g->open_aligned;
        memset(g->open, 0, sizeof g->open);
        g->open_t = 0.0;
        g->open_aligned = 1;
        g->boundary_done = 1;
    }
    if (a->gps_fresh) {
        const int jitter = g->since_fix - g->period;
        const int consistent = g->period != 0 && g->boundary_done && jitter >= -1 && jitter <= 1;
        push(g, a, consistent && g->closed_ok);
        if (!consistent) {
            g->open_aligned = 0;
        }
        g->period = (g->since_fix >= 2 && g->since_fix <= p->imu_rate) ? g->since_fix : 0;
        g->since_fix = 0;
        g->boundary_done = 0;
        if (g->count >= DCMR_GA_W) {
            window_error(g);
        } else {
            g->err_valid = 0;
        }
    } else if (g->period != 0 && g->since_fix > g->period + 2) {
        g->count = 0;
        g->err_valid = 0;
        g->period = 0;
        g->open_aligned = 0;
    }
}

int dcmr_ga_error(const dcmr_ga_t *g, double r[3][3], int heading_trusted, double e[3])
{
    double err[2] = {g->err[0], g->err[1]};
    const double h2 = g->h[0] * g->h[0] + g->h[1] * g->h[1];
    if (!heading_trusted && h2 > 0.0) {
        /* the part about the lean's direction, weighted by
         * min(1, |h|^2 / sin^2(10 deg)), dropped (dcm_gps_accel.c) */
        const double h0 = sin(10.0 * DCMR_PI / 180.0);
        const double w = h2 >= h0 * h0 ? 1.0 : h2 / (h0 * h0);
        const double hl = sqrt(h2), hn = g->h[0] / hl, he = g->h[1] / hl;
        const double along = (err[0] * hn + err[1] * he) * w;
        err[0] -= along * hn;
        err[1] -= along * he;
    }
    for (int j = 0; j < 3; j++) {
        e[j] = g->err_valid ? r[0][j] * err[0] + r[1][j] * err[1] : 0.0;
    }
    return g->err_valid;
}
