/*
 * sil_board.c - the host board of the SIL harness (see sil_board.h).
 */
#include "sil_board.h"

#include <math.h>
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
    if (err != NULL && err_len > 0) {
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

int sil_board_init(sil_board_t *b, const sil_config_t *cfg, char *err, size_t err_len)
{
    if (b == NULL || cfg == NULL) {
        return fail(err, err_len, "(null)");
    }
    memset(b, 0, sizeof(*b));

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
    p.schedule = (uint8_t)(cfg->schedule != 0);
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
    b->ready = 1;
    if (err != NULL && err_len > 0) {
        err[0] = '\0';
    }
    return 0;
}

/* --- the firmware control step (integer only) ------------------------- */

void sil_fw_step(sil_board_t *b, const sil_fw_sensors_t *s, const sil_fw_command_t *c,
                 sil_fw_output_t *o)
{
    memset(o, 0, sizeof(*o));
    if (b == NULL || s == NULL || c == NULL || !b->ready) {
        return;
    }
    /* outer loops; the altitude hold's integrator follows the measured
     * orientation (holds.h) */
    q16_t pitch = c->pitch_ratio;
    if (c->altitude_hold) {
        pitch = ht_alt_hold_step(&b->alt, &b->alt_state, c->altitude_cm, s->altitude_cm,
                                 s->climb_cm_s, (uint8_t)(s->imu.down_q14[2] < 0));
    }
    q14_t throttle = c->throttle;
    if (c->speed_hold) {
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
    const unsigned mode = (c->pitch_mode == (uint8_t)HT_PITCH_TILT_CROSS) ? 1u : 0u;
    ht_step(&b->law[mode], &in, &o->law);
    /* the output stage: mixing, trims, travel, end points */
    os_command_t cmd;
    cmd.aileron = o->law.aileron;
    cmd.elevator = o->law.elevator;
    cmd.rudder = o->law.rudder;
    cmd.throttle = throttle;
    uint16_t pulses[OS_MAX_CHANNELS];
    if (os_compute(&b->out, &cmd, pulses) != OS_OK) {
        return;
    }
    for (int i = 0; i < SIL_CH_COUNT; ++i) {
        o->pulse_us[i] = pulses[i];
        if (i < SIL_CH_THROTTLE &&
            (pulses[i] <= b->out.ch[i].min_us || pulses[i] >= b->out.ch[i].max_us)) {
            o->servo_clamped = 1;
        }
    }
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
    memset(a, 0, sizeof(*a));
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

    sil_fw_command_t fc;
    fc.turn_rate_rad_s = to_q11(c->turn_rate_rad_s);
    fc.pitch_ratio = to_q16(c->pitch_ratio);
    fc.altitude_cm = to_cm32(c->altitude_m);
    fc.airspeed_cm_s = to_cm16(c->airspeed_m_s);
    fc.throttle = to_q14(c->throttle < 0.0 ? 0.0 : (c->throttle > 1.0 ? 1.0 : c->throttle));
    fc.altitude_hold = (uint8_t)(c->altitude_hold != 0);
    fc.speed_hold = (uint8_t)(c->speed_hold != 0);
    fc.inverted = (uint8_t)(c->inverted != 0);
    fc.pitch_mode = (uint8_t)(c->pitch_mode != 0);

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
}
