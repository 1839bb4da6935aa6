/*
 * fw_link_types.h - the link's state (fw_link_t) and the types in it: what
 * every file of the link shares, below all of them (no functions). The API
 * is fw_link.h.
 */
#ifndef HT_FW_LINK_TYPES_H
#define HT_FW_LINK_TYPES_H

#include <stdint.h>

#include "fw_step.h"
#include "link/fw_link_params.h"

/* the generated headers (a SYSTEM include directory of the build tree):
 * here only their types (the link's frame buffers and parser states); the
 * messages are the link's own files' (fw_link_tx.h), so that a user of the
 * link does not parse the ~230 message headers of common.xml */
#include "mavlink/mavlink_types.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Telemetry streams (fw_link_telemetry.c), each at its parameter's rate. */
typedef enum {
    FW_LINK_S_HEARTBEAT = 0,
    FW_LINK_S_SYS_STATUS, /* also MISSION_CURRENT */
    FW_LINK_S_ATTITUDE,
    FW_LINK_S_POSITION, /* GLOBAL_POSITION_INT (once home is known) */
    FW_LINK_S_VFR_HUD,
    FW_LINK_S_SERVO, /* SERVO_OUTPUT_RAW */
    FW_LINK_S_RC,    /* RC_CHANNELS */
    FW_LINK_S_LAW,   /* DEBUG_VECT "HT_LAW": tilt target z, roll error, pitch error */
    FW_LINK_S_COUNT
} fw_link_stream_t;

/* The waypoint store: what the ground station uploaded (bounded). */
#define FW_LINK_MAX_WAYPOINTS 32u
typedef struct {
    int32_t lat_e7, lon_e7;
    int32_t z_cm;  /* the item's altitude, as uploaded (frame says its datum) */
    uint8_t frame; /* as uploaded: MAV_FRAME_GLOBAL(_INT) (above mean sea level) or
                      MAV_FRAME_GLOBAL_RELATIVE_ALT(_INT) (above home) */
} fw_link_item_t;

/* Transmit queue: whole frames only (a frame that does not fit is counted
 * in tx_overflow and not sent). */
#define FW_LINK_TX_BYTES 1024u

/* Counters (saturating at UINT32_MAX). */
typedef struct {
    uint32_t rx_ok;           /* frames with a good CRC, accepted */
    uint32_t rx_dropped;      /* = the four below */
    uint32_t rx_bad_crc;      /* a known id whose CRC does not match (also a truncated frame,
                                 whose length then runs into the next one) */
    uint32_t rx_garbled;      /* unknown incompat flags, a signed frame */
    uint32_t rx_unknown_id;   /* an id that is not in common.xml */
    uint32_t rx_wrong_target; /* addressed to another system or component */
    uint32_t rx_bad_content;  /* accepted (in rx_ok), but refused: a NaN, a value out of range,
                                 an unknown parameter, an unsupported command */
    uint32_t tx_frames;       /* frames queued */
    uint32_t tx_overflow;     /* frames not queued: the transmit queue was full */
    uint32_t tx_text_dropped; /* STATUSTEXT not sent: over the text rate (fw_link_text.h) */
} fw_link_counters_t;

/* STATUSTEXT rate (fw_link_text.c): a burst of 5, then one per 200 ms. */
#define FW_LINK_TEXT_BURST     5u
#define FW_LINK_TEXT_REFILL_MS 200u

/* Board hook: store the configuration persistently (MAV_CMD_PREFLIGHT_STORAGE
 * param1 = 1). Returns 0 on success. NULL: the command is answered
 * MAV_RESULT_UNSUPPORTED. */
typedef int (*fw_link_save_fn)(void *ctx, const fw_config_t *cfg, const fw_link_params_t *link);

/* Mission protocol state (fw_link_mission.c). */
typedef struct {
    uint8_t uploading; /* 1: a MISSION_COUNT started an upload */
    uint8_t partner_sysid, partner_compid;
    uint16_t count;        /* items of the upload */
    uint16_t next;         /* the item requested */
    uint8_t retries;       /* requests re-sent for this item */
    uint32_t deadline_ms;  /* when the request is re-sent */
    uint8_t apply_pending; /* an accepted upload (in upload[]) waits for the home position */
    uint8_t legacy;        /* the upload came as MISSION_ITEM: requests are MISSION_REQUEST */
    uint16_t last_current; /* the current item last reported (MISSION_ITEM_REACHED) */
} fw_link_mission_t;

typedef struct {
    fw_t *fw;
    fw_config_t *cfg; /* == fw->cfg, writable: the live configuration */
    fw_link_params_t params;
    uint8_t compid;
    /* receive */
    mavlink_status_t rx_status;
    mavlink_message_t rx_msg;
    /* send */
    mavlink_status_t tx_status;
    mavlink_message_t tx_msg;
    uint8_t tx_buf[FW_LINK_TX_BYTES];
    uint16_t tx_len;
    /* telemetry */
    uint32_t now_ms;
    uint32_t next_ms[FW_LINK_S_COUNT];
    int32_t interval_override_us[FW_LINK_S_COUNT]; /* SET_MESSAGE_INTERVAL: 0 = the parameter's,
                                                      -1 = off */
    uint8_t request_now[FW_LINK_S_COUNT];          /* REQUEST_MESSAGE: send at the next step */
    fw_output_t last;                              /* the last step's output */
    uint8_t have_output;
    int32_t home_alt_cm; /* altitude when the home position was first seen */
    uint8_t have_home_alt;
    /* parameter protocol */
    uint16_t param_list_next; /* PARAM_REQUEST_LIST: next index to send; >= count: idle */
    char param_refusal[50];   /* why the last PARAM_SET was refused, a STATUSTEXT's text ("" after
                                 one applied): fw_link_param_set (fw_link_param_table.c) */
    /* mission */
    fw_link_mission_t mission;
    fw_link_item_t items[FW_LINK_MAX_WAYPOINTS];  /* the active list (download answers it) */
    fw_link_item_t upload[FW_LINK_MAX_WAYPOINTS]; /* an upload in progress, or accepted and
                                                     waiting for the home position */
    uint16_t item_count;
    uint16_t upload_count;                          /* items in upload[] once it is complete */
    ht_waypoint_t waypoints[FW_LINK_MAX_WAYPOINTS]; /* the active list in the guidance's frame */
    ht_waypoint_t candidate[FW_LINK_MAX_WAYPOINTS]; /* an accepted upload, converted and checked
                                                       before it replaces waypoints[] */
    /* STATUSTEXT rate (fw_link_text.c) */
    uint8_t text_tokens;
    uint32_t text_refill_ms;
    /* board */
    fw_link_save_fn save;
    void *save_ctx;
    fw_link_counters_t count;
} fw_link_t;

#ifdef __cplusplus
}
#endif

#endif /* HT_FW_LINK_TYPES_H */
