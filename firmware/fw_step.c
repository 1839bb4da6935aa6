/*
 * fw_step.c - the one firmware step (see fw_step.h). Integer only. It reads
 * top to bottom in fw_step(): estimator, control-rate gate, navigation
 * solution, sensor failsafe, commands (guided or modes), upset guard, law,
 * surfaces, output stage.
 */
#include "fw_step.h"

#include <stddef.h>
#include <string.h>

#include "helical/estimator/air_data.h"

/* --- configuration ---------------------------------------------------------- */

void fw_config_default(fw_config_t *cfg)
{
    if (cfg == NULL) {
        return;
    }
    (void)memset(cfg, 0, sizeof *cfg);
    ht_dcm_params_default(&cfg->dcm);
    // cppcheck-suppress misra-c2012-10.8 ; D-10.8-FROM-REAL: the table's defaults, folded constants
    const ht_params_t law = HT_PARAMS_DEFAULT;
    cfg->law = law;
    ht_modes_params_default(&cfg->modes);
    ht_guide_params_default(&cfg->guide);
    const ht_upset_guard_params_t guard = HT_UPSET_GUARD_PARAMS_DEFAULT;
    cfg->guard = guard;
    static const uint8_t fn[5] = {OS_FN_AILERON, OS_FN_ELEVATOR, OS_FN_THROTTLE, OS_FN_RUDDER,
                                  OS_FN_AILERON2};
    cfg->out.count = 5u;
    for (uint8_t i = 0; i < OS_MAX_CHANNELS; ++i) {
        os_channel_default(&cfg->out.ch[i], i < 5u ? fn[i] : (uint8_t)OS_FN_NONE);
    }
    cfg->out.ch[4].reversed = 1u;
    cfg->control_divider = (uint16_t)(cfg->dcm.imu_rate_hz / cfg->modes.rate_hz);
    cfg->imu_timeout_samples = 40u; /* 0.2 s at 200 Hz */
    cfg->modes_pitch_mode = (uint8_t)HT_PITCH_EARTH_FRAME;
}

static int refuse(fw_t *fw, fw_bad_block_t block, int32_t sub)
{
    fw->bad = (uint8_t)block;
    fw->bad_sub = sub;
    fw->ready = 0u;
    return 0;
}

/* The lateral specific force's low-pass: y += (x - y) / 2^k at the IMU rate,
 * k = floor(log2(rate / 10)): a time constant of 2^k samples, 64 to 100 ms
 * over the legal IMU rates (50 to 1000 Hz) -- well below the control rate's
 * Nyquist (vibration and noise do not reach the rudder) and well above the
 * airframe's sideslip dynamics. */
#define ACCEL_LAT_PER_S 10u

static uint8_t accel_lat_shift(uint16_t imu_rate_hz)
{
    uint32_t samples = (uint32_t)imu_rate_hz / ACCEL_LAT_PER_S;
    uint8_t k = 0u;
    while (samples > 1u) {
        samples >>= 1;
        k++;
    }
    return k;
}

int fw_init(fw_t *fw, const fw_config_t *cfg)
{
    if (fw == NULL) {
        return 0;
    }
    (void)memset(fw, 0, sizeof *fw);
    if (cfg == NULL) {
        return refuse(fw, FW_BAD_NULL, 0);
    }
    fw->cfg = cfg;
    ht_dcm_param_id_t dcm_bad = HT_DCM_P_NONE;
    if (ht_dcm_init(&fw->dcm, &cfg->dcm, &dcm_bad) != 0) {
        return refuse(fw, FW_BAD_DCM, (int32_t)dcm_bad);
    }
    for (uint8_t mode = 0u; mode < 2u; ++mode) {
        ht_params_t p = cfg->law;
        p.pitch_mode = mode;
        ht_param_id_t bad = HT_P_NONE;
        if (ht_init(&fw->law[mode], &p, &bad) != HT_OK) {
            return refuse(fw, FW_BAD_LAW, (int32_t)bad);
        }
    }
    if (cfg->control_divider < 1u || cfg->control_divider > 100u ||
        (uint32_t)cfg->modes.rate_hz * cfg->control_divider != cfg->dcm.imu_rate_hz) {
        return refuse(fw, FW_BAD_DIVIDER, 0);
    }
    if (cfg->imu_timeout_samples < 1u || cfg->imu_timeout_samples > 10000u) {
        return refuse(fw, FW_BAD_TIMEOUT, 0);
    }
    const uint8_t pm = (cfg->modes_pitch_mode != 0u) ? 1u : 0u;
    if (ht_modes_init(&fw->modes, &cfg->modes, &fw->law[pm], cfg->waypoints, cfg->waypoint_count,
                      &fw->modes_bad) != 0) {
        return refuse(fw, FW_BAD_MODES, (int32_t)fw->modes_bad.field);
    }
    ht_guide_param_id_t guide_bad = HT_GUIDE_P_NONE;
    if (ht_guide_init(&fw->guide, &cfg->guide, cfg->modes.rate_hz, &guide_bad) != 0) {
        return refuse(fw, FW_BAD_GUIDE, (int32_t)guide_bad);
    }
    if (ht_upset_guard_check(&cfg->guard) != HT_UG_OK) {
        return refuse(fw, FW_BAD_GUARD, 0);
    }
    uint8_t bad_channel = 0u;
    if (os_config_check(&cfg->out, &bad_channel) != OS_OK) {
        return refuse(fw, FW_BAD_OUTPUT, (int32_t)bad_channel);
    }
    ht_dcm_reset(&fw->dcm_state);
    ht_modes_reset(&fw->modes_state, 0, 0);
    const int32_t max_i_q20 = cfg->modes.alt.max_integral_pitch * 16;
    for (unsigned i = 0u; i < 2u; ++i) {
        fw->modes_state.alt.integral_q20[i] =
            q_clamp32(cfg->alt_integral_q20[i], -max_i_q20, max_i_q20);
    }
    ht_upset_guard_reset(&fw->guard_state);
    ht_guide_reset(&fw->guide_state);
    fw->accel_lat_shift = accel_lat_shift(cfg->dcm.imu_rate_hz);
    fw->imu_age = cfg->imu_timeout_samples; /* nothing flies before the first sample */
    fw->ready = 1u;
    return 1;
}

/* --- the estimator and the slower sensors (every call) --------------------- */

static uint16_t age16(uint16_t a)
{
    return (a == UINT16_MAX) ? a : (uint16_t)(a + 1u);
}

/* The GPS course in centidegrees [0, 36000) from north/east velocity, for the
 * start-up alignment only: an octant and a linear interpolation of the
 * tangent (within 4 deg), which the yaw aiding then corrects. */
static uint16_t course_cdeg(int32_t vn, int32_t ve)
{
    int32_t an = (vn < 0) ? -(vn / 2) : vn / 2; /* halved: no overflow at INT32_MIN */
    int32_t ae = (ve < 0) ? -(ve / 2) : ve / 2;
    while (an > 32767 || ae > 32767) { /* at most 16 halvings: lo * 4500 fits */
        an /= 2;
        ae /= 2;
    }
    const int32_t hi = (an > ae) ? an : ae;
    const int32_t lo = (an > ae) ? ae : an;
    /* atan(lo/hi) ~ 45 deg * lo/hi, in cdeg (hi > 0 past the speed gate) */
    int32_t a = (lo * 4500) / ((hi > 0) ? hi : 1);
    if (ae > an) {
        a = 9000 - a; /* angle from north towards east in the first quadrant */
    }
    int32_t c;
    if (vn >= 0) {
        c = (ve >= 0) ? a : 36000 - a;
    } else {
        c = (ve >= 0) ? 18000 - a : 18000 + a;
    }
    return (uint16_t)((c >= 36000) ? c - 36000 : c);
}

static int32_t ground_speed2(const board_gps_t *g)
{
    /* in (cm/s)^2 / 256, each component held to +/-655 m/s first (any int32
     * comes in from a driver or a link): at most 2 * 4096^2 */
    const int32_t vn = q_clamp32(g->vel_ned_cm_s[0], -65535, 65535) / 16;
    const int32_t ve = q_clamp32(g->vel_ned_cm_s[1], -65535, 65535) / 16;
    return (vn * vn) + (ve * ve);
}

static void estimate(fw_t *fw, const fw_inputs_t *in)
{
    const fw_config_t *cfg = fw->cfg;
    const board_gps_t *g = &in->sensors.gps;
    const uint8_t fix3 = (g->fix >= 3u) ? 1u : 0u;
    if (in->sensors.baro_fresh != 0u) {
        fw->pressure_alt_cm = in->sensors.baro_alt_cm;
        fw->air_temp_valid = in->sensors.baro_temp_valid;
        fw->air_temp_cdeg = in->sensors.baro_temp_cdeg;
    }
    if (in->sensors.airspeed_fresh != 0u) {
        /* the board gives the pitot's indicated airspeed: true once, here,
         * with the latest baro (sea level until the first), for every user */
        fw->pitot_cm_s = ht_true_airspeed_cm_s(in->sensors.airspeed_cm_s, fw->pressure_alt_cm,
                                               fw->air_temp_cdeg, fw->air_temp_valid);
        fw->airspeed_live = 1u;
    }
    if (in->sensors.imu_fresh != 0u) {
        fw->imu_age = 0u;
        if (fw->aligned == 0u) {
            const int32_t min_v = cfg->dcm.gps_min_speed_cm_s / 16;
            const uint8_t course_ok = (fix3 != 0u && ground_speed2(g) > min_v * min_v) ? 1u : 0u;
            const uint16_t course =
                (course_ok != 0u) ? course_cdeg(g->vel_ned_cm_s[0], g->vel_ned_cm_s[1]) : 0u;
            if (ht_dcm_align(&fw->dcm, &fw->dcm_state, in->sensors.imu.accel_g, course_ok,
                             course) == 0) {
                fw->aligned = 1u;
            }
        }
        ht_dcm_aiding_t aid;
        (void)memset(&aid, 0, sizeof aid);
        aid.gps_fix = fix3;
        aid.gps_fresh = (g->fresh != 0u && fix3 != 0u) ? 1u : 0u;
        aid.vel_ned_cm_s[0] = g->vel_ned_cm_s[0];
        aid.vel_ned_cm_s[1] = g->vel_ned_cm_s[1];
        aid.vel_ned_cm_s[2] = g->vel_ned_cm_s[2];
        aid.airspeed_valid = fw->airspeed_live;
        aid.airspeed_cm_s = fw->pitot_cm_s;
        ht_dcm_update(&fw->dcm, &fw->dcm_state, &in->sensors.imu, &aid);
        /* the lateral specific force, held to +/-32 g (the largest full
         * scale), filtered in Q20 (2^25 at most) so that the rounding's dead
         * band (2^(k-1) LSB) is a small fraction of the law's Q14 LSB */
        const int32_t lat = q_clamp32(in->sensors.imu.accel_g[0], -32 * Q16_ONE, 32 * Q16_ONE);
        fw->accel_lat_q20 +=
            q_rshift_round((lat * 16) - fw->accel_lat_q20, (unsigned)fw->accel_lat_shift);
    } else {
        fw->imu_age = age16(fw->imu_age);
    }

    if (g->fresh != 0u && fix3 != 0u) {
        if (fw->have_home == 0u && ht_geo_origin_set(&fw->home, g->lat_e7, g->lon_e7) == 0) {
            fw->have_home = 1u;
        }
        ht_geo_to_local(&fw->home, g->lat_e7, g->lon_e7, &fw->nav.north_cm, &fw->nav.east_cm);
        fw->nav.vel_north_cm_s = g->vel_ned_cm_s[0];
        fw->nav.vel_east_cm_s = g->vel_ned_cm_s[1];
        fw->nav.climb_cm_s = q_sub_sat32(0, g->vel_ned_cm_s[2]); /* INT32_MIN: no overflow */
    }
    if (in->sensors.baro_fresh != 0u) {
        fw->nav.altitude_cm = in->sensors.baro_alt_cm;
        fw->have_baro = 1u;
    }
}

/* The estimate's navigation solution, once per control step. */
static void navigation(fw_t *fw, const fw_inputs_t *in, const ht_dcm_output_t *est)
{
    fw_nav_t *n = &fw->nav;
    for (unsigned i = 0u; i < 3u; ++i) {
        n->down_q14[i] = est->r[2][i];
        n->gyro_q11_rad_s[i] = q_sat16(q_rshift_round(est->gyro_rad_s[i], 5u));
    }
    /* the nose in earth axes: column 1 of R */
    n->heading_north = est->r[0][1];
    n->heading_east = est->r[1][1];
    /* A pitot reading below half the GPS ground speed is dead or blocked (a
     * wind that strong would be a gale): the law flies on the ground speed
     * instead of its v_min floor. Below 5 m/s over the ground nothing is
     * judged. */
    n->airspeed_cm_s = fw->pitot_cm_s;
    fw->pitot_suspect = 0u;
    if (in->sensors.gps.fix >= 3u) {
        const int32_t gs = 16 * (int32_t)q_isqrt32((uint32_t)ground_speed2(&in->sensors.gps));
        if (gs > 500 && 2 * (int32_t)fw->pitot_cm_s < gs) {
            n->airspeed_cm_s = (int16_t)q_clamp32(gs, 0, INT16_MAX);
            fw->pitot_suspect = 1u;
        }
    }
    /* Without a 3-D fix the climb rate comes from the baro: its difference
     * per control step, filtered over 32 steps (0.8 s at 40 Hz). */
    if (in->sensors.gps.fix < 3u && fw->have_baro != 0u) {
        const int32_t rate = fw->cfg->modes.rate_hz;
        const int32_t raw =
            q_clamp32(q_sub_sat32(n->altitude_cm, fw->baro_prev_cm), -100000, 100000) * rate;
        fw->baro_climb_cm_s += (raw - fw->baro_climb_cm_s) / 32;
        n->climb_cm_s = fw->baro_climb_cm_s;
    }
    fw->baro_prev_cm = n->altitude_cm;
}

/* --- the control chain (every control_divider-th call) --------------------- */

static void law_input(ht_input_t *li, const fw_nav_t *nav)
{
    li->x = nav->down_q14[0];
    li->y = nav->down_q14[1];
    li->z = nav->down_q14[2];
    li->airspeed_cm_s = nav->airspeed_cm_s;
    li->gyro_rad_s[0] = nav->gyro_q11_rad_s[0];
    li->gyro_rad_s[1] = nav->gyro_q11_rad_s[1];
    li->gyro_rad_s[2] = nav->gyro_q11_rad_s[2];
}

/* The turn acceleration for the roll-in option: the change of the turn
 * command (Q16 rad/s) since the previous control step, times the control
 * rate, in Q11 rad/s^2 (the change held to 16 rad/s per step first; the
 * result saturates at +/-16 rad/s^2). 0 on the first step. */
static q11_t turn_accel(fw_t *fw, q16_t cmd_q16)
{
    q11_t a = 0;
    if (fw->turn_primed != 0u) {
        const int32_t d = q_clamp32(q_sub_sat32(cmd_q16, fw->turn_prev_q16), -16 * Q16_ONE,
                                    16 * Q16_ONE);                 /* per step, |.| <= 2^20 */
        const int32_t a_q16 = d * (int32_t)fw->cfg->modes.rate_hz; /* rate <= 1000: < 2^30 */
        a = q_sat16(q_rshift_round(a_q16, 5u));
    }
    fw->turn_prev_q16 = cmd_q16;
    fw->turn_primed = 1u;
    return a;
}

/* The law's option inputs: the filtered lateral specific force always (Q14
 * g, saturating at +/-2 g), the turn acceleration from the turn command
 * (Q16) when roll_in is on, else 0. */
static void option_inputs(fw_t *fw, q16_t turn_cmd_q16, ht_input_t *li)
{
    li->accel_lat_g = q_sat16(q_rshift_round(fw->accel_lat_q20, 6u));
    li->turn_accel_rad_s2 = 0;
    if (fw->cfg->law.roll_in != 0u) {
        li->turn_accel_rad_s2 = turn_accel(fw, turn_cmd_q16);
    }
}

/* The turn-rate trim (guide.h) on the law's input, then the law. The trim
 * holds while the previous step was tilt-limited or had a surface at its
 * stop, while the pilot flies (manual: the law's output is not used), and
 * until the estimator knows its heading: before a turn has taught it the
 * wind, its heading follows the GPS course, whose crab swings the heading's
 * rate by the crab times the turn rate (20 % in a 10 m/s wind at 50 m/s). */
static void trimmed_law(fw_t *fw, const fw_nav_t *nav, uint8_t pitch_mode, uint8_t manual,
                        ht_input_t *li, ht_output_t *lo)
{
    const uint8_t busy = (uint8_t)HT_F_TILT_LIMITED | (uint8_t)HT_F_SURFACE_SATURATED;
    const uint8_t heading_known =
        ((fw->dcm_state.flags & (uint16_t)HT_DCM_F_HEADING_KNOWN) != 0u) ? 1u : 0u;
    const uint8_t hold =
        (manual != 0u || (fw->law_flags & busy) != 0u || heading_known == 0u) ? 1u : 0u;
    li->turn_rate_rad_s = ht_guide_turn_rate(&fw->guide, &fw->guide_state, li->turn_rate_rad_s,
                                             nav->heading_north, nav->heading_east, hold);
    ht_step(&fw->law[pitch_mode], li, lo);
    fw->law_flags = lo->flags;
}

/* The guided turn command's slew with roll_in on, in Q16 rad/s per control
 * step: the modes' turn_slew, or the turn-rate change whose bank rate at
 * wings level is roll_in_rate_max, if that is slower. The turn rate of a
 * coordinated turn is g tan(phi) / S, so d(turn)/dt = g / (S cos^2 phi) *
 * d(phi)/dt >= g / S * d(phi)/dt: at this slew the law's target bank rate
 * (ht_options.c) is at most roll_in_rate_max at every bank, and the roll-in
 * acts for the whole entry instead of the few steps of the stick slew.
 * S is the airspeed the law uses (floored at v_min); g is 981 cm/s^2 (0.03 %
 * above 980.665: the slew is that much faster). At least 1 LSB. */
static int32_t guided_turn_slew(const fw_t *fw, int16_t airspeed_cm_s)
{
    const int32_t v_min = fw->cfg->law.v_min_cm_s;
    const int32_t s_cm_s = (airspeed_cm_s < v_min) ? v_min : (int32_t)airspeed_cm_s;
    /* roll_in_rate_max <= 8 rad/s = 2^19 in Q16: times 981 below 2^29 */
    const int32_t per_s = (fw->cfg->law.roll_in_rate_max_rad_s * 981) / s_cm_s;
    int32_t step = per_s / (int32_t)fw->cfg->modes.rate_hz;
    if (step > fw->modes.turn_slew_rad_s_per_tick) {
        step = fw->modes.turn_slew_rad_s_per_tick;
    }
    return (step < 1) ? 1 : step;
}

/* Guided: holds -> upset guard -> law; the surfaces go straight to the mixer. */
static void guided(fw_t *fw, const fw_guided_t *c, const fw_nav_t *nav, fw_output_t *o,
                   os_command_t *cmd)
{
    ht_modes_state_t *st = &fw->modes_state;
    const uint8_t inverted = (c->inverted != 0u) ? 1u : 0u;
    q16_t pitch = c->pitch_ratio;
    if (c->altitude_hold != 0u) {
        /* the integrator follows the measured orientation (holds.h) */
        pitch = ht_alt_hold_step_v(&fw->modes.alt, &st->alt, c->altitude_cm, nav->altitude_cm,
                                   nav->climb_cm_s, (nav->down_q14[2] < 0) ? 1u : 0u,
                                   nav->airspeed_cm_s);
    }
    pitch = ht_upset_guard_step(&fw->cfg->guard, &fw->guard_state, nav->down_q14[0],
                                nav->down_q14[1], nav->down_q14[2], inverted, pitch);
    q14_t throttle = c->throttle;
    if (c->speed_hold != 0u) {
        throttle = ht_speed_hold_step(&fw->modes.speed, &st->speed, c->airspeed_cm_s,
                                      nav->airspeed_cm_s, pitch);
    }
    ht_input_t *li = &o->law_in;
    law_input(li, nav);
    li->turn_rate_rad_s = c->turn_rate_rad_s;
    /* With roll_in on, a guided command (the SIL's scenarios give steps) is
     * slewed: the derivative of a step would ask for an unbounded bank rate.
     * The slew is the modes' turn_slew or the one that asks for at most
     * roll_in_rate_max of bank rate, whichever is slower (guided_turn_slew). */
    q16_t turn_q16 = (q16_t)c->turn_rate_rad_s * 32;
    if (fw->cfg->law.roll_in != 0u) {
        if (fw->turn_primed != 0u) {
            const int32_t step = guided_turn_slew(fw, nav->airspeed_cm_s);
            turn_q16 =
                q_add_sat32(fw->guided_turn_q16,
                            q_clamp32(q_sub_sat32(turn_q16, fw->guided_turn_q16), -step, step));
        }
        fw->guided_turn_q16 = turn_q16;
        li->turn_rate_rad_s = q_sat16(q_rshift_round(turn_q16, 5u));
    }
    option_inputs(fw, turn_q16, li);
    li->pitch_ratio = pitch;
    li->inverted = inverted;
    const uint8_t pm = (c->pitch_mode == (uint8_t)HT_PITCH_TILT_CROSS) ? 1u : 0u;
    trimmed_law(fw, nav, pm, 0u, li, &o->law);
    cmd->aileron = o->law.aileron;
    cmd->elevator = o->law.elevator;
    cmd->rudder = o->law.rudder;
    cmd->throttle = throttle;
    o->throttle = throttle;
    o->pitch_cmd = pitch;
}

/* A ground station's mode in place of the mode switch (fw_t.gcs_mode): the
 * pulse that selects it, given only where the switch's own pulse is valid
 * (a lost or bad frame stays bad: the failsafe still wins). The pilot takes
 * the mode back by moving the switch. */
static void gcs_mode_pulse(fw_t *fw, ht_modes_input_t *mi)
{
    const uint8_t input = fw->modes.mode_input;
    if ((fw->gcs_mode == 0u) || (fw->gcs_mode > (uint8_t)HT_MODE_COUNT) ||
        (input >= mi->rc_count) || (input >= HT_MODES_RC_MAX)) {
        return;
    }
    const uint16_t us = mi->rc_us[input];
    if ((us < OS_RC_VALID_MIN_US) || (us > OS_RC_VALID_MAX_US)) {
        return;
    }
    const uint8_t sw = (uint8_t)ht_modes_from_pulse(&fw->modes, us);
    if (fw->gcs_switch == UINT8_MAX) {
        fw->gcs_switch = sw;
    } else if (sw != fw->gcs_switch) {
        fw->gcs_mode = 0u; /* the pilot moved the switch */
        return;
    } else {
        /* the switch is where it was */
    }
    const uint16_t *thr = fw->modes.mode_threshold_us;
    const uint8_t mode = (uint8_t)(fw->gcs_mode - 1u);
    mi->rc_us[input] =
        (mode == (uint8_t)HT_MODE_MANUAL) ? (uint16_t)OS_RC_VALID_MIN_US : thr[mode - 1u];
}

/* The pilot: RC -> flight modes (targets, holds, AoA model) -> upset guard
 * -> law -> the modes' surface blend. */
static void pilot(fw_t *fw, const fw_inputs_t *in, const fw_nav_t *nav, fw_output_t *o,
                  os_command_t *cmd)
{
    ht_modes_input_t mi;
    (void)memset(&mi, 0, sizeof mi);
    const uint8_t n = (in->rc_count > FW_RC_MAX) ? (uint8_t)FW_RC_MAX : in->rc_count;
    // cppcheck-suppress knownConditionTrueFalse ; false positive: n = min(rc_count, 16), D-FP-RC
    for (uint8_t i = 0u; i < n; ++i) {
        mi.rc_us[i] = in->rc_us[i];
    }
    mi.rc_count = n;
    mi.rc_fresh = in->rc_fresh;
    mi.x = nav->down_q14[0];
    mi.y = nav->down_q14[1];
    mi.z = nav->down_q14[2];
    mi.gyro_rad_s[0] = nav->gyro_q11_rad_s[0];
    mi.gyro_rad_s[1] = nav->gyro_q11_rad_s[1];
    mi.gyro_rad_s[2] = nav->gyro_q11_rad_s[2];
    mi.airspeed_cm_s = nav->airspeed_cm_s;
    mi.north_cm = nav->north_cm;
    mi.east_cm = nav->east_cm;
    mi.alt_cm = nav->altitude_cm;
    mi.climb_cm_s = nav->climb_cm_s;
    mi.vel_north_cm_s = nav->vel_north_cm_s;
    mi.vel_east_cm_s = nav->vel_east_cm_s;
    mi.heading_north = nav->heading_north;
    mi.heading_east = nav->heading_east;
    gcs_mode_pulse(fw, &mi);
    ht_modes_step(&fw->modes, &fw->modes_state, &mi, &o->modes);
    ht_input_t *li = &o->modes.law_in;
    option_inputs(fw, fw->modes_state.turn_cmd_rad_s, li);
    li->pitch_ratio = ht_upset_guard_step(&fw->cfg->guard, &fw->guard_state, li->x, li->y, li->z,
                                          li->inverted, li->pitch_ratio);
    const uint8_t pm = (fw->cfg->modes_pitch_mode != 0u) ? 1u : 0u;
    const uint8_t manual = (o->modes.mode == (uint8_t)HT_MODE_MANUAL) ? 1u : 0u;
    trimmed_law(fw, nav, pm, manual, li, &o->law);
    o->law_in = *li;
    ht_modes_surfaces(&o->modes, &o->law, cmd);
    o->throttle = o->modes.throttle;
    o->pitch_cmd = li->pitch_ratio;
}

static void output_stage(const fw_config_t *cfg, const os_command_t *cmd, fw_output_t *o)
{
    if (os_compute(&cfg->out, cmd, o->pulse_us) != OS_OK) {
        (void)os_failsafe(&cfg->out, o->pulse_us);
        o->failsafe = 1u;
    }
    o->pulse_count = cfg->out.count;
    for (uint8_t i = 0u; i < cfg->out.count; ++i) {
        const os_channel_t *ch = &cfg->out.ch[i];
        if (ch->function != (uint8_t)OS_FN_THROTTLE && ch->function != (uint8_t)OS_FN_NONE &&
            (o->pulse_us[i] <= ch->min_us || o->pulse_us[i] >= ch->max_us)) {
            o->servo_clamped = 1u;
        }
    }
}

int fw_align(fw_t *fw, const fw_nav_t *nav)
{
    if (fw == NULL || nav == NULL || fw->ready == 0u) {
        return 2;
    }
    const int rc = ht_dcm_align_to(&fw->dcm, &fw->dcm_state, nav->down_q14, nav->heading_north,
                                   nav->heading_east);
    if (rc == 0) {
        fw->aligned = 1u;
    }
    return rc;
}

/* --- the step ---------------------------------------------------------------- */

int fw_step(fw_t *fw, const fw_inputs_t *in, fw_output_t *out)
{
    if (fw == NULL || in == NULL || out == NULL) {
        return 0;
    }
    out->control_ran = 0u;
    if (fw->ready == 0u) {
        out->pulse_count = 0u; /* a refused configuration: no pulses at all */
        return 0;
    }
    const fw_config_t *cfg = fw->cfg;
    fw->samples++;

    /* 1. the attitude estimate, every IMU sample; GPS, baro, pitot as they come */
    estimate(fw, in);

    /* 2. the control rate */
    fw->divider_count++;
    if (fw->divider_count < cfg->control_divider) {
        return 0;
    }
    fw->divider_count = 0u;
    fw->control_steps++;
    (void)memset(out, 0, sizeof *out);
    out->control_ran = 1u;

    /* 3. the navigation solution the control flies on */
    ht_dcm_output(&fw->dcm_state, &out->est);
    navigation(fw, in, &out->est);
    const fw_nav_t *nav = (in->external != NULL) ? in->external : &fw->nav;
    out->nav = *nav;

    /* 4. no IMU (and no external solution): every channel to its failsafe */
    if (in->external == NULL && fw->imu_age >= cfg->imu_timeout_samples) {
        out->failsafe = 1u;
        (void)os_failsafe(&cfg->out, out->pulse_us);
        out->pulse_count = cfg->out.count;
        return 1;
    }

    /* 5. commands -> holds -> upset guard -> law -> surfaces */
    os_command_t cmd;
    if (in->guided != NULL) {
        guided(fw, in->guided, nav, out, &cmd);
    } else {
        pilot(fw, in, nav, out, &cmd);
    }
    out->guard_engaged = fw->guard_state.engaged;
    out->pitot_suspect = (in->external == NULL) ? fw->pitot_suspect : 0u;

    /* 6. mixer and output stage -> pulses */
    output_stage(cfg, &cmd, out);
    return 1;
}
