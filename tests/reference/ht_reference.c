/*
 * ht_reference.c - docs/control-law.md, step by step, in double.
 * Deliberately literal: no algebraic shortcuts that the fixed-point core uses
 * (it computes t from X^, Z^ and normalizes twice, as Eq. 5 and 6 say).
 */
#include "ht_reference.h"

#include <math.h>

#define G_M_S2 9.80665

static double sign_pos(double v)
{
    return (v >= 0.0) ? 1.0 : -1.0; /* sign(0) = +1 */
}

static double clamp1(double v)
{
    return (v > 1.0) ? 1.0 : ((v < -1.0) ? -1.0 : v);
}

void ht_ref_params_from_controller(const ht_controller_t *ctl, ht_ref_params_t *p)
{
    for (int i = 0; i < 3; i++) {
        p->kp[i] = ctl->gains.kp[i] / 65536.0;
        p->kff[i] = ctl->gains.kff[i] / 65536.0;
        p->kd[i] = ctl->gains.kd[i] / 65536.0;
    }
    p->v_ref = ctl->v_ref_cm_s / 100.0;
    p->v_min = ctl->v_min_cm_s / 100.0;
    p->max_tilt = ctl->max_tilt / 65536.0;
    p->schedule = ctl->schedule;
    p->pitch_mode = ctl->pitch_mode;
    p->roll_in = ctl->roll_in;
    p->roll_in_max = ctl->roll_in_max_q25 / 33554432.0;
    p->kp_sideslip = ctl->kp_sideslip / 65536.0;
    p->vertical_fade = ctl->vertical_fade / 65536.0;
}

void ht_ref_input_from_fixed(const ht_input_t *in, ht_ref_input_t *r)
{
    r->x = in->x / 16384.0;
    r->y = in->y / 16384.0;
    r->z = in->z / 16384.0;
    r->turn_rate = in->turn_rate_rad_s / 2048.0;
    r->pitch = in->pitch_ratio / 65536.0;
    r->airspeed = in->airspeed_cm_s / 100.0;
    for (int i = 0; i < 3; i++) {
        r->gyro[i] = in->gyro_rad_s[i] / 2048.0;
    }
    r->inverted = in->inverted != 0;
    r->turn_accel = in->turn_accel_rad_s2 / 2048.0;
    r->accel_lat = in->accel_lat_g / 16384.0;
}

void ht_ref_step(const ht_ref_params_t *p, const ht_ref_input_t *in, ht_ref_output_t *o)
{
    /* 1. airspeed floor, tilt ratio and its limit */
    double s = (in->airspeed > p->v_min) ? in->airspeed : p->v_min;
    double ratio = in->turn_rate * s / G_M_S2;
    double omega = in->turn_rate;
    o->ratio_margin = fabs(ratio) - p->max_tilt;
    if (fabs(ratio) > p->max_tilt) {
        ratio = (ratio > 0) ? p->max_tilt : -p->max_tilt;
        omega = ratio * G_M_S2 / s;
    }
    o->turn_rate_used = omega;
    o->ratio = ratio;

    /* 2. Eq. 5 */
    double n1 = sqrt(ratio * ratio + 1.0);
    double x1 = -ratio / n1, z1 = 1.0 / n1;
    /* 3. Eq. 6, inverted */
    double n2 = sqrt(in->pitch * in->pitch + 1.0);
    double xt = x1 / n2, yt = -in->pitch / n2, zt = z1 / n2;
    if (in->inverted) {
        xt = -xt;
        zt = -zt;
    }
    o->tilt[0] = xt;
    o->tilt[1] = yt;
    o->tilt[2] = zt;

    /* 4. Eq. 3 */
    double row[3] = {in->x, in->y, in->z};
    for (int i = 0; i < 3; i++) {
        o->rate[i] = omega * row[i];
    }

    /* 5. Eq. 8, 9 */
    o->roll_dot = in->x * xt + in->z * zt;
    o->roll_cross = in->z * xt - zt * in->x;
    o->roll_error = (o->roll_dot > 0) ? o->roll_cross : sign_pos(o->roll_cross);

    /* Option roll-in: d/dt atan(ratio) at constant S, none while the tilt
     * limit holds the target, bounded. */
    o->roll_in_rate = 0.0;
    if (p->roll_in && !(o->ratio_margin > 0)) {
        double rd = in->turn_accel * s / G_M_S2 / (1.0 + ratio * ratio);
        if (fabs(rd) > p->roll_in_max) {
            rd = (rd > 0) ? p->roll_in_max : -p->roll_in_max;
        }
        o->roll_in_rate = rd;
    }

    /* 6, 7. Eq. 10, 11 (or Eq. A.13) */
    double a = sqrt(in->x * in->x + in->z * in->z);
    /* Option vertical fade of the roll error. */
    o->roll_fade = 1.0;
    if (p->vertical_fade > 0 && a < p->vertical_fade) {
        o->roll_fade = a / p->vertical_fade;
        o->roll_error *= o->roll_fade;
    }
    double t = sqrt(xt * xt + zt * zt);
    o->a = a;
    double e[3];
    if (p->pitch_mode == HT_PITCH_TILT_CROSS) {
        o->pitch_raw = 0.0;
        o->pitch_agree = 1.0;
        o->pitch_error = 0.0;
        e[0] = in->y * zt - yt * in->z;
        e[2] = in->x * yt - xt * in->y;
    } else {
        double pe = yt * a - in->y * t;
        o->pitch_raw = pe;
        o->pitch_agree = in->y * yt + a * t;
        if (o->pitch_agree <= 0) {
            pe = sign_pos(pe);
        }
        o->pitch_error = pe;
        if (a > 0) {
            e[0] = pe / a * -in->z;
            e[2] = pe / a * in->x;
        } else { /* the core's documented choice for a vertical fuselage */
            e[0] = -pe;
            e[2] = 0.0;
        }
    }
    e[1] = o->roll_error;
    o->pitch_body_x = e[0];
    o->pitch_body_z = e[2];

    /* 9-11. */
    double s_ff = p->v_ref / s;
    double s_p = p->schedule ? s_ff : 1.0;
    double d[3];
    const double rate_d[3] = {o->rate[0], o->rate[1] + o->roll_in_rate, o->rate[2]};
    for (int i = 0; i < 3; i++) {
        d[i] = -p->kp[i] * s_p * e[i] + p->kff[i] * s_ff * rate_d[i] +
               p->kd[i] * s_p * (rate_d[i] - in->gyro[i]);
    }
    /* Option sideslip: rudder toward zero lateral specific force. */
    o->sideslip_rudder = p->kp_sideslip * in->accel_lat;
    d[2] += o->sideslip_rudder;
    for (int i = 0; i < 3; i++) {
        o->demand[i] = d[i];
    }
    o->aileron = clamp1(d[1]);
    o->elevator = clamp1(-d[0]);
    o->rudder = clamp1(d[2]);
}
