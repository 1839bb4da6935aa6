/*
 * fw_link_tx.h - the base of the link's files (fw_link_tx.c; not an API):
 * queueing a generated message, the mode the link reports, float fields by
 * bit pattern, the counters. The protocols (fw_link_telemetry.c,
 * fw_link_param_proto.c, fw_link_mission.c, fw_link_command.c) and the
 * dispatch above them (fw_link.c) use it; it uses none of them.
 */
#ifndef HT_FW_LINK_TX_H
#define HT_FW_LINK_TX_H

#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include "link/fw_link_types.h"
/* every message of common.xml (the generated headers of mavgen) */
#include "mavlink/common/mavlink.h"

/* Queue one message: the generated struct pkt (wire layout on a
 * little-endian target, as the generated pack functions copy it), framed
 * with the generated id, lengths and CRC extra. 0 = queued; 1 = no room
 * (tx_overflow counted). */
int fw_link_queue(fw_link_t *l, uint32_t msgid, const void *pkt, uint8_t len, uint8_t min_len,
                  uint8_t crc_extra);

/* the generated constants of message NAME */
// cppcheck-suppress misra-c2012-20.10 ; D-MAVLINK-NAMES: the generated constants by message name
#define FW_LINK_QUEUE(l, NAME, pkt)                                                                \
    fw_link_queue((l), MAVLINK_MSG_ID_##NAME, &(pkt), (uint8_t)MAVLINK_MSG_ID_##NAME##_LEN,        \
                  (uint8_t)MAVLINK_MSG_ID_##NAME##_MIN_LEN, (uint8_t)MAVLINK_MSG_ID_##NAME##_CRC)

/* now is at or after t (both free-running ms; apart by less than 2^31) */
static inline int fw_link_reached(uint32_t now, uint32_t t)
{
    return ((now - t) < 0x80000000U) ? 1 : 0;
}

/* A binary32 field of a generated (packed) struct, by its offset. */
static inline void fw_link_put_f32(void *pkt, size_t offset, uint32_t bits)
{
    // cppcheck-suppress misra-c2012-11.5 ; D-LINK-BYTES: a generated struct's bytes
    uint8_t *const bytes = (uint8_t *)pkt;
    // cppcheck-suppress misra-c2012-21.15 ; D-LINK-BYTES: a binary32 field's bytes
    (void)memcpy(&bytes[offset], &bits, sizeof bits);
}
static inline uint32_t fw_link_get_f32(const void *pkt, size_t offset)
{
    // cppcheck-suppress misra-c2012-11.5 ; D-LINK-BYTES: a generated struct's bytes
    const uint8_t *const bytes = (const uint8_t *)pkt;
    uint32_t bits;
    // cppcheck-suppress misra-c2012-21.15 ; D-LINK-BYTES: a binary32 field's bytes
    (void)memcpy(&bits, &bytes[offset], sizeof bits);
    return bits;
}

static inline void fw_link_count(uint32_t *c)
{
    if (*c != UINT32_MAX) {
        ++*c;
    }
}

/* The mode the link reports (ht_mode_t) from the last step. */
uint8_t fw_link_mode(const fw_link_t *l);

/* The armed state the link reports (HEARTBEAT's SAFETY_ARMED): the firmware
 * has no arming yet, so it is the truth of the image: armed once the step
 * drives the outputs (live from power-up). The one place the arming work
 * replaces (docs/mavlink.md "Arming"). */
int fw_link_armed(const fw_link_t *l);

#endif /* HT_FW_LINK_TX_H */
