/*
 * gps_ubx_link.c - u-blox start-up configuration and NAV-PVT to
 * board_gps_t (see gps_ubx_link.h).
 */
#include "gps_ubx_link.h"

#define GPS_UBX_BAUD_MIN 4800u
#define GPS_UBX_BAUD_MAX 921600u

static void count32(uint32_t *c)
{
    if (*c != UINT32_MAX) {
        (*c)++;
    }
}

/* mm to cm, rounded to nearest, halves away from zero. */
static int32_t mm_to_cm(int32_t mm)
{
    if (mm >= 0) {
        return (mm + 5) / 10;
    }
    return (mm - 5) / 10; /* C rounds the quotient towards zero */
}

static int32_t vel_cm_s(int32_t mm_s)
{
    /* INT32_MIN - 5 would overflow: clamp in mm/s first */
    const int32_t lim_mm_s = GPS_UBX_VEL_MAX_CM_S * 10;
    int32_t v = mm_s;
    if (v > lim_mm_s) {
        v = lim_mm_s;
    } else if (v < -lim_mm_s) {
        v = -lim_mm_s;
    } else {
        /* in range */
    }
    return mm_to_cm(v);
}

void gps_ubx_pvt_to_board(const ubx_nav_pvt_t *pvt, board_gps_t *out)
{
    if (pvt == NULL || out == NULL) {
        return;
    }
    uint8_t fix = 0u;
    if (pvt->gnss_fix_ok) {
        if (pvt->fix_type == UBX_FIX_3D || pvt->fix_type == UBX_FIX_GNSS_DR) {
            fix = 3u;
        } else if (pvt->fix_type == UBX_FIX_2D) {
            fix = 2u;
        } else {
            fix = 0u;
        }
    }
    out->fresh = 0u;
    out->fix = fix;
    out->lat_e7 = pvt->lat_e7;
    out->lon_e7 = pvt->lon_e7;
    /* hMSL is within +-2^31 mm; / 10 cannot overflow, +-5 only at the ends */
    const int32_t hmsl = pvt->hmsl_mm;
    if (hmsl > INT32_MAX - 5) {
        out->alt_cm = INT32_MAX / 10;
    } else if (hmsl < INT32_MIN + 5) {
        out->alt_cm = INT32_MIN / 10;
    } else {
        out->alt_cm = mm_to_cm(hmsl);
    }
    out->vel_ned_cm_s[0] = vel_cm_s(pvt->vel_n_mm_s);
    out->vel_ned_cm_s[1] = vel_cm_s(pvt->vel_e_mm_s);
    out->vel_ned_cm_s[2] = vel_cm_s(pvt->vel_d_mm_s);
}

board_status_t gps_ubx_link_init(gps_ubx_link_t *g, const gps_ubx_config_t *cfg,
                                 const gps_ubx_io_t *io, uint32_t now_ms)
{
    static const gps_ubx_config_t dflt = GPS_UBX_CONFIG_DEFAULT;
    if (g == NULL || io == NULL || io->write == NULL || io->set_baud == NULL) {
        return BOARD_ERR_NULL;
    }
    const gps_ubx_config_t *c = (cfg != NULL) ? cfg : &dflt;
    if ((c->port_id != 1u && c->port_id != 2u) || c->baud < GPS_UBX_BAUD_MIN ||
        c->baud > GPS_UBX_BAUD_MAX || c->meas_rate_ms == 0u || c->tries == 0u ||
        c->ack_timeout_ms == 0u || c->lost_after_ms == 0u) {
        return BOARD_ERR_RANGE;
    }
    g->cfg = *c;
    g->io = *io;
    ubx_init(&g->dec);
    /* Where a receiver may be listening: its default first after ours. */
    static const uint32_t probe_bauds[] = {9600u, 38400u, 57600u, 115200u, 230400u};
    g->probes[0] = c->baud;
    g->n_probes = 1u;
    for (unsigned i = 0u; i < sizeof probe_bauds / sizeof probe_bauds[0]; ++i) {
        if (probe_bauds[i] != c->baud && g->n_probes < GPS_UBX_PROBES_MAX) {
            g->probes[g->n_probes] = probe_bauds[i];
            g->n_probes++;
        }
    }
    g->state = GPS_UBX_START;
    g->probe = 0u;
    g->sent = 0u;
    g->nak_seen = 0u;
    g->ack = 0u;
    g->since_ms = now_ms;
    g->baud_now = 0u;
    g->solution.fresh = 0u;
    g->solution.fix = 0u;
    g->solution.lat_e7 = 0;
    g->solution.lon_e7 = 0;
    g->solution.alt_cm = 0;
    for (unsigned i = 0u; i < 3u; ++i) {
        g->solution.vel_ned_cm_s[i] = 0;
    }
    g->solution_seq = 0u;
    g->seq_read = 0u;
    g->last_pvt_ms = now_ms;
    g->lost = 1u;
    g->naks = 0u;
    g->ack_timeouts = 0u;
    g->short_writes = 0u;
    g->restarts = 0u;
    g->losses = 0u;
    return BOARD_OK;
}

static void send(gps_ubx_link_t *g, const uint8_t *frame, size_t n)
{
    if (n == 0u) {
        return; /* an encoder refused: the ACK timeout retries, then gives up */
    }
    if (g->io.write(g->io.ctx, frame, n) != n) {
        count32(&g->short_writes);
    }
}

static void set_baud(gps_ubx_link_t *g, uint32_t baud)
{
    g->io.set_baud(g->io.ctx, baud);
    g->baud_now = baud;
    ubx_init(&g->dec); /* bytes half-received at the old rate are garbage */
}

/* Step 1: CFG-PRT at the current probe baud. */
static void start_probe(gps_ubx_link_t *g, uint32_t now_ms)
{
    uint8_t frame[UBX_FRAME_MAX];
    set_baud(g, g->probes[g->probe]);
    send(g, frame, ubx_encode_cfg_prt_uart(g->cfg.port_id, g->cfg.baud, frame, sizeof frame));
    g->state = GPS_UBX_SETTLE;
    g->since_ms = now_ms;
}

/* Steps 3 and 4: (re)send the awaited message. */
static void send_step(gps_ubx_link_t *g, gps_ubx_state_t step, uint32_t now_ms)
{
    uint8_t frame[UBX_FRAME_MAX];
    size_t n;
    if (step == GPS_UBX_WAIT_MSG) {
        n = ubx_encode_cfg_msg(UBX_CLASS_NAV, UBX_ID_NAV_PVT, 1u, frame, sizeof frame);
    } else {
        n = ubx_encode_cfg_rate(g->cfg.meas_rate_ms, frame, sizeof frame);
    }
    send(g, frame, n);
    if (g->state != step) {
        g->sent = 0u;
        g->nak_seen = 0u;
    }
    g->sent++;
    g->ack = 0u;
    g->state = step;
    g->since_ms = now_ms;
}

static void restart(gps_ubx_link_t *g, uint32_t now_ms)
{
    count32(&g->restarts);
    g->probe = 0u;
    start_probe(g, now_ms);
}

/* The awaited message was not acknowledged in `tries` sends. */
static void step_failed(gps_ubx_link_t *g, uint32_t now_ms)
{
    /* A NAK means the receiver hears us at this baud and refuses: other
     * bauds will not help, wait and try the whole sequence again. */
    if (g->nak_seen == 0u && (uint32_t)g->probe + 1u < (uint32_t)g->n_probes) {
        g->probe++;
        start_probe(g, now_ms);
    } else {
        g->state = GPS_UBX_BACKOFF;
        g->since_ms = now_ms;
    }
}

static void on_ack(gps_ubx_link_t *g, const ubx_ack_t *a, int accepted)
{
    uint8_t want_id;
    if (g->state == GPS_UBX_WAIT_MSG) {
        want_id = UBX_ID_CFG_MSG;
    } else if (g->state == GPS_UBX_WAIT_RATE) {
        want_id = UBX_ID_CFG_RATE;
    } else {
        return; /* e.g. the ACK of CFG-PRT: not awaited */
    }
    if (a->cls != UBX_CLASS_CFG || a->id != want_id) {
        return;
    }
    if (accepted != 0) {
        g->ack = 1u;
    } else {
        g->ack = 2u;
        g->nak_seen = 1u;
        count32(&g->naks);
    }
}

static void on_pvt(gps_ubx_link_t *g, const ubx_nav_pvt_t *pvt, uint32_t now_ms)
{
    gps_ubx_pvt_to_board(pvt, &g->solution);
    g->solution_seq++;
    g->last_pvt_ms = now_ms;
    g->lost = 0u;
}

static void feed(gps_ubx_link_t *g, const uint8_t *bytes, size_t n, uint32_t now_ms)
{
    size_t off = 0u;
    while (off < n) {
        ubx_msg_t m;
        ubx_result_t r = UBX_NONE;
        const size_t used = ubx_feed(&g->dec, &bytes[off], n - off, &m, &r);
        if (used == 0u) {
            break; /* cannot happen with valid pointers; never loop on it */
        }
        off += used;
        if (r == UBX_NAV_PVT) {
            on_pvt(g, &m.pvt, now_ms);
        } else if (r == UBX_ACK_ACK) {
            on_ack(g, &m.ack, 1);
        } else if (r == UBX_ACK_NAK) {
            on_ack(g, &m.ack, 0);
        } else {
            /* UBX_NONE */
        }
    }
}

static void wait_step(gps_ubx_link_t *g, uint32_t now_ms)
{
    if (g->ack == 1u) {
        if (g->state == GPS_UBX_WAIT_MSG) {
            send_step(g, GPS_UBX_WAIT_RATE, now_ms);
        } else {
            g->state = GPS_UBX_RUNNING;
            g->since_ms = now_ms;
        }
        return;
    }
    const uint8_t timed_out = ((now_ms - g->since_ms) >= g->cfg.ack_timeout_ms) ? 1u : 0u;
    if (g->ack == 0u && timed_out == 0u) {
        return;
    }
    if (g->ack == 0u) {
        count32(&g->ack_timeouts);
    }
    if (g->sent < g->cfg.tries) {
        send_step(g, g->state, now_ms);
    } else {
        step_failed(g, now_ms);
    }
}

static void advance(gps_ubx_link_t *g, uint32_t now_ms)
{
    switch (g->state) {
    case GPS_UBX_START:
        g->probe = 0u;
        start_probe(g, now_ms);
        break;
    case GPS_UBX_SETTLE:
        if (now_ms - g->since_ms >= g->cfg.settle_ms) {
            set_baud(g, g->cfg.baud);
            send_step(g, GPS_UBX_WAIT_MSG, now_ms);
        }
        break;
    case GPS_UBX_WAIT_MSG:
    case GPS_UBX_WAIT_RATE:
        wait_step(g, now_ms);
        break;
    case GPS_UBX_RUNNING:
        if (now_ms - g->last_pvt_ms > g->cfg.reconfig_after_ms &&
            now_ms - g->since_ms > g->cfg.reconfig_after_ms) {
            restart(g, now_ms);
        }
        break;
    case GPS_UBX_BACKOFF:
        if (now_ms - g->since_ms >= g->cfg.backoff_ms) {
            restart(g, now_ms);
        }
        break;
    default:
        g->state = GPS_UBX_START; /* unreachable: start over */
        break;
    }
}

void gps_ubx_link_poll(gps_ubx_link_t *g, const uint8_t *bytes, size_t n, uint32_t now_ms)
{
    if (g == NULL || (bytes == NULL && n > 0u)) {
        return;
    }
    feed(g, bytes, n, now_ms);
    advance(g, now_ms);
    if (g->lost == 0u && now_ms - g->last_pvt_ms > g->cfg.lost_after_ms) {
        g->lost = 1u;
        count32(&g->losses);
    }
}

board_status_t gps_ubx_link_read(gps_ubx_link_t *g, board_gps_t *out)
{
    if (g == NULL || out == NULL) {
        return BOARD_ERR_NULL;
    }
    *out = g->solution;
    const uint8_t fresh = (g->solution_seq != g->seq_read && g->lost == 0u) ? 1u : 0u;
    g->seq_read = g->solution_seq;
    out->fresh = fresh;
    if (g->lost != 0u) {
        out->fix = 0u;
    }
    return (fresh != 0u) ? BOARD_OK : BOARD_ERR_NO_DATA;
}
