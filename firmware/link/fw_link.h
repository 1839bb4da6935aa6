/*
 * fw_link.h - the MAVLink 2 ground-station link of the firmware step
 * (docs/mavlink.md): telemetry, the parameter protocol over the one
 * parameter table, the mission protocol into the waypoint guidance, and the
 * mode commands. Every host (the flight image on a UART, the SIL on UDP)
 * moves bytes only; this code builds and parses every frame.
 *
 *   fw_link_init(&link, &fw, &cfg, sysid, compid);   // after fw_init(&fw, &cfg)
 *   loop:
 *     fw_link_rx(&link, bytes, n);                   // what the ground station sent
 *     fw_step(&fw, &in, &out);
 *     if (out.control_ran) fw_link_after_step(&link, &out, now_ms);
 *     n = fw_link_tx(&link, buf, sizeof buf);        // send these n bytes
 *
 * The messages are the pinned pymavlink generator's (mavgen, common.xml,
 * MAVLink 2: cmake/mavgen.cmake): its structs, ids, lengths, CRC extras.
 * None of its helpers that keep global state is called: the parser's and the
 * sender's status and buffers live in fw_link_t.
 *
 * Integer only on every path (MAVLink's float fields are produced and read as
 * IEEE-754 binary32 bit patterns, src/math/f32_bits.c); no allocation, no globals;
 * not reentrant: call all four functions from one thread, between steps (the
 * link changes the configuration and the controllers of fw_t).
 *
 * The files, from the base up (each uses only the ones above it):
 *   fw_link_params.c, src/math/f32_bits.c, fw_link_modes.c  the LINK rows, binary32,
 *                                                    custom_mode (public)
 *   fw_link_types.h        the state, fw_link_t
 *   fw_link_tx.c           the transmit queue and what the protocols share
 *   fw_link_param_table.c  the parameter table as MAVLink sees it (public)
 *   fw_link_telemetry.c    the telemetry streams
 *   fw_link_param_proto.c, fw_link_mission.c, fw_link_command.c  the protocols
 *   fw_link.c              this API: init, the receive side's parse and
 *                          dispatch, after_step, the queue's drain
 * This header includes the public ones; the others are the link's own.
 */
#ifndef HT_FW_LINK_H
#define HT_FW_LINK_H

#include <stddef.h>
#include <stdint.h>

#include "fw_step.h"
#include "helical/params.h"
#include "helical/math/f32_bits.h"
#include "link/fw_link_modes.h"
#include "link/fw_link_param_table.h"
#include "link/fw_link_params.h"
#include "link/fw_link_types.h"

/* The autopilot's component id, MAV_COMP_ID_AUTOPILOT1 of common.xml (which
 * this header does not include; test_fw_link checks that they agree). */
#define FW_LINK_COMPID_AUTOPILOT 1u

#ifdef __cplusplus
extern "C" {
#endif

/* 0 = ready; -1 = NULL argument or cfg_live is not fw->cfg. sysid 0 takes
 * the table's default (LNK_SYSID). */
int fw_link_init(fw_link_t *l, fw_t *fw, fw_config_t *cfg_live, uint8_t sysid, uint8_t compid);

/* Parse bytes (any split: a frame may span calls) and act on each frame. */
void fw_link_rx(fw_link_t *l, const uint8_t *bytes, size_t n);

/* After a control step (out->control_ran): queue the telemetry that is due
 * at now_ms, the parameter list's next values, the mission protocol's
 * retries. */
void fw_link_after_step(fw_link_t *l, const fw_output_t *out, uint32_t now_ms);

/* Move up to cap queued bytes to buf (whole frames first in, first out; a
 * frame may be split across calls). Returns the bytes written. */
size_t fw_link_tx(fw_link_t *l, uint8_t *buf, size_t cap);

#ifdef __cplusplus
}
#endif

#endif /* HT_FW_LINK_H */
