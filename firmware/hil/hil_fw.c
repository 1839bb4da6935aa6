/*
 * hil_fw.c - the firmware side of the HIL link (see hil_fw.h and
 * docs/hil-protocol.md). Integer only; no dynamic memory; every buffer is in
 * the caller's hil_fw_t.
 */
#include "hil/hil_fw.h"

#include <string.h>

#define HAVE_LAW 0x01u
#define HAVE_ALT 0x02u
#define HAVE_SPD 0x04u
#define HAVE_OUT 0x08u
#define HAVE_EST 0x10u

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
    h->rx_len[HIL_ID_CFG_EST] = HIL_LEN_CFG_EST;
    h->rx_len[HIL_ID_SENSORS] = HIL_LEN_SENSORS;
    h->rx_len[HIL_ID_STEP] = HIL_LEN_STEP;
    h->rx_len[HIL_ID_TRUTH] = HIL_LEN_TRUTH;
    h->rx_len[HIL_ID_IMU] = HIL_LEN_IMU;
    const hil_msg_table_t table = {h->rx_len, (uint8_t)HIL_ID_HOST_COUNT};
    hil_decoder_init(&h->rx, table);
    fw_config_default(&h->cfg);
    /* the receiver of the host it mirrors: the SIL board's scripted one
     * (boards/sil SIL_RC_COUNT; test_hil_fw compares the configurations) */
    h->cfg.modes.rc_channels = 8u;
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

/* --- CFG_LAW, CFG_EST, CFG_ALT, CFG_SPD: the table's rows in order ------- */

/* One field of a table format on the wire (little-endian). */
#define GET_Q16(p)     hil_get_i32(p)
#define GET_CM32(p)    hil_get_i32(p)
#define GET_CM16(p)    hil_get_i16(p)
#define GET_U8(p)      (*(p))
#define GET_U16(p)     hil_get_u16(p)
#define GET_Q14(p)     hil_get_i16(p)
#define GET_MS16(p)    hil_get_u16(p)
#define PUT_Q16(p, v)  hil_put_i32((p), (v))
#define PUT_CM32(p, v) hil_put_i32((p), (v))
#define PUT_CM16(p, v) hil_put_i16((p), (v))
#define PUT_U8(p, v)   (*(p) = (v))
#define PUT_U16(p, v)  hil_put_u16((p), (v))
#define PUT_Q14(p, v)  hil_put_i16((p), (v))
#define PUT_MS16(p, v) hil_put_u16((p), (v))

#define ROW_GET(id, name, field, unit, fmt, lo, hi, def, desc)                                     \
    s->field = GET_##fmt(&p[off]);                                                                 \
    off += HT_PFMT_BYTES_##fmt;
#define ROW_PUT(id, name, field, unit, fmt, lo, hi, def, desc)                                     \
    PUT_##fmt(&p[off], s->field);                                                                  \
    off += HT_PFMT_BYTES_##fmt;

_Static_assert(HIL_LEN_CFG_LAW <= HIL_PAYLOAD_MAX,
               "the law's rows no longer fit one CFG_LAW frame: split it (docs/parameters.md)");
_Static_assert(HIL_LEN_CFG_EST <= HIL_PAYLOAD_MAX,
               "the estimator's rows no longer fit one CFG_EST frame: split it");
_Static_assert(HIL_LEN_CFG_ALT <= HIL_PAYLOAD_MAX,
               "the altitude hold's rows no longer fit one CFG_ALT frame: split it");
_Static_assert(HIL_LEN_CFG_SPD <= HIL_PAYLOAD_MAX,
               "the airspeed hold's rows no longer fit one CFG_SPD frame: split it");

void hil_cfg_law_write(uint8_t *p, const ht_params_t *s)
{
    unsigned off = 0u;
    HT_PARAMS_LAW(ROW_PUT)
    (void)off;
}

void hil_cfg_law_parse(const uint8_t *p, ht_params_t *s)
{
    unsigned off = 0u;
    HT_PARAMS_LAW(ROW_GET)
    (void)off;
}

/* The guidance's rows, in CFG_EST after the timing (ROW_* read s). */
static unsigned guide_put(uint8_t *p, unsigned start, const ht_guide_params_t *s)
{
    unsigned off = start;
    HT_PARAMS_GUIDE(ROW_PUT)
    return off;
}

static unsigned guide_get(const uint8_t *p, unsigned start, ht_guide_params_t *s)
{
    unsigned off = start;
    HT_PARAMS_GUIDE(ROW_GET)
    return off;
}

/* The estimator and the IMU timing, as the SIL host board sets them (the
 * divider is given, not derived: fw_init checks that it agrees with the
 * rates), then the guidance. */
void hil_cfg_est_write(uint8_t *p, const fw_config_t *c)
{
    const ht_dcm_params_t *s = &c->dcm;
    unsigned off = 0u;
    HT_PARAMS_DCM(ROW_PUT)
    hil_put_u16(&p[off], c->control_divider);
    hil_put_u16(&p[off + 2u], c->imu_timeout_samples);
    (void)guide_put(p, off + 4u, &c->guide);
}

void hil_cfg_est_parse(const uint8_t *p, fw_config_t *c)
{
    ht_dcm_params_t *s = &c->dcm;
    unsigned off = 0u;
    HT_PARAMS_DCM(ROW_GET)
    c->control_divider = hil_get_u16(&p[off]);
    c->imu_timeout_samples = hil_get_u16(&p[off + 2u]);
    (void)guide_get(p, off + 4u, &c->guide);
}

/* The altitude hold's rows, its rate and the initial integrators. */
void hil_cfg_alt_write(uint8_t *p, const fw_config_t *c)
{
    const ht_alt_hold_params_t *s = &c->modes.alt;
    unsigned off = 0u;
    HT_PARAMS_ALT(ROW_PUT)
    hil_put_u16(&p[off], s->rate_hz);
    hil_put_i32(&p[off + 2u], c->alt_integral_q20[0]);
    hil_put_i32(&p[off + 6u], c->alt_integral_q20[1]);
}

void hil_cfg_alt_parse(const uint8_t *p, fw_config_t *c)
{
    ht_alt_hold_params_t *s = &c->modes.alt;
    unsigned off = 0u;
    HT_PARAMS_ALT(ROW_GET)
    s->rate_hz = hil_get_u16(&p[off]);
    c->alt_integral_q20[0] = hil_get_i32(&p[off + 2u]);
    c->alt_integral_q20[1] = hil_get_i32(&p[off + 6u]);
}

/* The airspeed hold's rows and its rate. */
void hil_cfg_spd_write(uint8_t *p, const fw_config_t *c)
{
    const ht_speed_hold_params_t *s = &c->modes.speed;
    unsigned off = 0u;
    HT_PARAMS_SPEED(ROW_PUT)
    hil_put_u16(&p[off], s->rate_hz);
}

void hil_cfg_spd_parse(const uint8_t *p, fw_config_t *c)
{
    ht_speed_hold_params_t *s = &c->modes.speed;
    unsigned off = 0u;
    HT_PARAMS_SPEED(ROW_GET)
    s->rate_hz = hil_get_u16(&p[off]);
}

static void cfg_law(hil_fw_t *h, const uint8_t *p)
{
    hil_cfg_law_parse(p, &h->cfg.law);
    h->have |= HAVE_LAW;
}

static void cfg_alt(hil_fw_t *h, const uint8_t *p)
{
    hil_cfg_alt_parse(p, &h->cfg);
    h->have |= HAVE_ALT;
}

static void cfg_spd(hil_fw_t *h, const uint8_t *p)
{
    hil_cfg_spd_parse(p, &h->cfg);
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

static void cfg_est(hil_fw_t *h, const uint8_t *p)
{
    hil_cfg_est_parse(p, &h->cfg);
    h->have |= HAVE_EST;
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
        if (fw->modes_bad.field == HT_MODES_P_ALT_HOLD ||
            fw->modes_bad.field == HT_MODES_P_SPEED_HOLD) {
            /* the row id (ht_alt/speed_param_id_t); its COUNT is rate_hz */
            detail = (uint8_t)fw->modes_bad.sub;
        }
        break;
    case FW_BAD_OUTPUT:
        block = (uint8_t)HIL_ID_CFG_OUT;
        detail = (uint8_t)fw->bad_sub;
        break;
    case FW_BAD_DCM:
        block = (uint8_t)HIL_ID_CFG_EST;
        detail = (uint8_t)fw->bad_sub; /* ht_dcm_param_id_t */
        break;
    case FW_BAD_DIVIDER: /* the divider does not agree with the rates */
        block = (uint8_t)HIL_ID_CFG_EST;
        detail = (uint8_t)HIL_EST_BAD_DIVIDER;
        break;
    case FW_BAD_TIMEOUT:
        block = (uint8_t)HIL_ID_CFG_EST;
        detail = (uint8_t)HIL_EST_BAD_TIMEOUT;
        break;
    case FW_BAD_GUIDE:
        block = (uint8_t)HIL_ID_CFG_EST;
        detail = (uint8_t)(HIL_EST_BAD_GUIDE + (uint32_t)fw->bad_sub); /* ht_guide_param_id_t */
        break;
    default:
        break; /* the upset guard follows CFG_ALT's rate */
    }
    ack(h, (uint8_t)HIL_ACK_REFUSED, block, detail);
}

/* Check everything staged, then put it in force with fresh states (the
 * altitude integrators from CFG_ALT, clamped as every host does). */
static void start(hil_fw_t *h)
{
    static const uint8_t block_id[5] = {HIL_ID_CFG_LAW, HIL_ID_CFG_ALT, HIL_ID_CFG_SPD,
                                        HIL_ID_CFG_OUT, HIL_ID_CFG_EST};
    h->started = 0u;
    h->step_open = 0u;
    for (unsigned i = 0; i < 5u; ++i) {
        if ((h->have & (1u << i)) == 0u) {
            ack(h, (uint8_t)HIL_ACK_MISSING, block_id[i], block_id[i]);
            return;
        }
    }
    if (h->cfg.out.count > board_servo_count()) {
        ack(h, (uint8_t)HIL_ACK_REFUSED, (uint8_t)HIL_ID_CFG_OUT, h->cfg.out.count);
        return;
    }
    h->cfg.modes.rate_hz = h->cfg.modes.alt.rate_hz; /* the control rate, as the SIL's */
    if (fw_init(&h->fw, &h->cfg) == 0) {
        refused(h);
        return;
    }
    h->steps = 0u;
    h->started = 1u;
    ack(h, (uint8_t)HIL_ACK_OK, (uint8_t)HIL_ID_START, 0u);
}

/* --- frames ---------------------------------------------------------------- */

void hil_step_write(uint8_t *p, const hil_step_t *s)
{
    const board_sensors_t *b = &s->sensors;
    const fw_guided_t *g = &s->guided;
    put_u32(&p[0], s->seq);
    p[4] = s->flags;
    p[5] = s->imu_count;
    p[6] = b->gps.fix;
    p[7] = (uint8_t)(((b->gps.fresh != 0u) ? HIL_FRESH_GPS : 0u) |
                     ((b->airspeed_fresh != 0u) ? HIL_FRESH_AIRSPEED : 0u) |
                     ((b->baro_fresh != 0u) ? HIL_FRESH_BARO : 0u));
    hil_put_i32(&p[8], b->gps.lat_e7);
    hil_put_i32(&p[12], b->gps.lon_e7);
    hil_put_i32(&p[16], b->gps.alt_cm);
    for (unsigned k = 0u; k < 3u; ++k) {
        hil_put_i32(&p[20u + 4u * k], b->gps.vel_ned_cm_s[k]);
    }
    hil_put_i16(&p[32], b->airspeed_cm_s);
    hil_put_i32(&p[34], b->baro_alt_cm);
    hil_put_i16(&p[38], g->turn_rate_rad_s);
    hil_put_i32(&p[40], g->pitch_ratio);
    hil_put_i32(&p[44], g->altitude_cm);
    hil_put_i16(&p[48], g->airspeed_cm_s);
    hil_put_i16(&p[50], g->throttle);
}

/* Reserved bits are kept in the struct (the caller refuses them); the
 * command's switches come from the flags. */
void hil_step_parse(const uint8_t *p, hil_step_t *s)
{
    (void)memset(s, 0, sizeof *s);
    board_sensors_t *b = &s->sensors;
    fw_guided_t *g = &s->guided;
    s->seq = get_u32(&p[0]);
    s->flags = p[4];
    s->imu_count = p[5];
    b->gps.fix = p[6];
    s->fresh = p[7];
    b->gps.fresh = ((s->fresh & HIL_FRESH_GPS) != 0u) ? 1u : 0u;
    b->airspeed_fresh = ((s->fresh & HIL_FRESH_AIRSPEED) != 0u) ? 1u : 0u;
    b->baro_fresh = ((s->fresh & HIL_FRESH_BARO) != 0u) ? 1u : 0u;
    b->gps.lat_e7 = hil_get_i32(&p[8]);
    b->gps.lon_e7 = hil_get_i32(&p[12]);
    b->gps.alt_cm = hil_get_i32(&p[16]);
    for (unsigned k = 0u; k < 3u; ++k) {
        b->gps.vel_ned_cm_s[k] = hil_get_i32(&p[20u + 4u * k]);
    }
    b->airspeed_cm_s = hil_get_i16(&p[32]);
    b->baro_alt_cm = hil_get_i32(&p[34]);
    g->turn_rate_rad_s = hil_get_i16(&p[38]);
    g->pitch_ratio = hil_get_i32(&p[40]);
    g->altitude_cm = hil_get_i32(&p[44]);
    g->airspeed_cm_s = hil_get_i16(&p[48]);
    g->throttle = hil_get_i16(&p[50]);
    g->altitude_hold = ((s->flags & HIL_SF_ALTITUDE_HOLD) != 0u) ? 1u : 0u;
    g->speed_hold = ((s->flags & HIL_SF_SPEED_HOLD) != 0u) ? 1u : 0u;
    g->inverted = ((s->flags & HIL_SF_INVERTED) != 0u) ? 1u : 0u;
    g->pitch_mode = ((s->flags & HIL_SF_TILT_CROSS) != 0u) ? 1u : 0u;
}

void hil_truth_write(uint8_t *p, const fw_nav_t *n)
{
    for (unsigned k = 0u; k < 3u; ++k) {
        hil_put_i16(&p[(size_t)2u * k], n->down_q14[k]);
        hil_put_i16(&p[6u + 2u * k], n->gyro_q11_rad_s[k]);
    }
    hil_put_i16(&p[12], n->airspeed_cm_s);
    hil_put_i32(&p[14], n->altitude_cm);
    hil_put_i32(&p[18], n->climb_cm_s);
    hil_put_i32(&p[22], n->north_cm);
    hil_put_i32(&p[26], n->east_cm);
    hil_put_i32(&p[30], n->vel_north_cm_s);
    hil_put_i32(&p[34], n->vel_east_cm_s);
    hil_put_i16(&p[38], n->heading_north);
    hil_put_i16(&p[40], n->heading_east);
}

void hil_truth_parse(const uint8_t *p, fw_nav_t *n)
{
    (void)memset(n, 0, sizeof *n);
    for (unsigned k = 0u; k < 3u; ++k) {
        n->down_q14[k] = hil_get_i16(&p[(size_t)2u * k]);
        n->gyro_q11_rad_s[k] = hil_get_i16(&p[6u + 2u * k]);
    }
    n->airspeed_cm_s = hil_get_i16(&p[12]);
    n->altitude_cm = hil_get_i32(&p[14]);
    n->climb_cm_s = hil_get_i32(&p[18]);
    n->north_cm = hil_get_i32(&p[22]);
    n->east_cm = hil_get_i32(&p[26]);
    n->vel_north_cm_s = hil_get_i32(&p[30]);
    n->vel_east_cm_s = hil_get_i32(&p[34]);
    n->heading_north = hil_get_i16(&p[38]);
    n->heading_east = hil_get_i16(&p[40]);
}

void hil_imu_write(uint8_t *p, const ht_imu_sample_t *s)
{
    for (unsigned k = 0u; k < 3u; ++k) {
        hil_put_i32(&p[(size_t)4u * k], s->gyro_rad_s[k]);
        hil_put_i32(&p[12u + 4u * k], s->accel_g[k]);
    }
}

void hil_imu_parse(const uint8_t *p, ht_imu_sample_t *s)
{
    for (unsigned k = 0u; k < 3u; ++k) {
        s->gyro_rad_s[k] = hil_get_i32(&p[(size_t)4u * k]);
        s->accel_g[k] = hil_get_i32(&p[12u + 4u * k]);
    }
}

void hil_state_write(uint8_t *p, const hil_state_t *s)
{
    const ht_dcm_output_t *e = &s->est;
    const fw_nav_t *n = &s->nav;
    put_u32(&p[0], s->seq);
    p[4] = s->flags;
    for (unsigned k = 0u; k < 3u; ++k) {
        hil_put_i16(&p[5u + 2u * k], e->r[2][k]);
        hil_put_i32(&p[17u + 4u * k], e->gyro_bias_rad_s[k]);
        hil_put_i16(&p[31u + 2u * k], n->down_q14[k]);
    }
    hil_put_i16(&p[11], e->roll_cdeg);
    hil_put_i16(&p[13], e->pitch_cdeg);
    hil_put_u16(&p[15], e->yaw_cdeg);
    hil_put_u16(&p[29], e->flags);
    hil_put_i16(&p[37], n->airspeed_cm_s);
    hil_put_i32(&p[39], n->altitude_cm);
    hil_put_i32(&p[43], n->climb_cm_s);
    hil_put_i32(&p[47], n->north_cm);
    hil_put_i32(&p[51], n->east_cm);
}

/* The fields STATE carries; the rest of *s is zero. */
void hil_state_parse(const uint8_t *p, hil_state_t *s)
{
    (void)memset(s, 0, sizeof *s);
    ht_dcm_output_t *e = &s->est;
    fw_nav_t *n = &s->nav;
    s->seq = get_u32(&p[0]);
    s->flags = p[4];
    for (unsigned k = 0u; k < 3u; ++k) {
        e->r[2][k] = hil_get_i16(&p[5u + 2u * k]);
        e->gyro_bias_rad_s[k] = hil_get_i32(&p[17u + 4u * k]);
        n->down_q14[k] = hil_get_i16(&p[31u + 2u * k]);
    }
    e->roll_cdeg = hil_get_i16(&p[11]);
    e->pitch_cdeg = hil_get_i16(&p[13]);
    e->yaw_cdeg = hil_get_u16(&p[15]);
    e->flags = hil_get_u16(&p[29]);
    n->airspeed_cm_s = hil_get_i16(&p[37]);
    n->altitude_cm = hil_get_i32(&p[39]);
    n->climb_cm_s = hil_get_i32(&p[43]);
    n->north_cm = hil_get_i32(&p[47]);
    n->east_cm = hil_get_i32(&p[51]);
}

/* --- the control step ------------------------------------------------------ */

/* One call of the firmware step with the open step's inputs. The slow
 * sensors' values hold for the whole step; their fresh flags and the truth
 * solution go with the last sample only (as in sil_board_step). */
static void call_step(hil_fw_t *h, const ht_imu_sample_t *imu, uint8_t last)
{
    fw_inputs_t *fi = &h->fw_in;
    const board_sensors_t *b = &h->step.sensors;
    (void)memset(fi, 0, sizeof *fi);
    fi->sensors = h->step.sensors;
    fi->sensors.imu_fresh = (imu != NULL) ? 1u : 0u;
    if (imu != NULL) {
        fi->sensors.imu = *imu;
    }
    fi->sensors.gps.fresh = (last != 0u) ? b->gps.fresh : 0u;
    fi->sensors.airspeed_fresh = (last != 0u) ? b->airspeed_fresh : 0u;
    fi->sensors.baro_fresh = (last != 0u) ? b->baro_fresh : 0u;
    fi->guided = &h->step.guided;
    fi->external = (last != 0u && (h->step.flags & HIL_SF_USE_TRUTH) != 0u) ? &h->truth : NULL;
    if (fw_step(&h->fw, fi, &h->fw_out) != 0) {
        h->step_ran = 1u;
    }
}

/* STEP: check it and open the control step (an unfinished one is dropped:
 * its samples have run, nothing is undone). */
static void on_step(hil_fw_t *h)
{
    h->step_open = 0u;
    hil_step_parse(h->rx.payload, &h->step);
    const hil_step_t *s = &h->step;
    if ((s->flags & (uint8_t)~HIL_SF_ALL) != 0u || s->imu_count > HIL_IMU_MAX ||
        s->sensors.gps.fix > 3u || (s->fresh & (uint8_t)~HIL_FRESH_ALL) != 0u) {
        nak(h, (uint8_t)HIL_ID_STEP, (uint8_t)HIL_NAK_BAD_FIELD);
        return;
    }
    if (h->started == 0u) {
        nak(h, (uint8_t)HIL_ID_STEP, (uint8_t)HIL_NAK_NOT_STARTED);
        return;
    }
    h->step_open = 1u;
    h->step_broken = 0u;
    h->step_truth = 0u;
    h->step_ran = 0u;
    h->step_imu = 0u;
}

/* TRUTH: only inside a step that flies on it (else the step is broken). */
static void on_truth(hil_fw_t *h)
{
    if (h->step_open == 0u || (h->step.flags & (HIL_SF_USE_TRUTH | HIL_SF_ALIGN)) == 0u) {
        h->step_broken = 1u;
        return;
    }
    hil_truth_parse(h->rx.payload, &h->truth);
    h->step_truth = 1u;
    if ((h->step.flags & HIL_SF_ALIGN) != 0u) {
        (void)fw_align(&h->fw, &h->truth); /* before the step's first sample, as the SIL */
    }
}

/* IMU: one sample, stepped now (not answered); beyond imu_count - 1 samples,
 * or outside a step, it is not stepped and the step is broken. */
static void on_imu(hil_fw_t *h)
{
    if (h->step_open == 0u || h->step_broken != 0u ||
        (uint32_t)h->step_imu + 1u >= (uint32_t)h->step.imu_count) {
        h->step_broken = 1u;
        return;
    }
    ht_imu_sample_t imu;
    hil_imu_parse(h->rx.payload, &imu);
    call_step(h, &imu, 0u);
    h->step_imu++;
}

/* SENSORS: the last sample closes the step; the pulses go to the timer, and
 * the answer is STATE (the estimate, the solution flown) and OUTPUT (what the
 * timer now holds, read back, the output stage's pulses, the law's
 * intermediates). */
static void on_sensors(hil_fw_t *h)
{
    const uint32_t seq = get_u32(&h->rx.payload[0]);
    if (h->started == 0u) {
        nak(h, (uint8_t)HIL_ID_SENSORS, (uint8_t)HIL_NAK_NOT_STARTED);
        return;
    }
    const hil_step_t *s = &h->step;
    const uint8_t want_imu = (s->imu_count > 0u) ? (uint8_t)(s->imu_count - 1u) : 0u;
    const uint8_t want_truth = ((s->flags & (HIL_SF_USE_TRUTH | HIL_SF_ALIGN)) != 0u) ? 1u : 0u;
    if (h->step_open == 0u || h->step_broken != 0u || seq != s->seq || h->step_imu != want_imu ||
        h->step_truth != want_truth) {
        h->step_open = 0u;
        nak(h, (uint8_t)HIL_ID_SENSORS, (uint8_t)HIL_NAK_SEQUENCE);
        return;
    }
    h->step_open = 0u;
    if (s->imu_count > 0u) {
        ht_imu_sample_t imu;
        hil_imu_parse(&h->rx.payload[4], &imu);
        call_step(h, &imu, 1u);
    } else {
        /* no sample: one control period of calls without one (the firmware
         * counts the gap), as the SIL host board does */
        const uint16_t calls = h->cfg.control_divider;
        for (uint16_t k = 0u; k < calls; ++k) {
            call_step(h, NULL, (k + 1u == calls) ? 1u : 0u);
        }
    }
    const fw_output_t *fo = &h->fw_out;
    if (h->step_ran != 0u) {
        for (uint8_t i = 0; i < fo->pulse_count; ++i) {
            (void)board_servo_write_us(i, fo->pulse_us[i]);
        }
        board_servo_commit();
    }
    h->steps++;

    hil_state_t *st = &h->state;
    st->seq = seq;
    st->flags = (uint8_t)(((h->step_ran != 0u) ? HIL_ST_CONTROL_RAN : 0u) |
                          ((fo->failsafe != 0u) ? HIL_ST_FAILSAFE : 0u) |
                          ((fo->guard_engaged != 0u) ? HIL_ST_GUARD_ENGAGED : 0u));
    st->est = fo->est;
    st->nav = fo->nav;
    hil_state_write(h->payload, st);
    send(h, (uint8_t)HIL_ID_STATE, (uint8_t)HIL_LEN_STATE);

    uint8_t *p = h->payload;
    put_u32(&p[0], seq);
    for (uint8_t i = 0; i < HIL_OUT_CHANNELS; ++i) {
        hil_put_u16(&p[4u + 2u * i], hil_servo_readback_us(i));
        hil_put_u16(&p[12u + 2u * i], (i < fo->pulse_count) ? fo->pulse_us[i] : 0u);
    }
    hil_put_i16(&p[20], fo->law.aileron);
    hil_put_i16(&p[22], fo->law.elevator);
    hil_put_i16(&p[24], fo->law.rudder);
    hil_put_i32(&p[26], fo->pitch_cmd);
    hil_put_i16(&p[30], fo->throttle);
    hil_put_i16(&p[32], fo->law.turn_rate_used_rad_s);
    hil_put_i16(&p[34], fo->law.roll_error);
    hil_put_i16(&p[36], fo->law.pitch_error);
    hil_put_u16(&p[38], (uint16_t)(fo->law.flags | ((fo->servo_clamped != 0u) ? 0x100u : 0u)));
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
    case HIL_ID_CFG_EST:
        h->started = 0u;
        cfg_est(h, p);
        break;
    case HIL_ID_START:
        start(h);
        break;
    case HIL_ID_STEP:
        on_step(h);
        break;
    case HIL_ID_TRUTH:
        on_truth(h);
        break;
    case HIL_ID_IMU:
        on_imu(h);
        break;
    case HIL_ID_SENSORS:
        on_sensors(h);
        break;
    default:
        break; /* the decoder's table admits no other id */
    }
}
