/*
 * test_gps_ubx_link.c - the u-blox start-up sequence against a simulated
 * receiver, and NAV-PVT to board_gps_t.
 *
 * The simulated receiver (sim_t) follows the u-blox M8 receiver description
 * (UBX-13003221) as far as the link needs: it starts at 9600 baud sending
 * an NMEA sentence a second; it hears only bytes sent at its own baud; it
 * answers CFG-PRT / CFG-MSG / CFG-RATE with ACK-ACK (or ACK-NAK when told
 * to), the CFG-PRT ACK at the old baud before switching; CFG-PRT with
 * outProtoMask UBX stops NMEA; once CFG-MSG enables NAV-PVT it sends one per
 * measurement period (1000 ms until CFG-RATE). Bytes it sends at a baud the
 * host is not set to arrive as garbage. It can drop bytes, add garbage, go
 * mute, or restart.
 *
 * Worked values of the conversion (gps_ubx_link.h):
 *   hMSL 488123 mm -> 48812.3 -> 48812 cm; 15 mm -> 1.5 -> 2; -15 -> -2;
 *   14 -> 1; -14 -> -1
 *   velN 12345 mm/s -> 1234.5 -> 1235 cm/s; velE -6789 -> -678.9 -> -679;
 *   velD 250 -> 25; 499994 -> 49999; 499995 -> 49999.5 -> 50000;
 *   600000 -> clamped 50000; INT32_MIN -> -50000
 * Timing with GPS_UBX_CONFIG_DEFAULT (115200, 200 ms, ACK wait 250 ms, 3
 * tries, settle 100 ms) from a receiver at 9600: probe 115200 (100 ms
 * settle + 3 x 250 ms unanswered CFG-MSG), then probe 9600 (100 ms settle,
 * CFG-MSG and CFG-RATE answered within a poll each): running at ~970 ms.
 */
#include "unity.h"

#include "gps_ubx_link.h"

#include <string.h>

/* ---- the simulated receiver ---------------------------------------------- */

#define SIM_QUEUE 16384u

typedef struct {
    uint32_t rx_baud;
    uint32_t host_baud;
    uint8_t ubx_only;
    uint8_t pvt_rate;
    uint8_t silent; /* configured but sends no NAV-PVT */
    uint8_t mute;   /* answers nothing, sends nothing */
    uint16_t meas_ms;
    int nak_msg, nak_rate;
    int swallow_acks; /* the next ACK-ACKs are lost on the wire */
    uint32_t drop_every;
    uint8_t garbage;
    uint32_t next_epoch_ms, next_nmea_ms;
    uint8_t q[SIM_QUEUE];
    uint32_t q_baud[SIM_QUEUE];
    size_t q_n;
    uint32_t delivered;
    /* what it saw */
    uint32_t prt, msg, rate, unheard, writes;
    uint32_t baud_log[64];
    size_t baud_log_n;
} sim_t;

static sim_t sim;
static gps_ubx_link_t link;
static uint32_t now_ms;

static void sim_emit(const uint8_t *b, size_t n)
{
    for (size_t i = 0; i < n && sim.q_n < SIM_QUEUE; ++i) {
        sim.q[sim.q_n] = b[i];
        sim.q_baud[sim.q_n] = sim.rx_baud;
        sim.q_n++;
    }
}

static void sim_ack(uint8_t id, int ok)
{
    if (ok && sim.swallow_acks > 0) {
        sim.swallow_acks--;
        return;
    }
    uint8_t f[16];
    const uint8_t p[2] = {UBX_CLASS_CFG, id};
    const size_t n =
        ubx_encode(UBX_CLASS_ACK, ok ? UBX_ID_ACK_ACK : UBX_ID_ACK_NAK, p, 2u, f, sizeof f);
    sim_emit(f, n);
}

static void sim_reset(uint32_t baud, int ubx_only)
{
    memset(&sim, 0, sizeof sim);
    sim.rx_baud = baud;
    sim.ubx_only = (uint8_t)ubx_only;
    sim.meas_ms = 1000u;
}

static uint32_t get_u32(const uint8_t *p)
{
    return (uint32_t)p[0] | ((uint32_t)p[1] << 8) | ((uint32_t)p[2] << 16) | ((uint32_t)p[3] << 24);
}

static size_t sim_write(void *ctx, const uint8_t *b, size_t n)
{
    (void)ctx;
    sim.writes++;
    if (sim.host_baud != sim.rx_baud) {
        sim.unheard++; /* framing garbage to the receiver */
        return n;
    }
    if (sim.mute || n < 8u || b[0] != UBX_SYNC1 || b[1] != UBX_SYNC2) {
        return n;
    }
    const size_t len = (size_t)b[4] | ((size_t)b[5] << 8);
    TEST_ASSERT_EQUAL_UINT64(len + 8u, (uint64_t)n); /* one whole frame per write */
    const uint16_t ck = ubx_checksum(&b[2], len + 4u);
    TEST_ASSERT_EQUAL_HEX8((uint8_t)(ck & 0xFFu), b[6u + len]);
    TEST_ASSERT_EQUAL_HEX8((uint8_t)(ck >> 8), b[7u + len]);
    const uint8_t *p = &b[6];
    TEST_ASSERT_EQUAL_HEX8(UBX_CLASS_CFG, b[2]);
    if (b[3] == UBX_ID_CFG_PRT && len == 20u) {
        sim.prt++;
        sim_ack(UBX_ID_CFG_PRT, 1); /* at the old baud */
        sim.rx_baud = get_u32(&p[8]);
        sim.ubx_only = (p[14] == 0x01u && p[15] == 0x00u) ? 1u : 0u;
    } else if (b[3] == UBX_ID_CFG_MSG && len == 3u) {
        sim.msg++;
        if (sim.nak_msg > 0) {
            sim.nak_msg--;
            sim_ack(UBX_ID_CFG_MSG, 0);
        } else {
            TEST_ASSERT_EQUAL_HEX8(UBX_CLASS_NAV, p[0]);
            TEST_ASSERT_EQUAL_HEX8(UBX_ID_NAV_PVT, p[1]);
            sim.pvt_rate = p[2];
            sim.next_epoch_ms = now_ms + sim.meas_ms;
            sim_ack(UBX_ID_CFG_MSG, 1);
        }
    } else if (b[3] == UBX_ID_CFG_RATE && len == 6u) {
        sim.rate++;
        if (sim.nak_rate > 0) {
            sim.nak_rate--;
            sim_ack(UBX_ID_CFG_RATE, 0);
        } else {
            sim.meas_ms = (uint16_t)(p[0] | (p[1] << 8));
            sim_ack(UBX_ID_CFG_RATE, 1);
        }
    } else {
        TEST_FAIL_MESSAGE("unexpected message");
    }
    return n;
}

static void sim_set_baud(void *ctx, uint32_t baud)
{
    (void)ctx;
    sim.host_baud = baud;
    if (sim.baud_log_n < 64u) {
        sim.baud_log[sim.baud_log_n++] = baud;
    }
}

static void put32(uint8_t *p, int32_t v)
{
    const uint32_t u = (uint32_t)v;
    p[0] = (uint8_t)(u & 0xFFu);
    p[1] = (uint8_t)((u >> 8) & 0xFFu);
    p[2] = (uint8_t)((u >> 16) & 0xFFu);
    p[3] = (uint8_t)(u >> 24);
}

static void sim_pvt(void)
{
    uint8_t p[92] = {0};
    uint8_t f[100];
    put32(&p[0], (int32_t)now_ms);
    p[20] = UBX_FIX_3D;
    p[21] = UBX_PVT_FLAG_GNSS_FIX_OK;
    p[23] = 12u;
    put32(&p[24], 85455938);  /* lon 8.5455938 deg */
    put32(&p[28], 473977418); /* lat 47.3977418 deg */
    put32(&p[36], 488123);    /* hMSL mm */
    put32(&p[48], 12345);
    put32(&p[52], -6789);
    put32(&p[56], 250);
    const size_t n = ubx_encode(UBX_CLASS_NAV, UBX_ID_NAV_PVT, p, 92u, f, sizeof f);
    if (sim.garbage) {
        static const uint8_t junk[7] = {0xB5u, 0x62u, 0x01u, 0x07u, 0xFFu, 0x13u, 0x24u};
        sim_emit(junk, sizeof junk);
    }
    sim_emit(f, n);
}

static void sim_step(void)
{
    if (sim.mute) {
        return;
    }
    if (!sim.ubx_only && now_ms >= sim.next_nmea_ms) {
        static const char nmea[] =
            "$GNGGA,120000.00,4723.86451,N,00832.73563,E,1,12,0.8,488.1,M,47.3,M,,*4C\r\n";
        sim_emit((const uint8_t *)nmea, sizeof nmea - 1u);
        sim.next_nmea_ms = now_ms + 1000u;
    }
    if (sim.pvt_rate != 0u && !sim.silent && now_ms >= sim.next_epoch_ms) {
        sim_pvt();
        sim.next_epoch_ms += sim.meas_ms;
    }
}

static size_t sim_deliver(uint8_t *out, size_t max)
{
    size_t n = 0u;
    for (size_t i = 0; i < sim.q_n && n < max; ++i) {
        sim.delivered++;
        if (sim.drop_every != 0u && sim.delivered % sim.drop_every == 0u) {
            continue;
        }
        /* sent at another baud: the UART reads garbage */
        out[n++] = (sim.q_baud[i] == sim.host_baud) ? sim.q[i] : (uint8_t)(sim.q[i] ^ 0x5Au);
    }
    sim.q_n = 0u;
    return n;
}

/* ---- the host side --------------------------------------------------------- */

static const gps_ubx_io_t IO = {NULL, sim_write, sim_set_baud};
static uint32_t fresh_reads;
static board_gps_t last_fresh;
static uint32_t running_at_ms;

void setUp(void)
{
    memset(&link, 0, sizeof link);
    sim_reset(9600u, 0);
    now_ms = 0u;
    fresh_reads = 0u;
    running_at_ms = 0u;
    memset(&last_fresh, 0, sizeof last_fresh);
}

void tearDown(void) {}

/* Poll every 10 ms until to_ms, reading the GPS seam each time. */
static void run_until(uint32_t to_ms)
{
    for (; now_ms < to_ms; now_ms += 10u) {
        uint8_t buf[SIM_QUEUE];
        sim_step();
        const size_t n = sim_deliver(buf, sizeof buf);
        gps_ubx_link_poll(&link, buf, n, now_ms);
        if (running_at_ms == 0u && link.state == GPS_UBX_RUNNING) {
            running_at_ms = now_ms;
        }
        board_gps_t out;
        if (gps_ubx_link_read(&link, &out) == BOARD_OK) {
            fresh_reads++;
            TEST_ASSERT_EQUAL_UINT8(1u, out.fresh);
            last_fresh = out;
        } else {
            TEST_ASSERT_EQUAL_UINT8(0u, out.fresh);
        }
    }
}

static void assert_sim_solution(const board_gps_t *g)
{
    TEST_ASSERT_EQUAL_UINT8(3u, g->fix);
    TEST_ASSERT_EQUAL_INT32(473977418, g->lat_e7);
    TEST_ASSERT_EQUAL_INT32(85455938, g->lon_e7);
    TEST_ASSERT_EQUAL_INT32(48812, g->alt_cm);
    TEST_ASSERT_EQUAL_INT32(1235, g->vel_ned_cm_s[0]);
    TEST_ASSERT_EQUAL_INT32(-679, g->vel_ned_cm_s[1]);
    TEST_ASSERT_EQUAL_INT32(25, g->vel_ned_cm_s[2]);
}

/* ---- tests ------------------------------------------------------------------ */

static void test_pvt_conversion(void)
{
    ubx_nav_pvt_t pvt;
    board_gps_t g;
    memset(&pvt, 0, sizeof pvt);
    struct {
        uint8_t fix_type;
        bool ok;
        uint8_t want;
    } fixes[] = {{0u, true, 0u}, {1u, true, 0u},  {2u, true, 2u},  {3u, true, 3u},  {4u, true, 3u},
                 {5u, true, 0u}, {2u, false, 0u}, {3u, false, 0u}, {4u, false, 0u}, {6u, true, 0u}};
    for (size_t i = 0; i < sizeof fixes / sizeof fixes[0]; ++i) {
        pvt.fix_type = fixes[i].fix_type;
        pvt.gnss_fix_ok = fixes[i].ok;
        gps_ubx_pvt_to_board(&pvt, &g);
        TEST_ASSERT_EQUAL_UINT8(fixes[i].want, g.fix);
        TEST_ASSERT_EQUAL_UINT8(0u, g.fresh);
    }
    const int32_t hmsl_mm[6] = {488123, 15, -15, 14, -14, INT32_MAX};
    const int32_t alt_cm[6] = {48812, 2, -2, 1, -1, 214748364};
    for (size_t i = 0; i < 6u; ++i) {
        pvt.hmsl_mm = hmsl_mm[i];
        gps_ubx_pvt_to_board(&pvt, &g);
        TEST_ASSERT_EQUAL_INT32(alt_cm[i], g.alt_cm);
    }
    pvt.hmsl_mm = INT32_MIN;
    gps_ubx_pvt_to_board(&pvt, &g);
    TEST_ASSERT_EQUAL_INT32(-214748364, g.alt_cm);
    const int32_t v_mm[7] = {12345, -6789, 250, 499994, 499995, 600000, INT32_MIN};
    const int32_t v_cm[7] = {1235, -679, 25, 49999, 50000, 50000, -50000};
    for (size_t i = 0; i < 7u; ++i) {
        pvt.vel_n_mm_s = v_mm[i];
        pvt.vel_e_mm_s = v_mm[(i + 1u) % 7u];
        pvt.vel_d_mm_s = INT32_MAX;
        gps_ubx_pvt_to_board(&pvt, &g);
        TEST_ASSERT_EQUAL_INT32(v_cm[i], g.vel_ned_cm_s[0]);
        TEST_ASSERT_EQUAL_INT32(v_cm[(i + 1u) % 7u], g.vel_ned_cm_s[1]);
        TEST_ASSERT_EQUAL_INT32(50000, g.vel_ned_cm_s[2]);
    }
    pvt.lat_e7 = -900000000;
    pvt.lon_e7 = 1800000000;
    gps_ubx_pvt_to_board(&pvt, &g);
    TEST_ASSERT_EQUAL_INT32(-900000000, g.lat_e7);
    TEST_ASSERT_EQUAL_INT32(1800000000, g.lon_e7);
    gps_ubx_pvt_to_board(NULL, &g);
    gps_ubx_pvt_to_board(&pvt, NULL);
}

static void test_init_refused(void)
{
    gps_ubx_config_t c = GPS_UBX_CONFIG_DEFAULT;
    const gps_ubx_io_t no_write = {NULL, NULL, sim_set_baud};
    TEST_ASSERT_EQUAL(BOARD_ERR_NULL, gps_ubx_link_init(NULL, &c, &IO, 0u));
    TEST_ASSERT_EQUAL(BOARD_ERR_NULL, gps_ubx_link_init(&link, &c, NULL, 0u));
    TEST_ASSERT_EQUAL(BOARD_ERR_NULL, gps_ubx_link_init(&link, &c, &no_write, 0u));
    c.port_id = 3u;
    TEST_ASSERT_EQUAL(BOARD_ERR_RANGE, gps_ubx_link_init(&link, &c, &IO, 0u));
    c.port_id = 1u;
    c.baud = 2400u;
    TEST_ASSERT_EQUAL(BOARD_ERR_RANGE, gps_ubx_link_init(&link, &c, &IO, 0u));
    c.baud = 115200u;
    c.tries = 0u;
    TEST_ASSERT_EQUAL(BOARD_ERR_RANGE, gps_ubx_link_init(&link, &c, &IO, 0u));
    c.tries = 3u;
    c.meas_rate_ms = 0u;
    TEST_ASSERT_EQUAL(BOARD_ERR_RANGE, gps_ubx_link_init(&link, &c, &IO, 0u));
    TEST_ASSERT_EQUAL_UINT32(0u, sim.writes);
    TEST_ASSERT_EQUAL(BOARD_OK, gps_ubx_link_init(&link, NULL, &IO, 0u));
    TEST_ASSERT_EQUAL_UINT32(0u, sim.writes); /* the first poll sends */
    /* probes: the working baud first, then the others once each */
    const uint32_t want[6] = {115200u, 9600u, 38400u, 57600u, 230400u, 0u};
    TEST_ASSERT_EQUAL_UINT8(5u, link.n_probes);
    TEST_ASSERT_EQUAL_UINT32_ARRAY(want, link.probes, 5);
    board_gps_t out;
    TEST_ASSERT_EQUAL(BOARD_ERR_NO_DATA, gps_ubx_link_read(&link, &out));
    TEST_ASSERT_EQUAL_UINT8(0u, out.fix);
    TEST_ASSERT_EQUAL(BOARD_ERR_NULL, gps_ubx_link_read(&link, NULL));
    gps_ubx_link_poll(NULL, NULL, 0u, 0u);
    gps_ubx_link_poll(&link, NULL, 5u, 0u); /* nothing */
    TEST_ASSERT_EQUAL_UINT32(0u, sim.writes);
}

/* A receiver fresh from the factory: 9600 baud, NMEA. */
static void test_end_to_end_from_default(void)
{
    TEST_ASSERT_EQUAL(BOARD_OK, gps_ubx_link_init(&link, NULL, &IO, 0u));
    run_until(3000u);
    TEST_ASSERT_EQUAL(GPS_UBX_RUNNING, link.state);
    TEST_ASSERT_UINT32_WITHIN(30u, 970u, running_at_ms);
    TEST_ASSERT_EQUAL_UINT32(115200u, sim.rx_baud);
    TEST_ASSERT_EQUAL_UINT32(115200u, sim.host_baud);
    TEST_ASSERT_EQUAL_UINT8(1u, sim.ubx_only);
    TEST_ASSERT_EQUAL_UINT8(1u, sim.pvt_rate);
    TEST_ASSERT_EQUAL_UINT16(200u, sim.meas_ms);
    TEST_ASSERT_EQUAL_UINT32(1u, sim.prt); /* heard once: at 9600 */
    TEST_ASSERT_EQUAL_UINT32(1u, sim.msg);
    TEST_ASSERT_EQUAL_UINT32(1u, sim.rate);
    TEST_ASSERT_EQUAL_UINT32(4u, sim.unheard); /* CFG-PRT and 3 CFG-MSG at 115200 */
    TEST_ASSERT_EQUAL_UINT32(3u, link.ack_timeouts);
    const uint32_t bauds[4] = {115200u, 115200u, 9600u, 115200u};
    TEST_ASSERT_EQUAL_UINT64(4u, (uint64_t)sim.baud_log_n);
    TEST_ASSERT_EQUAL_UINT32_ARRAY(bauds, sim.baud_log, 4);
    /* 5 Hz: 10 fresh solutions in 2 s */
    const uint32_t before = fresh_reads;
    run_until(5000u);
    TEST_ASSERT_EQUAL_UINT32(10u, fresh_reads - before);
    assert_sim_solution(&last_fresh);
    TEST_ASSERT_EQUAL_UINT8(0u, link.lost);
    TEST_ASSERT_EQUAL_UINT32(0u, link.restarts);
}

/* A receiver that kept the working baud: the first probe succeeds. */
static void test_already_at_working_baud(void)
{
    sim_reset(115200u, 1);
    TEST_ASSERT_EQUAL(BOARD_OK, gps_ubx_link_init(&link, NULL, &IO, 0u));
    run_until(1000u);
    TEST_ASSERT_EQUAL(GPS_UBX_RUNNING, link.state);
    TEST_ASSERT_TRUE(running_at_ms <= 130u);
    TEST_ASSERT_EQUAL_UINT32(0u, sim.unheard);
    TEST_ASSERT_EQUAL_UINT32(0u, link.ack_timeouts);
    TEST_ASSERT_EQUAL_UINT8(0u, link.probe);
}

/* ACK-NAK twice for CFG-RATE: the third send is accepted. */
static void test_nak_then_ack(void)
{
    sim_reset(115200u, 1);
    sim.nak_rate = 2;
    TEST_ASSERT_EQUAL(BOARD_OK, gps_ubx_link_init(&link, NULL, &IO, 0u));
    run_until(2000u);
    TEST_ASSERT_EQUAL(GPS_UBX_RUNNING, link.state);
    TEST_ASSERT_EQUAL_UINT32(2u, link.naks);
    TEST_ASSERT_EQUAL_UINT32(3u, sim.rate);
    TEST_ASSERT_EQUAL_UINT16(200u, sim.meas_ms);
    TEST_ASSERT_EQUAL_UINT32(0u, link.restarts);
}

/* ACK-ACKs lost on the wire (the CFG-PRT one included): the ACK wait times
 * out and the message is sent again. */
static void test_lost_ack_retried(void)
{
    sim_reset(115200u, 1);
    sim.swallow_acks = 3; /* CFG-PRT's, then CFG-MSG's first two */
    TEST_ASSERT_EQUAL(BOARD_OK, gps_ubx_link_init(&link, NULL, &IO, 0u));
    run_until(2000u);
    TEST_ASSERT_EQUAL(GPS_UBX_RUNNING, link.state);
    TEST_ASSERT_EQUAL_UINT32(2u, link.ack_timeouts);
    TEST_ASSERT_EQUAL_UINT32(3u, sim.msg);
    TEST_ASSERT_EQUAL_UINT32(1u, sim.rate);
    /* 100 ms settle, 2 x 250 ms waits, then two answered polls */
    TEST_ASSERT_UINT32_WITHIN(20u, 620u, running_at_ms);
}

/* ACK-NAK every time: after 3 sends, back off (no other baud tried), then
 * start again; once the receiver accepts, running. */
static void test_nak_exhausted_backs_off(void)
{
    sim_reset(115200u, 1);
    sim.nak_msg = 3;
    TEST_ASSERT_EQUAL(BOARD_OK, gps_ubx_link_init(&link, NULL, &IO, 0u));
    run_until(500u);
    TEST_ASSERT_EQUAL(GPS_UBX_BACKOFF, link.state);
    TEST_ASSERT_EQUAL_UINT32(3u, sim.msg);
    TEST_ASSERT_EQUAL_UINT32(3u, link.naks);
    TEST_ASSERT_EQUAL_UINT64(2u, (uint64_t)sim.baud_log_n); /* 115200 only */
    run_until(3500u);
    TEST_ASSERT_EQUAL(GPS_UBX_RUNNING, link.state);
    TEST_ASSERT_EQUAL_UINT32(1u, link.restarts);
    TEST_ASSERT_EQUAL_UINT32(4u, sim.msg);
}

/* A receiver that never answers: every probe in turn, then the back-off,
 * forever, a bounded number of writes per pass; never running. */
static void test_mute_receiver(void)
{
    sim.mute = 1u;
    TEST_ASSERT_EQUAL(BOARD_OK, gps_ubx_link_init(&link, NULL, &IO, 0u));
    run_until(20000u);
    TEST_ASSERT_EQUAL_UINT32(0u, running_at_ms);
    /* one pass: 5 probes x (100 + 3 x 250) ms = 4250 ms, + 2000 ms back-off */
    TEST_ASSERT_EQUAL_UINT32(3u, link.restarts);
    /* per probe: 1 CFG-PRT + 3 CFG-MSG */
    TEST_ASSERT_TRUE(sim.writes <= 4u * 4u * 5u);
    const uint32_t probes[10] = {115200u, 115200u, 9600u,   115200u, 38400u,
                                 115200u, 57600u,  115200u, 230400u, 115200u};
    TEST_ASSERT_EQUAL_UINT32_ARRAY(probes, sim.baud_log, 10);
    TEST_ASSERT_EQUAL_UINT32(115200u, sim.baud_log[10]); /* the next pass */
    board_gps_t out;
    TEST_ASSERT_EQUAL(BOARD_ERR_NO_DATA, gps_ubx_link_read(&link, &out));
    TEST_ASSERT_EQUAL_UINT8(0u, out.fix);
}

/* Fresh once per solution, however often it is read. */
static void test_fresh_once_per_solution(void)
{
    sim_reset(115200u, 1);
    TEST_ASSERT_EQUAL(BOARD_OK, gps_ubx_link_init(&link, NULL, &IO, 0u));
    run_until(1000u);
    board_gps_t a;
    board_gps_t b;
    /* a solution arrives; two reads */
    while (sim.q_n == 0u) {
        now_ms += 10u;
        sim_step();
    }
    uint8_t buf[256];
    const size_t n = sim_deliver(buf, sizeof buf);
    gps_ubx_link_poll(&link, buf, n, now_ms);
    TEST_ASSERT_EQUAL(BOARD_OK, gps_ubx_link_read(&link, &a));
    TEST_ASSERT_EQUAL(BOARD_ERR_NO_DATA, gps_ubx_link_read(&link, &b));
    TEST_ASSERT_EQUAL_UINT8(1u, a.fresh);
    TEST_ASSERT_EQUAL_UINT8(0u, b.fresh);
    assert_sim_solution(&a);
    assert_sim_solution(&b); /* the solution itself is held */
}

/* The stream stops: lost after lost_after_ms (fix 0), fresh again when it
 * resumes before the reconfiguration time. */
static void test_lost_and_back(void)
{
    sim_reset(115200u, 1);
    TEST_ASSERT_EQUAL(BOARD_OK, gps_ubx_link_init(&link, NULL, &IO, 0u));
    run_until(2000u);
    TEST_ASSERT_EQUAL_UINT8(0u, link.lost);
    sim.silent = 1u;
    const uint32_t last = link.last_pvt_ms;
    run_until(last + 1000u + 10u); /* polls up to last + 1000: not yet */
    TEST_ASSERT_EQUAL_UINT8(0u, link.lost);
    run_until(last + 1020u);
    TEST_ASSERT_EQUAL_UINT8(1u, link.lost);
    TEST_ASSERT_EQUAL_UINT32(1u, link.losses);
    board_gps_t out;
    TEST_ASSERT_EQUAL(BOARD_ERR_NO_DATA, gps_ubx_link_read(&link, &out));
    TEST_ASSERT_EQUAL_UINT8(0u, out.fix);
    TEST_ASSERT_EQUAL_INT32(473977418, out.lat_e7); /* the last solution held */
    sim.silent = 0u;
    sim.next_epoch_ms = now_ms;
    const uint32_t before = fresh_reads;
    run_until(now_ms + 1000u);
    TEST_ASSERT_EQUAL_UINT32(5u, fresh_reads - before);
    assert_sim_solution(&last_fresh);
    TEST_ASSERT_EQUAL_UINT32(0u, link.restarts);
}

/* The receiver restarts (power): back at 9600 with NMEA and no NAV-PVT.
 * After reconfig_after_ms the link configures it again. */
static void test_receiver_restart(void)
{
    TEST_ASSERT_EQUAL(BOARD_OK, gps_ubx_link_init(&link, NULL, &IO, 0u));
    run_until(2000u);
    TEST_ASSERT_EQUAL(GPS_UBX_RUNNING, link.state);
    const uint32_t host = sim.host_baud;
    sim_reset(9600u, 0);
    sim.host_baud = host;
    sim.next_nmea_ms = now_ms;
    running_at_ms = 0u;
    run_until(10000u);
    TEST_ASSERT_EQUAL(GPS_UBX_RUNNING, link.state);
    TEST_ASSERT_EQUAL_UINT32(1u, link.restarts);
    TEST_ASSERT_EQUAL_UINT32(115200u, sim.rx_baud);
    TEST_ASSERT_EQUAL_UINT16(200u, sim.meas_ms);
    TEST_ASSERT_EQUAL_UINT8(0u, link.lost);
    assert_sim_solution(&last_fresh);
}

/* Lost bytes and garbage: ACKs and solutions are lost now and then, the
 * sequence retries, and every solution that gets through is exact. */
static void test_drops_and_garbage(void)
{
    sim.drop_every = 331u; /* a prime, so the drops move through the frames */
    sim.garbage = 1u;
    TEST_ASSERT_EQUAL(BOARD_OK, gps_ubx_link_init(&link, NULL, &IO, 0u));
    run_until(4000u);
    TEST_ASSERT_EQUAL(GPS_UBX_RUNNING, link.state);
    const uint32_t before = fresh_reads;
    run_until(24000u);
    /* 100 solutions sent, 107 bytes each with the junk: 10700 bytes, 32
     * dropped, each in a different solution (331 > 107) or in the junk:
     * about 100 - 32 * 100 / 107 = 70 get through */
    TEST_ASSERT_TRUE(fresh_reads - before >= 60u);
    TEST_ASSERT_TRUE(fresh_reads - before <= 80u);
    assert_sim_solution(&last_fresh);
    TEST_ASSERT_TRUE(link.dec.counts.bad_checksum > 0u);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_pvt_conversion);
    RUN_TEST(test_init_refused);
    RUN_TEST(test_end_to_end_from_default);
    RUN_TEST(test_already_at_working_baud);
    RUN_TEST(test_nak_then_ack);
    RUN_TEST(test_lost_ack_retried);
    RUN_TEST(test_nak_exhausted_backs_off);
    RUN_TEST(test_mute_receiver);
    RUN_TEST(test_fresh_once_per_solution);
    RUN_TEST(test_lost_and_back);
    RUN_TEST(test_receiver_restart);
    RUN_TEST(test_drops_and_garbage);
    return UNITY_END();
}
