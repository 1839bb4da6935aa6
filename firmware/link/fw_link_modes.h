/*
 * fw_link_modes.h - the flight modes as HEARTBEAT.custom_mode
 * (fw_link_modes.c): the numbers the telemetry reports and the commands
 * accept.
 */
#ifndef HT_FW_LINK_MODES_H
#define HT_FW_LINK_MODES_H

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* The custom_mode of each flight mode: the numbers fixed-wing ground
 * stations already name (MAVProxy, Mission Planner and QGroundControl's
 * ArduPilot plugin read a fixed-wing custom_mode with the ArduPlane table),
 * so that a user sees "MANUAL", "FBWA", "AUTO" and "RTL" and can type
 * them; no other number is accepted. */
typedef enum {
    FW_LINK_CUSTOM_MANUAL = 0,    /* HT_MODE_MANUAL */
    FW_LINK_CUSTOM_FBW = 5,       /* HT_MODE_FBW: "FBWA" */
    FW_LINK_CUSTOM_WAYPOINT = 10, /* HT_MODE_WAYPOINT: "AUTO" */
    FW_LINK_CUSTOM_RTH = 11       /* HT_MODE_RTH: "RTL" */
} fw_link_custom_mode_t;

/* The custom_mode of an ht_mode_t (HT_MODE_MANUAL for anything else). */
uint32_t fw_link_custom_mode(uint8_t ht_mode);
/* The ht_mode_t of a custom_mode, or -1 for a number that names none. */
int32_t fw_link_mode_of_custom(uint32_t custom_mode);

#ifdef __cplusplus
}
#endif

#endif /* HT_FW_LINK_MODES_H */
