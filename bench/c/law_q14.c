/*
 * law_q14.c - the helical-turn law in 16-bit fixed point with 32-bit
 * intermediates (see law_q14.h), written from docs/control-law.md and
 * following law_impl.h step by step. Bench code: it measures what a law
 * without the library's Q28 internals and exact 32x32->64 products costs,
 * and how far its surfaces land from the double law as the gains grow.
 *
 * Formats: DCM row, target tilt, errors, surfaces Q14 (int16); turn rate and
 * body rates Q11 (int16); tilt ratio and pitch ratio int16 in Q14 below 2
 * and Q12 below 8 (their rounding moves the target tilt, which kp * s_p
 * amplifies, so the finer format where it fits); gains Q12 (int16, [0, 8));
 * the airspeed scale v_ref / S Q11 (int16, < 16); square-root mantissas Q15
 * (16 bits unsigned). Every product is of two such values (at most 2^30),
 * so int32 holds it; sums are sized to stay below 2^31.
 *
 * Where its error comes from (bench/README.md has the measured figures):
 * every value is rounded to its 16-bit format before the gains multiply it.
 * Half an LSB of a Q14 error times kp * s_p, and half an LSB of a Q11 target
 * rate (4 Q14 LSB) times (kff + kd) * s_ff, land on the surface as they are:
 * about 0.5 * 30 + 4 * 2 * 5 = 55 LSB on the elevator of the c172p set.
 *
 * Cost choices: one unsigned division per step for v_ref / S (SDIV/UDIV on
 * the M3/M4, libgcc's __aeabi_uidiv on the M0); one reciprocal square root
 * routine (a 24-entry table and two Newton steps, normalized with CLZ),
 * called three times: Eq. 5 (1 + r^2), Eq. 6 (1 + p^2) and Eq. 10-11
 * (X^2 + Z^2, which also gives a = sqrt(X^2 + Z^2) without a second root).
 * The target's horizontal length t of Eq. 10 is 1 / sqrt(1 + p^2) in closed
 * form.
 */
#include "law_q14.h"

#include <stddef.h>

#define ONE_Q14 16384
#define ONE_Q15 32768 /* the one mantissa that needs the 17th bit (int32) */

static int32_t sat16(int32_t v)
{
    return (v > INT16_MAX) ? INT16_MAX : ((v < INT16_MIN) ? INT16_MIN : v);
}

static int32_t clamp_unit(int32_t v)
{
    return (v > ONE_Q14) ? ONE_Q14 : ((v < -ONE_Q14) ? -ONE_Q14 : v);
}

/* round(v / 2^n), ties up, n in [0, 30]. */
static int32_t rshift_round(int32_t v, int n)
{
    return (n == 0) ? v : ((v + (1 << (n - 1))) >> n);
}

static int32_t sign_unit(int32_t v)
{
    return (v >= 0) ? ONE_Q14 : -ONE_Q14; /* sign(0) = +1 */
}

/* 32768 / sqrt(m) for m in [1, 4) at the midpoints of 24 intervals of 1/8:
 * a first guess within 3 %, which two Newton steps bring below the
 * rounding (one would leave ~1.5e-3). */
static const int16_t rsqrt_table[24] = {31790, 30070, 28602, 27330, 26214, 25225, 24339, 23541,
                                        22817, 22155, 21548, 20988, 20470, 19988, 19539, 19119,
                                        18725, 18354, 18004, 17674, 17361, 17064, 16782, 16514};

/*
 * 1/sqrt of an integer m > 0: m = mn * 4^j with mn in [2^14, 2^16) (Q14 in
 * [1, 4)); returns y = 1/sqrt(mn / 2^14) in Q15, (0.5, 1] (a 16-bit
 * unsigned mantissa: one more bit than Q14 for the products it scales), so
 * that 1/sqrt(m) = y * 2^(-22 - j), and *root = sqrt(mn / 2^14)
 * in Q14 (the mantissa of sqrt(m) = root * 2^(j - 7)). The even shift keeps
 * the exponent halvable; CLZ finds it (a libgcc call on the M0).
 */
static int32_t rsqrt_norm(uint32_t m, int *j, int32_t *root)
{
    const int b = 31 - __builtin_clz(m); /* top bit */
    const int jj = (b - 14) >> 1;        /* floor: the top bit lands on 14 or 15 */
    uint32_t mn;
    if (jj > 0) {
        /* rounded, capped so that the table index stays in range */
        mn = (m + (1u << (2 * jj - 1))) >> (2 * jj);
        mn = (mn > 0xFFFFu) ? 0xFFFFu : mn;
    } else {
        mn = m << (-2 * jj);
    }
    int32_t y = rsqrt_table[(mn >> 11) - 8u];
    for (int k = 0; k < 2; k++) {
        /* y <- y (3 - mn y^2) / 2 in Q15; mn * y < 2^31 as unsigned */
        const int32_t t = (int32_t)((mn * (uint32_t)y + 16384u) >> 15); /* ~ sqrt(mn), Q14 */
        const int32_t u = (t * y + 16384) >> 15;                        /* ~ 1, Q14 */
        y = (y * (3 * ONE_Q14 - u) + ONE_Q14) >> 15;
    }
    y = (y > ONE_Q15) ? ONE_Q15 : y;
    *j = jj;
    if (root != NULL) {
        const int32_t r = (int32_t)((mn * (uint32_t)y + 16384u) >> 15);
        *root = (r > INT16_MAX) ? INT16_MAX : r;
    }
    return y;
}

/* 1/sqrt(1 + v^2) for v = v_int / 2^f (f = 12 or 14, |v_int| < 2^15):
 * the Q15 mantissa, and *sh with the result = mantissa * 2^-(15 + sh).
 * 1 + v^2 is taken in Q(2f), below 2^31; from rsqrt_norm's exponent,
 * 1/sqrt(m / 2^(2f)) = y * 2^(f - 7 - j) / 2^15, so sh = j + 7 - f >= 0.
 * v == 0 (no turn, or level flight asked) skips the root, as the library
 * does. */
static int32_t inv_hypot1(int32_t v, int f, int *sh)
{
    if (v == 0) {
        *sh = 0;
        return ONE_Q15;
    }
    int j;
    const int32_t y = rsqrt_norm((uint32_t)(v * v) + (1u << (2 * f)), &j, NULL);
    *sh = j + 7 - f;
    return y;
}

/* One axis (step 10), Q14 command before the clamp:
 *   d = -kp*s_p*e + kff*s_ff*w + kd*s_p*(w - g).
 * The gain products are summed in Q20 (each below 2^27) and rounded once. */
static int32_t axis_demand(const law_q14_ctl_t *c, int i, int32_t s_ff, int32_t e, int32_t w,
                           int32_t g)
{
    const int32_t p_q20 = (c->kp[i] * e) >> 6; /* Q12 * Q14 = Q26 */
    if (c->schedule != 0u) {
        /* s_p = s_ff: d = s_ff * ((kff + kd) w - kd g - kp e), one scale */
        const int32_t sum = ((c->kffd[i] * w) >> 3) - ((c->kd[i] * g) >> 3) - p_q20;
        /* The bracket saturates at +/-2 in Q14 to stay a 16-bit factor: exact
         * while s_ff >= 1/2 (S <= 2 v_ref), where |bracket| >= 2 clamps the
         * surface anyway; beyond 2 v_ref a demand above 2 / s_ff is cut. */
        const int32_t inner = sat16(rshift_round(sum, 6));
        return rshift_round(inner * s_ff, 11);
    }
    const int32_t ff = sat16(rshift_round(c->kff[i] * w, 9)); /* Q12 * Q11 -> Q14 */
    const int32_t rate_err = sat16(w - g);
    const int32_t sum = ((ff * s_ff) >> 5) + ((c->kd[i] * rate_err) >> 3) - p_q20;
    return rshift_round(sum, 6);
}

int32_t law_q14_init(law_q14_ctl_t *ctl, const ht_params_t *p)
{
    if (ctl == NULL || p == NULL) {
        return 1;
    }
    const q16_t *kp[3] = {&p->kp_elevator, &p->kp_aileron, &p->kp_rudder};
    const q16_t *kff[3] = {&p->kff_elevator, &p->kff_aileron, &p->kff_rudder};
    const q16_t *kd[3] = {&p->kd_elevator, &p->kd_aileron, &p->kd_rudder};
    for (int i = 0; i < 3; i++) {
        /* Q16 -> Q12, rounded; gains of 8 and more saturate (the library
         * takes up to 64: the price of a 16-bit gain with a useful LSB) */
        const int32_t a = sat16((*kp[i] + 8) >> 4);
        const int32_t f = sat16((*kff[i] + 8) >> 4);
        const int32_t d = sat16((*kd[i] + 8) >> 4);
        ctl->kp[i] = (int16_t)a;
        ctl->kff[i] = (int16_t)f;
        ctl->kd[i] = (int16_t)d;
        ctl->kffd[i] = (int16_t)sat16(f + d);
    }
    ctl->v_ref_cm_s = (int16_t)sat16(p->v_ref_cm_s);
    ctl->v_min_cm_s = (int16_t)sat16(p->v_min_cm_s);
    ctl->schedule = p->schedule;
    const int32_t mt = sat16((p->max_tilt + 8) >> 4);
    ctl->max_tilt_q12 = (int16_t)mt;
    /* ratio * g * 2048 * 100 = ratio_q12 * 490.3325: 31381 / 64 */
    ctl->tilt_lim = (mt * 31381 + 32) >> 6;
    return 0;
}

void law_step_q14(const law_q14_ctl_t *c, const ht_input_t *in, law_q14_output_t *out)
{
    /* 1. Airspeed floor (v_min >= 1 m/s, so S > 0), the one division
     * s_ff = v_ref / S in Q11, and the tilt limit. */
    int32_t s = in->airspeed_cm_s;
    if (s < c->v_min_cm_s) {
        s = c->v_min_cm_s;
    }
    const uint32_t su = (uint32_t)s;
    const int32_t s_ff =
        sat16((int32_t)(((uint32_t)c->v_ref_cm_s * 2048u + su / 2u) / su)); /* < 16 */

    int32_t omega = in->turn_rate_rad_s; /* Q11 */
    const int32_t ws = omega * s;        /* |.| < 2^30 */
    const int32_t ws_mag = (ws < 0) ? -ws : ws;
    /* The tilt ratio in int16: Q14 below 2 (the usual turns: 4 times finer,
     * the error it leaves is amplified by kp * s_p), Q12 up to max_tilt. */
    int32_t ratio;
    int fr = 12;
    if (ws_mag > c->tilt_lim) {
        /* clamped: omega = max_tilt * g / S (a second division, on this
         * branch only; |omega| only shrinks, so it stays Q11) */
        ratio = c->max_tilt_q12;
        omega = (int32_t)(((uint32_t)c->tilt_lim + su / 2u) / su);
        if (ws < 0) {
            ratio = -ratio;
            omega = -omega;
        }
    } else {
        /* ratio = ws / 490.3325 in Q12 = (ws / 256) * 8554 / 2^14 (2^22 /
         * 490.3325 = 8554.0): ws < 2^24 here, so the product < 2^30; the
         * same constant gives Q14 from ws / 64 while ws < 2 * 4 * 490.3 */
        if (ws_mag < 4016000) {
            ratio = (((ws_mag + 32) >> 6) * 8554 + 8192) >> 14;
            fr = 14;
        } else {
            ratio = (((ws_mag + 128) >> 8) * 8554 + 8192) >> 14;
        }
        if (ws < 0) {
            ratio = -ratio;
        }
    }

    /* 2. Eq. 5: c1 = 1/sqrt(1 + r^2) = y1 * 2^-(15 + sh1). */
    int sh1;
    const int32_t y1 = inv_hypot1(ratio, fr, &sh1);

    /* 3. Eq. 6: c2 = 1/sqrt(1 + p^2) = y2 * 2^-(15 + sh2) and Yt = -p c2;
     * p (Q16 input) in int16 as Q14 below 2, Q12 below 8. */
    const int32_t pq16 = in->pitch_ratio;
    const uint32_t p_mag = (pq16 < 0) ? 0u - (uint32_t)pq16 : (uint32_t)pq16;
    int32_t y2, yt;
    int sh2;
    if (p_mag < 0x7FFF8u) {
        const int fp = (p_mag < 0x1FFFEu) ? 14 : 12;
        const int drop = 16 - fp;
        const int32_t pv = (pq16 + (1 << (drop - 1))) >> drop; /* fits int16 */
        y2 = inv_hypot1(pv, fp, &sh2);
        yt = -rshift_round(pv * y2, fp + 1 + sh2);
    } else {
        /* Beyond 83 degrees, p does not fit Q12: with q = 1/|p| (Q14, a
         * division on this branch only), h = 1/sqrt(1 + q^2) gives
         * Yt = -sign(p) h and c2 = q h. */
        const int32_t qq = (int32_t)(((1u << 30) + p_mag / 2u) / p_mag); /* <= 2048 */
        int shq;
        const int32_t h = inv_hypot1(qq, 14, &shq); /* shq == 0: 1 + q^2 < 4 */
        const int32_t h14 = rshift_round(h, 1);
        yt = (pq16 > 0) ? -h14 : h14;
        y2 = (qq * h + 8192) >> 14; /* Q15 */
        sh2 = 0;
    }
    /* Target [-r c1 c2, -p c2, c1 c2] in Q14 from the Q15 mantissas, one
     * rounding each. */
    const int32_t yy = (y1 * y2 + 16384) >> 15; /* c1 c2 * 2^(sh1 + sh2), Q15 */
    int32_t zt = rshift_round(yy, 1 + sh1 + sh2);
    int32_t xt = -rshift_round(ratio * yy, fr + 1 + sh1 + sh2);
    const int32_t t = rshift_round(y2, 1 + sh2); /* sqrt(Xt^2 + Zt^2) = c2 */
    if (in->inverted != 0u) {
        xt = -xt;
        zt = -zt;
    }

    /* 4. Eq. 3: target body rates from the actual row, Q11. */
    const int32_t x = in->x, y = in->y, z = in->z;
    int32_t w[3];
    w[0] = sat16(rshift_round(omega * x, 14));
    w[1] = sat16(rshift_round(omega * y, 14));
    w[2] = sat16(rshift_round(omega * z, 14));

    /* 5. Eq. 8-9: roll error. */
    int32_t e[3];
    const int32_t roll_dot = x * xt + z * zt; /* Q28, each |.| <= 2^29 */
    const int32_t roll_cross = sat16(rshift_round(z * xt - zt * x, 14));
    e[1] = (roll_dot > 0) ? roll_cross : sign_unit(roll_cross);

    /* 6. Eq. 10: a = sqrt(X^2 + Z^2) (Q28 sum, at most 2^31: unsigned). */
    const uint32_t m = (uint32_t)(x * x) + (uint32_t)(z * z);
    int32_t a = 0, ya = 0;
    int ja = 0;
    if (m != 0u) {
        int32_t root;
        ya = rsqrt_norm(m, &ja, &root);
        /* a = root * 2^(ja - 7) in Q14; ja in [-7, 8], a < 2.83 (int32) */
        a = (ja >= 7) ? root << (ja - 7) : rshift_round(root, 7 - ja);
    }
    int32_t pe = rshift_round(yt * a - y * t, 14);
    if (y * yt + a * t <= 0) {
        pe = sign_unit(pe); /* beyond 90 degrees */
    }
    /* |pe| > 2 only for a row far from unit length: saturate to 16 bits */
    pe = sat16(pe);

    /* 7. Eq. 11: e = pe / a * [-Z, X]; 1/a = ya * 2^(7 - ja) / 2^15, so
     * pe/a * X = (pe * ya / 2^15) * X / 2^(7 + ja), 7 + ja >= 0. */
    if (m != 0u) {
        const int32_t k = (pe * ya + 16384) >> 15; /* |.| <= 2^15 */
        e[0] = sat16(-rshift_round(z * k, 7 + ja));
        e[2] = sat16(rshift_round(x * k, 7 + ja));
    } else {
        /* Fuselage vertical: direction [-1, 0, 0], as the library. */
        e[0] = -pe;
        e[2] = 0;
    }

    /* 9-11. Demands and surfaces. */
    out->elevator = (int16_t)clamp_unit(-axis_demand(c, 0, s_ff, e[0], w[0], in->gyro_rad_s[0]));
    out->aileron = (int16_t)clamp_unit(axis_demand(c, 1, s_ff, e[1], w[1], in->gyro_rad_s[1]));
    out->rudder = (int16_t)clamp_unit(axis_demand(c, 2, s_ff, e[2], w[2], in->gyro_rad_s[2]));
    out->tilt_x = (int16_t)sat16(xt);
    out->tilt_y = (int16_t)sat16(yt);
    out->tilt_z = (int16_t)sat16(zt);
}
