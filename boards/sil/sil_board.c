/*
 * sil_board.c - the host board of the SIL harness (see sil_board.h).
 */
#include "sil_board.h"

#include <math.h>
// cppcheck-suppress misra-c2012-21.6 ; D-SIL-HOST: host-only SIL board, snprintf names a refused
// field for the Python caller
#include <stdio.h>
#include <string.h>

/* --- host-only conversions (floats allowed here, never in the library) ---- */

/* round(v * scale) saturated to [lo, hi]; NaN gives 0. */
static int64_t to_fixed(double v, double scale, int64_t lo, int64_t hi)
{
    if (v != v) {
        return 0;
    }
    double s = v * scale;
    if (s <= (double)lo) {
        return lo;
    }
    if (s >= (double)hi) {
        return hi;
    }
    return (int64_t)llround(s);
}

static q14_t to_q14(double v)
{
    return (q14_t)to_fixed(v, 16384.0, INT16_MIN, INT16_MAX);
}

static q11_t to_q11(double v)
{
    return (q11_t)to_fixed(v, 2048.0, INT16_MIN, INT16_MAX);
}

static q16_t to_q16(double v)
{
    return (q16_t)to_fixed(v, 65536.0, INT32_MIN, INT32_MAX);
}

static int16_t to_cm16(double v_m)
{
    return (int16_t)to_fixed(v_m, 100.0, INT16_MIN, INT16_MAX);
}

static int32_t to_cm32(double v_m)
{
    return (int32_t)to_fixed(v_m, 100.0, INT32_MIN, INT32_MAX);
}

static double from_q14(q14_t v)
{
    return (double)v / 16384.0;
}

static double from_q11(q11_t v)
{
    return (double)v / 2048.0;
}

static double from_q16(q16_t v)
{
    return (double)v / 65536.0;
}

/* A servo pulse as the deflection it produces: (pulse - centre) / travel;
 * reversing would be undone here as a real linkage would. */
static double from_pulse(const os_channel_t *ch, uint16_t pulse_us)
{
    double d = ((double)pulse_us - (double)ch->centre_us) / (double)ch->travel_us;
    return ch->reversed ? -d : d;
}

static int fail(char *err, size_t err_len, const char *field)
{
    if (err != NULL && err_len > 0u) {
        (void)snprintf(err, err_len, "%s", field);
    }
    return 1;
}

/* A physical value must be finite and in [lo, hi] before it is converted. */
static int in_range(double v, double lo, double hi)
{
    return v == v && v >= lo && v <= hi;
}

/* --- ABI -------------------------------------------------------------- */

int sil_board_abi_version(void)
{
    return SIL_BOARD_ABI_VERSION;
}
size_t sil_board_size(void)
{
    return sizeof(sil_board_t);
}
size_t sil_config_size(void)
{
    return sizeof(sil_config_t);
}
size_t sil_sensors_size(void)
{
    return sizeof(sil_sensors_t);
}
size_t sil_command_size(void)
{
    return sizeof(sil_command_t);
}
size_t sil_actuators_size(void)
{
    return sizeof(sil_actuators_t);
}

/* --- init ------------------------------------------------------------- */

/* The flight modes' parameters (physical units -> modes.h), the waypoints,
 * and the state. The holds are the board's own (already checked). */
static int modes_init(sil_board_t *b, const sil_config_t *cfg, char *err, size_t err_len)
{
    if (cfg->waypoint_count < 0 || cfg->waypoint_count > SIL_MAX_WAYPOINTS) {
        return fail(err, err_len, "waypoint_count");
    }
    for (int i = 0; i < cfg->waypoint_count; ++i) {
        for (int k = 0; k < 3; ++k) {
            if (!in_range(cfg->waypoints[i][k], -1.0e6, 1.0e6)) {
                return fail(err, err_len, "waypoints");
            }
        }
        b->waypoints[i].north_m = (int32_t)llround(cfg->waypoints[i][0]);
        b->waypoints[i].east_m = (int32_t)llround(cfg->waypoints[i][1]);
        b->waypoints[i].alt_m = (int32_t)llround(cfg->waypoints[i][2]);
    }
    /* every value is range-checked by ht_modes_init after conversion; refuse
     * here only what would not convert into the field's integer type */
    const double dvals[] = {cfg->nav_turn_rate_max_deg_s, cfg->nav_l1_m,
                            cfg->nav_arrival_radius_m,    cfg->nav_loiter_radius_m,
                            cfg->nav_home_alt_m,          cfg->cruise_m_s,
                            cfg->fbw_turn_rate_max_deg_s, cfg->fbw_pitch_max,
                            cfg->fbw_deadband_us,         cfg->turn_slew_deg_s2,
                            cfg->pitch_slew_per_s,        cfg->aoa_v_ref_m_s,
                            cfg->aoa_v_enable_m_s,        cfg->aoa_load_max,
                            cfg->aoa_normal_deg,          cfg->aoa_normal_slope_deg,
                            cfg->aoa_inverted_deg,        cfg->aoa_inverted_slope_deg,
                            cfg->aoa_trim_normal,         cfg->aoa_trim_normal_slope,
                            cfg->aoa_trim_inverted,       cfg->aoa_trim_inverted_slope};
    static const char *const dnames[] = {"nav.turn_rate_max_deg_s", "nav.l1_m",
                                         "nav.arrival_radius_m",    "nav.loiter_radius_m",
                                         "nav.home_alt_m",          "nav.cruise_m_s",
                                         "fbw.turn_rate_max_deg_s", "fbw.pitch_max",
                                         "fbw.deadband_us",         "modes.turn_slew_deg_s2",
                                         "modes.pitch_slew_per_s",  "aoa.v_ref_m_s",
                                         "aoa.v_enable_m_s",        "aoa.load_max",
                                         "aoa.aoa_normal_deg",      "aoa.aoa_normal_slope_deg",
                                         "aoa.aoa_inverted_deg",    "aoa.aoa_inverted_slope_deg",
                                         "aoa.trim_normal",         "aoa.trim_normal_slope",
                                         "aoa.trim_inverted",       "aoa.trim_inverted_slope"};
    for (size_t i = 0; i < sizeof dvals / sizeof dvals[0]; ++i) {
        if (!in_range(dvals[i], -30000.0, 30000.0)) {
            return fail(err, err_len, dnames[i]);
        }
    }
    ht_modes_params_t p;
    ht_modes_params_default(&p);
    p.rc_loss_ticks = (uint16_t)to_fixed(cfg->rc_loss_ticks, 1.0, 0, UINT16_MAX);
    p.rc_recover_ticks = (uint16_t)to_fixed(cfg->rc_recover_ticks, 1.0, 0, UINT16_MAX);
    p.blend_ticks = (uint16_t)to_fixed(cfg->blend_ticks, 1.0, 0, UINT16_MAX);
    p.turn_slew_deg_s2 = (int16_t)to_fixed(cfg->turn_slew_deg_s2, 1.0, INT16_MIN, INT16_MAX);
    p.pitch_slew_per_s = to_q16(cfg->pitch_slew_per_s);
    p.cruise_cm_s = to_cm16(cfg->cruise_m_s);
    p.rate_hz = (uint16_t)cfg->control_rate_hz;
    p.fbw.turn_rate_max_deg_s =
        (int16_t)to_fixed(cfg->fbw_turn_rate_max_deg_s, 1.0, INT16_MIN, INT16_MAX);
    p.fbw.pitch_max = to_q16(cfg->fbw_pitch_max);
    p.fbw.deadband_us = (uint16_t)to_fixed(cfg->fbw_deadband_us, 1.0, 0, UINT16_MAX);
    p.nav.law = (uint8_t)(cfg->nav_law != 0 ? HT_GUIDE_L1 : HT_GUIDE_HEADING);
    p.nav.loop = (cfg->nav_loop != 0) ? 1u : 0u;
    p.nav.turn_rate_max_deg_s =
        (int16_t)to_fixed(cfg->nav_turn_rate_max_deg_s, 1.0, INT16_MIN, INT16_MAX);
    p.nav.l1_m = (uint16_t)to_fixed(cfg->nav_l1_m, 1.0, 0, UINT16_MAX);
    p.nav.arrival_radius_m = (uint16_t)to_fixed(cfg->nav_arrival_radius_m, 1.0, 0, UINT16_MAX);
    p.nav.loiter_radius_m = (uint16_t)to_fixed(cfg->nav_loiter_radius_m, 1.0, 0, UINT16_MAX);
    p.nav.home_alt_m = (int32_t)llround(cfg->nav_home_alt_m);
    p.aoa.enabled = (cfg->aoa_enabled != 0) ? 1u : 0u;
    p.aoa.v_ref_cm_s = to_cm16(cfg->aoa_v_ref_m_s);
    p.aoa.v_enable_cm_s = to_cm16(cfg->aoa_v_enable_m_s);
    p.aoa.load_max = to_q16(cfg->aoa_load_max);
    p.aoa.aoa_normal_deg = to_q16(cfg->aoa_normal_deg);
    p.aoa.aoa_normal_slope_deg = to_q16(cfg->aoa_normal_slope_deg);
    p.aoa.aoa_inverted_deg = to_q16(cfg->aoa_inverted_deg);
    p.aoa.aoa_inverted_slope_deg = to_q16(cfg->aoa_inverted_slope_deg);
    p.aoa.trim_normal = to_q14(cfg->aoa_trim_normal);
    p.aoa.trim_normal_slope = to_q14(cfg->aoa_trim_normal_slope);
    p.aoa.trim_inverted = to_q14(cfg->aoa_trim_inverted);
    p.aoa.trim_inverted_slope = to_q14(cfg->aoa_trim_inverted_slope);
    p.alt = b->alt;
    p.speed = b->spd;
    b->modes_pitch_mode = (cfg->modes_pitch_mode != 0) ? 1u : 0u;
    ht_modes_bad_t bad;
    if (ht_modes_init(&b->modes, &p, &b->law[b->modes_pitch_mode], b->waypoints,
                      (uint16_t)cfg->waypoint_count, &bad) != 0) {
        char name[48];
        ht_modes_bad_name(&bad, name, (unsigned)sizeof name);
        return fail(err, err_len, name);
    }
    ht_modes_reset(&b->modes_state, 0, 0);
    b->modes_state.alt.integral_q20[0] = b->alt_state.integral_q20[0];
    b->modes_state.alt.integral_q20[1] = b->alt_state.integral_q20[1];
    b->modes_enabled = 1;
    return 0;
}

int sil_board_init(sil_board_t *b, const sil_config_t *cfg, char *err, size_t err_len)
{
    if (b == NULL || cfg == NULL) {
        return fail(err, err_len, "(null)");
    }
    (void)memset(b, 0, sizeof(*b));

    /* gains: the core checks [0, 64]; refuse values that would not convert */
    const double gains[9] = {cfg->kp_aileron,  cfg->kp_elevator,  cfg->kp_rudder,
                             cfg->kff_aileron, cfg->kff_elevator, cfg->kff_rudder,
                             cfg->kd_aileron,  cfg->kd_elevator,  cfg->kd_rudder};
    static const char *const gain_names[9] = {"kp_aileron",  "kp_elevator",  "kp_rudder",
                                              "kff_aileron", "kff_elevator", "kff_rudder",
                                              "kd_aileron",  "kd_elevator",  "kd_rudder"};
    for (int i = 0; i < 9; ++i) {
        if (!in_range(gains[i], 0.0, 64.0)) {
            return fail(err, err_len, gain_names[i]);
        }
    }
    if (!in_range(cfg->v_ref_m_s, 1.0, 327.0)) {
        return fail(err, err_len, "v_ref");
    }
    if (!in_range(cfg->v_min_m_s, 1.0, 327.0)) {
        return fail(err, err_len, "v_min");
    }
    if (!in_range(cfg->max_tilt, 0.0, 8.0)) {
        return fail(err, err_len, "max_tilt");
    }
    if (cfg->control_rate_hz < 1 || cfg->control_rate_hz > 1000) {
        return fail(err, err_len, "control_rate_hz");
    }
    ht_params_t p = HT_PARAMS_DEFAULT;
    p.kp_aileron = to_q16(cfg->kp_aileron);
    p.kp_elevator = to_q16(cfg->kp_elevator);
    p.kp_rudder = to_q16(cfg->kp_rudder);
    p.kff_aileron = to_q16(cfg->kff_aileron);
    p.kff_elevator = to_q16(cfg->kff_elevator);
    p.kff_rudder = to_q16(cfg->kff_rudder);
    p.kd_aileron = to_q16(cfg->kd_aileron);
    p.kd_elevator = to_q16(cfg->kd_elevator);
    p.kd_rudder = to_q16(cfg->kd_rudder);
    p.v_ref_cm_s = to_cm32(cfg->v_ref_m_s);
    p.v_min_cm_s = to_cm32(cfg->v_min_m_s);
    p.schedule = (cfg->schedule != 0) ? 1u : 0u;
    p.max_tilt = to_q16(cfg->max_tilt);
    for (int mode = 0; mode < 2; ++mode) {
        p.pitch_mode = (uint8_t)mode;
        ht_param_id_t bad = HT_P_NONE;
        if (ht_init(&b->law[mode], &p, &bad) != HT_OK) {
            return fail(err, err_len, ht_param_name(bad));
        }
    }

    b->alt.kp_pitch_per_m = to_q16(cfg->alt_kp_pitch_per_m);
    b->alt.ki_pitch_per_m_s = to_q16(cfg->alt_ki_pitch_per_m_s);
    b->alt.kd_pitch_per_m_s = to_q16(cfg->alt_kd_pitch_per_m_s);
    b->alt.max_pitch = to_q16(cfg->alt_max_pitch);
    b->alt.max_integral_pitch = to_q16(cfg->alt_max_integral_pitch);
    b->alt.max_error_cm = to_cm32(cfg->alt_max_error_m);
    b->alt.integral_band_cm = to_cm32(cfg->alt_integral_band_m);
    b->alt.rate_hz = (uint16_t)cfg->control_rate_hz;
    if (!in_range(cfg->alt_protect_m_s, 0.0, 327.0) ||
        !in_range(cfg->alt_protect_valid_m_s, 0.0, 327.0) ||
        !in_range(cfg->alt_protect_tau_s, 0.0, 60.0)) {
        return fail(err, err_len, "altitude_hold");
    }
    b->alt.protect_cm_s = to_cm32(cfg->alt_protect_m_s);
    b->alt.protect_valid_cm_s = to_cm32(cfg->alt_protect_valid_m_s);
    b->alt.kv_pitch_per_m_s = to_q16(cfg->alt_kv_pitch_per_m_s);
    b->alt.protect_tau_ms = (uint16_t)llround(cfg->alt_protect_tau_s * 1000.0);
    if (ht_alt_hold_check(&b->alt) != HT_HOLD_OK) {
        return fail(err, err_len, "altitude_hold");
    }
    ht_alt_hold_reset(&b->alt_state);
    const int32_t max_i_q20 = b->alt.max_integral_pitch * 16;
    b->alt_state.integral_q20[0] =
        q_clamp32((int32_t)to_fixed(cfg->alt_integral_upright, 1048576.0, INT32_MIN, INT32_MAX),
                  -max_i_q20, max_i_q20);
    b->alt_state.integral_q20[1] =
        q_clamp32((int32_t)to_fixed(cfg->alt_integral_inverted, 1048576.0, INT32_MIN, INT32_MAX),
                  -max_i_q20, max_i_q20);

    b->spd.throttle_trim = to_q14(cfg->spd_throttle_trim);
    b->spd.throttle_min = to_q14(cfg->spd_throttle_min);
    b->spd.throttle_max = to_q14(cfg->spd_throttle_max);
    b->spd.kp_throttle_per_m_s = to_q16(cfg->spd_kp_throttle_per_m_s);
    b->spd.ki_throttle_per_m = to_q16(cfg->spd_ki_throttle_per_m);
    b->spd.kff_throttle_per_pitch = to_q16(cfg->spd_kff_throttle_per_pitch);
    b->spd.max_integral_throttle = to_q14(cfg->spd_max_integral_throttle);
    b->spd.rate_hz = (uint16_t)cfg->control_rate_hz;
    if (ht_speed_hold_check(&b->spd) != HT_HOLD_OK) {
        return fail(err, err_len, "airspeed_hold");
    }
    const ht_upset_guard_params_t ug = HT_UPSET_GUARD_PARAMS_DEFAULT;
    b->ug = ug;
    if (ht_upset_guard_check(&b->ug) != HT_UG_OK) {
        return fail(err, err_len, "upset_guard");
    }
    ht_upset_guard_reset(&b->ug_state);
    ht_speed_hold_reset(&b->spd_state);

    const double trims[3] = {cfg->trim_aileron, cfg->trim_elevator, cfg->trim_rudder};
    static const char *const trim_names[3] = {"trim_aileron", "trim_elevator", "trim_rudder"};
    static const uint8_t functions[SIL_CH_COUNT] = {OS_FN_AILERON, OS_FN_ELEVATOR, OS_FN_RUDDER,
                                                    OS_FN_THROTTLE};
    b->out.count = SIL_CH_COUNT;
    for (int i = 0; i < SIL_CH_COUNT; ++i) {
        os_channel_default(&b->out.ch[i], functions[i]);
    }
    for (int i = 0; i < 3; ++i) {
        if (!in_range(trims[i], -1.0, 1.0)) {
            return fail(err, err_len, trim_names[i]);
        }
        b->out.ch[i].trim_us = (int16_t)to_fixed(trims[i], (double)b->out.ch[i].travel_us,
                                                 -OS_TRIM_MAX_US, OS_TRIM_MAX_US);
    }
    uint8_t bad_channel = 0;
    if (os_config_check(&b->out, &bad_channel) != OS_OK) {
        return fail(err, err_len, "output_stage");
    }
    if (cfg->modes_enabled != 0) {
        const int rc = modes_init(b, cfg, err, err_len);
        if (rc != 0) {
            return rc;
        }
    }
    b->ready = 1;
    if (err != NULL && err_len > 0u) {
        err[0] = '\0';
    }
    return 0;
}

/* --- the firmware control step (integer only) ------------------------- */

/* Pulses of the output stage; flags a surface on an end point. */
static void servo_out(const sil_board_t *b, const os_command_t *cmd, sil_fw_output_t *o)
{
    uint16_t pulses[OS_MAX_CHANNELS];
    if (os_compute(&b->out, cmd, pulses) != OS_OK) {
        return;
    }
    for (int i = 0; i < SIL_CH_COUNT; ++i) {
        o->pulse_us[i] = pulses[i];
        if (i < SIL_CH_THROTTLE &&
            (pulses[i] <= b->out.ch[i].min_us || pulses[i] >= b->out.ch[i].max_us)) {
            o->servo_clamped = 1;
        }
    }
}

/* The flight-modes step, as docs/flight-modes.md wires it on a board:
 * receiver + GPS + IMU -> ht_modes_step -> ht_step -> ht_modes_surfaces ->
 * output stage. The holds run inside ht_modes_step. */
static void modes_step(sil_board_t *b, const sil_fw_sensors_t *s, const sil_fw_command_t *c,
                       sil_fw_output_t *o)
{
    ht_modes_input_t in;
    (void)memset(&in, 0, sizeof in);
    for (int i = 0; i < SIL_RC_COUNT; ++i) {
        in.rc_us[i] = c->rc_us[i];
    }
    in.rc_count = (uint8_t)SIL_RC_COUNT;
    in.rc_fresh = c->rc_fresh;
    in.x = s->imu.down_q14[0];
    in.y = s->imu.down_q14[1];
    in.z = s->imu.down_q14[2];
    in.gyro_rad_s[0] = s->imu.gyro_q11_rad_s[0];
    in.gyro_rad_s[1] = s->imu.gyro_q11_rad_s[1];
    in.gyro_rad_s[2] = s->imu.gyro_q11_rad_s[2];
    in.airspeed_cm_s = s->imu.airspeed_cm_s;
    in.north_cm = s->north_cm;
    in.east_cm = s->east_cm;
    in.alt_cm = s->altitude_cm;
    in.climb_cm_s = s->climb_cm_s;
    in.vel_north_cm_s = s->vel_north_cm_s;
    in.vel_east_cm_s = s->vel_east_cm_s;
    in.heading_north = s->heading_north;
    in.heading_east = s->heading_east;
    ht_modes_step(&b->modes, &b->modes_state, &in, &o->modes);
    ht_step(&b->law[b->modes_pitch_mode], &o->modes.law_in, &o->law);
    os_command_t cmd;
    ht_modes_surfaces(&o->modes, &o->law, &cmd);
    servo_out(b, &cmd, o);
    o->throttle = o->modes.throttle;
    o->pitch_cmd = o->modes.law_in.pitch_ratio;
}

void sil_fw_step(sil_board_t *b, const sil_fw_sensors_t *s, const sil_fw_command_t *c,
                 sil_fw_output_t *o)
{
    (void)memset(o, 0, sizeof(*o));
    if (b == NULL || s == NULL || c == NULL || !b->ready) {
        return;
    }
    if (b->modes_enabled != 0u) {
        modes_step(b, s, c, o);
        return;
    }
    /* outer loops; the altitude hold's integrator follows the measured
     * orientation (holds.h) */
    q16_t pitch = c->pitch_ratio;
    if (c->altitude_hold != 0u) {
        pitch = ht_alt_hold_step_v(&b->alt, &b->alt_state, c->altitude_cm, s->altitude_cm,
                                   s->climb_cm_s, (s->imu.down_q14[2] < 0) ? 1u : 0u,
                                   s->imu.airspeed_cm_s);
    }
    /* nose-low inverted upset: unload, roll upright, then pull (upset_guard.h) */
    pitch = ht_upset_guard_step(&b->ug, &b->ug_state, s->imu.down_q14[0], s->imu.down_q14[1],
                                s->imu.down_q14[2], c->inverted, pitch);
    q14_t throttle = c->throttle;
    if (c->speed_hold != 0u) {
        throttle = ht_speed_hold_step(&b->spd, &b->spd_state, c->airspeed_cm_s,
                                      s->imu.airspeed_cm_s, pitch);
    }
    /* the helical-turn law */
    ht_input_t in;
    in.x = s->imu.down_q14[0];
    in.y = s->imu.down_q14[1];
    in.z = s->imu.down_q14[2];
    in.turn_rate_rad_s = c->turn_rate_rad_s;
    in.pitch_ratio = pitch;
    in.airspeed_cm_s = s->imu.airspeed_cm_s;
    in.gyro_rad_s[0] = s->imu.gyro_q11_rad_s[0];
    in.gyro_rad_s[1] = s->imu.gyro_q11_rad_s[1];
    in.gyro_rad_s[2] = s->imu.gyro_q11_rad_s[2];
    in.inverted = c->inverted;
    const uint8_t mode = (c->pitch_mode == (uint8_t)HT_PITCH_TILT_CROSS) ? 1u : 0u;
    ht_step(&b->law[mode], &in, &o->law);
    /* the output stage: mixing, trims, travel, end points */
    os_command_t cmd;
    cmd.aileron = o->law.aileron;
    cmd.elevator = o->law.elevator;
    cmd.rudder = o->law.rudder;
    cmd.throttle = throttle;
    servo_out(b, &cmd, o);
    o->throttle = throttle;
    o->pitch_cmd = pitch;
}

/* --- host wrapper ----------------------------------------------------- */

void sil_board_step(sil_board_t *b, const sil_sensors_t *s, const sil_command_t *c,
                    sil_actuators_t *a)
{
    if (a == NULL) {
        return;
    }
    (void)memset(a, 0, sizeof(*a));
    if (b == NULL || s == NULL || c == NULL) {
        return;
    }
    sil_fw_sensors_t fs;
    fs.imu.down_q14[0] = to_q14(s->dcm_x);
    fs.imu.down_q14[1] = to_q14(s->dcm_y);
    fs.imu.down_q14[2] = to_q14(s->dcm_z);
    fs.imu.gyro_q11_rad_s[0] = to_q11(s->gyro_x);
    fs.imu.gyro_q11_rad_s[1] = to_q11(s->gyro_y);
    fs.imu.gyro_q11_rad_s[2] = to_q11(s->gyro_z);
    fs.imu.airspeed_cm_s = to_cm16(s->airspeed_m_s);
    fs.altitude_cm = to_cm32(s->altitude_m);
    fs.climb_cm_s = to_cm32(s->climb_m_s);
    fs.north_cm = to_cm32(s->north_m);
    fs.east_cm = to_cm32(s->east_m);
    fs.vel_north_cm_s = to_cm32(s->vel_north_m_s);
    fs.vel_east_cm_s = to_cm32(s->vel_east_m_s);
    fs.heading_north = to_q14(cos(s->heading_rad));
    fs.heading_east = to_q14(sin(s->heading_rad));

    sil_fw_command_t fc;
    fc.turn_rate_rad_s = to_q11(c->turn_rate_rad_s);
    fc.pitch_ratio = to_q16(c->pitch_ratio);
    fc.altitude_cm = to_cm32(c->altitude_m);
    fc.airspeed_cm_s = to_cm16(c->airspeed_m_s);
    fc.throttle = to_q14(c->throttle < 0.0 ? 0.0 : (c->throttle > 1.0 ? 1.0 : c->throttle));
    fc.altitude_hold = (c->altitude_hold != 0) ? 1u : 0u;
    fc.speed_hold = (c->speed_hold != 0) ? 1u : 0u;
    fc.inverted = (c->inverted != 0) ? 1u : 0u;
    fc.pitch_mode = (c->pitch_mode != 0) ? 1u : 0u;
    for (int i = 0; i < SIL_RC_COUNT; ++i) {
        fc.rc_us[i] = (uint16_t)to_fixed(c->rc_us[i], 1.0, 0, UINT16_MAX);
    }
    fc.rc_fresh = (c->rc_fresh != 0) ? 1u : 0u;

    sil_fw_output_t o;
    sil_fw_step(b, &fs, &fc, &o);
    /* the "servo driver": each pulse back to the deflection JSBSim takes */
    a->aileron = from_pulse(&b->out.ch[SIL_CH_AILERON], o.pulse_us[SIL_CH_AILERON]);
    a->elevator = from_pulse(&b->out.ch[SIL_CH_ELEVATOR], o.pulse_us[SIL_CH_ELEVATOR]);
    a->rudder = from_pulse(&b->out.ch[SIL_CH_RUDDER], o.pulse_us[SIL_CH_RUDDER]);
    a->throttle = from_pulse(&b->out.ch[SIL_CH_THROTTLE], o.pulse_us[SIL_CH_THROTTLE]);
    a->law_aileron = from_q14(o.law.aileron);
    a->law_elevator = from_q14(o.law.elevator);
    a->law_rudder = from_q14(o.law.rudder);
    a->pitch_cmd = from_q16(o.pitch_cmd);
    a->turn_rate_used_rad_s = from_q11(o.law.turn_rate_used_rad_s);
    a->roll_error = from_q14(o.law.roll_error);
    a->pitch_error = from_q14(o.law.pitch_error);
    a->flags = (int32_t)o.law.flags | (o.servo_clamped ? 0x100 : 0);
    if (b->modes_enabled != 0u) {
        const ht_modes_output_t *m = &o.modes;
        a->mode = m->mode;
        a->selected_mode = m->selected_mode;
        a->failsafe = m->failsafe;
        a->rc_good = m->rc_good;
        a->inverted_cmd = m->law_in.inverted;
        a->nav_index = m->nav.index;
        a->nav_arrived = m->nav.arrived;
        a->nav_flags = m->nav.flags;
        a->nav_reached = (int32_t)(b->modes_state.nav.reached > (uint32_t)INT32_MAX
                                       ? (uint32_t)INT32_MAX
                                       : b->modes_state.nav.reached);
        a->turn_target_rad_s = from_q16(m->turn_target_rad_s);
        a->turn_cmd_rad_s = from_q11(m->law_in.turn_rate_rad_s);
        a->nav_turn_rate_rad_s = from_q16(m->nav.turn_rate_rad_s);
        a->cross_track_m = (double)m->nav.cross_track_cm / 100.0;
        a->nav_distance_m = (double)m->nav.distance_cm / 100.0;
        a->target_altitude_m = (double)m->nav.target_alt_cm / 100.0;
        a->leg_from_north_m = (double)b->modes_state.nav.from_north_cm / 100.0;
        a->leg_from_east_m = (double)b->modes_state.nav.from_east_cm / 100.0;
        a->blend = from_q14(m->blend);
        a->aoa_pitch_offset = from_q16(m->aoa.pitch_offset);
        a->aoa_trim = from_q14(m->aoa.elevator_trim);
        a->aoa_loading = from_q16(m->aoa.loading);
        a->aoa_active = m->aoa.active;
    }
}
