/*
 * fw_link_command.h - the commands (fw_link_command.c).
 */
#ifndef HT_FW_LINK_COMMAND_H
#define HT_FW_LINK_COMMAND_H

#include "link/fw_link_types.h"

#ifdef __cplusplus
extern "C" {
#endif

/* A received, accepted frame (ids not its own are ignored). */
void fw_link_command_rx(fw_link_t *l, const mavlink_message_t *msg);

#ifdef __cplusplus
}
#endif

#endif /* HT_FW_LINK_COMMAND_H */
