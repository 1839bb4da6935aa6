/*
 * fw_link_telemetry.c - the telemetry streams and their scheduler: each
 * stream at its parameter's rate (LNK_*_HZ; SET_MESSAGE_INTERVAL overrides,
 * REQUEST_MESSAGE sends one at the next step), from the last control step's
 * output. Due times advance by whole intervals, so a rate that does not
 * divide the control rate is still met on average (docs/mavlink.md).
 */
#include "link/fw_link_telemetry.h"

#include "helical/math/f32_bits.h"
#include "link/fw_link_modes.h"
#include "link/fw_link_tx.h"

/* pi / 18000 (rad per centidegree) in units of 2^-30 */
#define RAD_PER_CDEG_Q30 187406
#define Q30_DEN          0x40000000U /* 2^30 */

static uint32_t f32_cdeg_to_rad(int32_t cdeg)
{
    return ht_f32_from_ratio((int64_t)cdeg * RAD_PER_CDEG_Q30, Q30_DEN);
}

static int16_t sat16(int32_t v)
{
    int16_t r;
    if (v > INT16_MAX) {
        r = INT16_MAX;
    } else if (v < INT16_MIN) {
        r = INT16_MIN;
    } else {
        r = (int16_t)v;
    }
    return r;
}

static uint32_t isqrt64(uint64_t x)
{
    uint64_t rest = x;
    uint64_t r = 0u;
    uint64_t bit = 0x4000000000000000ULL; /* 2^62 */
    while (bit > rest) {
        bit >>= 2u;
    }
    while (bit != 0u) {
        if (rest >= r + bit) {
            rest -= r + bit;
            r = (r >> 1u) + bit;
        } else {
            r >>= 1u;
        }
        bit >>= 2u;
    }
    return (uint32_t)r;
}

/* --- the messages ---------------------------------------------------------- */

static void heartbeat(fw_link_t *l)
{
    const fw_output_t *o = &l->last;
    mavlink_heartbeat_t hb;
    (void)memset(&hb, 0, sizeof hb);
    hb.type = (uint8_t)MAV_TYPE_FIXED_WING;
    /* ArduPilot's identity: the clients pick their mode decoder by it
     * (docs/mavlink.md "Identity"), and custom_mode is ArduPlane's numbering */
    hb.autopilot = (uint8_t)MAV_AUTOPILOT_ARDUPILOTMEGA;
    const uint8_t mode = fw_link_mode(l);
    uint8_t base = (uint8_t)MAV_MODE_FLAG_CUSTOM_MODE_ENABLED;
    if (mode == (uint8_t)HT_MODE_MANUAL) {
        base |= (uint8_t)MAV_MODE_FLAG_MANUAL_INPUT_ENABLED;
    } else if (mode == (uint8_t)HT_MODE_FBW) {
        base |= (uint8_t)MAV_MODE_FLAG_MANUAL_INPUT_ENABLED;
        base |= (uint8_t)MAV_MODE_FLAG_STABILIZE_ENABLED;
    } else {
        base |= (uint8_t)MAV_MODE_FLAG_STABILIZE_ENABLED;
        base |= (uint8_t)MAV_MODE_FLAG_GUIDED_ENABLED;
        base |= (uint8_t)MAV_MODE_FLAG_AUTO_ENABLED;
    }
    if (fw_link_armed(l) != 0) {
        base |= (uint8_t)MAV_MODE_FLAG_SAFETY_ARMED; /* the servos and the motor are driven */
    }
    hb.base_mode = base;
    hb.custom_mode = fw_link_custom_mode(mode); /* 0 manual, 5 FBW, 10 waypoint, 11 RTH */
    if (l->have_output == 0u) {
        hb.system_status = (uint8_t)MAV_STATE_BOOT;
    } else if (o->failsafe != 0u) {
        hb.system_status = (uint8_t)MAV_STATE_EMERGENCY; /* IMU lost */
    } else if (o->modes.failsafe != 0u) {
        hb.system_status = (uint8_t)MAV_STATE_CRITICAL; /* RC lost: returning home */
    } else {
        hb.system_status = (uint8_t)MAV_STATE_ACTIVE;
    }
    hb.mavlink_version = 3u;
    (void)FW_LINK_QUEUE(l, HEARTBEAT, hb);
}

static void sys_status(fw_link_t *l)
{
    const fw_output_t *o = &l->last;
    mavlink_sys_status_t ss;
    (void)memset(&ss, 0, sizeof ss);
    const uint32_t present = (uint32_t)MAV_SYS_STATUS_SENSOR_3D_GYRO |
                             (uint32_t)MAV_SYS_STATUS_SENSOR_3D_ACCEL |
                             (uint32_t)MAV_SYS_STATUS_SENSOR_GPS |
                             (uint32_t)MAV_SYS_STATUS_SENSOR_DIFFERENTIAL_PRESSURE |
                             (uint32_t)MAV_SYS_STATUS_SENSOR_ABSOLUTE_PRESSURE |
                             (uint32_t)MAV_SYS_STATUS_SENSOR_RC_RECEIVER |
                             (uint32_t)MAV_SYS_STATUS_SENSOR_ANGULAR_RATE_CONTROL |
                             (uint32_t)MAV_SYS_STATUS_SENSOR_ATTITUDE_STABILIZATION |
                             (uint32_t)MAV_SYS_STATUS_SENSOR_XY_POSITION_CONTROL |
                             (uint32_t)MAV_SYS_STATUS_SENSOR_MOTOR_OUTPUTS;
    uint32_t health = present;
    if (o->failsafe != 0u) {
        health &=
            ~((uint32_t)MAV_SYS_STATUS_SENSOR_3D_GYRO | (uint32_t)MAV_SYS_STATUS_SENSOR_3D_ACCEL);
    }
    if (o->modes.failsafe != 0u) {
        health &= ~(uint32_t)MAV_SYS_STATUS_SENSOR_RC_RECEIVER;
    }
    if (l->fw->have_home == 0u) {
        health &= ~(uint32_t)MAV_SYS_STATUS_SENSOR_GPS;
    }
    if (o->pitot_suspect != 0u) {
        health &= ~(uint32_t)MAV_SYS_STATUS_SENSOR_DIFFERENTIAL_PRESSURE;
    }
    ss.onboard_control_sensors_present = present;
    ss.onboard_control_sensors_enabled = present;
    ss.onboard_control_sensors_health = health;
    ss.voltage_battery = UINT16_MAX; /* not measured */
    ss.current_battery = -1;
    ss.battery_remaining = -1;
    ss.errors_comm =
        (l->count.rx_dropped > UINT16_MAX) ? UINT16_MAX : (uint16_t)l->count.rx_dropped;
    (void)FW_LINK_QUEUE(l, SYS_STATUS, ss);

    mavlink_mission_current_t mc;
    (void)memset(&mc, 0, sizeof mc);
    mc.seq = l->fw->modes_state.nav.index;
    mc.total = l->cfg->waypoint_count;
    (void)FW_LINK_QUEUE(l, MISSION_CURRENT, mc);
}

static void attitude(fw_link_t *l)
{
    const ht_dcm_output_t *e = &l->last.est;
    mavlink_attitude_t a;
    (void)memset(&a, 0, sizeof a);
    a.time_boot_ms = l->now_ms;
    int32_t yaw = (int32_t)e->yaw_cdeg;
    if (yaw > 18000) {
        yaw -= 36000; /* (-pi, pi] */
    }
    fw_link_put_f32(&a, offsetof(mavlink_attitude_t, roll), f32_cdeg_to_rad(e->roll_cdeg));
    fw_link_put_f32(&a, offsetof(mavlink_attitude_t, pitch), f32_cdeg_to_rad(e->pitch_cdeg));
    fw_link_put_f32(&a, offsetof(mavlink_attitude_t, yaw), f32_cdeg_to_rad(yaw));
    fw_link_put_f32(&a, offsetof(mavlink_attitude_t, rollspeed),
                    ht_f32_from_ratio(e->gyro_rad_s[0], 65536u));
    fw_link_put_f32(&a, offsetof(mavlink_attitude_t, pitchspeed),
                    ht_f32_from_ratio(e->gyro_rad_s[1], 65536u));
    fw_link_put_f32(&a, offsetof(mavlink_attitude_t, yawspeed),
                    ht_f32_from_ratio(e->gyro_rad_s[2], 65536u));
    (void)FW_LINK_QUEUE(l, ATTITUDE, a);
}

/* The latitude / longitude of a local position (the inverse of
 * ht_geo_to_local on its plane), 1e-7 deg. */
static void local_to_global(const ht_geo_origin_t *h, int32_t north_cm, int32_t east_cm,
                            int32_t *lat_e7, int32_t *lon_e7)
{
    int64_t lat = h->lat0_e7;
    int64_t lon = h->lon0_e7;
    if (h->k_north_q16 > 0) {
        lat += ((int64_t)north_cm * 65536) / h->k_north_q16;
    }
    if (h->k_east_q16 > 0) {
        lon += ((int64_t)east_cm * 65536) / h->k_east_q16;
    }
    lat = (lat > 900000000) ? 900000000 : ((lat < -900000000) ? -900000000 : lat);
    while (lon > 1800000000) {
        lon -= 3600000000;
    }
    while (lon <= -1800000000) {
        lon += 3600000000;
    }
    *lat_e7 = (int32_t)lat;
    *lon_e7 = (int32_t)lon;
}

static void position(fw_link_t *l)
{
    const fw_nav_t *n = &l->last.nav;
    if ((l->fw->have_home == 0u) || (l->fw->home.set == 0u)) {
        return; /* no position before the first fix */
    }
    mavlink_global_position_int_t g;
    (void)memset(&g, 0, sizeof g);
    g.time_boot_ms = l->now_ms;
    local_to_global(&l->fw->home, n->north_cm, n->east_cm, &g.lat, &g.lon);
    g.alt = (int32_t)((int64_t)n->altitude_cm * 10);
    g.relative_alt = (int32_t)(((int64_t)n->altitude_cm - l->home_alt_cm) * 10);
    g.vx = sat16(n->vel_north_cm_s);
    g.vy = sat16(n->vel_east_cm_s);
    g.vz = sat16(-n->climb_cm_s);
    g.hdg = l->last.est.yaw_cdeg;
    (void)FW_LINK_QUEUE(l, GLOBAL_POSITION_INT, g);
}

static void vfr_hud(fw_link_t *l)
{
    const fw_nav_t *n = &l->last.nav;
    mavlink_vfr_hud_t v;
    (void)memset(&v, 0, sizeof v);
    const int32_t vn = n->vel_north_cm_s;
    const int32_t ve = n->vel_east_cm_s;
    const uint64_t an = (vn < 0) ? (0U - (uint64_t)vn) : (uint64_t)vn; /* < 2^31 */
    const uint64_t ae = (ve < 0) ? (0U - (uint64_t)ve) : (uint64_t)ve;
    const uint32_t ground_cm_s = isqrt64((an * an) + (ae * ae));
    fw_link_put_f32(&v, offsetof(mavlink_vfr_hud_t, airspeed),
                    ht_f32_from_ratio(n->airspeed_cm_s, 100u));
    fw_link_put_f32(&v, offsetof(mavlink_vfr_hud_t, groundspeed),
                    ht_f32_from_ratio((int64_t)ground_cm_s, 100u));
    fw_link_put_f32(&v, offsetof(mavlink_vfr_hud_t, alt), ht_f32_from_ratio(n->altitude_cm, 100u));
    fw_link_put_f32(&v, offsetof(mavlink_vfr_hud_t, climb), ht_f32_from_ratio(n->climb_cm_s, 100u));
    const uint16_t heading_deg = (uint16_t)(l->last.est.yaw_cdeg / 100u); /* [0, 359] */
    v.heading = (int16_t)heading_deg;
    const int32_t thr = (int32_t)l->last.throttle;
    v.throttle = (uint16_t)(((thr < 0) ? 0 : ((thr * 100) + 8192) / 16384));
    (void)FW_LINK_QUEUE(l, VFR_HUD, v);
}

static void servo_output(fw_link_t *l)
{
    const fw_output_t *o = &l->last;
    uint16_t p[16];
    (void)memset(p, 0, sizeof p);
    for (unsigned i = 0u; (i < (unsigned)o->pulse_count) && (i < 16u) && (i < OS_MAX_CHANNELS);
         ++i) {
        p[i] = o->pulse_us[i];
    }
    mavlink_servo_output_raw_t s;
    (void)memset(&s, 0, sizeof s);
    s.time_usec = (uint32_t)(l->now_ms * 1000u);
    s.port = 0u;
    s.servo1_raw = p[0];
    s.servo2_raw = p[1];
    s.servo3_raw = p[2];
    s.servo4_raw = p[3];
    s.servo5_raw = p[4];
    s.servo6_raw = p[5];
    s.servo7_raw = p[6];
    s.servo8_raw = p[7];
    s.servo9_raw = p[8];
    s.servo10_raw = p[9];
    s.servo11_raw = p[10];
    s.servo12_raw = p[11];
    s.servo13_raw = p[12];
    s.servo14_raw = p[13];
    s.servo15_raw = p[14];
    s.servo16_raw = p[15];
    (void)FW_LINK_QUEUE(l, SERVO_OUTPUT_RAW, s);
}

static void rc_channels(fw_link_t *l)
{
    const ht_modes_state_t *st = &l->fw->modes_state;
    uint16_t c[18];
    for (unsigned i = 0u; i < 18u; ++i) {
        c[i] = ((i < (unsigned)st->rc_count) && (i < HT_MODES_RC_MAX)) ? st->rc_us[i] : UINT16_MAX;
    }
    mavlink_rc_channels_t r;
    (void)memset(&r, 0, sizeof r);
    r.time_boot_ms = l->now_ms;
    r.chancount = st->rc_count;
    r.chan1_raw = c[0];
    r.chan2_raw = c[1];
    r.chan3_raw = c[2];
    r.chan4_raw = c[3];
    r.chan5_raw = c[4];
    r.chan6_raw = c[5];
    r.chan7_raw = c[6];
    r.chan8_raw = c[7];
    r.chan9_raw = c[8];
    r.chan10_raw = c[9];
    r.chan11_raw = c[10];
    r.chan12_raw = c[11];
    r.chan13_raw = c[12];
    r.chan14_raw = c[13];
    r.chan15_raw = c[14];
    r.chan16_raw = c[15];
    r.chan17_raw = c[16];
    r.chan18_raw = c[17];
    r.rssi = UINT8_MAX; /* unknown */
    (void)FW_LINK_QUEUE(l, RC_CHANNELS, r);
}

static void debug_vect(fw_link_t *l, const char *name, int32_t x, int32_t y, int32_t z,
                       uint32_t den)
{
    mavlink_debug_vect_t d;
    (void)memset(&d, 0, sizeof d);
    (void)memcpy(d.name, name, strlen(name)); /* < 10 characters */
    d.time_usec = (uint64_t)l->now_ms * 1000u;
    fw_link_put_f32(&d, offsetof(mavlink_debug_vect_t, x), ht_f32_from_ratio(x, den));
    fw_link_put_f32(&d, offsetof(mavlink_debug_vect_t, y), ht_f32_from_ratio(y, den));
    fw_link_put_f32(&d, offsetof(mavlink_debug_vect_t, z), ht_f32_from_ratio(z, den));
    (void)FW_LINK_QUEUE(l, DEBUG_VECT, d);
}

static void law_state(fw_link_t *l)
{
    const ht_output_t *w = &l->last.law;
    /* the target tilt (Eq. 5, 6) and the errors the law acts on, Q14 */
    debug_vect(l, "HT_TILT", w->tilt_x, w->tilt_y, w->tilt_z, 16384u);
    debug_vect(l, "HT_ERR", w->roll_error, w->pitch_error, w->roll_cross, 16384u);
}

/* --- the scheduler --------------------------------------------------------- */

void fw_link_send_stream(fw_link_t *l, fw_link_stream_t s)
{
    switch (s) {
    case FW_LINK_S_HEARTBEAT:
        heartbeat(l);
        break;
    case FW_LINK_S_SYS_STATUS:
        sys_status(l);
        break;
    case FW_LINK_S_ATTITUDE:
        attitude(l);
        break;
    case FW_LINK_S_POSITION:
        position(l);
        break;
    case FW_LINK_S_VFR_HUD:
        vfr_hud(l);
        break;
    case FW_LINK_S_SERVO:
        servo_output(l);
        break;
    case FW_LINK_S_RC:
        rc_channels(l);
        break;
    case FW_LINK_S_LAW:
        law_state(l);
        break;
    default:
        break;
    }
}

fw_link_stream_t fw_link_stream_of(uint32_t msgid)
{
    switch (msgid) {
    case MAVLINK_MSG_ID_HEARTBEAT:
        return FW_LINK_S_HEARTBEAT;
    case MAVLINK_MSG_ID_SYS_STATUS:
    case MAVLINK_MSG_ID_MISSION_CURRENT:
        return FW_LINK_S_SYS_STATUS;
    case MAVLINK_MSG_ID_ATTITUDE:
        return FW_LINK_S_ATTITUDE;
    case MAVLINK_MSG_ID_GLOBAL_POSITION_INT:
        return FW_LINK_S_POSITION;
    case MAVLINK_MSG_ID_VFR_HUD:
        return FW_LINK_S_VFR_HUD;
    case MAVLINK_MSG_ID_SERVO_OUTPUT_RAW:
        return FW_LINK_S_SERVO;
    case MAVLINK_MSG_ID_RC_CHANNELS:
        return FW_LINK_S_RC;
    case MAVLINK_MSG_ID_DEBUG_VECT:
        return FW_LINK_S_LAW;
    default:
        return FW_LINK_S_COUNT;
    }
}

static uint8_t stream_hz(const fw_link_params_t *p, fw_link_stream_t s)
{
    switch (s) {
    case FW_LINK_S_HEARTBEAT:
        return p->heartbeat_hz;
    case FW_LINK_S_SYS_STATUS:
        return p->sys_status_hz;
    case FW_LINK_S_ATTITUDE:
        return p->attitude_hz;
    case FW_LINK_S_POSITION:
        return p->position_hz;
    case FW_LINK_S_VFR_HUD:
        return p->vfr_hud_hz;
    case FW_LINK_S_SERVO:
        return p->servo_hz;
    case FW_LINK_S_RC:
        return p->rc_hz;
    case FW_LINK_S_LAW:
        return p->law_hz;
    default:
        return 0u;
    }
}

/* The stream's interval, ms; 0 = off. */
static uint32_t interval_ms(const fw_link_t *l, fw_link_stream_t s)
{
    const int32_t us = l->interval_override_us[s];
    if (us < 0) {
        return 0u;
    }
    if (us > 0) {
        return ((uint32_t)us < 1000u) ? 1u : ((uint32_t)us / 1000u);
    }
    const uint8_t hz = stream_hz(&l->params, s);
    return (hz == 0u) ? 0u : (1000u / hz);
}

int32_t fw_link_stream_interval_us(const fw_link_t *l, fw_link_stream_t s)
{
    if (s >= FW_LINK_S_COUNT) {
        return 0;
    }
    const int32_t us = l->interval_override_us[s];
    if (us != 0) {
        return (us < 0) ? 0 : us;
    }
    /* interval_ms is at most INT32_MAX / 1000 ms: the product fits an int32 */
    const uint32_t from_ms_us = interval_ms(l, s) * 1000u;
    return (int32_t)from_ms_us;
}

void fw_link_telemetry_after_step(fw_link_t *l)
{
    for (unsigned i = 0u; i < (unsigned)FW_LINK_S_COUNT; ++i) {
        const fw_link_stream_t s = (fw_link_stream_t)i;
        if (l->request_now[i] != 0u) {
            l->request_now[i] = 0u;
            fw_link_send_stream(l, s);
        }
        const uint32_t iv = interval_ms(l, s);
        if (iv == 0u) {
            continue;
        }
        if (fw_link_reached(l->now_ms, l->next_ms[i]) != 0) {
            fw_link_send_stream(l, s);
            l->next_ms[i] += iv;
            if (fw_link_reached(l->now_ms, l->next_ms[i]) != 0) {
                l->next_ms[i] = l->now_ms + iv; /* fell behind (or the first): restart */
            }
        }
    }
}
