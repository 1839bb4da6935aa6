/*
 * guide.c - the turn-rate trim (include/helical/guidance/guide.h has why and how).
 * Integer only; the caller owns the state.
 */
#include <stddef.h>

#include "helical/guidance/guide.h"

#include "math/q_inline.h"

void ht_guide_reset(ht_guide_state_t *s)
{
    if (s != NULL) {
        const ht_guide_state_t z = {0};
        *s = z;
    }
}

/* |h|^2 of a heading vector at least 0.3^2 (a nose within 72 degrees of the
 * vertical), Q26: below it the heading's direction is noise. */
#define MIN_H2_Q26 ((int32_t)6039798)

/*
 * The heading's rate between two steps, Q20 rad/s, into *rate; 0 when there
 * is none (no previous heading, a nose near the vertical, a turn of more
 * than 0.1 rad in one step). tan(dpsi) = cross / dot of the two vectors,
 * taken in Q13 (any int16 input: each product <= 2^28, the sums fit); the
 * tangent's 1 + dpsi^2/3 is 1.4e-5
 * at 15 deg/s and 40 Hz. The tangent is rounded to nearest in Q20 and the
 * rate is its exact multiple: a truncation, a rounding of ties (2.5 LSB
 * steps at 40 Hz) or the law's Q11 would bias a steady turn's rate every step
 * (up to 0.15 % at 10 deg/s in Q11), which the trim would fly. Summed over steps the angles
 * telescope, so the heading's Q14 rounding does not bias the mean either.
 */
static int heading_rate(const ht_guide_t *g, const ht_guide_state_t *s, q14_t n, q14_t e,
                        int32_t *rate)
{
    *rate = 0;
    if (s->have_prev == 0u) {
        return 0;
    }
    const int32_t pn = (int32_t)s->prev_north / 2;
    const int32_t pe = (int32_t)s->prev_east / 2;
    const int32_t cn = (int32_t)n / 2;
    const int32_t ce = (int32_t)e / 2;
    const int32_t cross = (pn * ce) - (pe * cn);
    const int32_t dot = (pn * cn) + (pe * ce);
    const int32_t h2 = (cn * cn) + (ce * ce);
    if (h2 < MIN_H2_Q26 || dot < MIN_H2_Q26) {
        return 0;
    }
    const int32_t lim = dot / 10;
    if (cross > lim || cross < -lim) {
        return 0; /* more than 0.1 rad in one step: a glitch, not a turn */
    }
    /* tan(dpsi) in Q20 = cross * 2^20 / dot, by dot's reciprocal (relative
     * error 3.7e-9, q_recip_q30): 1/dot = m 2^-(30+e), so the quotient is
     * cross * m / 2^(10+e), correctly rounded (e <= 30: the shift <= 40) */
    unsigned e2 = 0u;
    const int32_t m = q_recip_q30(dot, &e2);
    const int32_t ratio_q20 = q_mul32(cross, m, 10u + e2);
    /* |ratio| <= 0.1 * 2^20, times at most 1000: fits */
    *rate = ratio_q20 * (int32_t)g->rate_hz;
    return 1;
}

/* One step of k from the relative error of the measured rate (Q20). */
static int32_t learn(const ht_guide_t *g, int32_t k_q30, int32_t cmd, int32_t measured_q20)
{
    const int32_t mag = (cmd < 0) ? -cmd : cmd; /* Q11, >= min_rate_q11 >= 1 */
    /* (cmd - measured) / cmd, clamped to +/-0.5 before the division so that
     * a glitch (a gust, a stall) cannot throw the trim: |diff| <= 256 mag
     * (cmd in Q20 is cmd * 512, <= 2^24) */
    const int32_t half_q20 = mag * 256;
    const int32_t diff = q_clamp32((cmd * 512) - measured_q20, -half_q20, half_q20);
    const int32_t signed_diff = (cmd < 0) ? -diff : diff;
    /* the ratio in Q30 = diff_q20 * 2^21 / mag_q11, by mag's reciprocal
     * (1/mag = m 2^-(30+e), e <= 15): correctly rounded, |.| <= 2^29 */
    unsigned e = 0u;
    const int32_t m = q_recip_q30(mag, &e);
    const int32_t ratio_q30 = q_mul32(signed_diff, m, 9u + e);
    /* per tau_ticks steps, rounded half away from zero: a truncation would
     * drift k by up to an LSB a step in a steady turn */
    const int32_t step_q30 = qi_div_round(ratio_q30, g->tau_ticks);
    return q_clamp32(k_q30 + step_q30, -g->max_q30, g->max_q30);
}

q11_t ht_guide_turn_rate(const ht_guide_t *g, ht_guide_state_t *s, q11_t cmd, q14_t heading_north,
                         q14_t heading_east, uint8_t hold)
{
    if (g == NULL || s == NULL || g->ready == 0u || g->p.turn_trim == 0u) {
        return cmd;
    }
    int32_t measured = 0;
    const int have_rate = heading_rate(g, s, heading_north, heading_east, &measured);
    s->prev_north = heading_north;
    s->prev_east = heading_east;
    s->have_prev = 1u;
    const int32_t c = cmd;
    const int32_t mag = (c < 0) ? -c : c;
    if (mag < (int32_t)g->min_rate_q11) {
        s->k_q30 = 0;
        s->steady = 0u;
        s->last_cmd = cmd;
        return cmd;
    }
    if ((c < 0) != (s->last_cmd < 0) || s->last_cmd == 0) {
        s->k_q30 = 0; /* a new direction: its roll moment is another */
    }
    if (cmd != s->last_cmd) {
        s->steady = 0u; /* the modes are slewing it: an entry, not a turn */
    } else if (s->steady < g->hold_ticks) {
        s->steady++;
    } else {
        /* steady */
    }
    s->last_cmd = cmd;
    if (s->steady >= g->hold_ticks && hold == 0u && have_rate != 0) {
        s->k_q30 = learn(g, s->k_q30, c, measured);
    }
    /* cmd (1 + k), rounded; |k| <= 0.5 keeps |result| <= 1.5 * 32768 */
    return q_sat16(c + q_mul32(c, s->k_q30, 30u));
}
