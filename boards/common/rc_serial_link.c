/*
 * rc_serial_link.c - SBUS / CRSF bytes to RC pulses with freshness (see
 * rc_serial_link.h).
 */
#include "rc_serial_link.h"

static void count32(uint32_t *c)
{
    if (*c != UINT32_MAX) {
        (*c)++;
    }
}

board_status_t rc_serial_link_init(rc_serial_link_t *l, rc_serial_protocol_t protocol,
                                   uint32_t timeout_us, uint32_t now_us)
{
    if (l == NULL) {
        return BOARD_ERR_NULL;
    }
    if ((protocol != RC_SERIAL_SBUS && protocol != RC_SERIAL_CRSF) || timeout_us == 0u) {
        return BOARD_ERR_RANGE;
    }
    l->protocol = protocol;
    l->timeout_us = timeout_us;
    sbus_init(&l->sbus);
    crsf_init(&l->crsf);
    for (unsigned i = 0u; i < BOARD_MAX_RC_INPUTS; ++i) {
        l->pulse_us[i] = 0u;
    }
    l->last_frame_us = now_us;
    l->last_bytes_us = now_us;
    l->fresh = 0u;
    l->lost = 1u;
    l->crsf_link_down = 0u;
    l->gap_seen = 1u; /* nothing held at start: no gap to call */
    l->frames_usable = 0u;
    l->sbus_failsafe = 0u;
    l->sbus_frame_lost = 0u;
    l->crsf_lq_zero = 0u;
    l->crsf_held = 0u;
    l->timeouts = 0u;
    l->line_gaps = 0u;
    return BOARD_OK;
}

static void take_frame(rc_serial_link_t *l, const uint16_t *pulse_us, uint32_t now_us)
{
    for (unsigned i = 0u; i < BOARD_MAX_RC_INPUTS; ++i) {
        l->pulse_us[i] = pulse_us[i];
    }
    l->fresh = 1u;
    l->lost = 0u;
    l->last_frame_us = now_us;
    count32(&l->frames_usable);
}

static void on_sbus(rc_serial_link_t *l, const sbus_frame_t *f, uint32_t now_us)
{
    /* Freshness is the newest frame's: an unusable frame after a usable one
     * in the same poll leaves nothing fresh. */
    if (f->failsafe || !f->channels_usable) {
        count32(&l->sbus_failsafe);
        l->fresh = 0u;
        l->lost = 1u; /* the receiver says so: no need to wait for the timeout */
        return;
    }
    if (f->frame_lost) {
        count32(&l->sbus_frame_lost);
        l->fresh = 0u;
        return;
    }
    take_frame(l, f->pulse_us, now_us);
}

static void feed_sbus(rc_serial_link_t *l, const uint8_t *bytes, size_t n, uint32_t now_us)
{
    size_t off = 0u;
    while (off < n) {
        sbus_frame_t f;
        sbus_result_t r = SBUS_NONE;
        const size_t used = sbus_feed(&l->sbus, &bytes[off], n - off, &f, &r);
        if (used == 0u) {
            break; /* cannot happen with valid pointers; never loop on it */
        }
        off += used;
        if (r == SBUS_FRAME) {
            on_sbus(l, &f, now_us);
        }
    }
}

static void feed_crsf(rc_serial_link_t *l, const uint8_t *bytes, size_t n, uint32_t now_us)
{
    size_t off = 0u;
    while (off < n) {
        crsf_msg_t m;
        crsf_result_t r = CRSF_NONE;
        const size_t used = crsf_feed(&l->crsf, &bytes[off], n - off, &m, &r);
        if (used == 0u) {
            break;
        }
        off += used;
        if (r == CRSF_LINK_STATS) {
            if (m.link.link_lost) {
                count32(&l->crsf_lq_zero);
                l->crsf_link_down = 1u;
                l->fresh = 0u;
                l->lost = 1u;
            } else {
                l->crsf_link_down = 0u;
            }
        } else if (r == CRSF_RC_CHANNELS) {
            if (l->crsf_link_down != 0u) {
                count32(&l->crsf_held);
                l->fresh = 0u;
            } else {
                take_frame(l, m.rc.pulse_us, now_us);
            }
        } else {
            /* CRSF_NONE: mid-frame */
        }
    }
}

void rc_serial_link_poll(rc_serial_link_t *l, const uint8_t *bytes, size_t n, uint32_t now_us)
{
    if (l == NULL || (bytes == NULL && n > 0u)) {
        return;
    }
    if (n == 0u) {
        if (l->protocol == RC_SERIAL_SBUS && l->gap_seen == 0u &&
            now_us - l->last_bytes_us >= RC_SERIAL_SBUS_GAP_US) {
            /* idle since the last poll with bytes: a frame cannot span it */
            sbus_line_gap(&l->sbus);
            count32(&l->line_gaps);
            l->gap_seen = 1u;
        }
    } else {
        l->last_bytes_us = now_us;
        l->gap_seen = 0u;
        if (l->protocol == RC_SERIAL_SBUS) {
            feed_sbus(l, bytes, n, now_us);
        } else {
            feed_crsf(l, bytes, n, now_us);
        }
    }
    if (l->lost == 0u && now_us - l->last_frame_us > l->timeout_us) {
        l->lost = 1u;
        count32(&l->timeouts);
    }
}

board_status_t rc_serial_link_read_us(rc_serial_link_t *l, uint16_t pulse_us[], uint8_t count)
{
    if (l == NULL || pulse_us == NULL) {
        return BOARD_ERR_NULL;
    }
    if (count > BOARD_MAX_RC_INPUTS) {
        return BOARD_ERR_RANGE;
    }
    for (uint8_t i = 0u; i < count; ++i) {
        pulse_us[i] = l->pulse_us[i];
    }
    const board_status_t st = (l->fresh != 0u) ? BOARD_OK : BOARD_ERR_NO_DATA;
    l->fresh = 0u;
    return st;
}
