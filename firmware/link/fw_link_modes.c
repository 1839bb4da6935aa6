/*
 * fw_link_modes.c - the flight modes as HEARTBEAT.custom_mode (see
 * fw_link_modes.h): the telemetry reports them, the commands accept them.
 */
#include "link/fw_link_modes.h"

#include "helical/guidance/modes.h"

/* custom_mode of each ht_mode_t, in its order */
static const fw_link_custom_mode_t custom_of_mode[HT_MODE_COUNT] = {
    FW_LINK_CUSTOM_MANUAL, FW_LINK_CUSTOM_FBW, FW_LINK_CUSTOM_WAYPOINT, FW_LINK_CUSTOM_RTH};

uint32_t fw_link_custom_mode(uint8_t ht_mode)
{
    return (ht_mode < (uint8_t)HT_MODE_COUNT) ? (uint32_t)custom_of_mode[ht_mode]
                                              : (uint32_t)FW_LINK_CUSTOM_MANUAL;
}

int32_t fw_link_mode_of_custom(uint32_t custom_mode)
{
    int32_t mode = -1;
    for (uint8_t m = 0u; m < (uint8_t)HT_MODE_COUNT; ++m) {
        if ((uint32_t)custom_of_mode[m] == custom_mode) {
            mode = (int32_t)m;
        }
    }
    return mode;
}
