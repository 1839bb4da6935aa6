/*
 * gps_ubx_link.h - a u-blox GPS receiver on a UART: its start-up
 * configuration, and its NAV-PVT solutions as the firmware's board_gps_t.
 * MCU-independent: the board gives a byte sink and a baud switch (the
 * io callbacks), the bytes received since the last poll, and the time.
 *
 * Configuration (u-blox 8 / M8 receiver description, UBX-13003221: the
 * UBX-CFG-PRT, UBX-CFG-MSG, UBX-CFG-RATE and UBX-ACK message pages; the
 * encoders are the library's, ubx.h), a state machine advanced by
 * gps_ubx_link_poll, which never waits:
 *
 *   1. PROBE   set the host UART to a guess of the receiver's baud (the
 *              working baud first, in case the receiver kept it, then 9600,
 *              the u-blox default, 38400, 57600, 115200, 230400) and send
 *              CFG-PRT: this UART at the working baud, UBX in and out only.
 *              UBX-only output is what turns the default NMEA messages off
 *              on this port, so no per-message NMEA CFG-MSG is needed. The
 *              receiver answers (if at all) after switching, so its ACK is
 *              not waited for.
 *   2. SETTLE  after settle_ms (the CFG-PRT bytes must have left at the
 *              probe baud and the receiver must have switched) set the host
 *              UART to the working baud.
 *   3. MSG     send CFG-MSG NAV-PVT once per solution; wait ack_timeout_ms
 *              for ACK-ACK of CFG-MSG. ACK-NAK or silence: send again, up to
 *              `tries` times in all.
 *   4. RATE    send CFG-RATE meas_rate_ms (200: 5 Hz, one solution per
 *              measurement); the same ACK wait and tries.
 *   5. RUNNING NAV-PVT flows. If none comes for reconfig_after_ms the
 *              receiver is assumed to have restarted (power, brown-out: back
 *              at 9600 with NMEA) and the sequence starts again at 1.
 *
 * A step that runs out of tries without any answer: the receiver was not
 * listening at this baud, and the next probe baud is tried (step 1). After
 * the last probe, or when the receiver answered with ACK-NAK (it hears us
 * and refuses: another baud will not help), the link waits backoff_ms and
 * starts again with the first probe. Every step is bounded, the sequence
 * repeats forever, nothing blocks.
 *
 * Solutions: every NAV-PVT decoded (in any state) becomes the current
 * solution, converted by gps_ubx_pvt_to_board; gps_ubx_link_read reports it
 * with fresh = 1 once, fresh = 0 after. No NAV-PVT for more than
 * lost_after_ms (or none yet): lost, and the fix reads 0.
 *
 * Time is a free-running uint32 millisecond count (wraps after 49 days).
 */
#ifndef HT_GPS_UBX_LINK_H
#define HT_GPS_UBX_LINK_H

#include <stddef.h>
#include <stdint.h>

#include "helical/board.h"
#include "helical/protocols/ubx.h"

/* The u-blox M8's velocity limit is 500 m/s (its data sheet's operational
 * limits): a larger NAV-PVT velocity is garbage, clamped to this. */
#define GPS_UBX_VEL_MAX_CM_S 50000
#define GPS_UBX_PROBES_MAX   6u

typedef struct {
    void *ctx;
    /* Queue n bytes for sending; returns how many were taken (a short count
     * is counted, the ACK timeout then retries). */
    size_t (*write)(void *ctx, const uint8_t *bytes, size_t n);
    /* Reprogram the host UART's baud rate. */
    void (*set_baud)(void *ctx, uint32_t baud);
} gps_ubx_io_t;

typedef struct {
    uint8_t port_id;            /* the receiver's UART wired to us: 1 (UART1) or 2 */
    uint32_t baud;              /* the working baud */
    uint16_t meas_rate_ms;      /* CFG-RATE: 200 ms = 5 Hz */
    uint16_t ack_timeout_ms;    /* wait for ACK-ACK / ACK-NAK */
    uint8_t tries;              /* sends of one message per probe (>= 1) */
    uint16_t settle_ms;         /* after CFG-PRT, before switching our baud */
    uint16_t lost_after_ms;     /* no NAV-PVT this long: lost */
    uint16_t reconfig_after_ms; /* running, no NAV-PVT this long: configure again */
    uint16_t backoff_ms;        /* all probes failed: wait, then start again */
} gps_ubx_config_t;

/* 115200 baud leaves room: NAV-PVT is 100 bytes, 5 a second = 500 B/s.
 * settle 100 ms: CFG-PRT is 28 bytes, 29 ms at 9600 baud, plus the switch. */
#define GPS_UBX_CONFIG_DEFAULT                                                                     \
    {                                                                                              \
        1u, 115200u, 200u, 250u, 3u, 100u, 1000u, 3000u, 2000u                                     \
    }

typedef enum {
    GPS_UBX_START = 0, /* nothing sent yet: the first poll starts */
    GPS_UBX_SETTLE,    /* CFG-PRT sent at a probe baud */
    GPS_UBX_WAIT_MSG,  /* CFG-MSG NAV-PVT sent, waiting for its ACK */
    GPS_UBX_WAIT_RATE, /* CFG-RATE sent, waiting for its ACK */
    GPS_UBX_RUNNING,   /* configured */
    GPS_UBX_BACKOFF    /* every probe failed: waiting before starting again */
} gps_ubx_state_t;

typedef struct {
    gps_ubx_config_t cfg;
    gps_ubx_io_t io;
    ubx_decoder_t dec;

    gps_ubx_state_t state;
    uint32_t probes[GPS_UBX_PROBES_MAX];
    uint8_t n_probes;
    uint8_t probe;     /* index into probes */
    uint8_t sent;      /* sends of the awaited message at this probe */
    uint8_t nak_seen;  /* an ACK-NAK for the awaited message at this probe */
    uint8_t ack;       /* 0 none, 1 ACK-ACK, 2 ACK-NAK for the awaited message */
    uint32_t since_ms; /* when the current state's wait began */
    uint32_t baud_now; /* the host UART's baud, as last set */

    board_gps_t solution;  /* the latest NAV-PVT, converted */
    uint32_t solution_seq; /* NAV-PVTs decoded */
    uint32_t seq_read;     /* solution_seq at the last read */
    uint32_t last_pvt_ms;
    uint8_t lost; /* 1 until the first NAV-PVT */

    /* counters (saturating) */
    uint32_t naks;
    uint32_t ack_timeouts;
    uint32_t short_writes;
    uint32_t restarts; /* sequences started again (backoff or reconfiguration) */
    uint32_t losses;   /* times the solution stream was declared lost */
} gps_ubx_link_t;

/*
 * Set up the link (sends nothing: the first poll starts the sequence).
 * cfg NULL takes GPS_UBX_CONFIG_DEFAULT. BOARD_ERR_NULL (g, io, or a
 * callback NULL), BOARD_ERR_RANGE (port_id not 1 or 2, baud outside
 * 4800..921600, meas_rate_ms, tries, ack_timeout_ms or lost_after_ms 0):
 * nothing written. BOARD_OK.
 */
board_status_t gps_ubx_link_init(gps_ubx_link_t *g, const gps_ubx_config_t *cfg,
                                 const gps_ubx_io_t *io, uint32_t now_ms);

/*
 * Feed the n bytes received since the last poll (n may be 0; call every
 * tick), then advance the configuration and the lost check. Nothing on NULL
 * g, or NULL bytes with n > 0.
 */
void gps_ubx_link_poll(gps_ubx_link_t *g, const uint8_t *bytes, size_t n, uint32_t now_ms);

/*
 * The current solution into *out: fresh = 1 on the first read after each new
 * NAV-PVT; while lost, fix = 0 (the other fields hold the last solution).
 * BOARD_OK when fresh, BOARD_ERR_NO_DATA when not, BOARD_ERR_NULL.
 */
board_status_t gps_ubx_link_read(gps_ubx_link_t *g, board_gps_t *out);

/*
 * NAV-PVT to board_gps_t (fresh left 0):
 *   fix   3 for fixType 3 (3-D) or 4 (GNSS + dead reckoning), 2 for fixType
 *         2, each only with gnssFixOK (flags bit 0: within the DOP and
 *         accuracy masks); 0 otherwise (no fix, dead reckoning only, time
 *         only, or not gnssFixOK)
 *   lat/lon  1e-7 deg as sent
 *   alt_cm   hMSL mm / 10, rounded to nearest (halves away from zero)
 *   vel_ned_cm_s  velN/E/D mm/s / 10, rounded likewise, clamped to
 *                 +-GPS_UBX_VEL_MAX_CM_S
 */
void gps_ubx_pvt_to_board(const ubx_nav_pvt_t *pvt, board_gps_t *out);

#endif /* HT_GPS_UBX_LINK_H */
