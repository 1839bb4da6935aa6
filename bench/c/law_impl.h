/*
 * law_impl.h - the body of the float/double law (see law_real.h). Included by
 * law_f32.c / law_f64.c with LAW_REAL, LAW_SQRT, LAW_SUFFIX defined.
 */
#define LAW_CAT2(a, b) a##b
#define LAW_CAT(a, b)  LAW_CAT2(a, b)
#define LAW_T(name)    LAW_CAT(LAW_CAT(law_, name), LAW_CAT(_, LAW_SUFFIX))

static LAW_REAL LAW_T(clamp1)(LAW_REAL v)
{
    if (v > (LAW_REAL)1) {
        return (LAW_REAL)1;
    }
    if (v < (LAW_REAL)-1) {
        return (LAW_REAL)-1;
    }
    return v;
}

static LAW_REAL LAW_T(sign1)(LAW_REAL v)
{
    return (v >= (LAW_REAL)0) ? (LAW_REAL)1 : (LAW_REAL)-1; /* sign(0) = +1 */
}

void LAW_CAT(law_step_, LAW_SUFFIX)(const LAW_PARAMS *p, const LAW_INPUT *in, LAW_OUTPUT *out)
{
    const LAW_REAL g = (LAW_REAL)9.80665;
    const LAW_REAL one = (LAW_REAL)1;

    /* 1. Airspeed floor, tilt ratio and its limit. */
    LAW_REAL s = (in->airspeed > p->v_min) ? in->airspeed : p->v_min;
    LAW_REAL omega = in->turn_rate;
    LAW_REAL ratio = omega * s / g;
    if (ratio > p->max_tilt) {
        ratio = p->max_tilt;
        omega = ratio * g / s;
    } else if (ratio < -p->max_tilt) {
        ratio = -p->max_tilt;
        omega = ratio * g / s;
    }

    /* 2. Eq. 5: R1 = [-ratio, 0, 1] / sqrt(ratio^2 + 1). */
    LAW_REAL n1 = one / LAW_SQRT(ratio * ratio + one);
    LAW_REAL x1 = -ratio * n1;
    LAW_REAL z1 = n1;

    /* 3. Eq. 6: [X1, -p, Z1] / sqrt(p^2 + 1); inverted flips X and Z. */
    LAW_REAL n2 = one / LAW_SQRT(in->pitch * in->pitch + one);
    LAW_REAL xt = x1 * n2;
    LAW_REAL yt = -in->pitch * n2;
    LAW_REAL zt = z1 * n2;
    if (in->inverted) {
        xt = -xt;
        zt = -zt;
    }

    /* 4. Eq. 3: target body rate from the actual tilt. */
    LAW_REAL wd[3] = {omega * in->x, omega * in->y, omega * in->z};

    /* 5. Eq. 8-9: roll error. */
    LAW_REAL roll_dot = in->x * xt + in->z * zt;
    LAW_REAL roll_cross = in->z * xt - zt * in->x;
    LAW_REAL roll_err = (roll_dot > (LAW_REAL)0) ? roll_cross : LAW_T(sign1)(roll_cross);

    /* 6. Eq. 10: earth-frame pitch error, saturated beyond 90 degrees. */
    LAW_REAL a = LAW_SQRT(in->x * in->x + in->z * in->z);
    LAW_REAL t = LAW_SQRT(xt * xt + zt * zt);
    LAW_REAL pe = yt * a - in->y * t;
    if (in->y * yt + a * t <= (LAW_REAL)0) {
        pe = LAW_T(sign1)(pe);
    }

    /* 7. Eq. 11: projection; fuselage vertical (a == 0): direction [-1, 0, 0],
     * the library's documented choice. */
    LAW_REAL e[3];
    if (a > (LAW_REAL)0) {
        LAW_REAL k = pe / a;
        e[0] = -in->z * k;
        e[2] = in->x * k;
    } else {
        e[0] = -pe;
        e[2] = (LAW_REAL)0;
    }
    e[1] = roll_err;

    /* 9-10. Airspeed scales and the demands. */
    LAW_REAL s_ff = p->v_ref / s;
    LAW_REAL s_p = p->schedule ? s_ff : one;
    LAW_REAL d[3];
    for (int i = 0; i < 3; i++) {
        d[i] = -p->kp[i] * s_p * e[i] + p->kff[i] * s_ff * wd[i] +
               p->kd[i] * s_p * (wd[i] - in->gyro[i]);
    }

    /* 11. Surfaces. */
    out->aileron = LAW_T(clamp1)(d[1]);
    out->elevator = LAW_T(clamp1)(-d[0]);
    out->rudder = LAW_T(clamp1)(d[2]);
}
