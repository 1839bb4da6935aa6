/*
 * fw_log.c - the flight log writer (fw_log.h): records into the ring, the
 * ring to the sink within the tick's byte budget.
 */
#include "log/fw_log.h"

#include "helical/math/f32_bits.h"

/* Whole records or nothing: a torn record would desynchronise a reader
 * until its next header. */
static int ring_put(fw_log_t *log, const uint8_t *rec, size_t n)
{
    if ((size_t)(log->cfg.ring_size - log->used) < n) {
        ++log->dropped;
        return -1;
    }
    for (size_t i = 0u; i < n; ++i) {
        log->cfg.ring[log->head] = rec[i];
        ++log->head;
        if (log->head == log->cfg.ring_size) {
            log->head = 0u;
        }
    }
    log->used += (uint32_t)n;
    ++log->records;
    return 0;
}

static int ring_room(const fw_log_t *log, size_t n)
{
    return (size_t)(log->cfg.ring_size - log->used) >= n;
}

/* Offer at most limit bytes, in the ring's contiguous pieces; stop at the
 * first piece the sink does not take whole. */
static void ring_drain(fw_log_t *log, uint32_t limit)
{
    uint32_t left = limit;
    while ((left > 0u) && (log->used > 0u)) {
        uint32_t piece = log->cfg.ring_size - log->tail; /* up to the wrap */
        if (piece > log->used) {
            piece = log->used;
        }
        if (piece > left) {
            piece = left;
        }
        size_t took = log->cfg.write(log->cfg.write_ctx, &log->cfg.ring[log->tail], piece);
        if (took > piece) {
            took = piece; /* a sink that claims more than offered: believe the offer */
        }
        log->tail += (uint32_t)took;
        if (log->tail == log->cfg.ring_size) {
            log->tail = 0u;
        }
        log->used -= (uint32_t)took;
        log->written += (uint32_t)took;
        left -= (uint32_t)took;
        if (took < piece) {
            ++log->stalls;
            break;
        }
    }
}

int fw_log_init(fw_log_t *log, const fw_log_config_t *cfg)
{
    if (log == NULL) {
        return -1;
    }
    *log = (fw_log_t){0};
    if ((cfg == NULL) || (cfg->ring == NULL) || (cfg->write == NULL) ||
        (cfg->ring_size < 2u * FW_LOG_REC_MAX) || (cfg->budget_bytes < 1u) ||
        (cfg->decimation < 1u)) {
        return -1;
    }
    log->cfg = *cfg;
    log->last_mode = UINT8_MAX; /* the first step logs its mode */
    log->ready = 1u;
    return 0;
}

/* The header, as far as the ring has room: FMT records, the MSG, PARMs. */
static void queue_header(fw_log_t *log, uint64_t time_us)
{
    uint8_t rec[FW_LOG_REC_MAX];
    fw_log_rec_t r;
    while (log->fmt_next < (uint16_t)FW_LOG_KIND_COUNT) {
        if (!ring_room(log, FW_LOG_FMT_LEN)) {
            return;
        }
        (void)fw_log_fmt_record((fw_log_kind_t)log->fmt_next, rec);
        (void)ring_put(log, rec, FW_LOG_FMT_LEN);
        ++log->fmt_next;
    }
    if (log->fmt_next == (uint16_t)FW_LOG_KIND_COUNT) {
        const fw_log_format_t *f = fw_log_format(FW_LOG_MSG);
        if (!ring_room(log, f->length)) {
            return;
        }
        fw_log_rec_begin(&r, rec, f->type);
        fw_log_put_u64(&r, time_us);
        fw_log_put_text(&r, "helical flight log (docs/flight-log.md)", 64u);
        (void)ring_put(log, rec, r.n);
        ++log->fmt_next;
    }
    const fw_log_format_t *pf = fw_log_format(FW_LOG_PARM);
    while (log->cfg.param != NULL) {
        char name[17] = {0};
        int32_t raw = 0;
        int32_t scale = 1;
        if (log->cfg.param(log->cfg.param_ctx, log->parm_next, name, &raw, &scale) != 0) {
            break;
        }
        if (!ring_room(log, pf->length)) {
            return;
        }
        name[16] = '\0';
        fw_log_rec_begin(&r, rec, pf->type);
        fw_log_put_u64(&r, time_us);
        fw_log_put_text(&r, name, 16u);
        fw_log_put_u32(&r, ht_f32_from_ratio(raw, (scale > 0) ? (uint32_t)scale : 1u));
        (void)ring_put(log, rec, r.n);
        ++log->parm_next;
    }
    log->header_done = 1u;
}

static void put_event(fw_log_t *log, uint64_t time_us, uint8_t id)
{
    uint8_t rec[FW_LOG_REC_MAX];
    fw_log_rec_t r;
    fw_log_rec_begin(&r, rec, fw_log_format(FW_LOG_EV)->type);
    fw_log_put_u64(&r, time_us);
    fw_log_put_u8(&r, id);
    (void)ring_put(log, rec, r.n);
}

/* A flag's change is an event (on, off). */
static void edge(fw_log_t *log, uint64_t time_us, uint8_t *last, uint8_t now, uint8_t on_id)
{
    const uint8_t v = (now != 0u) ? 1u : 0u;
    if (v != *last) {
        put_event(log, time_us, (v != 0u) ? on_id : (uint8_t)(on_id + 1u));
        *last = v;
    }
}

static void queue_events(fw_log_t *log, uint64_t time_us, const fw_inputs_t *in,
                         const fw_output_t *out)
{
    const uint8_t mode = (in->guided != NULL) ? (uint8_t)FW_LOG_MODE_GUIDED : out->modes.mode;
    if (mode != log->last_mode) {
        uint8_t rec[FW_LOG_REC_MAX];
        fw_log_rec_t r;
        fw_log_rec_begin(&r, rec, fw_log_format(FW_LOG_MODE)->type);
        fw_log_put_u64(&r, time_us);
        fw_log_put_u8(&r, mode);
        fw_log_put_u8(&r, mode);
        fw_log_put_u8(&r, out->modes.failsafe); /* reason: 1 = the RC-loss failsafe */
        if (ring_put(log, rec, r.n) == 0) {
            log->last_mode = mode;
        }
    }
    edge(log, time_us, &log->last_imu_fs, out->failsafe, FW_LOG_EV_IMU_FAILSAFE_ON);
    edge(log, time_us, &log->last_rc_fs, out->modes.failsafe, FW_LOG_EV_RC_FAILSAFE_ON);
    edge(log, time_us, &log->last_guard, out->guard_engaged, FW_LOG_EV_GUARD_ON);
}

static void queue_sensors(fw_log_t *log, uint64_t t, const board_sensors_t *s)
{
    uint8_t rec[FW_LOG_REC_MAX];
    fw_log_rec_t r;
    fw_log_rec_begin(&r, rec, fw_log_format(FW_LOG_IMU)->type);
    fw_log_put_u64(&r, t);
    for (unsigned i = 0u; i < 3u; ++i) {
        fw_log_put_i32(&r, s->imu.gyro_rad_s[i]);
    }
    for (unsigned i = 0u; i < 3u; ++i) {
        fw_log_put_i32(&r, s->imu.accel_g[i]);
    }
    (void)ring_put(log, rec, r.n);

    fw_log_rec_begin(&r, rec, fw_log_format(FW_LOG_GPS)->type);
    fw_log_put_u64(&r, t);
    fw_log_put_u8(&r, s->gps.fix);
    fw_log_put_u32(&r, 0u); /* GMS: no GPS time on the board seam */
    fw_log_put_u16(&r, 0u); /* GWk */
    fw_log_put_i32(&r, s->gps.lat_e7);
    fw_log_put_i32(&r, s->gps.lon_e7);
    fw_log_put_i32(&r, s->gps.alt_cm);
    for (unsigned i = 0u; i < 3u; ++i) {
        fw_log_put_i32(&r, s->gps.vel_ned_cm_s[i]);
    }
    (void)ring_put(log, rec, r.n);

    fw_log_rec_begin(&r, rec, fw_log_format(FW_LOG_BARO)->type);
    fw_log_put_u64(&r, t);
    fw_log_put_i32(&r, s->baro_alt_cm);
    fw_log_put_u8(&r, s->baro_fresh);
    (void)ring_put(log, rec, r.n);

    fw_log_rec_begin(&r, rec, fw_log_format(FW_LOG_ARSP)->type);
    fw_log_put_u64(&r, t);
    fw_log_put_i16(&r, s->airspeed_cm_s);
    fw_log_put_u8(&r, s->airspeed_fresh);
    (void)ring_put(log, rec, r.n);
}

/* The controller the step ran (fw_t.law[]): the guided command's pitch
 * method, else the one the flight modes fly with (fw_step.c). */
static uint8_t pitch_mode_used(const fw_t *fw, const fw_inputs_t *in)
{
    if (in->guided != NULL) {
        return (in->guided->pitch_mode == (uint8_t)HT_PITCH_TILT_CROSS) ? 1u : 0u;
    }
    return ((fw->cfg != NULL) && (fw->cfg->modes_pitch_mode != 0u)) ? 1u : 0u;
}

static void queue_control(fw_log_t *log, uint64_t t, uint8_t pitch_mode, const fw_output_t *out)
{
    uint8_t rec[FW_LOG_REC_MAX];
    fw_log_rec_t r;
    fw_log_rec_begin(&r, rec, fw_log_format(FW_LOG_ATT)->type);
    fw_log_put_u64(&r, t);
    fw_log_put_i16(&r, out->est.roll_cdeg);
    fw_log_put_i16(&r, out->est.pitch_cdeg);
    fw_log_put_u16(&r, out->est.yaw_cdeg);
    for (unsigned i = 0u; i < 3u; ++i) {
        fw_log_put_i16(&r, out->est.r[2][i]);
    }
    (void)ring_put(log, rec, r.n);

    const ht_input_t *li = &out->law_in;
    fw_log_rec_begin(&r, rec, fw_log_format(FW_LOG_HTIN)->type);
    fw_log_put_u64(&r, t);
    fw_log_put_i16(&r, li->x);
    fw_log_put_i16(&r, li->y);
    fw_log_put_i16(&r, li->z);
    fw_log_put_i16(&r, li->turn_rate_rad_s);
    fw_log_put_i32(&r, li->pitch_ratio);
    fw_log_put_i16(&r, li->airspeed_cm_s);
    for (unsigned i = 0u; i < 3u; ++i) {
        fw_log_put_i16(&r, li->gyro_rad_s[i]);
    }
    fw_log_put_i16(&r, li->turn_accel_rad_s2);
    fw_log_put_i16(&r, li->accel_lat_g);
    fw_log_put_u8(&r, li->inverted);
    fw_log_put_u8(&r, pitch_mode);
    (void)ring_put(log, rec, r.n);

    const ht_output_t *lo = &out->law;
    fw_log_rec_begin(&r, rec, fw_log_format(FW_LOG_HTO)->type);
    fw_log_put_u64(&r, t);
    fw_log_put_i16(&r, lo->turn_rate_used_rad_s);
    fw_log_put_i32(&r, lo->tilt_ratio);
    fw_log_put_i16(&r, lo->tilt_x);
    fw_log_put_i16(&r, lo->tilt_y);
    fw_log_put_i16(&r, lo->tilt_z);
    fw_log_put_i16(&r, lo->roll_error);
    fw_log_put_i16(&r, lo->pitch_error);
    fw_log_put_i16(&r, lo->aileron);
    fw_log_put_i16(&r, lo->elevator);
    fw_log_put_i16(&r, lo->rudder);
    fw_log_put_i16(&r, lo->roll_in_rate_rad_s);
    fw_log_put_i16(&r, lo->roll_fade);
    fw_log_put_i16(&r, lo->sideslip_rudder);
    fw_log_put_u8(&r, lo->flags);
    (void)ring_put(log, rec, r.n);

    fw_log_rec_begin(&r, rec, fw_log_format(FW_LOG_CTRL)->type);
    fw_log_put_u64(&r, t);
    fw_log_put_i32(&r, out->pitch_cmd);
    fw_log_put_i16(&r, out->throttle);
    fw_log_put_u8(&r, out->control_ran);
    fw_log_put_u8(&r, out->failsafe);
    fw_log_put_u8(&r, out->modes.failsafe);
    fw_log_put_u8(&r, out->guard_engaged);
    fw_log_put_u8(&r, out->servo_clamped);
    (void)ring_put(log, rec, r.n);

    fw_log_rec_begin(&r, rec, fw_log_format(FW_LOG_RCOU)->type);
    fw_log_put_u64(&r, t);
    for (unsigned i = 0u; i < 8u; ++i) {
        fw_log_put_u16(&r,
                       ((i < out->pulse_count) && (i < OS_MAX_CHANNELS)) ? out->pulse_us[i] : 0u);
    }
    (void)ring_put(log, rec, r.n);
}

void fw_log_step(fw_log_t *log, const fw_t *fw, uint64_t time_us, const fw_inputs_t *in,
                 const fw_output_t *out)
{
    if ((log == NULL) || (log->ready == 0u)) {
        return;
    }
    if (log->header_done == 0u) {
        queue_header(log, time_us);
    }
    if ((log->header_done != 0u) && (fw != NULL) && (in != NULL) && (out != NULL)) {
        queue_events(log, time_us, in, out);
        if (log->decim_count == 0u) {
            queue_sensors(log, time_us, &in->sensors);
            queue_control(log, time_us, pitch_mode_used(fw, in), out);
        }
        ++log->decim_count;
        if (log->decim_count >= log->cfg.decimation) {
            log->decim_count = 0u;
        }
    }
    ring_drain(log, log->cfg.budget_bytes);
}

uint32_t fw_log_flush(fw_log_t *log)
{
    if ((log == NULL) || (log->ready == 0u)) {
        return 0u;
    }
    ring_drain(log, log->used);
    return log->used;
}
