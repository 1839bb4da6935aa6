/*
 * dcm_reference.c - the estimator's equations in double (dcm_reference.h).
 * Written from docs/estimator.md, not from src/estimator/dcm.c: no fixed point, no
 * saturation beyond the documented clamps.
 */
#include "dcm_reference.h"

#include <math.h>
#include <string.h>

#define G_CM_S2 980.665

static double q16r(int32_t v)
{
    return (double)v / 65536.0;
}

void dcmr_params_from(const ht_dcm_params_t *p, dcmr_params_t *o)
{
    o->dt = 1.0 / (double)p->imu_rate_hz;
    o->kp_rp = q16r(p->kp_rollpitch);
    o->ki_rp = q16r(p->ki_rollpitch);
    o->kp_yaw = q16r(p->kp_yaw);
    o->ki_yaw = q16r(p->ki_yaw);
    o->bias_max = q16r(p->gyro_bias_max_rad_s);
    o->gyro_limit = q16r(p->gyro_limit_rad_s);
    o->accel_limit = q16r(p->accel_limit_g);
    o->band = q16r(p->accel_band_g);
    o->gps_min_speed_cm_s = (double)p->gps_min_speed_cm_s;
    o->centripetal = p->centripetal;
    o->imu_rate = p->imu_rate_hz;
    o->lat_samples = (int)((p->gps_latency_ms * p->imu_rate_hz + 500u) / 1000u);
    o->wind_tau = (double)HT_DCM_WIND_TAU_S;
}

static void cross(const double a[3], const double b[3], double o[3])
{
    o[0] = a[1] * b[2] - a[2] * b[1];
    o[1] = a[2] * b[0] - a[0] * b[2];
    o[2] = a[0] * b[1] - a[1] * b[0];
}

static double dot(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static double clampd(double x, double lim)
{
    return x > lim ? lim : (x < -lim ? -lim : x);
}

void dcmr_reset(dcmr_state_t *s)
{
    memset(s, 0, sizeof *s);
    s->r[0][0] = s->r[1][1] = s->r[2][2] = 1.0;
}

int dcmr_align(dcmr_state_t *s, const double f[3], double psi)
{
    const double n = sqrt(dot(f, f));
    if (n < 0.5) {
        return 1;
    }
    const double d[3] = {-f[0] / n, -f[1] / n, -f[2] / n};
    double h[3];
    double c = cos(psi), sn = sin(psi);
    if (1.0 - d[1] * d[1] < 1.0 / 64.0) {
        const double w[3] = {-1, 0, 0};
        const double k = dot(w, d);
        for (int i = 0; i < 3; i++) {
            h[i] = w[i] - k * d[i];
        }
        const double t = c;
        c = -sn;
        sn = t;
    } else {
        for (int i = 0; i < 3; i++) {
            h[i] = (i == 1 ? 1.0 : 0.0) - d[1] * d[i];
        }
    }
    const double hn = sqrt(dot(h, h));
    for (int i = 0; i < 3; i++) {
        h[i] /= hn;
    }
    double k[3];
    cross(d, h, k);
    for (int i = 0; i < 3; i++) {
        s->r[0][i] = c * h[i] - sn * k[i];
        s->r[1][i] = sn * h[i] + c * k[i];
        s->r[2][i] = d[i];
    }
    s->bias[0] = s->bias[1] = s->bias[2] = 0.0;
    s->aligned = 1;
    s->g_filt_valid = 0;
    memset(&s->ga, 0, sizeof s->ga);
    return 0;
}

static double yaw_between(double an, double ae, double bn, double be)
{
    const double cr = an * be - ae * bn;
    if (an * bn + ae * be < 0) {
        return cr >= 0 ? 1.0 : -1.0;
    }
    return cr;
}

/* the air velocity in the plane of symmetry (dcm.c air_velocity), cm/s */
static void air_velocity(const dcmr_state_t *s, double vv, double climb, double v[3])
{
    double vz = 0.0;
    if (fabs(s->r[2][2]) >= 0.25) {
        vz = clampd(clampd(-climb - vv * s->r[2][1], 65535.0) / s->r[2][2], vv / 2);
    }
    v[0] = 0.0;
    v[1] = vv - vz * vz / (2 * vv);
    v[2] = vz;
}

/* What the course step leaves for the wind's (dcm_wind.h) */
typedef struct {
    int course;    /* the GPS course aided the heading */
    double air[2]; /* the air velocity's horizontal part, earth axes, cm/s */
    double turn;   /* the heading's turn over the GPS velocity's age, rad */
} dcmr_course_t;

static double yaw_error(const dcmr_params_t *p, const dcmr_state_t *s, const ht_dcm_aiding_t *a,
                        const double v[3], dcmr_course_t *g)
{
    g->course = 0;
    g->air[0] = s->r[0][1] * v[1] + s->r[0][2] * v[2];
    g->air[1] = s->r[1][1] * v[1] + s->r[1][2] * v[2];
    const double nn0 = s->r[0][1], ne0 = s->r[1][1];
    const double nl = hypot(nn0, ne0);
    if (nl == 0.0) {
        return 0.0;
    }
    const double nn = nn0 / nl, ne = ne0 / nl;
    if (a->gps_fix) {
        /* the GPS velocity through the air, v_gps - W */
        const double vn = clampd(a->vel_ned_cm_s[0], 32767.0) - s->w[0];
        const double ve = clampd(a->vel_ned_cm_s[1], 32767.0) - s->w[1];
        const double sp = hypot(vn, ve);
        if (sp > p->gps_min_speed_cm_s) {
            g->course = 1;
            /* the air velocity's direction (dcm.c air_earth) */
            const double hn = g->air[0], he = g->air[1];
            const double hl = hypot(hn, he);
            const double dn = hl > 0.0 ? hn / hl : nn, de = hl > 0.0 ? he / hl : ne;
            /* the course carried forward by the heading rate times its age
             * (dcm.c gps_age_turn), at most one second, 0.5 rad */
            const int age = s->gps_age + p->lat_samples;
            const double t = (age > p->imu_rate ? p->imu_rate : age) * p->dt;
            double rq[3]; /* the rate as the library keeps it: Q16 */
            for (int i = 0; i < 3; i++) {
                rq[i] = round(s->rate[i] * 65536.0) / 65536.0;
            }
            const double psi_dot = dot(s->r[2], rq);
            const double an = clampd(psi_dot * t, 0.5);
            g->turn = an;
            const double cn = vn / sp, ce = ve / sp;
            const double c = cos(an), sn = sin(an);
            return nl * yaw_between(dn, de, cn * c - ce * sn, ce * c + cn * sn);
        }
    }
    if (a->mag_valid) {
        double mh[2] = {0, 0};
        for (int i = 0; i < 2; i++) {
            for (int j = 0; j < 3; j++) {
                mh[i] += s->r[i][j] * a->mag[j];
            }
        }
        const double ml = hypot(mh[0], mh[1]);
        if (ml > 0.0) {
            const double dec = a->mag_declination_cdeg / 100.0 * DCMR_PI / 180.0;
            return yaw_between(mh[0] / ml, mh[1] / ml, cos(dec), sin(dec));
        }
    }
    return 0.0;
}

/*
 * The wind (dcm_wind.h): at a new solution that aided the course, with a
 * live pitot, every rate within 20 deg/s and the nose within 60 degrees of
 * the horizon, the regression of the GPS velocity y on the air velocity x
 * (turned back to the epoch) learns; A and W follow in a turn.
 */
static void wind_step(const dcmr_params_t *p, dcmr_state_t *s, const ht_dcm_aiding_t *a,
                      const dcmr_course_t *g, int period)
{
    if (!g->course || !a->gps_fresh || !a->airspeed_valid || a->airspeed_cm_s <= 0) {
        return;
    }
    for (int i = 0; i < 3; i++) {
        /* the rate as the library keeps it, Q16: the gate is a comparison */
        if (fabs(round(s->rate[i] * 65536.0)) > 22876.0) {
            return;
        }
    }
    if (fabs(s->r[2][1]) > sin(60.0 * DCMR_PI / 180.0)) {
        return;
    }
    const double c = cos(g->turn), sn = sin(g->turn);
    const double x[2] = {clampd(g->air[0] * c + g->air[1] * sn, 23170.0),
                         clampd(g->air[1] * c - g->air[0] * sn, 23170.0)};
    const double y[2] = {clampd(a->vel_ned_cm_s[0], 23170.0), clampd(a->vel_ned_cm_s[1], 23170.0)};
    const double xx = x[0] * x[0] + x[1] * x[1];
    const double xy[2] = {y[0] * x[0] + y[1] * x[1], y[1] * x[0] - y[0] * x[1]};
    if (!s->wind_primed) {
        memcpy(s->mx, x, sizeof x);
        memcpy(s->my, y, sizeof y);
        s->sxx = xx;
        memcpy(s->sxy, xy, sizeof xy);
        s->a[0] = 1.0;
        s->a[1] = 0.0;
        s->wind_primed = 1;
    } else {
        const int n = period > p->imu_rate ? p->imu_rate : period;
        const double al = n * p->dt / p->wind_tau;
        for (int i = 0; i < 2; i++) {
            s->mx[i] += (x[i] - s->mx[i]) * al;
            s->my[i] += (y[i] - s->my[i]) * al;
            s->sxy[i] += (xy[i] - s->sxy[i]) * al;
        }
        s->sxx += (xx - s->sxx) * al;
    }
    const double den = s->sxx - s->mx[0] * s->mx[0] - s->mx[1] * s->mx[1];
    const double nr = s->sxy[0] - (s->my[0] * s->mx[0] + s->my[1] * s->mx[1]);
    const double ni = s->sxy[1] - (s->my[1] * s->mx[0] - s->my[0] * s->mx[1]);
    if (den <= 0.0 || den < s->sxx / 8.0) {
        return;
    }
    const double ar = nr / den, ai = ni / den;
    const double m2 = ar * ar + ai * ai;
    if (fabs(ar) > 2.0 || fabs(ai) > 2.0 || ar <= 0.0 || m2 < 0.25 || m2 > 4.0) {
        return;
    }
    s->a[0] = ar;
    s->a[1] = ai;
    const double wn = s->my[0] - (ar * s->mx[0] - ai * s->mx[1]);
    const double we = s->my[1] - (ar * s->mx[1] + ai * s->mx[0]);
    if (fabs(wn) <= 5000.0 && fabs(we) <= 5000.0) {
        s->w[0] = wn;
        s->w[1] = we;
        s->wind_solved = 1;
    }
}

void dcmr_update(const dcmr_params_t *p, dcmr_state_t *s, const double gyro_in[3],
                 const double acc_in[3], const ht_dcm_aiding_t *a)
{
    double gyro[3], acc[3];
    int acc_sat = 0;
    for (int i = 0; i < 3; i++) {
        gyro[i] = clampd(gyro_in[i], p->gyro_limit);
        acc[i] = clampd(acc_in[i], p->accel_limit);
        acc_sat |= fabs(acc_in[i]) >= p->accel_limit;
    }
    if (!s->aligned) {
        (void)dcmr_align(s, acc, 0.0);
    }
    for (int i = 0; i < 3; i++) {
        s->rate[i] = gyro[i] - s->bias[i];
    }
    /* the body air velocity (dcm.c body_velocity), cm/s: the airspeed, or the
     * GPS speed when there is none; the GPS climb (neither with CF_AIRSPEED) */
    double v_air[3] = {0, 0, 0};
    {
        const int gps = p->centripetal != HT_DCM_CF_AIRSPEED && a->gps_fix;
        double vv = 0.0;
        if (a->airspeed_valid && a->airspeed_cm_s > 0) {
            vv = a->airspeed_cm_s;
        } else if (gps) {
            double s2 = 0.0;
            for (int i = 0; i < 3; i++) {
                const double h = clampd(a->vel_ned_cm_s[i], 65535.0);
                s2 += h * h;
            }
            vv = fmin(sqrt(s2), 32767.0);
        }
        if (vv > 0.0) {
            air_velocity(s, vv, gps ? -clampd(a->vel_ned_cm_s[2], 32767.0) : 0.0, v_air);
        }
    }
    /* gravity reference: (w x v - f) / |.|, v in g*s (none with CF_OFF) */
    double v[3] = {0, 0, 0};
    if (p->centripetal != HT_DCM_CF_OFF) {
        memcpy(v, v_air, sizeof v);
    }
    for (int i = 0; i < 3; i++) {
        v[i] /= G_CM_S2;
    }
    /* the acceleration along the path (dcm.c forward_acceleration) */
    {
        double raw = 0.0;
        if (a->airspeed_valid && s->speed_prev_valid) {
            raw = clampd(a->airspeed_cm_s - s->speed_prev, 2000.0) / p->dt / G_CM_S2;
        }
        s->accel_fwd += (raw - s->accel_fwd) / 32.0;
        s->speed_prev_valid = a->airspeed_valid != 0;
        s->speed_prev = a->airspeed_cm_s;
    }
    double g[3];
    cross(s->rate, v, g);
    if (p->centripetal != HT_DCM_CF_OFF) {
        g[1] += s->accel_fwd;
    }
    for (int i = 0; i < 3; i++) {
        g[i] -= acc[i];
    }
    /* the vibration low-pass over 8 samples (dcm.c rollpitch_error) */
    for (int i = 0; i < 3; i++) {
        s->g_filt[i] = s->g_filt_valid ? s->g_filt[i] + (g[i] - s->g_filt[i]) / 8.0 : g[i];
        g[i] = s->g_filt[i];
        s->r2_filt[i] =
            s->g_filt_valid ? s->r2_filt[i] + (s->r[2][i] - s->r2_filt[i]) / 8.0 : s->r[2][i];
    }
    s->g_filt_valid = 1;
    const double gm = sqrt(dot(g, g));
    double w = 0.0;
    if (gm > 0.0 && !acc_sat) {
        w = 1.0 - fabs(gm - 1.0) / p->band;
        w = w < 0.0 ? 0.0 : w;
    }
    double erp[3] = {0, 0, 0};
    if (w > 0.0) {
        const double dm[3] = {g[0] / gm, g[1] / gm, g[2] / gm};
        cross(dm, s->r2_filt, erp);
        for (int i = 0; i < 3; i++) {
            erp[i] *= w;
        }
    }
    const int gps_period = s->gps_age + 1;
    s->gps_age = a->gps_fresh ? 0 : s->gps_age + 1;
    /* the GPS acceleration reference replaces the w x v one when it has a
     * window (dcm_gps_accel.c) */
    dcmr_ga_sample(p, &s->ga, s->r, acc, acc_sat, a);
    double ega[3];
    const int ga = dcmr_ga_error(&s->ga, s->r, s->wind_solved || a->mag_valid, ega);
    if (ga) {
        memcpy(erp, ega, sizeof ega);
        s->g_filt_valid = 0;
    } else {
        /* the w x v model's loop at half the gains (dcm.c) */
        for (int i = 0; i < 3; i++) {
            erp[i] *= 0.5;
        }
    }
    dcmr_course_t gc;
    const double ey = yaw_error(p, s, a, v_air, &gc);
    wind_step(p, s, a, &gc, gps_period);
    /* the integral learns below 20 deg/s on every axis (dcm.c), unless the
     * reference is the GPS acceleration's */
    int learn = 1;
    for (int i = 0; i < 3; i++) {
        learn &= ga || fabs(gyro[i]) <= 22876.0 / 65536.0;
    }
    /* the yaw integral learns within 10 degrees of heading error */
    const int yaw_learn = fabs(ey) <= sin(10.0 * DCMR_PI / 180.0);
    double th[3];
    for (int i = 0; i < 3; i++) {
        const double eyb = ey * s->r[2][i];
        if (learn) {
            s->bias[i] = clampd(
                s->bias[i] - (p->ki_rp * erp[i] + (yaw_learn ? p->ki_yaw * eyb : 0.0)) * p->dt,
                p->bias_max);
        }
        th[i] = clampd((gyro[i] - s->bias[i] + p->kp_rp * erp[i] + p->kp_yaw * eyb) * p->dt, 0.5);
    }
    /* propagate, second order: r <- r + c + (c x theta) / 2, c = r x theta */
    for (int k = 0; k < 3; k++) {
        double c[3], c2[3];
        cross(s->r[k], th, c);
        cross(c, th, c2);
        for (int i = 0; i < 3; i++) {
            s->r[k][i] += c[i] + 0.5 * c2[i];
        }
    }
    /* renormalize */
    const double err = dot(s->r[0], s->r[1]);
    double a0[3], a1[3];
    for (int i = 0; i < 3; i++) {
        a0[i] = s->r[0][i] - 0.5 * err * s->r[1][i];
        a1[i] = s->r[1][i] - 0.5 * err * s->r[0][i];
    }
    memcpy(s->r[0], a0, sizeof a0);
    memcpy(s->r[1], a1, sizeof a1);
    cross(a0, a1, s->r[2]);
    for (int k = 0; k < 3; k++) {
        const double sc = 0.5 * (3.0 - dot(s->r[k], s->r[k]));
        for (int i = 0; i < 3; i++) {
            s->r[k][i] *= sc;
        }
    }
}

void dcmr_from_euler(double phi, double th, double psi, double r[3][3])
{
    const double cf = cos(phi), sf = sin(phi), ct = cos(th), st = sin(th), cp = cos(psi),
                 sp = sin(psi);
    /* the FRD body-to-NED matrix C, then columns (X, Y, Z) = (-C.y, C.x, C.z) */
    const double c[3][3] = {{ct * cp, sf * st * cp - cf * sp, cf * st * cp + sf * sp},
                            {ct * sp, sf * st * sp + cf * cp, cf * st * sp - sf * cp},
                            {-st, sf * ct, cf * ct}};
    for (int i = 0; i < 3; i++) {
        r[i][0] = -c[i][1];
        r[i][1] = c[i][0];
        r[i][2] = c[i][2];
    }
}

void dcmr_rotate_body(double r0[3][3], const double w[3], double t, double out[3][3])
{
    const double wn = sqrt(dot(w, w));
    double e[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    if (wn > 0.0) {
        const double k[3] = {w[0] / wn, w[1] / wn, w[2] / wn};
        const double an = wn * t, s = sin(an), c1 = 1.0 - cos(an);
        const double kx[3][3] = {{0, -k[2], k[1]}, {k[2], 0, -k[0]}, {-k[1], k[0], 0}};
        for (int i = 0; i < 3; i++) {
            for (int j = 0; j < 3; j++) {
                double kk = 0.0;
                for (int m = 0; m < 3; m++) {
                    kk += kx[i][m] * kx[m][j];
                }
                e[i][j] += s * kx[i][j] + c1 * kk;
            }
        }
    }
    double o[3][3];
    for (int i = 0; i < 3; i++) {
        for (int j = 0; j < 3; j++) {
            o[i][j] = 0.0;
            for (int m = 0; m < 3; m++) {
                o[i][j] += r0[i][m] * e[m][j];
            }
        }
    }
    memcpy(out, o, sizeof o);
}

double dcmr_angle_between(double a[3][3], double b[3][3])
{
    /* M = A^T B: the rotation from a to b in body axes */
    double m[3][3];
    for (int i = 0; i < 3; i++) {
        for (int j = 0; j < 3; j++) {
            m[i][j] = 0.0;
            for (int k = 0; k < 3; k++) {
                m[i][j] += a[k][i] * b[k][j];
            }
        }
    }
    const double sx = 0.5 * (m[2][1] - m[1][2]), sy = 0.5 * (m[0][2] - m[2][0]),
                 sz = 0.5 * (m[1][0] - m[0][1]);
    const double c = 0.5 * (m[0][0] + m[1][1] + m[2][2] - 1.0);
    return atan2(sqrt(sx * sx + sy * sy + sz * sz), c);
}

double dcmr_ortho_err(double r[3][3])
{
    double worst = 0.0;
    for (int i = 0; i < 3; i++) {
        for (int j = 0; j < 3; j++) {
            const double e = dot(r[i], r[j]) - (i == j ? 1.0 : 0.0);
            worst = fabs(e) > worst ? fabs(e) : worst;
        }
    }
    return worst;
}

void dcmr_from_state(const ht_dcm_state_t *s, double r[3][3])
{
    for (int i = 0; i < 3; i++) {
        for (int j = 0; j < 3; j++) {
            r[i][j] = (double)s->r[i][j] / 1073741824.0;
        }
    }
}

void dcmr_to_state(double r[3][3], ht_dcm_state_t *s)
{
    for (int i = 0; i < 3; i++) {
        for (int j = 0; j < 3; j++) {
            s->r[i][j] = (int32_t)llround(r[i][j] * 1073741824.0);
        }
    }
}

void dcmr_euler(double r[3][3], double *roll, double *pitch, double *yaw)
{
    *roll = atan2(-r[2][0], r[2][2]);
    *pitch = atan2(-r[2][1], hypot(r[2][0], r[2][2]));
    double y = atan2(r[1][1], r[0][1]);
    *yaw = y < 0 ? y + 2 * DCMR_PI : y;
}
