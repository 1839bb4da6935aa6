/*
 * fw_link_telemetry.h - the telemetry streams and their scheduler
 * (fw_link_telemetry.c).
 */
#ifndef HT_FW_LINK_TELEMETRY_H
#define HT_FW_LINK_TELEMETRY_H

#include <stdint.h>

#include "link/fw_link_types.h"

#ifdef __cplusplus
extern "C" {
#endif

/* After a control step: the telemetry that is due. */
void fw_link_telemetry_after_step(fw_link_t *l);

/* Send a telemetry stream's message now (also REQUEST_MESSAGE). */
void fw_link_send_stream(fw_link_t *l, fw_link_stream_t s);
/* The stream a message id belongs to, or FW_LINK_S_COUNT. */
fw_link_stream_t fw_link_stream_of(uint32_t msgid);
/* A stream's interval now (MESSAGE_INTERVAL): us; 0 = off. */
int32_t fw_link_stream_interval_us(const fw_link_t *l, fw_link_stream_t s);

#ifdef __cplusplus
}
#endif

#endif /* HT_FW_LINK_TELEMETRY_H */
