/*
 * rc_serial_link.h - a serial RC receiver (SBUS or CRSF) as the firmware's
 * RC seam sees it: the bytes the UART received, fed through the library's
 * frame decoder (rx_sbus.h, rx_crsf.h), become pulse widths in microseconds
 * with a freshness flag and a link-lost flag. MCU-independent: the board
 * moves bytes from its receive ring (boards/stm32f4/serial_rx_ring.h) and
 * gives the time; board_rc_read_us() is then rc_serial_link_read_us().
 *
 * A frame is usable (fresh, its pulses taken) unless:
 *   SBUS  - its failsafe flag is set (the receiver lost the link: its
 *           channels are hold or failsafe values): not usable, and the link
 *           is lost at once;
 *         - its frame-lost flag is set (the receiver missed a radio frame and
 *           repeats old values): not usable, the link not yet lost.
 *   CRSF  - it arrives while the last LINK_STATISTICS reported uplink link
 *           quality 0 (crsf_link_stats_t.link_lost: the receiver goes on
 *           sending held or failsafe channels): not usable; the link is lost
 *           from that report until a report with link quality above 0.
 * Both: no usable frame for more than timeout_us, and the link is lost.
 * Freshness follows the newest frame: an unusable frame decoded after a
 * usable one in the same poll leaves nothing fresh.
 * While not fresh, the firmware's own RC-loss policy counts the ticks.
 *
 * SBUS frames may only start after an idle line (rx_sbus.h: otherwise the
 * decoder can stay on a false frame phase with still sticks). The poll sees
 * time, not the line: a poll that brings no byte, RC_SERIAL_SBUS_GAP_US or
 * more after the last poll that brought bytes, knows the line has been idle
 * since that poll, so it calls sbus_line_gap() once. Within a frame the
 * bytes come every 120 us (12 bits at 100 kbaud), between frames the line
 * is idle for 4 ms or more (a 3 ms frame every 7 ms or more). The gap is
 * therefore seen when the board polls at least every 3 ms (every 1 ms
 * recommended, e.g. from the main loop); polled only at the 25 ms control
 * tick, every poll finds bytes and no gap is seen: the decoder then relies
 * on its start/end byte search alone.
 *
 * Channels: receiver channel k (0..15) is pulse_us[k] for k <
 * BOARD_MAX_RC_INPUTS (8); the rest are not passed on.
 *
 * Time is a free-running uint32 microsecond count (wraps after 71 minutes:
 * differences are taken modulo 2^32, and the lost flag latches, so a stale
 * time stamp is never compared after a wrap).
 */
#ifndef HT_RC_SERIAL_LINK_H
#define HT_RC_SERIAL_LINK_H

#include <stddef.h>
#include <stdint.h>

#include "helical/board.h"
#include "helical/protocols/rx_crsf.h"
#include "helical/protocols/rx_sbus.h"

#define RC_SERIAL_SBUS_GAP_US 1000u /* > 8 byte times, < a quarter of the 4 ms gap */
/* No usable frame for this long: lost (5 frames at 50 Hz, the slowest CRSF
 * rate; 7 to 14 SBUS frames). */
#define RC_SERIAL_TIMEOUT_US_DEFAULT 100000u

typedef enum { RC_SERIAL_SBUS = 1, RC_SERIAL_CRSF = 2 } rc_serial_protocol_t;

typedef struct {
    rc_serial_protocol_t protocol;
    uint32_t timeout_us;
    sbus_decoder_t sbus;
    crsf_decoder_t crsf;
    uint16_t pulse_us[BOARD_MAX_RC_INPUTS]; /* the last usable frame's (0 before one) */
    uint32_t last_frame_us;                 /* when the last usable frame was decoded */
    uint32_t last_bytes_us;                 /* the last poll that brought bytes */
    uint8_t fresh;                          /* a usable frame since the last read */
    uint8_t lost;                           /* link lost (1 until the first usable frame) */
    uint8_t crsf_link_down;                 /* the last link statistics said LQ 0 */
    uint8_t gap_seen;                       /* sbus_line_gap called for this idle spell */

    /* counters (saturating) */
    uint32_t frames_usable;
    uint32_t sbus_failsafe;   /* SBUS frames with the failsafe flag */
    uint32_t sbus_frame_lost; /* SBUS frames with the frame-lost flag */
    uint32_t crsf_lq_zero;    /* CRSF link statistics with uplink LQ 0 */
    uint32_t crsf_held;       /* CRSF channel frames ignored: link down */
    uint32_t timeouts;        /* times the link was declared lost for silence */
    uint32_t line_gaps;       /* sbus_line_gap calls */
} rc_serial_link_t;

/*
 * Start a link: protocol RC_SERIAL_SBUS or RC_SERIAL_CRSF, timeout_us > 0,
 * now_us the current time. Lost, not fresh, pulses 0, until the first usable
 * frame. BOARD_ERR_NULL, BOARD_ERR_RANGE (nothing written) or BOARD_OK.
 */
board_status_t rc_serial_link_init(rc_serial_link_t *l, rc_serial_protocol_t protocol,
                                   uint32_t timeout_us, uint32_t now_us);

/*
 * Feed the n bytes received since the last poll (n may be 0: call it anyway,
 * the timeout and the SBUS gap need the time). Bounded: each decoder call
 * takes at least one byte. Nothing on NULL l, or NULL bytes with n > 0.
 */
void rc_serial_link_poll(rc_serial_link_t *l, const uint8_t *bytes, size_t n, uint32_t now_us);

/*
 * board_rc_read_us for this link: pulse_us[0, count) from the last usable
 * frame (0 before one). BOARD_OK when a usable frame arrived since the
 * previous read, BOARD_ERR_NO_DATA when not; BOARD_ERR_NULL; BOARD_ERR_RANGE
 * for count > BOARD_MAX_RC_INPUTS (nothing written).
 */
board_status_t rc_serial_link_read_us(rc_serial_link_t *l, uint16_t pulse_us[], uint8_t count);

#endif /* HT_RC_SERIAL_LINK_H */
