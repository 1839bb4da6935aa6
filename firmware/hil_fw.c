/*
 * hil_fw.c - the firmware side of the HIL link (see hil_fw.h and
 * docs/hil-protocol.md). Integer only; no dynamic memory; every buffer is in
 * the caller's hil_fw_t.
 */
#include "hil_fw.h"

#include <string.h>

#define HAVE_LAW 0x01u
#define HAVE_ALT 0x02u
#define HAVE_SPD 0x04u
#define HAVE_OUT 0x08u

#define NO_SUCH_LENGTH 0xFEu /* longer than any payload: the id is unknown */

static void count16(uint16_t *c)
{
    if (*c != UINT16_MAX) {
        (*c)++;
    }
}

static uint32_t get_u32(const uint8_t *p)
{
    return (uint32_t)hil_get_i32(p);
}

static void put_u32(uint8_t *p, uint32_t v)
{
    hil_put_i32(p, (int32_t)v);
}

static void send(hil_fw_t *h, uint8_t id, uint8_t len)
{
    const size_t n = hil_encode(id, h->payload, len, h->frame, sizeof h->frame);
    if (n > 0u) {
        hil_link_send(h->frame, n);
    }
}

void hil_fw_init(hil_fw_t *h)
{
    (void)memset(h, 0, sizeof *h);
    for (unsigned i = 0; i < HIL_ID_HOST_COUNT; ++i) {
        h->rx_len[i] = NO_SUCH_LENGTH;
    }
    h->rx_len[HIL_ID_HELLO] = 0u;
    h->rx_len[HIL_ID_CFG_LAW] = HIL_LEN_CFG_LAW;
    h->rx_len[HIL_ID_CFG_ALT] = HIL_LEN_CFG_ALT;
    h->rx_len[HIL_ID_CFG_SPD] = HIL_LEN_CFG_SPD;
    h->rx_len[HIL_ID_CFG_OUT] = HIL_LEN_CFG_OUT;
    h->rx_len[HIL_ID_START] = 0u;
    h->rx_len[HIL_ID_SENSORS] = HIL_LEN_SENSORS;
    const hil_msg_table_t table = {h->rx_len, (uint8_t)HIL_ID_HOST_COUNT};
    hil_decoder_init(&h->rx, table);
    fw_config_default(&h->cfg);
}

void hil_fw_send_ready(hil_fw_t *h)
{
    uint8_t *p = h->payload;
    const hil_stats_t *st = &h->rx.stats;
    p[0] = (uint8_t)'H';
    p[1] = (uint8_t)'T';
    p[2] = (uint8_t)HIL_PROTOCOL_VERSION;
    p[3] = h->started;
    p[4] = board_servo_count();
    p[5] = 0u;
    hil_put_u16(&p[6], st->frames_ok);
    hil_put_u16(&p[8], st->bad_crc);
    hil_put_u16(&p[10], st->bad_length);
    hil_put_u16(&p[12], st->unknown_id);
    hil_put_u16(&p[14], st->skipped_bytes);
    hil_put_u16(&p[16], h->naks);
    put_u32(&p[18], h->steps);
    hil_put_u16(&p[22], hil_link_errors());
    send(h, (uint8_t)HIL_ID_READY, (uint8_t)HIL_LEN_READY);
}

static void nak(hil_fw_t *h, uint8_t id, uint8_t reason)
{
    count16(&h->naks);
    h->payload[0] = id;
    h->payload[1] = reason;
    send(h, (uint8_t)HIL_ID_NAK, (uint8_t)HIL_LEN_NAK);
}

static void ack(hil_fw_t *h, uint8_t status, uint8_t block, uint8_t detail)
{
    h->payload[0] = status;
    h->payload[1] = block;
    h->payload[2] = detail;
    h->payload[3] = 0u;
    send(h, (uint8_t)HIL_ID_ACK, (uint8_t)HIL_LEN_ACK);
}

/* --- configuration --------------------------------------------------------- */

static void cfg_law(hil_fw_t *h, const uint8_t *p)
{
    ht_params_t *l = &h->cfg.law;
    l->kp_aileron = hil_get_i32(&p[0]);
    l->kp_elevator = hil_get_i32(&p[4]);
    l->kp_rudder = hil_get_i32(&p[8]);
    l->kff_aileron = hil_get_i32(&p[12]);
    l->kff_elevator = hil_get_i32(&p[16]);
    l->kff_rudder = hil_get_i32(&p[20]);
    l->kd_aileron = hil_get_i32(&p[24]);
    l->kd_elevator = hil_get_i32(&p[28]);
    l->kd_rudder = hil_get_i32(&p[32]);
    l->v_ref_cm_s = hil_get_i32(&p[36]);
    l->v_min_cm_s = hil_get_i32(&p[40]);
    l->max_tilt = hil_get_i32(&p[44]);
    l->schedule = (p[48] != 0u) ? 1u : 0u;
    h->have |= HAVE_LAW;
}

static void cfg_alt(hil_fw_t *h, const uint8_t *p)
{
    ht_alt_hold_params_t *a = &h->cfg.modes.alt;
    a->kp_pitch_per_m = hil_get_i32(&p[0]);
    a->ki_pitch_per_m_s = hil_get_i32(&p[4]);
    a->kd_pitch_per_m_s = hil_get_i32(&p[8]);
    a->max_pitch = hil_get_i32(&p[12]);
    a->max_integral_pitch = hil_get_i32(&p[16]);
    a->max_error_cm = hil_get_i32(&p[20]);
    a->integral_band_cm = hil_get_i32(&p[24]);
    a->rate_hz = hil_get_u16(&p[28]);
    h->cfg.alt_integral_q20[0] = hil_get_i32(&p[30]);
    h->cfg.alt_integral_q20[1] = hil_get_i32(&p[34]);
    a->protect_cm_s = hil_get_i32(&p[38]);
    a->protect_valid_cm_s = hil_get_i32(&p[42]);
    a->kv_pitch_per_m_s = hil_get_i32(&p[46]);
    a->protect_tau_ms = hil_get_u16(&p[50]);
    h->have |= HAVE_ALT;
}

static void cfg_spd(hil_fw_t *h, const uint8_t *p)
{
    ht_speed_hold_params_t *s = &h->cfg.modes.speed;
    s->throttle_trim = hil_get_i16(&p[0]);
    s->throttle_min = hil_get_i16(&p[2]);
    s->throttle_max = hil_get_i16(&p[4]);
    s->kp_throttle_per_m_s = hil_get_i32(&p[6]);
    s->ki_throttle_per_m = hil_get_i32(&p[10]);
    s->kff_throttle_per_pitch = hil_get_i32(&p[14]);
    s->max_integral_throttle = hil_get_i16(&p[18]);
    s->rate_hz = hil_get_u16(&p[20]);
    h->have |= HAVE_SPD;
}

static void cfg_out(hil_fw_t *h, const uint8_t *p)
{
    const uint8_t n = p[0], first = p[1];
    if (n == 0u || n > OS_MAX_CHANNELS || first >= OS_MAX_CHANNELS || (first % 4u) != 0u) {
        nak(h, (uint8_t)HIL_ID_CFG_OUT, (uint8_t)HIL_NAK_BAD_FIELD);
        return;
    }
    h->cfg.out.count = n;
    for (unsigned i = 0; i < 4u; ++i) {
        const uint8_t *r = &p[2u + 14u * i];
        os_channel_t *ch = &h->cfg.out.ch[first + i];
        ch->function = r[0];
        ch->reversed = (r[1] != 0u) ? 1u : 0u;
        ch->centre_us = hil_get_u16(&r[2]);
        ch->trim_us = hil_get_i16(&r[4]);
        ch->travel_us = hil_get_u16(&r[6]);
        ch->min_us = hil_get_u16(&r[8]);
        ch->max_us = hil_get_u16(&r[10]);
        ch->failsafe_us = hil_get_u16(&r[12]);
    }
    h->have |= HAVE_OUT;
}

/* The IMU rate of the step: the control rate (CFG_ALT rate_hz) times the
 * smallest divider that brings it into the estimator's range (>= 50 Hz). */
static void rates(fw_config_t *c)
{
    const uint16_t rate = (c->modes.alt.rate_hz > 0u) ? c->modes.alt.rate_hz : 1u;
    uint16_t div = 1u;
    while ((uint32_t)rate * div < 50u && div < 100u) {
        div++;
    }
    c->modes.rate_hz = rate;
    c->control_divider = div;
    c->dcm.imu_rate_hz = (uint16_t)((uint32_t)rate * div > 1000u ? 1000u : rate * div);
}

/* The ACK of a refused START: which block, which field. */
static void refused(hil_fw_t *h)
{
    const fw_t *fw = &h->fw;
    uint8_t block = (uint8_t)HIL_ID_CFG_ALT;
    uint8_t detail = 0u;
    switch ((fw_bad_block_t)fw->bad) {
    case FW_BAD_LAW:
        block = (uint8_t)HIL_ID_CFG_LAW;
        detail = (uint8_t)fw->bad_sub;
        break;
    case FW_BAD_MODES:
        block = (fw->modes_bad.field == HT_MODES_P_SPEED_HOLD) ? (uint8_t)HIL_ID_CFG_SPD
                                                               : (uint8_t)HIL_ID_CFG_ALT;
        break;
    case FW_BAD_OUTPUT:
        block = (uint8_t)HIL_ID_CFG_OUT;
        detail = (uint8_t)fw->bad_sub;
        break;
    default:
        break; /* the estimator, the guard, the rates: all follow CFG_ALT's rate */
    }
    ack(h, (uint8_t)HIL_ACK_REFUSED, block, detail);
}

/* Check everything staged, then put it in force with fresh states (the
 * altitude integrators from CFG_ALT, clamped as every host does). */
static void start(hil_fw_t *h)
{
    static const uint8_t block_id[4] = {HIL_ID_CFG_LAW, HIL_ID_CFG_ALT, HIL_ID_CFG_SPD,
                                        HIL_ID_CFG_OUT};
    h->started = 0u;
    for (unsigned i = 0; i < 4u; ++i) {
        if ((h->have & (1u << i)) == 0u) {
            ack(h, (uint8_t)HIL_ACK_MISSING, block_id[i], block_id[i]);
            return;
        }
    }
    if (h->cfg.out.count > board_servo_count()) {
        ack(h, (uint8_t)HIL_ACK_REFUSED, (uint8_t)HIL_ID_CFG_OUT, h->cfg.out.count);
        return;
    }
    rates(&h->cfg);
    if (fw_init(&h->fw, &h->cfg) == 0) {
        refused(h);
        return;
    }
    h->steps = 0u;
    h->started = 1u;
    ack(h, (uint8_t)HIL_ACK_OK, (uint8_t)HIL_ID_START, 0u);
}

/* --- the control step ------------------------------------------------------ */

void hil_fw_step(hil_fw_t *h, const hil_step_in_t *in, hil_step_out_t *o)
{
    (void)memset(o, 0, sizeof *o);
    if (h->started == 0u) {
        return;
    }
    fw_nav_t *n = &h->nav;
    (void)memset(n, 0, sizeof *n);
    for (unsigned i = 0u; i < 3u; ++i) {
        n->down_q14[i] = in->imu.down_q14[i];
        n->gyro_q11_rad_s[i] = in->imu.gyro_q11_rad_s[i];
    }
    n->airspeed_cm_s = in->imu.airspeed_cm_s;
    n->altitude_cm = in->altitude_cm;
    n->climb_cm_s = in->climb_cm_s;
    fw_guided_t *g = &h->guided;
    g->turn_rate_rad_s = in->turn_rate_rad_s;
    g->pitch_ratio = in->pitch_ratio;
    g->altitude_cm = in->altitude_cmd_cm;
    g->airspeed_cm_s = in->airspeed_cmd_cm_s;
    g->throttle = in->throttle;
    g->altitude_hold = ((in->flags & HIL_SF_ALTITUDE_HOLD) != 0u) ? 1u : 0u;
    g->speed_hold = ((in->flags & HIL_SF_SPEED_HOLD) != 0u) ? 1u : 0u;
    g->inverted = ((in->flags & HIL_SF_INVERTED) != 0u) ? 1u : 0u;
    g->pitch_mode = ((in->flags & HIL_SF_TILT_CROSS) != 0u) ? 1u : 0u;
    fw_inputs_t *fi = &h->fw_in;
    (void)memset(fi, 0, sizeof *fi); /* no raw samples in protocol version 2 */
    fi->guided = g;
    fi->external = n;
    /* the frame is one control period: the step runs until its control chain has */
    for (uint16_t k = 0u; k < h->cfg.control_divider; ++k) {
        if (fw_step(&h->fw, fi, &h->fw_out) != 0) {
            break;
        }
    }
    const fw_output_t *fo = &h->fw_out;
    for (unsigned i = 0; i < HIL_OUT_CHANNELS && i < fo->pulse_count; ++i) {
        o->pulse_us[i] = fo->pulse_us[i];
    }
    o->law = fo->law;
    o->throttle = fo->throttle;
    o->pitch_cmd = fo->pitch_cmd;
    o->servo_clamped = fo->servo_clamped;
}

/* --- frames ---------------------------------------------------------------- */

void hil_sensors_parse(const uint8_t *p, uint32_t *seq, hil_step_in_t *in)
{
    *seq = get_u32(&p[0]);
    in->imu.down_q14[0] = hil_get_i16(&p[4]);
    in->imu.down_q14[1] = hil_get_i16(&p[6]);
    in->imu.down_q14[2] = hil_get_i16(&p[8]);
    in->imu.gyro_q11_rad_s[0] = hil_get_i16(&p[10]);
    in->imu.gyro_q11_rad_s[1] = hil_get_i16(&p[12]);
    in->imu.gyro_q11_rad_s[2] = hil_get_i16(&p[14]);
    in->imu.airspeed_cm_s = hil_get_i16(&p[16]);
    in->altitude_cm = hil_get_i32(&p[18]);
    in->climb_cm_s = hil_get_i32(&p[22]);
    in->turn_rate_rad_s = hil_get_i16(&p[26]);
    in->pitch_ratio = hil_get_i32(&p[28]);
    in->altitude_cmd_cm = hil_get_i32(&p[32]);
    in->airspeed_cmd_cm_s = hil_get_i16(&p[36]);
    in->throttle = hil_get_i16(&p[38]);
    in->flags = p[40];
}

void hil_sensors_write(uint8_t *p, uint32_t seq, const hil_step_in_t *in)
{
    put_u32(&p[0], seq);
    hil_put_i16(&p[4], in->imu.down_q14[0]);
    hil_put_i16(&p[6], in->imu.down_q14[1]);
    hil_put_i16(&p[8], in->imu.down_q14[2]);
    hil_put_i16(&p[10], in->imu.gyro_q11_rad_s[0]);
    hil_put_i16(&p[12], in->imu.gyro_q11_rad_s[1]);
    hil_put_i16(&p[14], in->imu.gyro_q11_rad_s[2]);
    hil_put_i16(&p[16], in->imu.airspeed_cm_s);
    hil_put_i32(&p[18], in->altitude_cm);
    hil_put_i32(&p[22], in->climb_cm_s);
    hil_put_i16(&p[26], in->turn_rate_rad_s);
    hil_put_i32(&p[28], in->pitch_ratio);
    hil_put_i32(&p[32], in->altitude_cmd_cm);
    hil_put_i16(&p[36], in->airspeed_cmd_cm_s);
    hil_put_i16(&p[38], in->throttle);
    p[40] = in->flags;
}

/* One step on a SENSORS frame: the pulses go to the timer, and the answer
 * carries what the timer now holds (read back), the output stage's pulses
 * and the law's intermediates. */
static void on_sensors(hil_fw_t *h)
{
    uint32_t seq = 0u;
    hil_sensors_parse(h->rx.payload, &seq, &h->in);
    if ((h->in.flags & (uint8_t)~HIL_SF_ALL) != 0u) {
        nak(h, (uint8_t)HIL_ID_SENSORS, (uint8_t)HIL_NAK_BAD_FIELD);
        return;
    }
    if (h->started == 0u) {
        nak(h, (uint8_t)HIL_ID_SENSORS, (uint8_t)HIL_NAK_NOT_STARTED);
        return;
    }
    hil_fw_step(h, &h->in, &h->res);
    for (uint8_t i = 0; i < h->fw_out.pulse_count; ++i) {
        (void)board_servo_write_us(i, h->fw_out.pulse_us[i]);
    }
    board_servo_commit();
    h->steps++;

    uint8_t *p = h->payload;
    const hil_step_out_t *o = &h->res;
    put_u32(&p[0], seq);
    for (uint8_t i = 0; i < HIL_OUT_CHANNELS; ++i) {
        hil_put_u16(&p[4u + 2u * i], hil_servo_readback_us(i));
        hil_put_u16(&p[12u + 2u * i], o->pulse_us[i]);
    }
    hil_put_i16(&p[20], o->law.aileron);
    hil_put_i16(&p[22], o->law.elevator);
    hil_put_i16(&p[24], o->law.rudder);
    hil_put_i32(&p[26], o->pitch_cmd);
    hil_put_i16(&p[30], o->throttle);
    hil_put_i16(&p[32], o->law.turn_rate_used_rad_s);
    hil_put_i16(&p[34], o->law.roll_error);
    hil_put_i16(&p[36], o->law.pitch_error);
    hil_put_u16(&p[38], (uint16_t)(o->law.flags | (o->servo_clamped ? 0x100u : 0u)));
    send(h, (uint8_t)HIL_ID_OUTPUT, (uint8_t)HIL_LEN_OUTPUT);
}

void hil_fw_on_byte(hil_fw_t *h, uint8_t byte)
{
    if (!hil_decoder_push(&h->rx, byte)) {
        return; /* no frame yet, or a bad one (counted by the decoder) */
    }
    const uint8_t *p = h->rx.payload;
    switch (h->rx.id) {
    case HIL_ID_HELLO:
        hil_fw_send_ready(h);
        break;
    case HIL_ID_CFG_LAW:
        h->started = 0u;
        cfg_law(h, p);
        break;
    case HIL_ID_CFG_ALT:
        h->started = 0u;
        cfg_alt(h, p);
        break;
    case HIL_ID_CFG_SPD:
        h->started = 0u;
        cfg_spd(h, p);
        break;
    case HIL_ID_CFG_OUT:
        h->started = 0u;
        cfg_out(h, p);
        break;
    case HIL_ID_START:
        start(h);
        break;
    case HIL_ID_SENSORS:
        on_sensors(h);
        break;
    default:
        break; /* the decoder's table admits no other id */
    }
}
