/*
 * nav.c - waypoint navigation and the two guidance laws (nav.h).
 * Integer only: no float, no libm, no allocation, no recursion, no global
 * mutable state. Directions are Q28 unit vectors from q_unit2_q28.
 */
#include "helical/guidance/nav.h"

#include <stdbool.h>
#include <stddef.h>

#define DEG_TO_RAD_Q30 18740330L /* pi / 180 in Q30 */
#define Q28_ONE        ((int32_t)HT_Q28_ONE)

static int32_t abs32_sat(int32_t v)
{
    return (v == INT32_MIN) ? INT32_MAX : ((v < 0) ? -v : v);
}

static ht_nav_param_id_t check(const ht_nav_params_t *p, const ht_waypoint_t *w, uint16_t count,
                               uint16_t *bad_wp)
{
    const ht_nav_param_id_t row = ht_nav_first_bad(p);
    if (row != HT_NAV_P_NONE) {
        return row;
    }
    if (count > HT_NAV_MAX_WAYPOINTS || (count > 0u && w == NULL)) {
        return HT_NAV_P_WAYPOINT_COUNT;
    }
    for (uint16_t i = 0; i < count; i++) {
        if (abs32_sat(w[i].north_m) > HT_NAV_COORD_MAX_M ||
            abs32_sat(w[i].east_m) > HT_NAV_COORD_MAX_M ||
            abs32_sat(w[i].alt_m) > HT_NAV_ALT_MAX_M) {
            *bad_wp = i;
            return HT_NAV_P_WAYPOINT;
        }
    }
    return HT_NAV_P_NONE;
}

/* floor(2^36 / len) for len in [500, 500000] cm: below 2^28, exact. */
static int32_t inv_q36(int32_t len)
{
    uint32_t l = (uint32_t)len;
    uint32_t q = ((uint32_t)1u << 31) / l;
    uint32_t r = ((uint32_t)1u << 31) % l;
    const uint32_t v = (q * 32u) + ((r * 32u) / l);
    return (int32_t)v;
}

int ht_nav_init(ht_nav_t *nav, const ht_nav_params_t *p, const ht_waypoint_t *waypoints,
                uint16_t count, ht_nav_param_id_t *bad_field, uint16_t *bad_waypoint)
{
    if (bad_field != NULL) {
        *bad_field = HT_NAV_P_NONE;
    }
    if (bad_waypoint != NULL) {
        *bad_waypoint = 0u;
    }
    if (nav == NULL || p == NULL) {
        return 1;
    }
    ht_nav_t z = {0};
    *nav = z;
    uint16_t bad_wp = 0u;
    ht_nav_param_id_t bad = check(p, waypoints, count, &bad_wp);
    if (bad != HT_NAV_P_NONE) {
        if (bad_field != NULL) {
            *bad_field = bad;
        }
        if (bad_waypoint != NULL) {
            *bad_waypoint = bad_wp;
        }
        return 2;
    }
    nav->law = p->law;
    nav->loop = p->loop;
    nav->turn_rate_max_rad_s =
        q_mul32((int32_t)p->turn_rate_max_deg_s * 65536, DEG_TO_RAD_Q30, 30u);
    nav->l1_cm = (int32_t)p->l1_m * 100;
    nav->inv_l1_q36 = inv_q36(nav->l1_cm);
    nav->arrival_cm = (int32_t)p->arrival_radius_m * 100;
    nav->loiter_cm = (int32_t)p->loiter_radius_m * 100;
    nav->inv_loiter_q36 = inv_q36(nav->loiter_cm);
    nav->home_alt_cm = p->home_alt_m * 100;
    nav->v_floor_cm_s = p->v_floor_cm_s;
    nav->course_min_cm_s = p->course_min_cm_s;
    nav->waypoints = waypoints;
    nav->count = count;
    nav->ready = 1u;
    return 0;
}

void ht_nav_reset(ht_nav_state_t *s, int32_t north_cm, int32_t east_cm)
{
    if (s == NULL) {
        return;
    }
    ht_nav_state_t z = {0};
    *s = z;
    s->from_north_cm = north_cm;
    s->from_east_cm = east_cm;
}

void ht_nav_start_leg(ht_nav_state_t *s, int32_t north_cm, int32_t east_cm)
{
    if (s == NULL) {
        return;
    }
    s->from_north_cm = north_cm;
    s->from_east_cm = east_cm;
    s->home_loiter = 0u;
}

/* --- vector helpers (Q28 unit vectors, cm lengths) ----------------------- */

/* u . v with u a Q28 unit vector and v in any format: the result in v's format. */
static int32_t dot_u(int32_t un, int32_t ue, int32_t vn, int32_t ve)
{
    return q_add_sat32(q_mul32(vn, un, 28u), q_mul32(ve, ue, 28u));
}

/* u x v = u_n v_e - u_e v_n (+ when v is clockwise from u), in v's format. */
static int32_t cross_u(int32_t un, int32_t ue, int32_t vn, int32_t ve)
{
    return q_sub_sat32(q_mul32(ve, un, 28u), q_mul32(vn, ue, 28u));
}

int32_t ht_nav_sin_error_q28(int32_t a_north, int32_t a_east, int32_t d_north, int32_t d_east,
                             uint8_t *beyond_90)
{
    int32_t an, ae, dn, de;
    if (beyond_90 != NULL) {
        *beyond_90 = 0u;
    }
    if (!q_unit2_q28(a_north, a_east, &an, &ae) || !q_unit2_q28(d_north, d_east, &dn, &de)) {
        return 0;
    }
    int32_t s = cross_u(an, ae, dn, de);
    int32_t c = dot_u(an, ae, dn, de);
    if (c <= 0) {
        if (beyond_90 != NULL) {
            *beyond_90 = 1u;
        }
        return (s >= 0) ? Q28_ONE : -Q28_ONE;
    }
    return s;
}

/* The direction of motion (Q28 unit) and the ground speed; 0 when none. */
static int motion(const ht_nav_t *nav, const ht_nav_input_t *in, int32_t *un, int32_t *ue,
                  int32_t *speed_cm_s)
{
    int32_t vn = q_clamp32(in->vel_north_cm_s, -HT_NAV_VEL_MAX_CM_S, HT_NAV_VEL_MAX_CM_S);
    int32_t ve = q_clamp32(in->vel_east_cm_s, -HT_NAV_VEL_MAX_CM_S, HT_NAV_VEL_MAX_CM_S);
    int have_v = q_unit2_q28(vn, ve, un, ue);
    *speed_cm_s = have_v ? dot_u(*un, *ue, vn, ve) : 0;
    if (have_v && *speed_cm_s >= nav->course_min_cm_s) {
        return 1;
    }
    int32_t hn, he;
    if (q_unit2_q28(in->heading_north, in->heading_east, &hn, &he) != 0) {
        *un = hn;
        *ue = he;
        return 1;
    }
    return have_v; /* slow and no heading: the slow velocity is still a direction */
}

static int32_t limit_turn(const ht_nav_t *nav, int32_t turn, uint8_t *flags)
{
    int32_t lim = nav->turn_rate_max_rad_s;
    if (turn > lim || turn < -lim) {
        *flags |= HT_NAV_F_LIMITED;
        return (turn > 0) ? lim : -lim;
    }
    return turn;
}

/* sin of the error from the motion direction to desired direction (dn, de). */
static int32_t sin_to(int32_t un, int32_t ue, int32_t dn, int32_t de, uint8_t *flags)
{
    uint8_t b = 0u;
    int32_t s = ht_nav_sin_error_q28(un, ue, dn, de, &b);
    if (b != 0u) {
        *flags |= HT_NAV_F_BEYOND_90;
    }
    return s;
}

/* 2 V / L (Q16 per second) from the ground speed, floored, and 2^36 / L_cm. */
static int32_t speed_over(const ht_nav_t *nav, int32_t speed_cm_s, int32_t inv_q36, int32_t mult)
{
    int32_t v = (speed_cm_s < nav->v_floor_cm_s) ? nav->v_floor_cm_s : speed_cm_s;
    return q_mul32(v * mult, inv_q36, 20u);
}

typedef struct {
    int32_t n, e; /* cm */
} pt_t;

/* Guidance along the leg a -> b with the selected law. */
static void guide_leg(const ht_nav_t *nav, pt_t a, pt_t b, const ht_nav_input_t *in,
                      ht_nav_output_t *o)
{
    int32_t un, ue, speed;
    int32_t to_n = q_sub_sat32(b.n, in->north_cm);
    int32_t to_e = q_sub_sat32(b.e, in->east_cm);
    int32_t tn, te;
    if (q_unit2_q28(to_n, to_e, &tn, &te) != 0) {
        o->distance_cm = dot_u(tn, te, to_n, to_e);
    }
    /* Track direction; a leg of length 0 is flown as go-to-point. */
    int32_t leg_n = q_sub_sat32(b.n, a.n), leg_e = q_sub_sat32(b.e, a.e);
    int32_t kn, ke;
    if (!q_unit2_q28(leg_n, leg_e, &kn, &ke)) {
        o->flags |= HT_NAV_F_ZERO_LEG;
        a.n = in->north_cm;
        a.e = in->east_cm;
        kn = tn;
        ke = te;
    }
    int32_t rn = q_sub_sat32(in->north_cm, a.n), re = q_sub_sat32(in->east_cm, a.e);
    o->cross_track_cm = cross_u(kn, ke, rn, re);
    if (!motion(nav, in, &un, &ue, &speed)) {
        o->flags |= HT_NAV_F_NO_DIRECTION;
        return;
    }
    if (o->distance_cm == 0) {
        return; /* on the point: nothing to steer at */
    }
    if (nav->law == (uint8_t)HT_GUIDE_HEADING) {
        o->sin_error_q28 = sin_to(un, ue, to_n, to_e, &o->flags);
        o->turn_rate_rad_s = q_mul32(nav->turn_rate_max_rad_s, o->sin_error_q28, 28u);
        return;
    }
    /* L1: h = sqrt(L1^2 - xt^2) along the track from the foot, 0 beyond L1. */
    int32_t xt = o->cross_track_cm;
    int32_t axt = abs32_sat(xt);
    int32_t h = 0;
    if (axt < nav->l1_cm) {
        const int32_t l1_minus = nav->l1_cm - axt;
        const int32_t l1_plus = nav->l1_cm + axt;
        uint32_t d2 = (uint32_t)l1_minus * (uint32_t)l1_plus;
        h = (int32_t)q_isqrt32_round(d2);
    }
    /* Vector to the L1 point: h * k - xt * n, n = (-k_e, k_n) the right normal. */
    int32_t pn = q_add_sat32(q_mul32(h, kn, 28u), q_mul32(xt, ke, 28u));
    int32_t pe = q_sub_sat32(q_mul32(h, ke, 28u), q_mul32(xt, kn, 28u));
    if (pn == 0 && pe == 0) {
        pn = kn; /* on the track with h rounding to 0 cannot happen (L1 >= 500 cm) */
        pe = ke;
    }
    o->sin_error_q28 = sin_to(un, ue, pn, pe, &o->flags);
    int32_t k = speed_over(nav, speed, nav->inv_l1_q36, 2);
    o->turn_rate_rad_s = limit_turn(nav, q_mul32(k, o->sin_error_q28, 28u), &o->flags);
}

/* Clockwise loiter of radius loiter_cm about c. */
static void guide_loiter(const ht_nav_t *nav, pt_t c, const ht_nav_input_t *in, ht_nav_output_t *o)
{
    int32_t un, ue, speed;
    int32_t rn = q_sub_sat32(in->north_cm, c.n), re = q_sub_sat32(in->east_cm, c.e);
    int32_t on, oe; /* outward unit vector; north at the centre */
    int32_t d = 0;
    if (q_unit2_q28(rn, re, &on, &oe) != 0) {
        d = dot_u(on, oe, rn, re);
    } else {
        on = Q28_ONE;
        oe = 0;
    }
    int32_t r = nav->loiter_cm;
    int32_t e = q_clamp32(q_sub_sat32(d, r), -r, r);
    o->flags |= HT_NAV_F_LOITER;
    o->distance_cm = d;
    o->cross_track_cm = q_sub_sat32(d, r);
    /* tangent (clockwise) = (-o_e, o_n); desired = r * tangent - e * outward. */
    int32_t dn = q_sub_sat32(q_mul32(r, -oe, 28u), q_mul32(e, on, 28u));
    int32_t de = q_sub_sat32(q_mul32(r, on, 28u), q_mul32(e, oe, 28u));
    if (!motion(nav, in, &un, &ue, &speed)) {
        o->flags |= HT_NAV_F_NO_DIRECTION;
        return;
    }
    o->sin_error_q28 = sin_to(un, ue, dn, de, &o->flags);
    int32_t ff = speed_over(nav, speed, nav->inv_loiter_q36, 1);
    int32_t fb = q_mul32(nav->turn_rate_max_rad_s, o->sin_error_q28, 28u);
    o->turn_rate_rad_s = limit_turn(nav, q_add_sat32(ff, fb), &o->flags);
}

static pt_t wp_cm(const ht_waypoint_t *w)
{
    pt_t p = {w->north_m * 100, w->east_m * 100};
    return p;
}

static int nav_ok(const ht_nav_t *nav, const ht_nav_state_t *s, const ht_nav_input_t *in,
                  ht_nav_output_t *out)
{
    if (out == NULL) {
        return 0;
    }
    ht_nav_output_t z = {0};
    *out = z;
    return nav != NULL && s != NULL && in != NULL && nav->ready;
}

void ht_nav_waypoint_step(const ht_nav_t *nav, ht_nav_state_t *s, const ht_nav_input_t *in,
                          ht_nav_output_t *out)
{
    if (!nav_ok(nav, s, in, out)) {
        return;
    }
    ht_nav_output_t o = {0};
    if (nav->count == 0u) {
        pt_t home = {0, 0};
        o.flags |= HT_NAV_F_NO_WAYPOINTS;
        guide_loiter(nav, home, in, &o);
        o.target_alt_cm = nav->home_alt_cm;
        *out = o;
        return;
    }
    if (s->index >= nav->count) {
        s->index = 0u; /* a state from another list: start over */
    }
    if (s->done != 0u) {
        const ht_waypoint_t *last = &nav->waypoints[nav->count - 1u];
        guide_loiter(nav, wp_cm(last), in, &o);
        o.target_alt_cm = last->alt_m * 100;
        o.index = s->index;
        *out = o;
        return;
    }
    pt_t a = {s->from_north_cm, s->from_east_cm};
    pt_t b = wp_cm(&nav->waypoints[s->index]);
    guide_leg(nav, a, b, in, &o);
    /* Arrival: within the radius, or past the perpendicular through b. */
    bool arrived = (o.distance_cm <= nav->arrival_cm);
    if (!arrived && ((o.flags & (uint8_t)HT_NAV_F_ZERO_LEG) == 0u)) {
        int32_t ln = q_sub_sat32(b.n, a.n), le = q_sub_sat32(b.e, a.e), kn, ke;
        (void)q_unit2_q28(ln, le, &kn, &ke);
        int32_t len = dot_u(kn, ke, ln, le);
        int32_t along =
            dot_u(kn, ke, q_sub_sat32(in->north_cm, a.n), q_sub_sat32(in->east_cm, a.e));
        if (along >= len) {
            arrived = true;
            o.flags |= HT_NAV_F_PASSED;
        }
    }
    if (arrived) {
        uint8_t keep = o.flags & (uint8_t)HT_NAV_F_PASSED;
        if (s->reached < UINT32_MAX) {
            s->reached++;
        }
        s->from_north_cm = b.n;
        s->from_east_cm = b.e;
        if ((s->index + 1u) < nav->count) {
            s->index++;
        } else if (nav->loop != 0u) {
            s->index = 0u;
        } else {
            s->done = 1u;
        }
        ht_nav_output_t n = {0};
        if (s->done != 0u) {
            guide_loiter(nav, b, in, &n);
            n.target_alt_cm = nav->waypoints[s->index].alt_m * 100;
        } else {
            pt_t a2 = {s->from_north_cm, s->from_east_cm};
            guide_leg(nav, a2, wp_cm(&nav->waypoints[s->index]), in, &n);
            n.target_alt_cm = nav->waypoints[s->index].alt_m * 100;
        }
        n.arrived = 1u;
        n.flags |= keep;
        n.index = s->index;
        *out = n;
        return;
    }
    o.target_alt_cm = nav->waypoints[s->index].alt_m * 100;
    o.index = s->index;
    *out = o;
}

void ht_nav_home_step(const ht_nav_t *nav, ht_nav_state_t *s, const ht_nav_input_t *in,
                      ht_nav_output_t *out)
{
    if (!nav_ok(nav, s, in, out)) {
        return;
    }
    ht_nav_output_t o = {0};
    pt_t home = {0, 0};
    o.target_alt_cm = nav->home_alt_cm;
    if (!s->home_loiter) {
        pt_t a = {s->from_north_cm, s->from_east_cm};
        guide_leg(nav, a, home, in, &o);
        if (o.distance_cm <= q_add_sat32(nav->loiter_cm, nav->loiter_cm) ||
            o.distance_cm <= nav->arrival_cm) {
            s->home_loiter = 1u;
        }
    }
    if (s->home_loiter != 0u) {
        ht_nav_output_t l = {0};
        guide_loiter(nav, home, in, &l);
        l.target_alt_cm = nav->home_alt_cm;
        o = l;
    }
    o.index = s->index;
    *out = o;
}
