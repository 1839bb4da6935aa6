/*
 * test_hil_fw.c - the firmware side of the HIL link on the host, against the
 * SIL host board (boards/sil, sil_board_step with the truth solution): both
 * hosts call the one firmware step; configured with the same parameters and
 * fed the same solution and command, one through the link's frames and one
 * through the SIL's doubles, both give the same pulses, intermediates and
 * hold states, bit for bit, step after step. Also:
 * the configuration handshake, and that bad frames (CRC, length, unknown id,
 * reserved bits, before START) are counted or refused and never acted on.
 *
 * The link functions of hil_fw.h are faked here: sent bytes are collected and
 * decoded; the servo read-back is fake_board's committed pulse.
 */
#include "unity.h"

#include "fake_board.h"
#include "hil/hil_fw.h"
#include "ht_test_support.h"
#include "sil_board.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

static hil_fw_t fw;
static sil_board_t sil;
static uint8_t sent[4096];
static size_t sent_n;

void hil_link_send(const uint8_t *data, size_t n)
{
    TEST_ASSERT_TRUE(sent_n + n <= sizeof sent);
    memcpy(&sent[sent_n], data, n);
    sent_n += n;
}

uint16_t hil_servo_readback_us(uint8_t channel)
{
    return channel < BOARD_MAX_SERVOS ? fake_board.committed_us[channel] : 0u;
}

uint16_t hil_link_errors(void)
{
    return 7u;
}

int hil_link_init(void)
{
    return 1;
}

int hil_link_poll(uint8_t *byte)
{
    (void)byte;
    return 0;
}

/* --- the host's side of the link ----------------------------------------- */

static uint8_t fw_len[0xA2];
static hil_decoder_t host_rx;

/* Decode everything the firmware sent since the last call into got_id /
 * got (at most 16 frames); returns the number of frames. */
static uint8_t got_id[16];
static uint8_t got[16][HIL_PAYLOAD_MAX];

static int replies(void)
{
    int n = 0;
    for (size_t i = 0; i < sent_n; ++i) {
        if (hil_decoder_push(&host_rx, sent[i])) {
            TEST_ASSERT_TRUE(n < 16);
            got_id[n] = host_rx.id;
            memcpy(got[n], host_rx.payload, HIL_PAYLOAD_MAX);
            n++;
        }
    }
    sent_n = 0;
    return n;
}

static void push_frame(uint8_t id, const uint8_t *payload, uint8_t len)
{
    uint8_t f[HIL_FRAME_MAX];
    const size_t n = hil_encode(id, payload, len, f, sizeof f);
    TEST_ASSERT_TRUE(n > 0u);
    for (size_t i = 0; i < n; ++i) {
        hil_fw_on_byte(&fw, f[i]);
    }
}

/* --- the configuration, in both boards' terms ----------------------------- */

static int32_t q16(double v)
{
    return (int32_t)llround(v * 65536.0);
}

/* One group of the parameter table at its defaults, in the table's units. */
static void table_defaults(double *dst, int group)
{
    for (int i = 0; i < sil_param_count(group); ++i) {
        const ht_param_info_t *info = sil_param_info(group, i);
        dst[i] = (double)info->default_raw / (double)info->scale;
    }
}

static sil_config_t config(void)
{
    sil_config_t c;
    memset(&c, 0, sizeof c);
    /* the table's defaults first */
    table_defaults(c.law, SIL_GROUP_LAW);
    table_defaults(c.estimator, SIL_GROUP_ESTIMATOR);
    table_defaults(c.guidance, SIL_GROUP_GUIDANCE);
    table_defaults(c.alt_hold, SIL_GROUP_ALT_HOLD);
    table_defaults(c.speed_hold, SIL_GROUP_SPEED_HOLD);
    table_defaults(c.modes, SIL_GROUP_MODES);
    table_defaults(c.fbw, SIL_GROUP_FBW);
    table_defaults(c.nav, SIL_GROUP_NAV);
    table_defaults(c.aoa, SIL_GROUP_AOA);
    c.law[HT_P_KP_AILERON - 1] = 2.0;
    c.law[HT_P_KP_ELEVATOR - 1] = 6.0;
    c.law[HT_P_KP_RUDDER - 1] = 0.3;
    c.law[HT_P_KFF_ELEVATOR - 1] = 1.0;
    c.law[HT_P_KFF_RUDDER - 1] = 0.5;
    c.law[HT_P_KD_AILERON - 1] = 0.3;
    c.law[HT_P_KD_ELEVATOR - 1] = 1.0;
    c.law[HT_P_KD_RUDDER - 1] = 1.0;
    c.law[HT_P_V_REF - 1] = 110.0;
    c.law[HT_P_V_MIN - 1] = 30.0;
    c.law[HT_P_MAX_TILT - 1] = 2.0;
    c.law[HT_P_SCHEDULE - 1] = 1.0;
    c.alt_hold[HT_ALT_P_KP - 1] = 0.012;
    c.alt_hold[HT_ALT_P_KI - 1] = 0.004;
    c.alt_hold[HT_ALT_P_KD - 1] = 0.015;
    c.alt_hold[HT_ALT_P_MAX_PITCH - 1] = 0.3;
    c.alt_hold[HT_ALT_P_MAX_INTEGRAL - 1] = 0.2;
    c.alt_hold[HT_ALT_P_MAX_ERROR - 1] = 100.0;
    c.alt_hold[HT_ALT_P_INTEGRAL_BAND - 1] = 20.0;
    c.alt_integral_upright = 0.01;
    c.alt_integral_inverted = -0.5; /* beyond max_integral: both boards clamp it */
    /* the airspeed protection on (protocol 2), near the T-37's cruise so the
     * steps below reach it */
    c.alt_hold[HT_ALT_P_PROTECT - 1] = 100.0;
    c.alt_hold[HT_ALT_P_PROTECT_VALID - 1] = 30.0;
    c.alt_hold[HT_ALT_P_KV - 1] = 0.03;
    c.alt_hold[HT_ALT_P_PROTECT_TAU - 1] = 1.0;
    c.speed_hold[HT_SPEED_P_THROTTLE_TRIM - 1] = 0.55;
    c.speed_hold[HT_SPEED_P_THROTTLE_MIN - 1] = 0.05;
    c.speed_hold[HT_SPEED_P_THROTTLE_MAX - 1] = 1.0;
    c.speed_hold[HT_SPEED_P_KP - 1] = 0.05;
    c.speed_hold[HT_SPEED_P_KI - 1] = 0.01;
    c.speed_hold[HT_SPEED_P_KFF - 1] = 1.0;
    c.speed_hold[HT_SPEED_P_MAX_INTEGRAL - 1] = 0.3;
    c.trim_aileron = 0.013;
    c.trim_elevator = -0.021;
    c.trim_rudder = 0.004;
    c.control_rate_hz = 40;
    c.estimator[HT_DCM_P_IMU_RATE - 1] = 120.0;
    c.estimator[HT_DCM_P_KP_ROLLPITCH - 1] = 0.2;
    c.estimator[HT_DCM_P_KI_ROLLPITCH - 1] = 0.002;
    c.estimator[HT_DCM_P_KP_YAW - 1] = 0.5;
    c.estimator[HT_DCM_P_KI_YAW - 1] = 0.005;
    c.estimator[HT_DCM_P_BIAS_MAX - 1] = 5.7 * 3.14159265358979323846 / 180.0;
    c.estimator[HT_DCM_P_GYRO_LIMIT - 1] = 2000.0 * 3.14159265358979323846 / 180.0;
    c.estimator[HT_DCM_P_ACCEL_LIMIT - 1] = 16.0;
    c.estimator[HT_DCM_P_ACCEL_BAND - 1] = 0.5;
    c.estimator[HT_DCM_P_GPS_MIN_SPEED - 1] = 3.0;
    c.estimator[HT_DCM_P_CENTRIPETAL - 1] = 2.0;
    c.estimator[HT_DCM_P_GPS_LATENCY - 1] = 0.0; /* as before protocol 4 */
    return c;
}

static void put32(uint8_t *p, int32_t v)
{
    hil_put_i32(p, v);
}

/* The CFG frames from the same doubles, converted as the PIL host does. */
static void send_config(const sil_config_t *c, int32_t kp_aileron_q16)
{
    uint8_t p[HIL_PAYLOAD_MAX];
    memset(p, 0, sizeof p);
    /* protocol 5: the law's rows of the parameter table in order
     * (docs/hil-protocol.md): nine i32 Q16 gains (0..32), i32 cm/s v_ref (36)
     * and v_min (40), u8 schedule (44), i32 Q16 max_tilt (45), u8 pitch_mode
     * (49) */
    for (int i = 0; i < 9; ++i) {
        put32(&p[4 * i], q16(c->law[i]));
    }
    put32(&p[0], kp_aileron_q16);
    put32(&p[36], (int32_t)llround(c->law[HT_P_V_REF - 1] * 100.0));
    put32(&p[40], (int32_t)llround(c->law[HT_P_V_MIN - 1] * 100.0));
    p[44] = (uint8_t)llround(c->law[HT_P_SCHEDULE - 1]);
    put32(&p[45], q16(c->law[HT_P_MAX_TILT - 1]));
    p[49] = (uint8_t)llround(c->law[HT_P_PITCH_MODE - 1]);
    /* protocol 8: the law's options (docs/control-law.md "Extensions beyond
     * the seed"): u8 roll_in (50), i32 Q16 roll_in_rate_max_rad_s (51),
     * kp_sideslip (55), vertical_fade (59) */
    p[50] = (uint8_t)llround(c->law[HT_P_ROLL_IN - 1]);
    put32(&p[51], q16(c->law[HT_P_ROLL_IN_RATE_MAX - 1]));
    put32(&p[55], q16(c->law[HT_P_KP_SIDESLIP - 1]));
    put32(&p[59], q16(c->law[HT_P_VERTICAL_FADE - 1]));
    TEST_ASSERT_EQUAL_UINT8(63u, HIL_LEN_CFG_LAW);
    push_frame(HIL_ID_CFG_LAW, p, HIL_LEN_CFG_LAW);

    /* protocol 7: the altitude hold's rows (docs/hil-protocol.md): five i32
     * Q16 (0..16), i32 cm max_error (20), band (24), i32 cm/s protect (28),
     * valid (32), i32 Q16 kv (36), u16 ms tau (40); then u16 rate_hz (42),
     * i32 Q20 integrators upright (44) and inverted (48) */
    const double *a = c->alt_hold;
    for (int i = 0; i < 5; ++i) {
        put32(&p[4 * i], q16(a[i]));
    }
    put32(&p[20], (int32_t)llround(a[HT_ALT_P_MAX_ERROR - 1] * 100.0));
    put32(&p[24], (int32_t)llround(a[HT_ALT_P_INTEGRAL_BAND - 1] * 100.0));
    put32(&p[28], (int32_t)llround(a[HT_ALT_P_PROTECT - 1] * 100.0));
    put32(&p[32], (int32_t)llround(a[HT_ALT_P_PROTECT_VALID - 1] * 100.0));
    put32(&p[36], q16(a[HT_ALT_P_KV - 1]));
    hil_put_u16(&p[40], (uint16_t)llround(a[HT_ALT_P_PROTECT_TAU - 1] * 1000.0));
    hil_put_u16(&p[42], (uint16_t)c->control_rate_hz);
    put32(&p[44], (int32_t)llround(c->alt_integral_upright * 1048576.0));
    put32(&p[48], (int32_t)llround(c->alt_integral_inverted * 1048576.0));
    TEST_ASSERT_EQUAL_UINT8(52u, HIL_LEN_CFG_ALT);
    push_frame(HIL_ID_CFG_ALT, p, HIL_LEN_CFG_ALT);

    /* the airspeed hold's rows: three i16 Q14 throttles (0..4), three i32 Q16
     * gains (6..14), i16 Q14 max_integral (18); then u16 rate_hz (20) */
    const double *v = c->speed_hold;
    for (int i = 0; i < 3; ++i) {
        hil_put_i16(&p[2 * i], (int16_t)llround(v[i] * 16384.0));
        put32(&p[6 + 4 * i], q16(v[3 + i]));
    }
    hil_put_i16(&p[18], (int16_t)llround(v[HT_SPEED_P_MAX_INTEGRAL - 1] * 16384.0));
    hil_put_u16(&p[20], (uint16_t)c->control_rate_hz);
    TEST_ASSERT_EQUAL_UINT8(22u, HIL_LEN_CFG_SPD);
    push_frame(HIL_ID_CFG_SPD, p, HIL_LEN_CFG_SPD);

    /* the SIL board's channels, from its own (checked) output stage */
    memset(p, 0, sizeof p);
    p[0] = SIL_CH_COUNT;
    p[1] = 0u;
    for (int i = 0; i < SIL_CH_COUNT; ++i) {
        const os_channel_t *ch = &sil.cfg.out.ch[i];
        uint8_t *r = &p[2 + 14 * i];
        r[0] = ch->function;
        r[1] = ch->reversed;
        hil_put_u16(&r[2], ch->centre_us);
        hil_put_i16(&r[4], ch->trim_us);
        hil_put_u16(&r[6], ch->travel_us);
        hil_put_u16(&r[8], ch->min_us);
        hil_put_u16(&r[10], ch->max_us);
        hil_put_u16(&r[12], ch->failsafe_us);
    }
    push_frame(HIL_ID_CFG_OUT, p, HIL_LEN_CFG_OUT);

    /* the estimator and the IMU timing (protocol 3), from the SIL board's own
     * converted configuration */
    hil_cfg_est_write(p, &sil.cfg);
    push_frame(HIL_ID_CFG_EST, p, HIL_LEN_CFG_EST);
}

static void expect_ack(uint8_t status, uint8_t block, uint8_t detail)
{
    TEST_ASSERT_EQUAL_INT(1, replies());
    TEST_ASSERT_EQUAL_HEX8(HIL_ID_ACK, got_id[0]);
    TEST_ASSERT_EQUAL_UINT8(status, got[0][0]);
    TEST_ASSERT_EQUAL_HEX8(block, got[0][1]);
    TEST_ASSERT_EQUAL_UINT8(detail, got[0][2]);
}

static void start_both(void)
{
    sil_config_t c = config();
    char err[64];
    TEST_ASSERT_EQUAL_INT_MESSAGE(0, sil_board_init(&sil, &c, err, sizeof err), err);
    send_config(&c, q16(c.law[HT_P_KP_AILERON - 1]));
    TEST_ASSERT_EQUAL_INT(0, replies()); /* CFG frames are not answered */
    push_frame(HIL_ID_START, NULL, 0);
    expect_ack(HIL_ACK_OK, HIL_ID_START, 0u);
}

void setUp(void)
{
    fake_board_reset();
    hil_fw_init(&fw);
    memset(&sil, 0, sizeof sil);
    sent_n = 0;
    memset(fw_len, 0xFE, sizeof fw_len);
    fw_len[HIL_ID_READY] = HIL_LEN_READY;
    fw_len[HIL_ID_NAK] = HIL_LEN_NAK;
    fw_len[HIL_ID_ACK] = HIL_LEN_ACK;
    fw_len[HIL_ID_OUTPUT] = HIL_LEN_OUTPUT;
    fw_len[HIL_ID_STATE] = HIL_LEN_STATE;
    const hil_msg_table_t t = {fw_len, (uint8_t)sizeof fw_len};
    hil_decoder_init(&host_rx, t);
}

void tearDown(void) {}

/* --- tests ------------------------------------------------------------------ */

static void test_ready_banner_and_hello(void)
{
    hil_fw_send_ready(&fw);
    TEST_ASSERT_EQUAL_INT(1, replies());
    TEST_ASSERT_EQUAL_HEX8(HIL_ID_READY, host_rx.id);
    TEST_ASSERT_EQUAL_UINT8('H', host_rx.payload[0]);
    TEST_ASSERT_EQUAL_UINT8('T', host_rx.payload[1]);
    TEST_ASSERT_EQUAL_UINT8(HIL_PROTOCOL_VERSION, host_rx.payload[2]);
    TEST_ASSERT_EQUAL_UINT8(0u, host_rx.payload[3]); /* not started */
    TEST_ASSERT_EQUAL_UINT8(8u, host_rx.payload[4]);
    TEST_ASSERT_EQUAL_UINT16(7u, hil_get_u16(&host_rx.payload[22]));
    push_frame(HIL_ID_HELLO, NULL, 0);
    TEST_ASSERT_EQUAL_INT(1, replies());
    TEST_ASSERT_EQUAL_HEX8(HIL_ID_READY, host_rx.id);
    TEST_ASSERT_EQUAL_UINT16(1u, hil_get_u16(&host_rx.payload[6])); /* frames_ok */
}

/* One control step's inputs in the firmware's formats, as the test draws
 * them: the STEP frame's contents, the samples, the truth solution, and the
 * heading the truth's nose direction comes from. */
typedef struct {
    hil_step_t step;
    ht_imu_sample_t imu[HIL_IMU_MAX];
    fw_nav_t truth;
    double heading_rad;
} fx_step_t;

static int16_t rnd16(uint64_t *rng)
{
    return (int16_t)(ts_rng_next(rng) & 0xFFFFu);
}

static int32_t rnd32(uint64_t *rng)
{
    return (int32_t)(uint32_t)ts_rng_next(rng);
}

static int32_t rnd_in(uint64_t *rng, double lo, double hi)
{
    return (int32_t)llround(ts_uniform(rng, lo, hi));
}

/* wild: anything at all (every branch and saturation); else flying: gravity
 * on the accelerometers, modest rates, a GPS over Switzerland. use_truth:
 * the step flies on the truth solution. */
static void random_step(uint64_t *rng, uint32_t seq, int wild, int use_truth, fx_step_t *x)
{
    memset(x, 0, sizeof *x);
    hil_step_t *s = &x->step;
    board_sensors_t *b = &s->sensors;
    fw_guided_t *g = &s->guided;
    s->seq = seq;
    const uint64_t pick = ts_rng_next(rng) % 16u;
    /* mostly the divider (3); sometimes none, or a count off the divider */
    s->imu_count = (uint8_t)(pick < 11u ? 3u : (pick < 13u ? 0u : ts_rng_next(rng) % 8u));
    const double roll = ts_uniform(rng, -3.1, 3.1), pitch = ts_uniform(rng, -1.2, 1.2);
    for (unsigned i = 0; i < s->imu_count; ++i) {
        ht_imu_sample_t *m = &x->imu[i];
        for (int k = 0; k < 3; ++k) {
            m->gyro_rad_s[k] = wild ? rnd32(rng) : rnd_in(rng, -0.5 * 65536.0, 0.5 * 65536.0);
            m->accel_g[k] = wild ? rnd32(rng) : rnd_in(rng, -0.05 * 65536.0, 0.05 * 65536.0);
        }
        if (!wild) { /* specific force of level, unaccelerated flight: -down */
            m->accel_g[0] += (int32_t)llround(sin(roll) * cos(pitch) * 65536.0);
            m->accel_g[1] += (int32_t)llround(sin(pitch) * 65536.0);
            m->accel_g[2] += (int32_t)llround(-cos(roll) * cos(pitch) * 65536.0);
        }
    }
    const uint64_t f = ts_rng_next(rng);
    b->gps.fix = (uint8_t)(wild ? (f & 3u) : ((f & 7u) != 0u ? 3u : 0u));
    b->gps.fresh = (uint8_t)((f >> 3) & 1u);
    b->airspeed_fresh = (uint8_t)((f >> 4) & 1u);
    b->baro_fresh = (uint8_t)((f >> 5) & 1u);
    b->gps.lat_e7 = wild ? rnd_in(rng, -9e8, 9e8) : rnd_in(rng, 4.70e8, 4.71e8);
    b->gps.lon_e7 = wild ? rnd_in(rng, -1.8e9, 1.8e9) : rnd_in(rng, 8.0e7, 8.1e7);
    b->gps.alt_cm = wild ? rnd32(rng) : rnd_in(rng, 120000.0, 180000.0);
    for (int k = 0; k < 3; ++k) {
        b->gps.vel_ned_cm_s[k] = wild ? rnd32(rng) : rnd_in(rng, -6000.0, 6000.0);
    }
    b->airspeed_cm_s = wild ? rnd16(rng) : (int16_t)rnd_in(rng, 2000.0, 15000.0);
    b->baro_alt_cm = wild ? rnd32(rng) : rnd_in(rng, 120000.0, 180000.0);
    g->turn_rate_rad_s = (int16_t)rnd_in(rng, -0.3 * 2048.0, 0.3 * 2048.0);
    g->pitch_ratio = rnd_in(rng, -0.3 * 65536.0, 0.3 * 65536.0);
    g->altitude_cm = 150000 + rnd_in(rng, -2000.0, 2000.0);
    g->airspeed_cm_s = (int16_t)rnd_in(rng, 3000.0, 12000.0);
    g->throttle = (int16_t)rnd_in(rng, 0.0, 16384.0);
    s->flags = (uint8_t)((f >> 6) & 0x0Fu) | (use_truth ? HIL_SF_USE_TRUTH : 0u);
    if (use_truth) {
        fw_nav_t *n = &x->truth;
        n->down_q14[0] = (int16_t)llround(-sin(roll) * cos(pitch) * 16384.0);
        n->down_q14[1] = (int16_t)llround(-sin(pitch) * 16384.0);
        n->down_q14[2] = (int16_t)llround(cos(roll) * cos(pitch) * 16384.0);
        for (int k = 0; k < 3; ++k) {
            n->gyro_q11_rad_s[k] = wild ? rnd16(rng) : (int16_t)rnd_in(rng, -2048.0, 2048.0);
            if (wild) {
                n->down_q14[k] = rnd16(rng);
            }
        }
        n->airspeed_cm_s = wild ? rnd16(rng) : (int16_t)rnd_in(rng, 2000.0, 15000.0);
        n->altitude_cm = wild ? rnd_in(rng, -1e6, 1e6) : rnd_in(rng, 147000.0, 153000.0);
        n->climb_cm_s = rnd_in(rng, -1000.0, 1000.0);
        n->north_cm = rnd_in(rng, -1e7, 1e7);
        n->east_cm = rnd_in(rng, -1e7, 1e7);
        n->vel_north_cm_s = rnd_in(rng, -6000.0, 6000.0);
        n->vel_east_cm_s = rnd_in(rng, -6000.0, 6000.0);
        x->heading_rad = ts_uniform(rng, -3.2, 3.2);
        n->heading_north = (int16_t)llround(cos(x->heading_rad) * 16384.0);
        n->heading_east = (int16_t)llround(sin(x->heading_rad) * 16384.0);
    }
}

/* The same step as the SIL harness gives it: doubles that the host board
 * converts back to exactly these integers. */
static void sil_step(const fx_step_t *x, sil_actuators_t *a)
{
    static sil_sensors_t ss;
    static sil_command_t sc;
    memset(&ss, 0, sizeof ss);
    memset(&sc, 0, sizeof sc);
    const hil_step_t *s = &x->step;
    const board_sensors_t *b = &s->sensors;
    ss.imu_count = s->imu_count;
    for (unsigned i = 0; i < s->imu_count; ++i) {
        for (int k = 0; k < 3; ++k) {
            ss.gyro_rad_s[i][k] = x->imu[i].gyro_rad_s[k] / 65536.0;
            ss.accel_g[i][k] = x->imu[i].accel_g[k] / 65536.0;
        }
    }
    ss.gps_fresh = b->gps.fresh;
    ss.gps_fix = b->gps.fix;
    ss.gps_lat_deg = b->gps.lat_e7 / 1e7;
    ss.gps_lon_deg = b->gps.lon_e7 / 1e7;
    ss.gps_alt_m = b->gps.alt_cm / 100.0;
    for (int k = 0; k < 3; ++k) {
        ss.gps_vel_ned_m_s[k] = b->gps.vel_ned_cm_s[k] / 100.0;
    }
    ss.airspeed_fresh = b->airspeed_fresh;
    ss.pitot_m_s = b->airspeed_cm_s / 100.0;
    ss.baro_fresh = b->baro_fresh;
    ss.baro_alt_m = b->baro_alt_cm / 100.0;
    ss.use_truth = (s->flags & HIL_SF_USE_TRUTH) != 0u;
    const fw_nav_t *n = &x->truth;
    ss.dcm_x = n->down_q14[0] / 16384.0;
    ss.dcm_y = n->down_q14[1] / 16384.0;
    ss.dcm_z = n->down_q14[2] / 16384.0;
    ss.gyro_x = n->gyro_q11_rad_s[0] / 2048.0;
    ss.gyro_y = n->gyro_q11_rad_s[1] / 2048.0;
    ss.gyro_z = n->gyro_q11_rad_s[2] / 2048.0;
    ss.airspeed_m_s = n->airspeed_cm_s / 100.0;
    ss.altitude_m = n->altitude_cm / 100.0;
    ss.climb_m_s = n->climb_cm_s / 100.0;
    ss.north_m = n->north_cm / 100.0;
    ss.east_m = n->east_cm / 100.0;
    ss.vel_north_m_s = n->vel_north_cm_s / 100.0;
    ss.vel_east_m_s = n->vel_east_cm_s / 100.0;
    ss.heading_rad = x->heading_rad;
    const fw_guided_t *g = &s->guided;
    sc.turn_rate_rad_s = g->turn_rate_rad_s / 2048.0;
    sc.pitch_ratio = g->pitch_ratio / 65536.0;
    sc.altitude_m = g->altitude_cm / 100.0;
    sc.airspeed_m_s = g->airspeed_cm_s / 100.0;
    sc.throttle = g->throttle / 16384.0;
    sc.altitude_hold = (s->flags & HIL_SF_ALTITUDE_HOLD) != 0u;
    sc.speed_hold = (s->flags & HIL_SF_SPEED_HOLD) != 0u;
    sc.inverted = (s->flags & HIL_SF_INVERTED) != 0u;
    sc.pitch_mode = (s->flags & HIL_SF_TILT_CROSS) != 0u;
    sil_board_step(&sil, &ss, &sc, a);
}

/* The host's frames of one step: STEP, TRUTH, the IMU frames, SENSORS. */
static void push_step(const fx_step_t *x)
{
    uint8_t p[HIL_PAYLOAD_MAX];
    const hil_step_t *s = &x->step;
    hil_step_write(p, s);
    push_frame(HIL_ID_STEP, p, HIL_LEN_STEP);
    if ((s->flags & HIL_SF_USE_TRUTH) != 0u) {
        hil_truth_write(p, &x->truth);
        push_frame(HIL_ID_TRUTH, p, HIL_LEN_TRUTH);
    }
    for (unsigned i = 0; i + 1u < s->imu_count; ++i) {
        hil_imu_write(p, &x->imu[i]);
        push_frame(HIL_ID_IMU, p, HIL_LEN_IMU);
    }
    memset(p, 0, sizeof p);
    hil_put_i32(&p[0], (int32_t)s->seq);
    if (s->imu_count > 0u) {
        hil_imu_write(&p[4], &x->imu[s->imu_count - 1u]);
    }
    push_frame(HIL_ID_SENSORS, p, HIL_LEN_SENSORS);
}

/* One step on both boards, the firmware's through frames; compare all.
 * Returns 1 when the step ran the control chain. */
static int step_both(const fx_step_t *x)
{
    static sil_actuators_t a;
    sil_step(x, &a);
    const fw_output_t *o = &sil.out;
    const uint32_t commits = fake_board.commits;
    push_step(x);
    TEST_ASSERT_EQUAL_INT(2, replies());
    TEST_ASSERT_EQUAL_HEX8(HIL_ID_STATE, got_id[0]);
    TEST_ASSERT_EQUAL_HEX8(HIL_ID_OUTPUT, got_id[1]);
    /* the firmware step's whole output and state, not only what is sent */
    TEST_ASSERT_EQUAL_MEMORY(o, &fw.fw_out, sizeof *o);
    TEST_ASSERT_EQUAL_MEMORY(&sil.fw.dcm_state, &fw.fw.dcm_state, sizeof sil.fw.dcm_state);
    TEST_ASSERT_EQUAL_MEMORY(&sil.fw.nav, &fw.fw.nav, sizeof sil.fw.nav);
    TEST_ASSERT_EQUAL_MEMORY(&sil.fw.modes_state, &fw.fw.modes_state, sizeof sil.fw.modes_state);
    TEST_ASSERT_EQUAL_MEMORY(&sil.fw.home, &fw.fw.home, sizeof sil.fw.home);
    TEST_ASSERT_EQUAL_UINT32(sil.fw.samples, fw.fw.samples);
    TEST_ASSERT_EQUAL_UINT32(sil.fw.control_steps, fw.fw.control_steps);
    TEST_ASSERT_EQUAL_UINT16(sil.fw.imu_age, fw.fw.imu_age);
    TEST_ASSERT_EQUAL_UINT8(sil.fw.guard_state.engaged, fw.fw.guard_state.engaged);

    /* STATE: what the SIL's actuators carry of the estimate and the solution */
    hil_state_t st;
    hil_state_parse(got[0], &st);
    TEST_ASSERT_EQUAL_UINT32(x->step.seq, st.seq);
    TEST_ASSERT_EQUAL_UINT8((uint8_t)((a.control_ran ? HIL_ST_CONTROL_RAN : 0u) |
                                      (a.control_ran && o->failsafe ? HIL_ST_FAILSAFE : 0u) |
                                      (a.guard_engaged ? HIL_ST_GUARD_ENGAGED : 0u)),
                            (uint8_t)(st.flags & (a.control_ran ? 0xFFu : HIL_ST_CONTROL_RAN)));
    if (!a.control_ran) {
        return 0; /* the SIL answers zeros: nothing more to compare */
    }
    TEST_ASSERT_EQUAL_DOUBLE(a.est_x, st.est.r[2][0] / 16384.0);
    TEST_ASSERT_EQUAL_DOUBLE(a.est_y, st.est.r[2][1] / 16384.0);
    TEST_ASSERT_EQUAL_DOUBLE(a.est_z, st.est.r[2][2] / 16384.0);
    TEST_ASSERT_EQUAL_DOUBLE(a.est_roll_deg, st.est.roll_cdeg / 100.0);
    TEST_ASSERT_EQUAL_DOUBLE(a.est_pitch_deg, st.est.pitch_cdeg / 100.0);
    TEST_ASSERT_EQUAL_DOUBLE(a.est_yaw_deg, st.est.yaw_cdeg / 100.0);
    for (int k = 0; k < 3; ++k) {
        TEST_ASSERT_EQUAL_DOUBLE(a.est_bias_rad_s[k], st.est.gyro_bias_rad_s[k] / 65536.0);
    }
    TEST_ASSERT_EQUAL_INT32(a.est_flags, st.est.flags);
    TEST_ASSERT_EQUAL_DOUBLE(a.nav_x, st.nav.down_q14[0] / 16384.0);
    TEST_ASSERT_EQUAL_DOUBLE(a.nav_y, st.nav.down_q14[1] / 16384.0);
    TEST_ASSERT_EQUAL_DOUBLE(a.nav_z, st.nav.down_q14[2] / 16384.0);
    TEST_ASSERT_EQUAL_DOUBLE(a.nav_airspeed_m_s, st.nav.airspeed_cm_s / 100.0);
    TEST_ASSERT_EQUAL_DOUBLE(a.nav_altitude_m, st.nav.altitude_cm / 100.0);
    TEST_ASSERT_EQUAL_DOUBLE(a.nav_climb_m_s, st.nav.climb_cm_s / 100.0);
    TEST_ASSERT_EQUAL_DOUBLE(a.nav_north_m, st.nav.north_cm / 100.0);
    TEST_ASSERT_EQUAL_DOUBLE(a.nav_east_m, st.nav.east_cm / 100.0);

    /* OUTPUT: the pulses (read back and computed) and the intermediates */
    const uint8_t *r = got[1];
    TEST_ASSERT_EQUAL_UINT32(x->step.seq, (uint32_t)hil_get_i32(&r[0]));
    TEST_ASSERT_EQUAL_UINT32(commits + 1u, fake_board.commits);
    for (int i = 0; i < SIL_CH_COUNT; ++i) {
        TEST_ASSERT_EQUAL_UINT16(o->pulse_us[i], hil_get_u16(&r[4 + 2 * i]));  /* read back */
        TEST_ASSERT_EQUAL_UINT16(o->pulse_us[i], hil_get_u16(&r[12 + 2 * i])); /* computed */
        TEST_ASSERT_EQUAL_UINT16(o->pulse_us[i], fake_board.committed_us[i]);
    }
    TEST_ASSERT_EQUAL_INT16(o->law.aileron, hil_get_i16(&r[20]));
    TEST_ASSERT_EQUAL_INT16(o->law.elevator, hil_get_i16(&r[22]));
    TEST_ASSERT_EQUAL_INT16(o->law.rudder, hil_get_i16(&r[24]));
    TEST_ASSERT_EQUAL_INT32(o->pitch_cmd, hil_get_i32(&r[26]));
    TEST_ASSERT_EQUAL_INT16(o->throttle, hil_get_i16(&r[30]));
    TEST_ASSERT_EQUAL_INT16(o->law.turn_rate_used_rad_s, hil_get_i16(&r[32]));
    TEST_ASSERT_EQUAL_INT16(o->law.roll_error, hil_get_i16(&r[34]));
    TEST_ASSERT_EQUAL_INT16(o->law.pitch_error, hil_get_i16(&r[36]));
    TEST_ASSERT_EQUAL_UINT16((uint16_t)(o->law.flags | (o->servo_clamped ? 0x100u : 0u)),
                             hil_get_u16(&r[38]));
    return 1;
}

static void start_checks(void)
{
    start_both();
    /* the configuration in force is the SIL's, field for field */
    TEST_ASSERT_EQUAL_MEMORY(&sil.cfg.dcm, &fw.cfg.dcm, sizeof sil.cfg.dcm);
    TEST_ASSERT_EQUAL_MEMORY(&sil.cfg.law, &fw.cfg.law, sizeof sil.cfg.law);
    TEST_ASSERT_EQUAL_MEMORY(&sil.cfg.modes, &fw.cfg.modes, sizeof sil.cfg.modes);
    TEST_ASSERT_EQUAL_MEMORY(&sil.cfg.guard, &fw.cfg.guard, sizeof sil.cfg.guard);
    TEST_ASSERT_EQUAL_UINT16(sil.cfg.control_divider, fw.cfg.control_divider);
    TEST_ASSERT_EQUAL_UINT16(sil.cfg.imu_timeout_samples, fw.cfg.imu_timeout_samples);
    TEST_ASSERT_EQUAL_INT32(sil.cfg.alt_integral_q20[0], fw.cfg.alt_integral_q20[0]);
    TEST_ASSERT_EQUAL_INT32(sil.cfg.alt_integral_q20[1], fw.cfg.alt_integral_q20[1]);
    TEST_ASSERT_EQUAL_UINT8(sil.cfg.out.count, fw.cfg.out.count); /* the channels in use */
    TEST_ASSERT_EQUAL_MEMORY(sil.cfg.out.ch, fw.cfg.out.ch,
                             sil.cfg.out.count * sizeof(os_channel_t));
    TEST_ASSERT_EQUAL_UINT16(3u, fw.cfg.control_divider);
    TEST_ASSERT_EQUAL_UINT16(120u, fw.cfg.dcm.imu_rate_hz);
    /* the clamped initial integrators, the controllers */
    const ht_alt_hold_state_t *sa = &sil.fw.modes_state.alt, *fa = &fw.fw.modes_state.alt;
    TEST_ASSERT_EQUAL_INT32(sa->integral_q20[0], fa->integral_q20[0]);
    TEST_ASSERT_EQUAL_INT32(sa->integral_q20[1], fa->integral_q20[1]);
    TEST_ASSERT_EQUAL_MEMORY(&sil.fw.law[0], &fw.fw.law[0], sizeof sil.fw.law[0]);
    TEST_ASSERT_EQUAL_MEMORY(&sil.fw.law[1], &fw.fw.law[1], sizeof sil.fw.law[1]);
}

/* steps, seed, use_truth: 0 never, 1 always, 2 a random half */
static void run_steps(uint32_t steps, uint64_t rng, int truth)
{
    start_checks();
    static fx_step_t x;
    uint32_t ran = 0u, ran_mid = 0u, aligned = 0u, aided = 0u;
    for (uint32_t k = 0; k < steps; ++k) {
        const int use_truth = (truth == 2) ? (int)(ts_rng_next(&rng) & 1u) : truth;
        random_step(&rng, k, (k % 8u) == 7u, use_truth, &x);
        const int r = step_both(&x);
        ran += (uint32_t)r;
        ran_mid += (r != 0 && sil.out.control_ran == 0u) ? 1u : 0u; /* on an IMU frame */
        aligned += (fw.fw.dcm_state.flags & HT_DCM_F_ALIGNED) != 0u;
        aided += (fw.fw.dcm_state.flags & HT_DCM_F_YAW_AIDED) != 0u;
    }
    TEST_ASSERT_EQUAL_UINT32(steps, fw.steps);
    TEST_ASSERT_EQUAL_UINT16(0u, fw.rx.stats.bad_crc);
    TEST_ASSERT_EQUAL_UINT16(0u, fw.naks);
    /* the sweep reached what it is for: control steps, an aligned and aided
     * estimator, and steps without control (imu_count off the divider) */
    printf("%u steps: control ran %u (%u on an IMU frame), aligned %u, yaw aided %u\n", steps, ran,
           ran_mid, aligned, aided);
    TEST_ASSERT_TRUE(ran > steps / 2u && ran < steps);
    TEST_ASSERT_TRUE(aligned > steps / 2u);
    TEST_ASSERT_TRUE(aided > 0u);
}

static void test_same_step_as_the_sil_board_estimate(void)
{
    run_steps(6000u, 2024u, 0);
}

static void test_same_step_as_the_sil_board_truth(void)
{
    run_steps(6000u, 2025u, 1);
}

static void test_same_step_as_the_sil_board_mixed(void)
{
    run_steps(3000u, 2026u, 2);
}

static void test_bad_frames_are_never_acted_on(void)
{
    start_checks();
    uint64_t rng = 5;
    static fx_step_t x;
    random_step(&rng, 0u, 0, 0, &x);
    step_both(&x);
    const uint32_t samples = fw.fw.samples, steps = fw.steps, commits = fake_board.commits;
    const ht_dcm_state_t dcm = fw.fw.dcm_state;

    uint8_t p[HIL_PAYLOAD_MAX], f[HIL_FRAME_MAX];
    random_step(&rng, 1u, 0, 0, &x);
    hil_step_write(p, &x.step);
    size_t n = hil_encode(HIL_ID_STEP, p, HIL_LEN_STEP, f, sizeof f);
    f[10] ^= 0x01u; /* one payload bit: bad CRC */
    for (size_t i = 0; i < n; ++i) {
        hil_fw_on_byte(&fw, f[i]);
    }
    /* a known id with the wrong length */
    n = hil_encode(HIL_ID_IMU, p, HIL_LEN_IMU - 1u, f, sizeof f);
    for (size_t i = 0; i < n; ++i) {
        hil_fw_on_byte(&fw, f[i]);
    }
    push_frame(0x33, p, 8);       /* an id nobody knows */
    push_frame(HIL_ID_ACK, p, 4); /* a firmware-to-host id */
    const uint8_t garbage[5] = {0x00, 0xA5, 0xA5, 0x13, 0x77};
    for (size_t i = 0; i < sizeof garbage; ++i) {
        hil_fw_on_byte(&fw, garbage[i]);
    }
    /* an IMU frame outside a step: not stepped, not answered */
    push_frame(HIL_ID_IMU, p, HIL_LEN_IMU);
    TEST_ASSERT_EQUAL_INT(0, replies()); /* no answer to any */
    TEST_ASSERT_EQUAL_UINT16(1u, fw.rx.stats.bad_crc);
    TEST_ASSERT_EQUAL_UINT16(3u, fw.rx.stats.unknown_id); /* wrong length counts here */
    TEST_ASSERT_EQUAL_UINT32(samples, fw.fw.samples);

    /* reserved bits, a count over the maximum, a fix over 3: NAK, no step */
    hil_step_t bad = x.step;
    bad.flags = 0x40u; /* the first reserved bit */
    hil_step_write(p, &bad);
    push_frame(HIL_ID_STEP, p, HIL_LEN_STEP);
    bad = x.step;
    bad.imu_count = HIL_IMU_MAX + 1u;
    hil_step_write(p, &bad);
    push_frame(HIL_ID_STEP, p, HIL_LEN_STEP);
    bad = x.step;
    bad.sensors.gps.fix = 4u;
    hil_step_write(p, &bad);
    push_frame(HIL_ID_STEP, p, HIL_LEN_STEP);
    hil_step_write(p, &x.step);
    p[7] |= 0x08u; /* a reserved fresh bit */
    push_frame(HIL_ID_STEP, p, HIL_LEN_STEP);
    TEST_ASSERT_EQUAL_INT(4, replies());
    for (int i = 0; i < 4; ++i) {
        TEST_ASSERT_EQUAL_HEX8(HIL_ID_NAK, got_id[i]);
        TEST_ASSERT_EQUAL_HEX8(HIL_ID_STEP, got[i][0]);
        TEST_ASSERT_EQUAL_UINT8(HIL_NAK_BAD_FIELD, got[i][1]);
    }
    /* SENSORS that do not close the open step: NAK, no sample stepped */
    uint8_t sp[HIL_LEN_SENSORS];
    memset(sp, 0, sizeof sp);
    hil_put_i32(&sp[0], 1);
    push_frame(HIL_ID_SENSORS, sp, HIL_LEN_SENSORS); /* no step open */
    hil_step_t s3 = x.step;
    s3.imu_count = 3u;
    s3.flags &= (uint8_t)~HIL_SF_USE_TRUTH;
    hil_step_write(p, &s3);
    push_frame(HIL_ID_STEP, p, HIL_LEN_STEP);
    push_frame(HIL_ID_SENSORS, sp, HIL_LEN_SENSORS); /* two IMU frames missing */
    s3.imu_count = 1u;
    hil_step_write(p, &s3);
    push_frame(HIL_ID_STEP, p, HIL_LEN_STEP);
    hil_put_i32(&sp[0], 2);
    push_frame(HIL_ID_SENSORS, sp, HIL_LEN_SENSORS); /* another seq */
    s3.flags |= HIL_SF_USE_TRUTH;
    hil_step_write(p, &s3);
    push_frame(HIL_ID_STEP, p, HIL_LEN_STEP);
    hil_put_i32(&sp[0], 1);
    push_frame(HIL_ID_SENSORS, sp, HIL_LEN_SENSORS); /* TRUTH missing */
    s3.flags &= (uint8_t)~HIL_SF_USE_TRUTH;
    hil_step_write(p, &s3);
    push_frame(HIL_ID_STEP, p, HIL_LEN_STEP);
    push_frame(HIL_ID_TRUTH, p, HIL_LEN_TRUTH); /* TRUTH not asked for */
    push_frame(HIL_ID_SENSORS, sp, HIL_LEN_SENSORS);
    TEST_ASSERT_EQUAL_INT(5, replies());
    for (int i = 0; i < 5; ++i) {
        TEST_ASSERT_EQUAL_HEX8(HIL_ID_NAK, got_id[i]);
        TEST_ASSERT_EQUAL_HEX8(HIL_ID_SENSORS, got[i][0]);
        TEST_ASSERT_EQUAL_UINT8(HIL_NAK_SEQUENCE, got[i][1]);
    }
    TEST_ASSERT_EQUAL_UINT16(9u, fw.naks);
    TEST_ASSERT_EQUAL_UINT32(samples, fw.fw.samples);
    TEST_ASSERT_EQUAL_UINT32(steps, fw.steps);
    TEST_ASSERT_EQUAL_UINT32(commits, fake_board.commits);
    TEST_ASSERT_EQUAL_MEMORY(&dcm, &fw.fw.dcm_state, sizeof dcm);

    /* the stream is still in sync: the next good step is stepped, and
     * matches the SIL board (which saw none of the bad frames) */
    random_step(&rng, 3u, 0, 1, &x);
    step_both(&x);
    random_step(&rng, 4u, 0, 0, &x);
    step_both(&x);
}

static void test_sensors_before_start_are_refused(void)
{
    uint8_t p[HIL_PAYLOAD_MAX];
    memset(p, 0, sizeof p);
    push_frame(HIL_ID_SENSORS, p, HIL_LEN_SENSORS);
    hil_step_t s;
    memset(&s, 0, sizeof s);
    hil_step_write(p, &s);
    push_frame(HIL_ID_STEP, p, HIL_LEN_STEP);
    TEST_ASSERT_EQUAL_INT(2, replies());
    TEST_ASSERT_EQUAL_HEX8(HIL_ID_NAK, got_id[0]);
    TEST_ASSERT_EQUAL_UINT8(HIL_NAK_NOT_STARTED, got[0][1]);
    TEST_ASSERT_EQUAL_HEX8(HIL_ID_STEP, got[1][0]);
    TEST_ASSERT_EQUAL_UINT8(HIL_NAK_NOT_STARTED, got[1][1]);
    TEST_ASSERT_EQUAL_UINT32(0u, fake_board.writes);
    TEST_ASSERT_EQUAL_UINT32(0u, fw.steps);
}

/* Every frame survives its writer and parser (fields at their documented
 * offsets; the extremes of every integer). */
static void test_frames_round_trip(void)
{
    uint64_t rng = 77;
    for (int t = 0; t < 200; ++t) {
        fx_step_t x;
        random_step(&rng, (uint32_t)ts_rng_next(&rng), t % 2, 1, &x);
        x.step.imu_count = (uint8_t)(t % 33);
        uint8_t p[HIL_PAYLOAD_MAX];
        hil_step_t s;
        hil_step_write(p, &x.step);
        hil_step_parse(p, &s);
        TEST_ASSERT_EQUAL_UINT8(x.step.flags & 0x0Fu, s.flags & 0x0Fu);
        s.fresh = 0u;
        s.guided.altitude_hold = x.step.guided.altitude_hold;
        s.guided.speed_hold = x.step.guided.speed_hold;
        s.guided.inverted = x.step.guided.inverted;
        s.guided.pitch_mode = x.step.guided.pitch_mode;
        TEST_ASSERT_EQUAL_MEMORY(&x.step, &s, sizeof s);
        fw_nav_t n;
        hil_truth_write(p, &x.truth);
        hil_truth_parse(p, &n);
        TEST_ASSERT_EQUAL_MEMORY(&x.truth, &n, sizeof n);
        ht_imu_sample_t m = {{INT32_MIN, INT32_MAX, -1}, {1, INT32_MIN, INT32_MAX}}, m2;
        hil_imu_write(p, &m);
        hil_imu_parse(p, &m2);
        TEST_ASSERT_EQUAL_MEMORY(&m, &m2, sizeof m);
    }
    /* the guided switches come from the flags */
    hil_step_t s;
    memset(&s, 0, sizeof s);
    s.flags = HIL_SF_ALTITUDE_HOLD | HIL_SF_INVERTED;
    uint8_t p[HIL_PAYLOAD_MAX];
    hil_step_write(p, &s);
    hil_step_parse(p, &s);
    TEST_ASSERT_EQUAL_UINT8(1u, s.guided.altitude_hold);
    TEST_ASSERT_EQUAL_UINT8(0u, s.guided.speed_hold);
    TEST_ASSERT_EQUAL_UINT8(1u, s.guided.inverted);
    TEST_ASSERT_EQUAL_UINT8(0u, s.guided.pitch_mode);
}

static void test_start_checks_the_configuration(void)
{
    push_frame(HIL_ID_START, NULL, 0);
    expect_ack(HIL_ACK_MISSING, HIL_ID_CFG_LAW, HIL_ID_CFG_LAW);

    sil_config_t c = config();
    char err[64];
    TEST_ASSERT_EQUAL_INT(0, sil_board_init(&sil, &c, err, sizeof err));
    send_config(&c, q16(65.0)); /* kp_aileron over 64 */
    push_frame(HIL_ID_START, NULL, 0);
    expect_ack(HIL_ACK_REFUSED, HIL_ID_CFG_LAW, (uint8_t)HT_P_KP_AILERON);
    TEST_ASSERT_EQUAL_UINT8(0u, fw.started);

    /* a bad channel block is refused when it arrives */
    uint8_t p[HIL_PAYLOAD_MAX];
    memset(p, 0, sizeof p);
    p[0] = 9u;
    push_frame(HIL_ID_CFG_OUT, p, HIL_LEN_CFG_OUT);
    TEST_ASSERT_EQUAL_INT(1, replies());
    TEST_ASSERT_EQUAL_HEX8(HIL_ID_NAK, host_rx.id);

    /* the estimator's block: a divider that does not give the IMU rate, a
     * timeout of 0, an IMU rate under 50 Hz: refused, naming the field */
    send_config(&c, q16(c.law[HT_P_KP_AILERON - 1]));
    fw_config_t est = sil.cfg;
    est.control_divider = 2u;
    hil_cfg_est_write(p, &est);
    push_frame(HIL_ID_CFG_EST, p, HIL_LEN_CFG_EST);
    push_frame(HIL_ID_START, NULL, 0);
    expect_ack(HIL_ACK_REFUSED, HIL_ID_CFG_EST, HIL_EST_BAD_DIVIDER);
    est = sil.cfg;
    est.imu_timeout_samples = 0u;
    hil_cfg_est_write(p, &est);
    push_frame(HIL_ID_CFG_EST, p, HIL_LEN_CFG_EST);
    push_frame(HIL_ID_START, NULL, 0);
    expect_ack(HIL_ACK_REFUSED, HIL_ID_CFG_EST, HIL_EST_BAD_TIMEOUT);
    est = sil.cfg;
    est.dcm.imu_rate_hz = 40u;
    est.control_divider = 1u;
    hil_cfg_est_write(p, &est);
    push_frame(HIL_ID_CFG_EST, p, HIL_LEN_CFG_EST);
    push_frame(HIL_ID_START, NULL, 0);
    expect_ack(HIL_ACK_REFUSED, HIL_ID_CFG_EST, (uint8_t)HT_DCM_P_IMU_RATE);
    TEST_ASSERT_EQUAL_UINT8(0u, fw.started);
    /* a guidance row beyond its bound: 0x80 + its id */
    est = sil.cfg;
    est.guide.turn_trim_max = 65536; /* 1.0 > 0.5 */
    hil_cfg_est_write(p, &est);
    push_frame(HIL_ID_CFG_EST, p, HIL_LEN_CFG_EST);
    push_frame(HIL_ID_START, NULL, 0);
    expect_ack(HIL_ACK_REFUSED, HIL_ID_CFG_EST,
               (uint8_t)(HIL_EST_BAD_GUIDE + (uint32_t)HT_GUIDE_P_TURN_TRIM_MAX));
    TEST_ASSERT_EQUAL_UINT8(0u, fw.started);

    send_config(&c, q16(c.law[HT_P_KP_AILERON - 1]));
    push_frame(HIL_ID_START, NULL, 0);
    expect_ack(HIL_ACK_OK, HIL_ID_START, 0u);
    TEST_ASSERT_EQUAL_UINT8(1u, fw.started);
    /* a configuration frame stops the steps until the next START */
    send_config(&c, q16(c.law[HT_P_KP_AILERON - 1]));
    TEST_ASSERT_EQUAL_UINT8(0u, fw.started);
}

/* CFG_LAW, CFG_EST, CFG_ALT and CFG_SPD follow the parameter table (protocol 8,
 * docs/hil-protocol.md): each field at its documented offset and width, and
 * the parser gives back every field the writer wrote (a row missing from
 * either, or a width that disagrees, fails here). */
static void test_cfg_frames_follow_the_table(void)
{
    uint8_t p[HIL_PAYLOAD_MAX];
    ht_params_t l;
    memset(&l, 0, sizeof l);
    l.kp_aileron = 0x01010101;
    l.kp_elevator = 0x02020202;
    l.kp_rudder = 0x03030303;
    l.kff_aileron = 0x04040404;
    l.kff_elevator = 0x05050505;
    l.kff_rudder = 0x06060606;
    l.kd_aileron = 0x07070707;
    l.kd_elevator = 0x08080808;
    l.kd_rudder = 0x09090909;
    l.v_ref_cm_s = -123456;
    l.v_min_cm_s = 4567;
    l.schedule = 0xA1u;
    l.max_tilt = 0x0B0C0D0E;
    l.pitch_mode = 0xA2u;
    l.roll_in = 0xA3u;
    l.roll_in_rate_max_rad_s = 0x3A3B3C3D;
    l.kp_sideslip = 0x1A1B1C1D;
    l.vertical_fade = -0x2A2B2C2D;
    memset(p, 0xEE, sizeof p);
    hil_cfg_law_write(p, &l);
    TEST_ASSERT_EQUAL_UINT8(63u, HIL_LEN_CFG_LAW);
    for (int i = 0; i < 9; ++i) {
        TEST_ASSERT_EQUAL_INT32(0x01010101 * (i + 1), hil_get_i32(&p[4 * i]));
    }
    TEST_ASSERT_EQUAL_INT32(-123456, hil_get_i32(&p[36]));
    TEST_ASSERT_EQUAL_INT32(4567, hil_get_i32(&p[40]));
    TEST_ASSERT_EQUAL_HEX8(0xA1u, p[44]);
    TEST_ASSERT_EQUAL_INT32(0x0B0C0D0E, hil_get_i32(&p[45]));
    TEST_ASSERT_EQUAL_HEX8(0xA2u, p[49]);
    TEST_ASSERT_EQUAL_HEX8(0xA3u, p[50]);
    TEST_ASSERT_EQUAL_INT32(0x3A3B3C3D, hil_get_i32(&p[51]));
    TEST_ASSERT_EQUAL_INT32(0x1A1B1C1D, hil_get_i32(&p[55]));
    TEST_ASSERT_EQUAL_INT32(-0x2A2B2C2D, hil_get_i32(&p[59]));
    TEST_ASSERT_EQUAL_HEX8(0xEEu, p[63]); /* nothing written beyond the frame */
    ht_params_t back;
    memset(&back, 0, sizeof back);
    hil_cfg_law_parse(p, &back);
    TEST_ASSERT_EQUAL_MEMORY(&l, &back, sizeof l);

    fw_config_t c;
    memset(&c, 0, sizeof c);
    ht_dcm_params_t *d = &c.dcm;
    d->imu_rate_hz = 0xB1B2u;
    d->kp_rollpitch = 0x11111111;
    d->ki_rollpitch = 0x12121212;
    d->kp_yaw = 0x13131313;
    d->ki_yaw = 0x14141414;
    d->gyro_bias_max_rad_s = 0x15151515;
    d->gyro_limit_rad_s = 0x16161616;
    d->accel_limit_g = 0x17171717;
    d->accel_band_g = 0x18181818;
    d->gps_min_speed_cm_s = -2345;
    d->centripetal = 0xC1u;
    d->gps_latency_ms = 0xD1D2u;
    c.control_divider = 0xE1E2u;
    c.imu_timeout_samples = 0xF1F2u;
    ht_guide_params_t *g = &c.guide;
    g->turn_trim = 0xA7u;
    g->turn_trim_tau_s = 0x21212121;
    g->turn_trim_max = 0x22222222;
    g->turn_trim_min_rate_rad_s = 0x23232323;
    g->turn_trim_hold_s = 0x24242424;
    memset(p, 0xEE, sizeof p);
    hil_cfg_est_write(p, &c);
    TEST_ASSERT_EQUAL_UINT8(60u, HIL_LEN_CFG_EST);
    TEST_ASSERT_EQUAL_HEX16(0xB1B2u, hil_get_u16(&p[0]));
    for (int i = 0; i < 8; ++i) {
        TEST_ASSERT_EQUAL_INT32(0x11111111 + 0x01010101 * i, hil_get_i32(&p[2 + 4 * i]));
    }
    TEST_ASSERT_EQUAL_INT16(-2345, hil_get_i16(&p[34]));
    TEST_ASSERT_EQUAL_HEX8(0xC1u, p[36]);
    TEST_ASSERT_EQUAL_HEX16(0xD1D2u, hil_get_u16(&p[37]));
    TEST_ASSERT_EQUAL_HEX16(0xE1E2u, hil_get_u16(&p[39]));
    TEST_ASSERT_EQUAL_HEX16(0xF1F2u, hil_get_u16(&p[41]));
    TEST_ASSERT_EQUAL_HEX8(0xA7u, p[43]); /* protocol 6: the guidance's rows */
    for (int i = 0; i < 4; ++i) {
        TEST_ASSERT_EQUAL_INT32(0x21212121 + 0x01010101 * i, hil_get_i32(&p[44 + 4 * i]));
    }
    TEST_ASSERT_EQUAL_HEX8(0xEEu, p[60]);
    fw_config_t cb;
    memset(&cb, 0, sizeof cb);
    hil_cfg_est_parse(p, &cb);
    TEST_ASSERT_EQUAL_MEMORY(&c.dcm, &cb.dcm, sizeof c.dcm);
    TEST_ASSERT_EQUAL_UINT16(c.control_divider, cb.control_divider);
    TEST_ASSERT_EQUAL_UINT16(c.imu_timeout_samples, cb.imu_timeout_samples);
    TEST_ASSERT_EQUAL_MEMORY(&c.guide, &cb.guide, sizeof c.guide);

    /* protocol 7: the holds */
    memset(&c, 0, sizeof c);
    ht_alt_hold_params_t *a = &c.modes.alt;
    a->kp_pitch_per_m = 0x31313131;
    a->ki_pitch_per_m_s = 0x32323232;
    a->kd_pitch_per_m_s = 0x33333333;
    a->max_pitch = 0x34343434;
    a->max_integral_pitch = 0x35353535;
    a->max_error_cm = 0x36363636;
    a->integral_band_cm = 0x37373737;
    a->protect_cm_s = 0x38383838;
    a->protect_valid_cm_s = 0x39393939;
    a->kv_pitch_per_m_s = 0x3A3A3A3A;
    a->protect_tau_ms = 0xC3C4u;
    a->rate_hz = 0xC5C6u;
    c.alt_integral_q20[0] = -0x12345678;
    c.alt_integral_q20[1] = 0x2345678;
    memset(p, 0xEE, sizeof p);
    hil_cfg_alt_write(p, &c);
    for (int i = 0; i < 10; ++i) {
        TEST_ASSERT_EQUAL_INT32(0x31313131 + 0x01010101 * i, hil_get_i32(&p[4 * i]));
    }
    TEST_ASSERT_EQUAL_HEX16(0xC3C4u, hil_get_u16(&p[40]));
    TEST_ASSERT_EQUAL_HEX16(0xC5C6u, hil_get_u16(&p[42]));
    TEST_ASSERT_EQUAL_INT32(-0x12345678, hil_get_i32(&p[44]));
    TEST_ASSERT_EQUAL_INT32(0x2345678, hil_get_i32(&p[48]));
    TEST_ASSERT_EQUAL_HEX8(0xEEu, p[52]);
    ht_speed_hold_params_t *sp = &c.modes.speed;
    sp->throttle_trim = 0x4142;
    sp->throttle_min = -0x4344;
    sp->throttle_max = 0x4546;
    sp->kp_throttle_per_m_s = 0x51515151;
    sp->ki_throttle_per_m = 0x52525252;
    sp->kff_throttle_per_pitch = 0x53535353;
    sp->max_integral_throttle = 0x4748;
    sp->rate_hz = 0xD1D2u;
    uint8_t q[HIL_PAYLOAD_MAX];
    memset(q, 0xEE, sizeof q);
    hil_cfg_spd_write(q, &c);
    TEST_ASSERT_EQUAL_INT16(0x4142, hil_get_i16(&q[0]));
    TEST_ASSERT_EQUAL_INT16(-0x4344, hil_get_i16(&q[2]));
    TEST_ASSERT_EQUAL_INT16(0x4546, hil_get_i16(&q[4]));
    for (int i = 0; i < 3; ++i) {
        TEST_ASSERT_EQUAL_INT32(0x51515151 + 0x01010101 * i, hil_get_i32(&q[6 + 4 * i]));
    }
    TEST_ASSERT_EQUAL_INT16(0x4748, hil_get_i16(&q[18]));
    TEST_ASSERT_EQUAL_HEX16(0xD1D2u, hil_get_u16(&q[20]));
    TEST_ASSERT_EQUAL_HEX8(0xEEu, q[22]);
    memset(&cb, 0, sizeof cb);
    hil_cfg_alt_parse(p, &cb);
    hil_cfg_spd_parse(q, &cb);
    TEST_ASSERT_EQUAL_MEMORY(&c.modes.alt, &cb.modes.alt, sizeof c.modes.alt);
    TEST_ASSERT_EQUAL_MEMORY(&c.modes.speed, &cb.modes.speed, sizeof c.modes.speed);
    TEST_ASSERT_EQUAL_INT32(c.alt_integral_q20[0], cb.alt_integral_q20[0]);
    TEST_ASSERT_EQUAL_INT32(c.alt_integral_q20[1], cb.alt_integral_q20[1]);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_ready_banner_and_hello);
    RUN_TEST(test_frames_round_trip);
    RUN_TEST(test_same_step_as_the_sil_board_estimate);
    RUN_TEST(test_same_step_as_the_sil_board_truth);
    RUN_TEST(test_same_step_as_the_sil_board_mixed);
    RUN_TEST(test_bad_frames_are_never_acted_on);
    RUN_TEST(test_sensors_before_start_are_refused);
    RUN_TEST(test_start_checks_the_configuration);
    RUN_TEST(test_cfg_frames_follow_the_table);
    return UNITY_END();
}
