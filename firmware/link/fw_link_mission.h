/*
 * fw_link_mission.h - the MAVLink mission protocol (fw_link_mission.c).
 */
#ifndef HT_FW_LINK_MISSION_H
#define HT_FW_LINK_MISSION_H

#include "link/fw_link_types.h"

#ifdef __cplusplus
extern "C" {
#endif

/* A received, accepted frame (ids not its own are ignored). */
void fw_link_mission_rx(fw_link_t *l, const mavlink_message_t *msg);
/* After a control step: the mission protocol's timeouts and pending list. */
void fw_link_mission_after_step(fw_link_t *l);

#ifdef __cplusplus
}
#endif

#endif /* HT_FW_LINK_MISSION_H */
