/*
 * sil_board.c - the host board of the SIL harness (see sil_board.h).
 */
#include "sil_board.h"

#include <math.h>
#include <stdbool.h>
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

/* The flight modes' parameters (physical units -> modes.h) and the
 * waypoints; every value is range-checked by ht_modes_init after
 * conversion, so only what would not convert into its field is refused here. */
static int group_params(int group, const double *values, const char *prefix, void *dst,
                        void (*set)(void *, int, int64_t), char *err, size_t err_len);
static void set_modes(void *dst, int id, int64_t raw);
static void set_fbw(void *dst, int id, int64_t raw);
static void set_nav(void *dst, int id, int64_t raw);
static void set_aoa(void *dst, int id, int64_t raw);

/* The flight modes: the waypoints, then the table's groups. */
static int modes_params(sil_board_t *b, const sil_config_t *cfg, ht_modes_params_t *p, char *err,
                        size_t err_len)
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
    if (group_params(SIL_GROUP_MODES, cfg->modes, "modes.", p, set_modes, err, err_len) != 0 ||
        group_params(SIL_GROUP_FBW, cfg->fbw, "fbw.", &p->fbw, set_fbw, err, err_len) != 0 ||
        group_params(SIL_GROUP_NAV, cfg->nav, "nav.", &p->nav, set_nav, err, err_len) != 0 ||
        group_params(SIL_GROUP_AOA, cfg->aoa, "aoa.", &p->aoa, set_aoa, err, err_len) != 0) {
        return 1;
    }
    return 0;
}

/* --- the parameter table (include/helical/params.def) ------------------ */

/* A row's value in the table's unit, refused with the row's bounds unless
 * finite and within them; otherwise its stored integer (llround of value *
 * scale, which the bounds keep inside the field's type). */
static int table_value(double v, const ht_param_info_t *info, const char *prefix, int64_t *raw,
                       char *err, size_t err_len)
{
    const double scale = (double)info->scale;
    const double lo = (double)info->min_raw / scale;
    const double hi = (double)info->max_raw / scale;
    if (!in_range(v, lo, hi)) {
        if (err != NULL && err_len > 0u) {
            (void)snprintf(err, err_len, "%s%s = %.9g is outside [%.9g, %.9g] (%s, %s)", prefix,
                           info->name, v, lo, hi, info->unit, info->format);
        }
        return 1;
    }
    if (info->scale == 1 && v != floor(v)) { /* an integer field (U8, U16) */
        if (err != NULL && err_len > 0u) {
            (void)snprintf(err, err_len, "%s%s = %.9g is not a whole number (%s, %s)", prefix,
                           info->name, v, info->unit, info->format);
        }
        return 1;
    }
    *raw = to_fixed(v, scale, info->min_raw, info->max_raw);
    return 0;
}

/* One setter per group of the table: the stored value of row id into its
 * field (the value is already within the row's bounds, so it fits). */
// cppcheck-suppress misra-c2012-20.7 ; D-PARAM-TABLE: field is a member name, not an expression
#define SIL_SET(prefix, id, field, fmt)                                                            \
    case prefix##id:                                                                               \
        p->field = (HT_PFMT_TYPE_##fmt)raw;                                                        \
        break;
#define SIL_SET_LAW(id, name, field, unit, fmt, lo, hi, def, desc) SIL_SET(HT_P_, id, field, fmt)
#define SIL_SET_DCM(id, name, field, unit, fmt, lo, hi, def, desc)                                 \
    SIL_SET(HT_DCM_P_, id, field, fmt)
#define SIL_SET_GUIDE(id, name, field, unit, fmt, lo, hi, def, desc)                               \
    SIL_SET(HT_GUIDE_P_, id, field, fmt)
#define SIL_SET_ALT(id, name, field, unit, fmt, lo, hi, def, desc)                                 \
    SIL_SET(HT_ALT_P_, id, field, fmt)
#define SIL_SET_SPEED(id, name, field, unit, fmt, lo, hi, def, desc)                               \
    SIL_SET(HT_SPEED_P_, id, field, fmt)
#define SIL_SET_MODES(id, name, field, unit, fmt, lo, hi, def, desc)                               \
    SIL_SET(HT_MODES_P_, id, field, fmt)
#define SIL_SET_FBW(id, name, field, unit, fmt, lo, hi, def, desc)                                 \
    SIL_SET(HT_FBW_P_, id, field, fmt)
#define SIL_SET_NAV(id, name, field, unit, fmt, lo, hi, def, desc)                                 \
    SIL_SET(HT_NAV_P_, id, field, fmt)
#define SIL_SET_AOA(id, name, field, unit, fmt, lo, hi, def, desc)                                 \
    SIL_SET(HT_AOA_P_, id, field, fmt)

/* A group's setter: the stored value of row id into its field of *dst. The
 * arguments are a function name, a type, a list and its row expander: none
 * is an expression to parenthesize (D-PARAM-TABLE). */
// cppcheck-suppress misra-c2012-20.7 ; D-PARAM-TABLE: names and a type, not expressions
#define SIL_SETTER(fn, type, list, row)                                                            \
    static void fn(void *dst, int id, int64_t raw)                                                 \
    {                                                                                              \
        type *p = dst; /* NOLINT(bugprone-macro-parentheses): a type */                            \
        switch (id) {                                                                              \
            list(row) default : break;                                                             \
        }                                                                                          \
    }

SIL_SETTER(set_law, ht_params_t, HT_PARAMS_LAW, SIL_SET_LAW)
SIL_SETTER(set_dcm, ht_dcm_params_t, HT_PARAMS_DCM, SIL_SET_DCM)
SIL_SETTER(set_guide, ht_guide_params_t, HT_PARAMS_GUIDE, SIL_SET_GUIDE)
SIL_SETTER(set_alt, ht_alt_hold_params_t, HT_PARAMS_ALT, SIL_SET_ALT)
SIL_SETTER(set_speed, ht_speed_hold_params_t, HT_PARAMS_SPEED, SIL_SET_SPEED)
SIL_SETTER(set_modes, ht_modes_params_t, HT_PARAMS_MODES, SIL_SET_MODES)
SIL_SETTER(set_fbw, ht_fbw_params_t, HT_PARAMS_FBW, SIL_SET_FBW)
SIL_SETTER(set_nav, ht_nav_params_t, HT_PARAMS_NAV, SIL_SET_NAV)
SIL_SETTER(set_aoa, ht_aoa_params_t, HT_PARAMS_AOA, SIL_SET_AOA)

const ht_param_info_t *sil_param_info(int group, int index)
{
    const int id = index + 1;
    switch (group) {
    case SIL_GROUP_LAW:
        return ht_param_info((ht_param_id_t)id);
    case SIL_GROUP_ESTIMATOR:
        return ht_dcm_param_info((ht_dcm_param_id_t)id);
    case SIL_GROUP_GUIDANCE:
        return ht_guide_param_info((ht_guide_param_id_t)id);
    case SIL_GROUP_ALT_HOLD:
        return ht_alt_hold_param_info((ht_alt_param_id_t)id);
    case SIL_GROUP_SPEED_HOLD:
        return ht_speed_hold_param_info((ht_speed_param_id_t)id);
    case SIL_GROUP_MODES:
        return ht_modes_param_info((ht_modes_param_id_t)id);
    case SIL_GROUP_FBW:
        return ht_fbw_param_info((ht_fbw_param_id_t)id);
    case SIL_GROUP_NAV:
        return ht_nav_param_info((ht_nav_param_id_t)id);
    case SIL_GROUP_AOA:
        return ht_aoa_param_info((ht_aoa_param_id_t)id);
    default:
        return NULL;
    }
}

int sil_param_count(int group)
{
    static const int counts[SIL_GROUP_COUNT] = {
        HT_PARAM_LAW_COUNT, HT_PARAM_DCM_COUNT,   HT_PARAM_GUIDE_COUNT,
        HT_PARAM_ALT_COUNT, HT_PARAM_SPEED_COUNT, HT_PARAM_MODES_COUNT,
        HT_PARAM_FBW_COUNT, HT_PARAM_NAV_COUNT,   HT_PARAM_AOA_COUNT};
    return (group >= 0 && group < SIL_GROUP_COUNT) ? counts[group] : 0;
}

/* One group of sil_config_t (values in the table's units and order) into
 * its struct: each value checked against its row, a refusal quoting the
 * row's bounds under the group's prefix ("estimator.gps_latency = ..."). */
static int group_params(int group, const double *values, const char *prefix, void *dst,
                        void (*set)(void *, int, int64_t), char *err, size_t err_len)
{
    for (int i = 0; i < sil_param_count(group); ++i) {
        int64_t raw = 0;
        if (table_value(values[i], sil_param_info(group, i), prefix, &raw, err, err_len) != 0) {
            return 1;
        }
        set(dst, i + 1, raw);
    }
    return 0;
}

/* The holds, and the altitude hold's initial integrators (harness state, not
 * parameters: a run that starts in trimmed flight). The joint limits are
 * ht_modes_init's (fw_init refuses them, naming the field). */
static int hold_params(const sil_config_t *cfg, fw_config_t *fc, char *err, size_t err_len)
{
    const uint16_t rate = (uint16_t)cfg->control_rate_hz;
    ht_alt_hold_params_default(&fc->modes.alt, rate);
    ht_speed_hold_params_default(&fc->modes.speed, rate);
    if (group_params(SIL_GROUP_ALT_HOLD, cfg->alt_hold, "", &fc->modes.alt, set_alt, err,
                     err_len) != 0 ||
        group_params(SIL_GROUP_SPEED_HOLD, cfg->speed_hold, "", &fc->modes.speed, set_speed, err,
                     err_len) != 0) {
        return 1;
    }
    if (!in_range(cfg->alt_integral_upright, -4.0, 4.0)) {
        return fail(err, err_len, "alt_integral_upright");
    }
    if (!in_range(cfg->alt_integral_inverted, -4.0, 4.0)) {
        return fail(err, err_len, "alt_integral_inverted");
    }
    fc->alt_integral_q20[0] =
        (int32_t)to_fixed(cfg->alt_integral_upright, 1048576.0, INT32_MIN, INT32_MAX);
    fc->alt_integral_q20[1] =
        (int32_t)to_fixed(cfg->alt_integral_inverted, 1048576.0, INT32_MIN, INT32_MAX);
    return 0;
}

/* The name of what fw_init refused. */
static int fw_refused(const fw_t *fw, char *err, size_t err_len)
{
    char name[64];
    switch ((fw_bad_block_t)fw->bad) {
    case FW_BAD_DCM:
        (void)snprintf(name, sizeof name, "estimator.%s",
                       ht_dcm_param_name((ht_dcm_param_id_t)fw->bad_sub));
        break;
    case FW_BAD_LAW:
        (void)snprintf(name, sizeof name, "%s", ht_param_name((ht_param_id_t)fw->bad_sub));
        break;
    case FW_BAD_GUIDE:
        (void)snprintf(name, sizeof name, "guidance.%s",
                       ht_guide_param_name((ht_guide_param_id_t)fw->bad_sub));
        break;
    case FW_BAD_MODES:
        ht_modes_bad_name(&fw->modes_bad, name, (unsigned)sizeof name);
        break;
    case FW_BAD_GUARD:
        (void)snprintf(name, sizeof name, "upset_guard");
        break;
    case FW_BAD_OUTPUT:
        (void)snprintf(name, sizeof name, "output_stage");
        break;
    case FW_BAD_DIVIDER:
        (void)snprintf(name, sizeof name, "imu_rate_hz");
        break;
    default:
        (void)snprintf(name, sizeof name, "firmware");
        break;
    }
    return fail(err, err_len, name);
}

int sil_board_init(sil_board_t *b, const sil_config_t *cfg, char *err, size_t err_len)
{
    if (b == NULL || cfg == NULL) {
        return fail(err, err_len, "(null)");
    }
    (void)memset(b, 0, sizeof(*b));
    fw_config_t *fc = &b->cfg;
    fw_config_default(fc);
    fc->modes.rc_channels = (uint8_t)SIL_RC_COUNT; /* the scripted receiver's (config_check.h) */
    if (cfg->control_rate_hz < 1 || cfg->control_rate_hz > 1000) {
        return fail(err, err_len, "control_rate_hz");
    }
    const int imu_row = (int)HT_DCM_P_IMU_RATE - 1;
    const double imu_hz = cfg->estimator[imu_row];
    if (!in_range(imu_hz, 1.0, 1000.0) || imu_hz != floor(imu_hz)) {
        return fail(err, err_len, "imu_rate_hz");
    }
    const int32_t imu_rate_hz = (int32_t)imu_hz;
    if (imu_rate_hz < cfg->control_rate_hz || imu_rate_hz > 1000 ||
        imu_rate_hz % cfg->control_rate_hz != 0 ||
        imu_rate_hz / cfg->control_rate_hz > SIL_IMU_MAX) {
        return fail(err, err_len, "imu_rate_hz");
    }
    int rc = group_params(SIL_GROUP_LAW, cfg->law, "", &fc->law, set_law, err, err_len);
    if (rc == 0) {
        fc->modes.rate_hz = (uint16_t)cfg->control_rate_hz;
        rc = hold_params(cfg, fc, err, err_len);
    }
    if (rc == 0) {
        rc = group_params(SIL_GROUP_ESTIMATOR, cfg->estimator, "estimator.", &fc->dcm, set_dcm, err,
                          err_len);
    }
    if (rc == 0) {
        rc = group_params(SIL_GROUP_GUIDANCE, cfg->guidance, "guidance.", &fc->guide, set_guide,
                          err, err_len);
    }
    if (rc == 0 && cfg->modes_enabled != 0) {
        rc = modes_params(b, cfg, &fc->modes, err, err_len);
        fc->waypoints = b->waypoints;
        fc->waypoint_count = (uint16_t)cfg->waypoint_count;
    }
    if (rc != 0) {
        return rc;
    }
    fc->modes_pitch_mode = (cfg->modes_pitch_mode != 0) ? 1u : 0u;
    const int32_t divider = imu_rate_hz / cfg->control_rate_hz;
    fc->control_divider = (uint16_t)divider;
    const int32_t timeout = imu_rate_hz / 5; /* 0.2 s */
    fc->imu_timeout_samples = (uint16_t)timeout;

    const double trims[3] = {cfg->trim_aileron, cfg->trim_elevator, cfg->trim_rudder};
    static const char *const trim_names[3] = {"trim_aileron", "trim_elevator", "trim_rudder"};
    static const uint8_t functions[SIL_CH_COUNT] = {OS_FN_AILERON, OS_FN_ELEVATOR, OS_FN_RUDDER,
                                                    OS_FN_THROTTLE};
    fc->out.count = SIL_CH_COUNT;
    for (int i = 0; i < (int)OS_MAX_CHANNELS; ++i) {
        os_channel_default(&fc->out.ch[i], (i < SIL_CH_COUNT) ? functions[i] : (uint8_t)OS_FN_NONE);
    }
    for (int i = 0; i < 3; ++i) {
        if (!in_range(trims[i], -1.0, 1.0)) {
            return fail(err, err_len, trim_names[i]);
        }
        fc->out.ch[i].trim_us = (int16_t)to_fixed(trims[i], (double)fc->out.ch[i].travel_us,
                                                  -OS_TRIM_MAX_US, OS_TRIM_MAX_US);
    }
    if (fw_init(&b->fw, fc) == 0) {
        return fw_refused(&b->fw, err, err_len);
    }
    if (cfg->link_sysid < 0 || cfg->link_sysid > 255) {
        return fail(err, err_len, "link_sysid");
    }
    if (cfg->link_compid < 0 || cfg->link_compid > 255) {
        return fail(err, err_len, "link_compid");
    }
    const uint8_t compid = (cfg->link_compid == 0) ? 1u : (uint8_t)cfg->link_compid;
    if (fw_link_init(&b->link, &b->fw, fc, (uint8_t)cfg->link_sysid, compid) != 0) {
        return fail(err, err_len, "link");
    }
    b->modes_enabled = (cfg->modes_enabled != 0) ? 1u : 0u;
    b->ready = 1;
    if (err != NULL && err_len > 0u) {
        err[0] = '\0';
    }
    return 0;
}

/* --- one control step: the host's sensor and servo "drivers" ------------- */

/* JSBSim's true state as the external navigation solution. */
static void truth_solution(const sil_sensors_t *s, fw_nav_t *n)
{
    n->down_q14[0] = to_q14(s->dcm_x);
    n->down_q14[1] = to_q14(s->dcm_y);
    n->down_q14[2] = to_q14(s->dcm_z);
    n->gyro_q11_rad_s[0] = to_q11(s->gyro_x);
    n->gyro_q11_rad_s[1] = to_q11(s->gyro_y);
    n->gyro_q11_rad_s[2] = to_q11(s->gyro_z);
    n->airspeed_cm_s = to_cm16(s->airspeed_m_s);
    n->altitude_cm = to_cm32(s->altitude_m);
    n->climb_cm_s = to_cm32(s->climb_m_s);
    n->north_cm = to_cm32(s->north_m);
    n->east_cm = to_cm32(s->east_m);
    n->vel_north_cm_s = to_cm32(s->vel_north_m_s);
    n->vel_east_cm_s = to_cm32(s->vel_east_m_s);
    n->heading_north = to_q14(cos(s->heading_rad));
    n->heading_east = to_q14(sin(s->heading_rad));
}

static void guided_command(const sil_command_t *c, fw_guided_t *g)
{
    g->turn_rate_rad_s = to_q11(c->turn_rate_rad_s);
    g->pitch_ratio = to_q16(c->pitch_ratio);
    g->altitude_cm = to_cm32(c->altitude_m);
    g->airspeed_cm_s = to_cm16(c->airspeed_m_s);
    g->throttle = to_q14(c->throttle < 0.0 ? 0.0 : (c->throttle > 1.0 ? 1.0 : c->throttle));
    g->altitude_hold = (c->altitude_hold != 0) ? 1u : 0u;
    g->speed_hold = (c->speed_hold != 0) ? 1u : 0u;
    g->inverted = (c->inverted != 0) ? 1u : 0u;
    g->pitch_mode = (c->pitch_mode != 0) ? 1u : 0u;
}

/* The slower sensors of this control step (given with its last sample). */
static void slow_sensors(const sil_sensors_t *s, fw_inputs_t *in)
{
    in->sensors.gps.fresh = (s->gps_fresh != 0) ? 1u : 0u;
    in->sensors.gps.fix = (uint8_t)to_fixed(s->gps_fix, 1.0, 0, 3);
    in->sensors.gps.lat_e7 = (int32_t)to_fixed(s->gps_lat_deg, 1.0e7, -900000000, 900000000);
    in->sensors.gps.lon_e7 = (int32_t)to_fixed(s->gps_lon_deg, 1.0e7, -1800000000, 1800000000);
    in->sensors.gps.alt_cm = to_cm32(s->gps_alt_m);
    for (int k = 0; k < 3; ++k) {
        in->sensors.gps.vel_ned_cm_s[k] = to_cm32(s->gps_vel_ned_m_s[k]);
    }
    in->sensors.airspeed_fresh = (s->airspeed_fresh != 0) ? 1u : 0u;
    in->sensors.airspeed_cm_s = to_cm16(s->pitot_m_s);
    in->sensors.baro_fresh = (s->baro_fresh != 0) ? 1u : 0u;
    in->sensors.baro_alt_cm = to_cm32(s->baro_alt_m);
}

/* The "servo driver": each pulse back to the deflection JSBSim takes, and the
 * firmware's telemetry. */
static void actuators(const sil_board_t *b, sil_actuators_t *a)
{
    const fw_output_t *o = &b->out;
    const os_channel_t *ch = b->cfg.out.ch;
    a->control_ran = 1;
    a->aileron = from_pulse(&ch[SIL_CH_AILERON], o->pulse_us[SIL_CH_AILERON]);
    a->elevator = from_pulse(&ch[SIL_CH_ELEVATOR], o->pulse_us[SIL_CH_ELEVATOR]);
    a->rudder = from_pulse(&ch[SIL_CH_RUDDER], o->pulse_us[SIL_CH_RUDDER]);
    a->throttle = from_pulse(&ch[SIL_CH_THROTTLE], o->pulse_us[SIL_CH_THROTTLE]);
    a->law_aileron = from_q14(o->law.aileron);
    a->law_elevator = from_q14(o->law.elevator);
    a->law_rudder = from_q14(o->law.rudder);
    a->pitch_cmd = from_q16(o->pitch_cmd);
    a->turn_rate_used_rad_s = from_q11(o->law.turn_rate_used_rad_s);
    a->roll_error = from_q14(o->law.roll_error);
    a->pitch_error = from_q14(o->law.pitch_error);
    a->flags = (int32_t)o->law.flags | (o->servo_clamped ? 0x100 : 0);
    const ht_dcm_output_t *e = &o->est;
    a->est_x = from_q14(e->r[2][0]);
    a->est_y = from_q14(e->r[2][1]);
    a->est_z = from_q14(e->r[2][2]);
    a->est_roll_deg = (double)e->roll_cdeg / 100.0;
    a->est_pitch_deg = (double)e->pitch_cdeg / 100.0;
    a->est_yaw_deg = (double)e->yaw_cdeg / 100.0;
    for (int k = 0; k < 3; ++k) {
        a->est_bias_rad_s[k] = from_q16(e->gyro_bias_rad_s[k]);
    }
    a->est_flags = (int32_t)e->flags;
    a->nav_x = from_q14(o->nav.down_q14[0]);
    a->nav_y = from_q14(o->nav.down_q14[1]);
    a->nav_z = from_q14(o->nav.down_q14[2]);
    a->nav_airspeed_m_s = (double)o->nav.airspeed_cm_s / 100.0;
    a->nav_altitude_m = (double)o->nav.altitude_cm / 100.0;
    a->nav_climb_m_s = (double)o->nav.climb_cm_s / 100.0;
    a->nav_north_m = (double)o->nav.north_cm / 100.0;
    a->nav_east_m = (double)o->nav.east_cm / 100.0;
    a->guard_engaged = o->guard_engaged;
    if (b->modes_enabled != 0u) {
        const ht_modes_output_t *m = &o->modes;
        const ht_modes_state_t *st = &b->fw.modes_state;
        a->mode = m->mode;
        a->selected_mode = m->selected_mode;
        a->failsafe = m->failsafe;
        a->rc_good = m->rc_good;
        a->inverted_cmd = m->law_in.inverted;
        a->nav_index = m->nav.index;
        a->nav_arrived = m->nav.arrived;
        a->nav_flags = m->nav.flags;
        a->nav_reached = (int32_t)(st->nav.reached > (uint32_t)INT32_MAX ? (uint32_t)INT32_MAX
                                                                         : st->nav.reached);
        a->turn_target_rad_s = from_q16(m->turn_target_rad_s);
        a->turn_cmd_rad_s = from_q11(m->law_in.turn_rate_rad_s);
        a->nav_turn_rate_rad_s = from_q16(m->nav.turn_rate_rad_s);
        a->cross_track_m = (double)m->nav.cross_track_cm / 100.0;
        a->nav_distance_m = (double)m->nav.distance_cm / 100.0;
        a->target_altitude_m = (double)m->nav.target_alt_cm / 100.0;
        a->leg_from_north_m = (double)st->nav.from_north_cm / 100.0;
        a->leg_from_east_m = (double)st->nav.from_east_cm / 100.0;
        a->blend = from_q14(m->blend);
        a->aoa_pitch_offset = from_q16(m->aoa.pitch_offset);
        a->aoa_trim = from_q14(m->aoa.elevator_trim);
        a->aoa_loading = from_q16(m->aoa.loading);
        a->aoa_active = m->aoa.active;
    }
}

void sil_board_step(sil_board_t *b, const sil_sensors_t *s, const sil_command_t *c,
                    sil_actuators_t *a)
{
    if (a == NULL) {
        return;
    }
    (void)memset(a, 0, sizeof(*a));
    if (b == NULL || s == NULL || c == NULL || !b->ready) {
        return;
    }
    fw_inputs_t in;
    (void)memset(&in, 0, sizeof in);
    fw_guided_t guided;
    guided_command(c, &guided);
    in.guided = (b->modes_enabled != 0u) ? NULL : &guided;
    fw_nav_t truth;
    truth_solution(s, &truth);
    if (s->align_to_truth != 0) {
        (void)fw_align(&b->fw, &truth);
    }
    in.rc_count = (uint8_t)SIL_RC_COUNT;
    for (int i = 0; i < SIL_RC_COUNT; ++i) {
        in.rc_us[i] = (uint16_t)to_fixed(c->rc_us[i], 1.0, 0, UINT16_MAX);
    }
    in.rc_fresh = (c->rc_fresh != 0) ? 1u : 0u;
    const int n =
        (s->imu_count < 0) ? 0 : (s->imu_count > SIL_IMU_MAX ? SIL_IMU_MAX : s->imu_count);
    /* no sample: one call without one (the firmware counts the gap) */
    const int calls = (n == 0) ? (int)b->cfg.control_divider : n;
    /* the slower sensors' values hold for the whole batch; their "fresh"
     * flags go with the last sample, the one taken now */
    slow_sensors(s, &in);
    const uint8_t gps_fresh = in.sensors.gps.fresh, airspeed_fresh = in.sensors.airspeed_fresh;
    const uint8_t baro_fresh = in.sensors.baro_fresh;
    bool ran = false;
    for (int i = 0; i < calls; ++i) {
        in.sensors.imu_fresh = (n > 0) ? 1u : 0u;
        for (int k = 0; k < 3 && n > 0; ++k) {
            in.sensors.imu.gyro_rad_s[k] = to_q16(s->gyro_rad_s[i][k]);
            in.sensors.imu.accel_g[k] = to_q16(s->accel_g[i][k]);
        }
        const bool last = (i == (calls - 1));
        in.sensors.gps.fresh = last ? gps_fresh : 0u;
        in.sensors.airspeed_fresh = last ? airspeed_fresh : 0u;
        in.sensors.baro_fresh = last ? baro_fresh : 0u;
        in.external = (last && s->use_truth != 0) ? &truth : NULL;
        if (fw_step(&b->fw, &in, &b->out) != 0) {
            ran = true;
        }
    }
    if (ran) {
        actuators(b, a);
        /* the board's clock: the control steps run so far, in ms (wraps
         * after 49 days, as a board's millisecond tick does) */
        const uint64_t ms =
            ((uint64_t)b->fw.control_steps * 1000u) / (uint64_t)b->cfg.modes.rate_hz;
        fw_link_after_step(&b->link, &b->out, (uint32_t)(ms & UINT32_MAX));
        if (b->after_step != NULL) {
            const uint64_t us =
                ((uint64_t)b->fw.samples * 1000000u) / (uint64_t)b->cfg.dcm.imu_rate_hz;
            b->after_step(b->after_step_ctx, &b->fw, &in, &b->out, us);
        }
    }
}

/* --- the ground-station link (ABI 15) ------------------------------------- */

void sil_link_rx(sil_board_t *b, const uint8_t *bytes, size_t n)
{
    if (b != NULL && b->ready && bytes != NULL) {
        fw_link_rx(&b->link, bytes, n);
    }
}

size_t sil_link_tx(sil_board_t *b, uint8_t *buf, size_t cap)
{
    if (b == NULL || !b->ready || buf == NULL) {
        return 0u;
    }
    return fw_link_tx(&b->link, buf, cap);
}

/* fw_link_counters_t's fields, by name, in its order */
#define SIL_COUNTER_COUNT 9

int sil_link_counter_count(void)
{
    return SIL_COUNTER_COUNT;
}

const char *sil_link_counter_name(int index)
{
    static const char *const names[SIL_COUNTER_COUNT] = {
        "rx_ok",           "rx_dropped",     "rx_bad_crc", "rx_garbled", "rx_unknown_id",
        "rx_wrong_target", "rx_bad_content", "tx_frames",  "tx_overflow"};
    return (index >= 0 && index < SIL_COUNTER_COUNT) ? names[index] : NULL;
}

uint32_t sil_link_counter(const sil_board_t *b, int index)
{
    if (b == NULL || !b->ready) {
        return 0u;
    }
    const fw_link_counters_t *c = &b->link.count;
    switch (index) {
    case 0:
        return c->rx_ok;
    case 1:
        return c->rx_dropped;
    case 2:
        return c->rx_bad_crc;
    case 3:
        return c->rx_garbled;
    case 4:
        return c->rx_unknown_id;
    case 5:
        return c->rx_wrong_target;
    case 6:
        return c->rx_bad_content;
    case 7:
        return c->tx_frames;
    case 8:
        return c->tx_overflow;
    default:
        return 0u;
    }
}
