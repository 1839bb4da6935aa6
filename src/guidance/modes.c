/*
 * modes.c - flight modes, RC-loss failsafe and bumpless transfer (modes.h).
 * Integer only: no float, no libm, no allocation, no recursion, no global
 * mutable state.
 */
#include "helical/guidance/modes.h"
#include "helical/params/param_rows.h"

#include <stddef.h>

#include "helical/guidance/config_check.h"

_Static_assert(HT_CFG_RC_MAX == HT_MODES_RC_MAX, "the joint check's receiver is the modes'");

#define DEG_TO_RAD_Q30      18740330L /* pi / 180 in Q30 */
#define G_CM_S2_Q16         64268042L /* 980.665 cm/s^2 in Q16 */
#define PITCH_MATCH_MAX_Q14 (4L * 16384L)

/* The names of what is not a row of the table (HT_MODES_P_RC_AILERON on). */
static const char *const other_names[HT_MODES_P_COUNT - HT_MODES_P_RC_AILERON] = {
    "rc.aileron", "rc.elevator", "rc.rudder", "rc.throttle", "mode_threshold_us",
    "rate_hz",    "controller",  "fbw",       "nav",         "aoa",
    "alt",        "speed",       "joint",
};

static const char *field_name(ht_modes_param_id_t id)
{
    if (id >= HT_MODES_P_RC_AILERON) {
        return other_names[(unsigned)id - (unsigned)HT_MODES_P_RC_AILERON];
    }
    return ht_param_row_name(ht_modes_param_info(id));
}

static void append(char *buf, unsigned size, unsigned *at, const char *s)
{
    const char *c = s;
    while ((*c != '\0') && ((*at + 1u) < size)) {
        buf[*at] = *c;
        (*at)++;
        c++;
    }
    buf[*at] = '\0';
}

void ht_modes_bad_name(const ht_modes_bad_t *bad, char *buf, unsigned size)
{
    if (buf == NULL || size == 0u) {
        return;
    }
    unsigned at = 0u;
    buf[0] = '\0';
    if (bad == NULL || (unsigned)bad->field >= (unsigned)HT_MODES_P_COUNT) {
        return;
    }
    append(buf, size, &at, field_name(bad->field));
    const char *sub = NULL;
    if (bad->field == HT_MODES_P_FBW) {
        sub = ht_fbw_param_name((ht_fbw_param_id_t)bad->sub);
    } else if (bad->field == HT_MODES_P_NAV) {
        sub = ht_nav_param_name((ht_nav_param_id_t)bad->sub);
    } else if (bad->field == HT_MODES_P_AOA) {
        sub = ht_aoa_param_name((ht_aoa_param_id_t)bad->sub);
    } else if (bad->field == HT_MODES_P_ALT_HOLD) {
        sub = ht_alt_hold_param_name((ht_alt_param_id_t)bad->sub);
    } else if (bad->field == HT_MODES_P_SPEED_HOLD) {
        sub = ht_speed_hold_param_name((ht_speed_param_id_t)bad->sub);
    } else if (bad->field == HT_MODES_P_JOINT) {
        sub = ht_config_reason((ht_cfg_status_t)bad->sub);
    } else {
        /* a field without sub-fields: the name alone */
    }
    if (sub != NULL && sub[0] != '\0') {
        append(buf, size, &at, ".");
        append(buf, size, &at, sub);
    }
}

void ht_modes_params_default(ht_modes_params_t *p)
{
    if (p == NULL) {
        return;
    }
    ht_modes_params_t d = {0}; /* fields the holds may add later start at 0 */
    // cppcheck-suppress misra-c2012-10.8 ; D-10.8-FROM-REAL: the table's defaults, folded constants
    const ht_fbw_params_t fbw = HT_FBW_PARAMS_DEFAULT;
    // cppcheck-suppress misra-c2012-10.8 ; D-10.8-FROM-REAL: the table's defaults, folded constants
    const ht_nav_params_t nav = HT_NAV_PARAMS_DEFAULT;
    // cppcheck-suppress misra-c2012-10.8 ; D-10.8-FROM-REAL: the table's defaults, folded constants
    const ht_aoa_params_t aoa = HT_AOA_PARAMS_DEFAULT;
    const os_rc_cal_t stick = {0u, 0u, 0u, 1500u, 500u};
    d.rc.aileron = stick;
    d.rc.elevator = stick;
    d.rc.elevator.input = 1u;
    d.rc.throttle = stick;
    d.rc.throttle.input = 2u;
    d.rc.throttle.unipolar = 1u;
    d.rc.throttle.centre_us = 1000u;
    d.rc.throttle.travel_us = 1000u;
    d.rc.rudder = stick;
    d.rc.rudder.input = 3u;
    d.rc_channels = (uint8_t)HT_MODES_RC_MAX; /* a board with fewer says so (fw_main.c) */
    d.mode_threshold_us[0] = 1250u;
    d.mode_threshold_us[1] = 1750u;
    d.mode_threshold_us[2] = 2100u;
    d.rate_hz = 40u;
    d.fbw = fbw;
    d.nav = nav;
    d.aoa = aoa;
    ht_alt_hold_params_default(&d.alt, d.rate_hz);
    ht_speed_hold_params_default(&d.speed, d.rate_hz);
    *p = d;
    /* the modes' own rows: the table's defaults (mode switch on input 4,
     * 0.5 s of RC loss, recovery and blend at 40 Hz, 180 deg/s^2, 15 m/s) */
    // cppcheck-suppress misra-c2012-10.8 ; D-10.8-FROM-REAL: the table's defaults, folded constants
    HT_PARAMS_MODES(HT_PARAM_X_SET_DEFAULT)
}

static ht_modes_param_id_t check_own(const ht_modes_params_t *p)
{
    const ht_modes_param_id_t row = ht_modes_first_bad_row(p);
    if (row != HT_MODES_P_NONE) {
        return row;
    }
    // cppcheck-suppress misra-c2012-9.3 ; false positive: all 4 elements are initialized
    const os_rc_cal_t *cals[] = {&p->rc.aileron, &p->rc.elevator, &p->rc.rudder, &p->rc.throttle};
    for (unsigned i = 0; i < 4u; i++) {
        if (os_rc_cal_check(cals[i]) != OS_OK || cals[i]->input >= HT_MODES_RC_MAX) {
            const unsigned id = (unsigned)HT_MODES_P_RC_AILERON + i;
            return (ht_modes_param_id_t)id;
        }
    }
    const uint16_t *t = p->mode_threshold_us;
    if (t[0] <= OS_RC_VALID_MIN_US || t[0] >= t[1] || t[1] >= t[2] || t[2] > OS_RC_VALID_MAX_US) {
        return HT_MODES_P_MODE_THRESHOLD;
    }
    if (p->rate_hz < 1u || p->rate_hz > 1000u) {
        return HT_MODES_P_RATE_HZ;
    }
    return HT_MODES_P_NONE;
}

int ht_modes_init(ht_modes_t *m, const ht_modes_params_t *p, const ht_controller_t *ctl,
                  const ht_waypoint_t *waypoints, uint16_t count, ht_modes_bad_t *bad)
{
    ht_modes_bad_t b = {HT_MODES_P_NONE, 0, 0u};
    if (bad != NULL) {
        *bad = b;
    }
    if (m == NULL || p == NULL) {
        return 1;
    }
    ht_modes_t z = {0};
    *m = z;
    b.field = check_own(p);
    if (b.field == HT_MODES_P_NONE && (ctl == NULL || !ctl->ready)) {
        b.field = HT_MODES_P_CONTROLLER;
    }
    if (b.field == HT_MODES_P_NONE) {
        ht_fbw_param_id_t fb = HT_FBW_P_NONE;
        if (ht_fbw_init(&m->fbw, &p->fbw, &fb) != 0) {
            b.field = HT_MODES_P_FBW;
            b.sub = (int)fb;
        } else if (p->fbw.inverted_input >= HT_MODES_RC_MAX) {
            b.field = HT_MODES_P_FBW;
            b.sub = (int)HT_FBW_P_INVERTED_INPUT;
        } else {
            /* the FBW parameters are valid */
        }
    }
    if (b.field == HT_MODES_P_NONE) {
        ht_nav_param_id_t nb = HT_NAV_P_NONE;
        if (ht_nav_init(&m->nav, &p->nav, waypoints, count, &nb, &b.waypoint) != 0) {
            b.field = HT_MODES_P_NAV;
            b.sub = (int)nb;
        }
    }
    if (b.field == HT_MODES_P_NONE) {
        ht_aoa_param_id_t ab = HT_AOA_P_NONE;
        if (ht_aoa_init(&m->aoa, &p->aoa, &ab) != 0) {
            b.field = HT_MODES_P_AOA;
            b.sub = (int)ab;
        }
    }
    if (b.field == HT_MODES_P_NONE) {
        ht_alt_param_id_t ab = ht_alt_hold_first_bad(&p->alt);
        if (ab == HT_ALT_P_NONE && p->alt.rate_hz != p->rate_hz) {
            ab = HT_ALT_P_RATE_HZ;
        }
        if (ab != HT_ALT_P_NONE) {
            b.field = HT_MODES_P_ALT_HOLD;
            b.sub = (int)ab;
        }
    }
    if (b.field == HT_MODES_P_NONE) {
        ht_speed_param_id_t sb = ht_speed_hold_first_bad(&p->speed);
        if (sb == HT_SPEED_P_NONE && p->speed.rate_hz != p->rate_hz) {
            sb = HT_SPEED_P_RATE_HZ;
        }
        if (sb != HT_SPEED_P_NONE) {
            b.field = HT_MODES_P_SPEED_HOLD;
            b.sub = (int)sb;
        }
    }
    if (b.field == HT_MODES_P_NONE) {
        /* the rows are in range one by one: now together (config_check.h) */
        const ht_cfg_status_t cs = ht_config_check(p, waypoints, count, &b.waypoint);
        if (cs != HT_CFG_OK) {
            b.field = HT_MODES_P_JOINT;
            b.sub = (int)cs;
        }
    }
    if (b.field != HT_MODES_P_NONE) {
        ht_modes_t z2 = {0};
        *m = z2;
        if (bad != NULL) {
            *bad = b;
        }
        return 2;
    }
    m->rc = p->rc;
    m->mode_input = p->mode_input;
    for (unsigned i = 0; i < 3u; i++) {
        m->mode_threshold_us[i] = p->mode_threshold_us[i];
    }
    m->rc_loss_ticks = p->rc_loss_ticks;
    m->rc_recover_ticks = p->rc_recover_ticks;
    m->blend_ticks = p->blend_ticks;
    /* deg/s^2 -> rad/s per tick (Q16), at least 1 LSB. */
    int32_t turn_slew = q_mul32((int32_t)p->turn_slew_deg_s2 * 65536, DEG_TO_RAD_Q30, 30u);
    turn_slew = (turn_slew + ((int32_t)p->rate_hz / 2)) / (int32_t)p->rate_hz;
    m->turn_slew_rad_s_per_tick = (turn_slew < 1) ? 1 : turn_slew;
    int32_t ps = (p->pitch_slew_per_s + ((int32_t)p->rate_hz / 2)) / (int32_t)p->rate_hz;
    m->pitch_slew_per_tick = (ps < 1) ? 1 : ps;
    m->max_tilt = ctl->max_tilt;
    m->v_min_cm_s = ctl->v_min_cm_s;
    m->cruise_cm_s = p->cruise_cm_s;
    m->alt = p->alt;
    m->speed = p->speed;
    m->ready = 1u;
    return 0;
}

void ht_modes_reset(ht_modes_state_t *st, int32_t north_cm, int32_t east_cm)
{
    if (st == NULL) {
        return;
    }
    ht_modes_state_t z = {0};
    *st = z;
    st->mode = (uint8_t)HT_MODE_MANUAL;
    ht_nav_reset(&st->nav, north_cm, east_cm);
    ht_alt_hold_reset(&st->alt);
    ht_speed_hold_reset(&st->speed);
}

ht_mode_t ht_modes_from_pulse(const ht_modes_t *m, uint16_t pulse_us)
{
    if (m == NULL) {
        return HT_MODE_MANUAL;
    }
    unsigned mode = 0u;
    for (unsigned i = 0; i < 3u; i++) {
        if (pulse_us >= m->mode_threshold_us[i]) {
            mode = i + 1u;
        }
    }
    return (ht_mode_t)mode;
}

static int pulse_ok(const ht_modes_input_t *in, uint8_t input)
{
    if (input >= in->rc_count || input >= HT_MODES_RC_MAX) {
        return 0;
    }
    uint16_t us = in->rc_us[input];
    return us >= OS_RC_VALID_MIN_US && us <= OS_RC_VALID_MAX_US;
}

static int frame_good(const ht_modes_t *m, const ht_modes_input_t *in)
{
    return in->rc_fresh && pulse_ok(in, m->rc.aileron.input) &&
           pulse_ok(in, m->rc.elevator.input) && pulse_ok(in, m->rc.rudder.input) &&
           pulse_ok(in, m->rc.throttle.input) && pulse_ok(in, m->mode_input) &&
           pulse_ok(in, m->fbw.inverted_input);
}

static uint16_t inc_sat16(uint16_t v)
{
    return (v < UINT16_MAX) ? (uint16_t)(v + 1u) : v;
}

/* RC bookkeeping: good frames, loss and recovery. */
static uint8_t update_rc(const ht_modes_t *m, ht_modes_state_t *st, const ht_modes_input_t *in)
{
    if (frame_good(m, in) != 0) {
        uint8_t n = (in->rc_count > HT_MODES_RC_MAX) ? (uint8_t)HT_MODES_RC_MAX : in->rc_count;
        for (unsigned i = 0; i < HT_MODES_RC_MAX; i++) {
            // cppcheck-suppress knownConditionTrueFalse ; false positive: n = min(rc_count, 16)
            st->rc_us[i] = (i < n) ? in->rc_us[i] : 0u;
        }
        st->rc_count = n;
        st->have_rc = 1u;
        st->bad_ticks = 0u;
        st->good_ticks = inc_sat16(st->good_ticks);
        if (st->rc_lost && st->good_ticks >= m->rc_recover_ticks) {
            st->rc_lost = 0u;
        }
        return 1u;
    }
    st->good_ticks = 0u;
    st->bad_ticks = inc_sat16(st->bad_ticks);
    if (st->have_rc && st->bad_ticks >= m->rc_loss_ticks) {
        st->rc_lost = 1u;
    }
    return 0u;
}

/* a / b in Q16 with |a| <= 32767 in the same format as b > 0, clamped to +-lim_q16. */
static int32_t ratio_q16(int32_t a, int32_t b, int32_t lim_q16)
{
    if (b <= 0) {
        return (a > 0) ? lim_q16 : ((a < 0) ? -lim_q16 : 0);
    }
    int32_t q = (a * 65536) / b; /* |a| * 65536 < 2^31 */
    return q_clamp32(q, -lim_q16, lim_q16);
}

static int32_t clamp_row(q14_t v)
{
    return (v == INT16_MIN) ? -32767 : (int32_t)v;
}

/* The turn rate that matches the current bank: ratio -X/Z (limited to
 * max_tilt) times g / max(V, v_min). Z = 0: +-max_tilt by the sign of -X. */
static q16_t turn_match(const ht_modes_t *m, const ht_modes_input_t *in)
{
    int32_t x = clamp_row(in->x), z = clamp_row(in->z);
    int32_t ratio;
    if (z == 0) {
        ratio = (x < 0) ? m->max_tilt : ((x > 0) ? -m->max_tilt : 0);
    } else {
        int32_t num = (z > 0) ? -x : x;
        ratio = ratio_q16(num, (z > 0) ? z : -z, m->max_tilt);
    }
    int32_t v = (in->airspeed_cm_s < m->v_min_cm_s) ? m->v_min_cm_s : in->airspeed_cm_s;
    int32_t acc_q16 = q_mul32(ratio, G_CM_S2_Q16, 16u); /* ratio * g, cm/s^2, |.| < 2^23 Q16 */
    return acc_q16 / v;
}

/* The pitch ratio that matches the current pitch: -Y / sqrt(X^2 + Z^2), limited to +-4. */
static q16_t pitch_match(const ht_modes_input_t *in)
{
    q16_t a_q16 = q14_norm2_q16(in->x, in->z);
    int32_t y = clamp_row(in->y);
    /* -Y (Q14) / a (Q16) = ratio in Q14; * 4 -> Q16. */
    return ratio_q16(-y, a_q16, PITCH_MATCH_MAX_Q14) * 4;
}

static int32_t slew(int32_t cmd, int32_t target, int32_t step)
{
    int32_t d = q_sub_sat32(target, cmd);
    d = q_clamp32(d, -step, step);
    return q_add_sat32(cmd, d);
}

static q14_t lerp_q14(q14_t from, q14_t to, q14_t w)
{
    int32_t d = (int32_t)to - (int32_t)from;
    return (q14_t)((int32_t)from + q_rshift_round(d * (int32_t)w, 14u));
}

static q14_t count_weight(uint16_t count, uint16_t ticks)
{
    const uint32_t w = (((uint32_t)count * 16384u) + ((uint32_t)ticks / 2u)) / ticks;
    return (q14_t)w;
}

static uint16_t count_toward(uint16_t count, int up, uint16_t ticks)
{
    if (up != 0) {
        return (count < ticks) ? (uint16_t)(count + 1u) : ticks;
    }
    return (count > 0u) ? (uint16_t)(count - 1u) : 0u;
}

void ht_modes_step(const ht_modes_t *m, ht_modes_state_t *st, const ht_modes_input_t *in,
                   ht_modes_output_t *out)
{
    if (out == NULL) {
        return;
    }
    ht_modes_output_t o = {0};
    if (m == NULL || st == NULL || in == NULL || !m->ready) {
        *out = o;
        return;
    }
    /* 1. RC and mode. */
    o.rc_good = update_rc(m, st, in);
    ht_mode_t selected = HT_MODE_MANUAL;
    if (st->have_rc && m->mode_input < st->rc_count) {
        selected = ht_modes_from_pulse(m, st->rc_us[m->mode_input]);
    }
    ht_mode_t mode = st->rc_lost ? HT_MODE_RTH : selected;
    o.selected_mode = (uint8_t)selected;
    o.failsafe = st->rc_lost;
    o.mode = (uint8_t)mode;
    o.mode_changed = (mode != (ht_mode_t)st->mode) ? 1u : 0u;
    if ((o.mode_changed != 0u) && (mode == HT_MODE_WAYPOINT || mode == HT_MODE_RTH)) {
        ht_nav_start_leg(&st->nav, in->north_cm, in->east_cm);
    }
    st->mode = (uint8_t)mode;

    /* 2. The pilot: sticks of the last good frame (neutral before any). */
    ht_fbw_output_t pilot = {0};
    if (st->have_rc != 0u) {
        (void)os_rc_command(&m->rc, st->rc_us, st->rc_count, &o.manual);
        ht_fbw_step(&m->fbw, &m->rc, st->rc_us, st->rc_count, &pilot);
    }
    if (st->rc_lost != 0u) {
        ht_fbw_output_t none = {0};
        pilot = none;
    }

    /* 3. The AoA model (its offset is part of the state match). */
    ht_aoa_step(&m->aoa, in->x, in->z, in->airspeed_cm_s, &o.aoa);
    /* Both always reach the law (its surfaces are weighted by the blend, so
     * in manual they have no effect, and blending in or out moves them
     * smoothly). */
    q16_t offset = o.aoa.pitch_offset;
    o.elevator_trim = o.aoa.elevator_trim;

    /* 4. Targets per mode. */
    q16_t turn_t = turn_match(m, in);
    q16_t pitch_t = q_sub_sat32(pitch_match(in), offset);
    uint8_t inverted = (in->z < 0) ? 1u : 0u;
    ht_nav_input_t ni = {in->north_cm,      in->east_cm,       in->vel_north_cm_s,
                         in->vel_east_cm_s, in->heading_north, in->heading_east};
    int speed_hold = 0;
    switch (mode) {
    case HT_MODE_FBW:
        turn_t = pilot.turn_rate_rad_s;
        pitch_t = pilot.pitch_ratio;
        inverted = pilot.inverted;
        break;
    case HT_MODE_WAYPOINT:
    case HT_MODE_RTH:
        if (mode == HT_MODE_WAYPOINT) {
            ht_nav_waypoint_step(&m->nav, &st->nav, &ni, &o.nav);
        } else {
            ht_nav_home_step(&m->nav, &st->nav, &ni, &o.nav);
        }
        turn_t = q_clamp32(q_add_sat32(o.nav.turn_rate_rad_s, pilot.turn_rate_rad_s),
                           -m->nav.turn_rate_max_rad_s, m->nav.turn_rate_max_rad_s);
        inverted = pilot.inverted;
        /* with the hold's airspeed protection (off when alt.protect_cm_s = 0) */
        pitch_t = ht_alt_hold_step_v(&m->alt, &st->alt, o.nav.target_alt_cm, in->alt_cm,
                                     in->climb_cm_s, inverted, in->airspeed_cm_s);
        speed_hold = 1;
        break;
    case HT_MODE_MANUAL:
    default:
        break;
    }
    o.turn_target_rad_s = turn_t;
    o.pitch_target = pitch_t;

    /* 5. Slew from the state match (while the law is unused, follow it). */
    if (mode == HT_MODE_MANUAL && st->blend_count == 0u) {
        st->turn_cmd_rad_s = turn_t;
        st->pitch_cmd = pitch_t;
    } else {
        st->turn_cmd_rad_s = slew(st->turn_cmd_rad_s, turn_t, m->turn_slew_rad_s_per_tick);
        st->pitch_cmd = slew(st->pitch_cmd, pitch_t, m->pitch_slew_per_tick);
    }
    q16_t pitch_out = q_add_sat32(st->pitch_cmd, offset);

    /* 6. Blends. */
    st->blend_count = count_toward(st->blend_count, mode != HT_MODE_MANUAL, m->blend_ticks);
    st->throttle_blend_count = count_toward(st->throttle_blend_count, speed_hold, m->blend_ticks);
    o.blend = count_weight(st->blend_count, m->blend_ticks);
    q14_t thr_auto = o.manual.throttle;
    if (st->throttle_blend_count > 0u || speed_hold) {
        thr_auto =
            ht_speed_hold_step(&m->speed, &st->speed, m->cruise_cm_s, in->airspeed_cm_s, pitch_out);
    }
    o.throttle = lerp_q14(o.manual.throttle, thr_auto,
                          count_weight(st->throttle_blend_count, m->blend_ticks));
    if (!st->have_rc) {
        o.throttle = 0;
    }

    /* 7. The law's input. */
    ht_input_t li;
    li.x = in->x;
    li.y = in->y;
    li.z = in->z;
    li.turn_rate_rad_s = q_sat16(q_rshift_round(st->turn_cmd_rad_s, 5u));
    li.pitch_ratio = pitch_out;
    li.airspeed_cm_s = in->airspeed_cm_s;
    for (unsigned i = 0; i < 3u; i++) {
        li.gyro_rad_s[i] = in->gyro_rad_s[i];
    }
    li.inverted = inverted;
    /* the law's option inputs are the firmware step's (it knows the IMU and
     * the command's history): zero here, so a caller of the modes alone
     * flies every option's input at "none" */
    li.turn_accel_rad_s2 = 0;
    li.accel_lat_g = 0;
    st->law_inverted = inverted;
    o.law_in = li;
    *out = o;
}

static q14_t clamp_unit(int32_t v)
{
    return (q14_t)q_clamp32(v, -Q14_ONE, Q14_ONE);
}

void ht_modes_surfaces(const ht_modes_output_t *o, const ht_output_t *law, os_command_t *cmd)
{
    if (cmd == NULL) {
        return;
    }
    os_command_t c = {0, 0, 0, 0};
    if (o == NULL) {
        *cmd = c;
        return;
    }
    q14_t la = 0, le = 0, lr = 0;
    if (law != NULL) {
        la = clamp_unit(law->aileron);
        le = clamp_unit((int32_t)law->elevator + (int32_t)o->elevator_trim);
        lr = clamp_unit(law->rudder);
    }
    c.aileron = lerp_q14(clamp_unit(o->manual.aileron), la, o->blend);
    c.elevator = lerp_q14(clamp_unit(o->manual.elevator), le, o->blend);
    c.rudder = lerp_q14(clamp_unit(o->manual.rudder), lr, o->blend);
    c.throttle = o->throttle;
    *cmd = c;
}

void ht_modes_fly(const ht_modes_t *m, ht_modes_state_t *st, const ht_controller_t *ctl,
                  const ht_modes_input_t *in, ht_modes_output_t *out, ht_output_t *law,
                  os_command_t *cmd)
{
    ht_modes_output_t o;
    ht_output_t l;
    ht_modes_step(m, st, in, &o);
    ht_step(ctl, &o.law_in, &l);
    ht_modes_surfaces(&o, &l, cmd);
    if (out != NULL) {
        *out = o;
    }
    if (law != NULL) {
        *law = l;
    }
}
