/*
 * fw_link_param_proto.h - the MAVLink parameter protocol
 * (fw_link_param_proto.c).
 */
#ifndef HT_FW_LINK_PARAM_PROTO_H
#define HT_FW_LINK_PARAM_PROTO_H

#include <stdint.h>

#include "link/fw_link_types.h"

#ifdef __cplusplus
extern "C" {
#endif

/* A received, accepted frame (ids not its own are ignored). */
void fw_link_param_rx(fw_link_t *l, const mavlink_message_t *msg);
/* After a control step: the parameter list's next values. */
void fw_link_param_after_step(fw_link_t *l);

/* One PARAM_VALUE for a flat index. */
int fw_link_send_param_value(fw_link_t *l, uint16_t index);

#ifdef __cplusplus
}
#endif

#endif /* HT_FW_LINK_PARAM_PROTO_H */
