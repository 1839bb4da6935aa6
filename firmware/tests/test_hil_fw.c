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
#include "hil_fw.h"
#include "ht_test_support.h"
#include "sil_board.h"

#include <math.h>
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

static uint8_t fw_len[0xA1];
static hil_decoder_t host_rx;

/* Decode everything the firmware sent since the last call; returns the
 * number of frames, the last one stays in host_rx. */
static int replies(void)
{
    int n = 0;
    for (size_t i = 0; i < sent_n; ++i) {
        n += hil_decoder_push(&host_rx, sent[i]);
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

static sil_config_t config(void)
{
    sil_config_t c;
    memset(&c, 0, sizeof c);
    c.kp_aileron = 2.0;
    c.kp_elevator = 6.0;
    c.kp_rudder = 0.3;
    c.kff_elevator = 1.0;
    c.kff_rudder = 0.5;
    c.kd_aileron = 0.3;
    c.kd_elevator = 1.0;
    c.kd_rudder = 1.0;
    c.v_ref_m_s = 110.0;
    c.v_min_m_s = 30.0;
    c.max_tilt = 2.0;
    c.schedule = 1;
    c.alt_kp_pitch_per_m = 0.012;
    c.alt_ki_pitch_per_m_s = 0.004;
    c.alt_kd_pitch_per_m_s = 0.015;
    c.alt_max_pitch = 0.3;
    c.alt_max_integral_pitch = 0.2;
    c.alt_max_error_m = 100.0;
    c.alt_integral_band_m = 20.0;
    c.alt_integral_upright = 0.01;
    c.alt_integral_inverted = -0.5; /* beyond max_integral: both boards clamp it */
    /* the airspeed protection on (protocol 2), near the T-37's cruise so the
     * steps below reach it */
    c.alt_protect_m_s = 100.0;
    c.alt_protect_valid_m_s = 30.0;
    c.alt_kv_pitch_per_m_s = 0.03;
    c.alt_protect_tau_s = 1.0;
    c.spd_throttle_trim = 0.55;
    c.spd_throttle_min = 0.05;
    c.spd_throttle_max = 1.0;
    c.spd_kp_throttle_per_m_s = 0.05;
    c.spd_ki_throttle_per_m = 0.01;
    c.spd_kff_throttle_per_pitch = 1.0;
    c.spd_max_integral_throttle = 0.3;
    c.trim_aileron = 0.013;
    c.trim_elevator = -0.021;
    c.trim_rudder = 0.004;
    c.control_rate_hz = 40;
    c.imu_rate_hz = 120;
    c.dcm_kp_rollpitch = 0.2;
    c.dcm_ki_rollpitch = 0.002;
    c.dcm_kp_yaw = 0.5;
    c.dcm_ki_yaw = 0.005;
    c.dcm_gyro_bias_max_deg_s = 5.7;
    c.dcm_gyro_limit_deg_s = 2000.0;
    c.dcm_accel_limit_g = 16.0;
    c.dcm_accel_band_g = 0.5;
    c.dcm_gps_min_speed_m_s = 3.0;
    c.dcm_centripetal = 2;
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
    const double law[9] = {c->kp_aileron,  c->kp_elevator,  c->kp_rudder,
                           c->kff_aileron, c->kff_elevator, c->kff_rudder,
                           c->kd_aileron,  c->kd_elevator,  c->kd_rudder};
    for (int i = 0; i < 9; ++i) {
        put32(&p[4 * i], q16(law[i]));
    }
    put32(&p[0], kp_aileron_q16);
    put32(&p[36], (int32_t)llround(c->v_ref_m_s * 100.0));
    put32(&p[40], (int32_t)llround(c->v_min_m_s * 100.0));
    put32(&p[44], q16(c->max_tilt));
    p[48] = (uint8_t)c->schedule;
    push_frame(HIL_ID_CFG_LAW, p, HIL_LEN_CFG_LAW);

    put32(&p[0], q16(c->alt_kp_pitch_per_m));
    put32(&p[4], q16(c->alt_ki_pitch_per_m_s));
    put32(&p[8], q16(c->alt_kd_pitch_per_m_s));
    put32(&p[12], q16(c->alt_max_pitch));
    put32(&p[16], q16(c->alt_max_integral_pitch));
    put32(&p[20], (int32_t)llround(c->alt_max_error_m * 100.0));
    put32(&p[24], (int32_t)llround(c->alt_integral_band_m * 100.0));
    hil_put_u16(&p[28], (uint16_t)c->control_rate_hz);
    put32(&p[30], (int32_t)llround(c->alt_integral_upright * 1048576.0));
    put32(&p[34], (int32_t)llround(c->alt_integral_inverted * 1048576.0));
    put32(&p[38], (int32_t)llround(c->alt_protect_m_s * 100.0));
    put32(&p[42], (int32_t)llround(c->alt_protect_valid_m_s * 100.0));
    put32(&p[46], q16(c->alt_kv_pitch_per_m_s));
    hil_put_u16(&p[50], (uint16_t)llround(c->alt_protect_tau_s * 1000.0));
    push_frame(HIL_ID_CFG_ALT, p, HIL_LEN_CFG_ALT);

    hil_put_i16(&p[0], (int16_t)llround(c->spd_throttle_trim * 16384.0));
    hil_put_i16(&p[2], (int16_t)llround(c->spd_throttle_min * 16384.0));
    hil_put_i16(&p[4], (int16_t)llround(c->spd_throttle_max * 16384.0));
    put32(&p[6], q16(c->spd_kp_throttle_per_m_s));
    put32(&p[10], q16(c->spd_ki_throttle_per_m));
    put32(&p[14], q16(c->spd_kff_throttle_per_pitch));
    hil_put_i16(&p[18], (int16_t)llround(c->spd_max_integral_throttle * 16384.0));
    hil_put_u16(&p[20], (uint16_t)c->control_rate_hz);
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
}

static void expect_ack(uint8_t status, uint8_t block, uint8_t detail)
{
    TEST_ASSERT_EQUAL_INT(1, replies());
    TEST_ASSERT_EQUAL_HEX8(HIL_ID_ACK, host_rx.id);
    TEST_ASSERT_EQUAL_UINT8(status, host_rx.payload[0]);
    TEST_ASSERT_EQUAL_HEX8(block, host_rx.payload[1]);
    TEST_ASSERT_EQUAL_UINT8(detail, host_rx.payload[2]);
}

static void start_both(void)
{
    sil_config_t c = config();
    char err[64];
    TEST_ASSERT_EQUAL_INT_MESSAGE(0, sil_board_init(&sil, &c, err, sizeof err), err);
    send_config(&c, q16(c.kp_aileron));
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

/* The step's fixed-point inputs as the test draws them. */
typedef struct {
    hil_attitude_t imu;
    int32_t altitude_cm, climb_cm_s;
} fx_sensors_t;

typedef struct {
    q11_t turn_rate_rad_s;
    q16_t pitch_ratio;
    int32_t altitude_cm;
    int16_t airspeed_cm_s;
    q14_t throttle;
    uint8_t altitude_hold, speed_hold, inverted, pitch_mode;
} fx_command_t;

static void random_inputs(uint64_t *rng, fx_sensors_t *s, fx_command_t *c, int wild)
{
    memset(s, 0, sizeof *s);
    memset(c, 0, sizeof *c);
    if (wild) { /* anything at all: every branch and saturation */
        for (int i = 0; i < 3; ++i) {
            s->imu.down_q14[i] = (int16_t)ts_rng_next(rng);
            s->imu.gyro_q11_rad_s[i] = (int16_t)ts_rng_next(rng);
        }
        s->imu.airspeed_cm_s = (int16_t)ts_rng_next(rng);
        s->altitude_cm = (int32_t)(ts_rng_next(rng) % 2000000u) - 1000000;
        s->climb_cm_s = (int32_t)(ts_rng_next(rng) % 20000u) - 10000;
    } else { /* flying: a unit tilt row, modest rates */
        const double roll = ts_uniform(rng, -3.1, 3.1), pitch = ts_uniform(rng, -1.2, 1.2);
        s->imu.down_q14[0] = (int16_t)llround(-sin(roll) * cos(pitch) * 16384.0);
        s->imu.down_q14[1] = (int16_t)llround(-sin(pitch) * 16384.0);
        s->imu.down_q14[2] = (int16_t)llround(cos(roll) * cos(pitch) * 16384.0);
        for (int i = 0; i < 3; ++i) {
            s->imu.gyro_q11_rad_s[i] = (int16_t)llround(ts_uniform(rng, -1.0, 1.0) * 2048.0);
        }
        s->imu.airspeed_cm_s = (int16_t)llround(ts_uniform(rng, 2000.0, 15000.0));
        s->altitude_cm = 150000 + (int32_t)llround(ts_uniform(rng, -3000.0, 3000.0));
        s->climb_cm_s = (int32_t)llround(ts_uniform(rng, -1000.0, 1000.0));
    }
    c->turn_rate_rad_s = (int16_t)llround(ts_uniform(rng, -0.3, 0.3) * 2048.0);
    c->pitch_ratio = (int32_t)llround(ts_uniform(rng, -0.3, 0.3) * 65536.0);
    c->altitude_cm = 150000 + (int32_t)llround(ts_uniform(rng, -2000.0, 2000.0));
    c->airspeed_cm_s = (int16_t)llround(ts_uniform(rng, 3000.0, 12000.0));
    c->throttle = (int16_t)llround(ts_uniform(rng, 0.0, 1.0) * 16384.0);
    const uint64_t f = ts_rng_next(rng);
    c->altitude_hold = (uint8_t)(f & 1u);
    c->speed_hold = (uint8_t)((f >> 1) & 1u);
    c->inverted = (uint8_t)((f >> 2) & 1u);
    c->pitch_mode = (uint8_t)((f >> 3) & 1u);
}

static void to_hil(const fx_sensors_t *s, const fx_command_t *c, hil_step_in_t *in)
{
    memset(in, 0, sizeof *in);
    in->imu = s->imu;
    in->altitude_cm = s->altitude_cm;
    in->climb_cm_s = s->climb_cm_s;
    in->turn_rate_rad_s = c->turn_rate_rad_s;
    in->pitch_ratio = c->pitch_ratio;
    in->altitude_cmd_cm = c->altitude_cm;
    in->airspeed_cmd_cm_s = c->airspeed_cm_s;
    in->throttle = c->throttle;
    in->flags =
        (uint8_t)((c->altitude_hold ? HIL_SF_ALTITUDE_HOLD : 0u) |
                  (c->speed_hold ? HIL_SF_SPEED_HOLD : 0u) | (c->inverted ? HIL_SF_INVERTED : 0u) |
                  (c->pitch_mode ? HIL_SF_TILT_CROSS : 0u));
}

/* The same inputs as the SIL harness gives them: doubles that convert back
 * to exactly these fixed-point values, the truth solution, one control
 * period of (zero) IMU samples. */
static void sil_step(const fx_sensors_t *s, const fx_command_t *c)
{
    static sil_sensors_t ss;
    static sil_command_t sc;
    static sil_actuators_t a;
    memset(&ss, 0, sizeof ss);
    memset(&sc, 0, sizeof sc);
    ss.imu_count = 3; /* imu_rate_hz / control_rate_hz */
    ss.use_truth = 1;
    ss.dcm_x = s->imu.down_q14[0] / 16384.0;
    ss.dcm_y = s->imu.down_q14[1] / 16384.0;
    ss.dcm_z = s->imu.down_q14[2] / 16384.0;
    ss.gyro_x = s->imu.gyro_q11_rad_s[0] / 2048.0;
    ss.gyro_y = s->imu.gyro_q11_rad_s[1] / 2048.0;
    ss.gyro_z = s->imu.gyro_q11_rad_s[2] / 2048.0;
    ss.airspeed_m_s = s->imu.airspeed_cm_s / 100.0;
    ss.altitude_m = s->altitude_cm / 100.0;
    ss.climb_m_s = s->climb_cm_s / 100.0;
    sc.turn_rate_rad_s = c->turn_rate_rad_s / 2048.0;
    sc.pitch_ratio = c->pitch_ratio / 65536.0;
    sc.altitude_m = c->altitude_cm / 100.0;
    sc.airspeed_m_s = c->airspeed_cm_s / 100.0;
    sc.throttle = c->throttle / 16384.0;
    sc.altitude_hold = c->altitude_hold;
    sc.speed_hold = c->speed_hold;
    sc.inverted = c->inverted;
    sc.pitch_mode = c->pitch_mode;
    sil_board_step(&sil, &ss, &sc, &a);
    TEST_ASSERT_EQUAL_INT(1, a.control_ran);
}

/* One step on both boards, the firmware's through frames; compare all. */
static void step_both(uint32_t seq, const fx_sensors_t *s, const fx_command_t *c)
{
    sil_step(s, c);
    const fw_output_t o = sil.out;
    hil_step_in_t in;
    to_hil(s, c, &in);
    uint8_t p[HIL_LEN_SENSORS];
    hil_sensors_write(p, seq, &in);
    push_frame(HIL_ID_SENSORS, p, HIL_LEN_SENSORS);
    TEST_ASSERT_EQUAL_INT(1, replies());
    TEST_ASSERT_EQUAL_HEX8(HIL_ID_OUTPUT, host_rx.id);
    const uint8_t *r = host_rx.payload;
    TEST_ASSERT_EQUAL_UINT32(seq, (uint32_t)hil_get_i32(&r[0]));
    for (int i = 0; i < SIL_CH_COUNT; ++i) {
        TEST_ASSERT_EQUAL_UINT16(o.pulse_us[i], hil_get_u16(&r[4 + 2 * i]));  /* read back */
        TEST_ASSERT_EQUAL_UINT16(o.pulse_us[i], hil_get_u16(&r[12 + 2 * i])); /* computed */
        TEST_ASSERT_EQUAL_UINT16(o.pulse_us[i], fake_board.committed_us[i]);
    }
    TEST_ASSERT_EQUAL_INT16(o.law.aileron, hil_get_i16(&r[20]));
    TEST_ASSERT_EQUAL_INT16(o.law.elevator, hil_get_i16(&r[22]));
    TEST_ASSERT_EQUAL_INT16(o.law.rudder, hil_get_i16(&r[24]));
    TEST_ASSERT_EQUAL_INT32(o.pitch_cmd, hil_get_i32(&r[26]));
    TEST_ASSERT_EQUAL_INT16(o.throttle, hil_get_i16(&r[30]));
    TEST_ASSERT_EQUAL_INT16(o.law.turn_rate_used_rad_s, hil_get_i16(&r[32]));
    TEST_ASSERT_EQUAL_INT16(o.law.roll_error, hil_get_i16(&r[34]));
    TEST_ASSERT_EQUAL_INT16(o.law.pitch_error, hil_get_i16(&r[36]));
    TEST_ASSERT_EQUAL_UINT16((uint16_t)(o.law.flags | (o.servo_clamped ? 0x100u : 0u)),
                             hil_get_u16(&r[38]));
    /* the whole law output, and the holds' states, not only what is sent */
    TEST_ASSERT_EQUAL_MEMORY(&o.law, &fw.res.law, sizeof o.law);
    TEST_ASSERT_EQUAL_MEMORY(&o.law_in, &fw.fw_out.law_in, sizeof o.law_in);
    TEST_ASSERT_EQUAL_MEMORY(&sil.fw.modes_state.alt, &fw.fw.modes_state.alt,
                             sizeof fw.fw.modes_state.alt);
    TEST_ASSERT_EQUAL_MEMORY(&sil.fw.modes_state.speed, &fw.fw.modes_state.speed,
                             sizeof fw.fw.modes_state.speed);
    TEST_ASSERT_EQUAL_UINT8(sil.fw.guard_state.engaged, fw.fw.guard_state.engaged);
}

static void test_same_step_as_the_sil_board(void)
{
    start_both();
    /* the clamped initial integrators */
    const ht_alt_hold_state_t *sa = &sil.fw.modes_state.alt, *fa = &fw.fw.modes_state.alt;
    TEST_ASSERT_EQUAL_INT32(sa->integral_q20[0], fa->integral_q20[0]);
    TEST_ASSERT_EQUAL_INT32(sa->integral_q20[1], fa->integral_q20[1]);
    TEST_ASSERT_EQUAL_UINT8(sil.cfg.out.count, fw.cfg.out.count); /* the channels in use */
    TEST_ASSERT_EQUAL_MEMORY(sil.cfg.out.ch, fw.cfg.out.ch,
                             sil.cfg.out.count * sizeof(os_channel_t));
    TEST_ASSERT_EQUAL_MEMORY(&sil.fw.law[0], &fw.fw.law[0], sizeof sil.fw.law[0]);
    TEST_ASSERT_EQUAL_MEMORY(&sil.fw.law[1], &fw.fw.law[1], sizeof sil.fw.law[1]);
    uint64_t rng = 2024;
    fx_sensors_t s;
    fx_command_t c;
    for (uint32_t k = 0; k < 20000u; ++k) {
        random_inputs(&rng, &s, &c, (k % 4u) == 3u);
        step_both(k, &s, &c);
    }
    TEST_ASSERT_EQUAL_UINT32(20000u, fw.steps);
    TEST_ASSERT_EQUAL_UINT16(0u, fw.rx.stats.bad_crc);
}

static void test_bad_frames_are_never_acted_on(void)
{
    start_both();
    uint64_t rng = 5;
    fx_sensors_t s;
    fx_command_t c;
    random_inputs(&rng, &s, &c, 0);
    step_both(0, &s, &c);
    const hil_fw_t before = fw;

    hil_step_in_t in;
    to_hil(&s, &c, &in);
    uint8_t p[HIL_LEN_SENSORS], f[HIL_FRAME_MAX];
    hil_sensors_write(p, 1, &in);
    size_t n = hil_encode(HIL_ID_SENSORS, p, HIL_LEN_SENSORS, f, sizeof f);
    f[10] ^= 0x01u; /* one payload bit: bad CRC */
    for (size_t i = 0; i < n; ++i) {
        hil_fw_on_byte(&fw, f[i]);
    }
    /* the right payload with one byte too many: a known id, the wrong length */
    n = hil_encode(HIL_ID_SENSORS, p, HIL_LEN_SENSORS - 1u, f, sizeof f);
    for (size_t i = 0; i < n; ++i) {
        hil_fw_on_byte(&fw, f[i]);
    }
    push_frame(0x33, p, 8);       /* an id nobody knows */
    push_frame(HIL_ID_ACK, p, 4); /* a firmware-to-host id */
    const uint8_t garbage[5] = {0x00, 0xA5, 0xA5, 0x13, 0x77};
    for (size_t i = 0; i < sizeof garbage; ++i) {
        hil_fw_on_byte(&fw, garbage[i]);
    }
    TEST_ASSERT_EQUAL_INT(0, replies()); /* no answer to any */
    TEST_ASSERT_EQUAL_UINT16(1u, fw.rx.stats.bad_crc);
    TEST_ASSERT_EQUAL_UINT16(3u, fw.rx.stats.unknown_id); /* wrong length counts here */
    TEST_ASSERT_EQUAL_UINT32(before.steps, fw.steps);
    TEST_ASSERT_EQUAL_MEMORY(&before.fw.modes_state, &fw.fw.modes_state, sizeof fw.fw.modes_state);
    TEST_ASSERT_EQUAL_UINT32(1u, fake_board.commits);

    /* reserved flag bits: refused with a NAK, not stepped */
    in.flags = 0x10u;
    hil_sensors_write(p, 2, &in);
    push_frame(HIL_ID_SENSORS, p, HIL_LEN_SENSORS);
    TEST_ASSERT_EQUAL_INT(1, replies());
    TEST_ASSERT_EQUAL_HEX8(HIL_ID_NAK, host_rx.id);
    TEST_ASSERT_EQUAL_HEX8(HIL_ID_SENSORS, host_rx.payload[0]);
    TEST_ASSERT_EQUAL_UINT8(HIL_NAK_BAD_FIELD, host_rx.payload[1]);
    TEST_ASSERT_EQUAL_UINT32(before.steps, fw.steps);

    /* the stream is still in sync: the next good frame is stepped, and
     * matches the SIL board (which saw none of the bad ones) */
    random_inputs(&rng, &s, &c, 0);
    step_both(3, &s, &c);
}

static void test_sensors_before_start_are_refused(void)
{
    uint8_t p[HIL_LEN_SENSORS];
    hil_step_in_t in;
    memset(&in, 0, sizeof in);
    hil_sensors_write(p, 0, &in);
    push_frame(HIL_ID_SENSORS, p, HIL_LEN_SENSORS);
    TEST_ASSERT_EQUAL_INT(1, replies());
    TEST_ASSERT_EQUAL_HEX8(HIL_ID_NAK, host_rx.id);
    TEST_ASSERT_EQUAL_UINT8(HIL_NAK_NOT_STARTED, host_rx.payload[1]);
    TEST_ASSERT_EQUAL_UINT32(0u, fake_board.writes);
    TEST_ASSERT_EQUAL_UINT32(0u, fw.steps);
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
    uint8_t p[HIL_LEN_CFG_OUT];
    memset(p, 0, sizeof p);
    p[0] = 9u;
    push_frame(HIL_ID_CFG_OUT, p, HIL_LEN_CFG_OUT);
    TEST_ASSERT_EQUAL_INT(1, replies());
    TEST_ASSERT_EQUAL_HEX8(HIL_ID_NAK, host_rx.id);

    send_config(&c, q16(c.kp_aileron));
    push_frame(HIL_ID_START, NULL, 0);
    expect_ack(HIL_ACK_OK, HIL_ID_START, 0u);
    TEST_ASSERT_EQUAL_UINT8(1u, fw.started);
    /* a configuration frame stops the steps until the next START */
    send_config(&c, q16(c.kp_aileron));
    TEST_ASSERT_EQUAL_UINT8(0u, fw.started);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_ready_banner_and_hello);
    RUN_TEST(test_same_step_as_the_sil_board);
    RUN_TEST(test_bad_frames_are_never_acted_on);
    RUN_TEST(test_sensors_before_start_are_refused);
    RUN_TEST(test_start_checks_the_configuration);
    return UNITY_END();
}
