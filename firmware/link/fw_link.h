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
 * IEEE-754 binary32 bit patterns, fw_link_f32.c); no allocation, no globals;
 * not reentrant: call all four functions from one thread, between steps (the
 * link changes the configuration and the controllers of fw_t).
 */
#ifndef HT_FW_LINK_H
#define HT_FW_LINK_H

#include <stddef.h>
#include <stdint.h>

#include "fw_step.h"
#include "helical/params.h"

/* the generated headers (a SYSTEM include directory of the build tree):
 * here only their types (the link's frame buffers and parser states); the
 * messages are the link's own files' (fw_link_internal.h), so that a user
 * of the link does not parse the ~230 message headers of common.xml */
#include "mavlink/mavlink_types.h"

/* The autopilot's component id, MAV_COMP_ID_AUTOPILOT1 of common.xml (which
 * this header does not include; test_fw_link checks that they agree). */
#define FW_LINK_COMPID_AUTOPILOT 1u

#ifdef __cplusplus
extern "C" {
#endif

/* The link's own parameters: params.def HT_PARAMS_LINK (rates, system id,
 * the mission protocol's timing). fw_link_params.c checks them. */
typedef struct {
    HT_PARAMS_LINK(HT_PARAM_X_FIELD)
} fw_link_params_t;

#define HT_PARAM_LINK_COUNT (0 HT_PARAMS_LINK(HT_PARAM_X_ONE))

#define HT_PARAM_X_LINK_ID(id, name, field, unit, fmt, lo, hi, def, desc) HT_LINK_P_##id,
typedef enum {
    HT_LINK_P_NONE = 0,
    HT_PARAMS_LINK(HT_PARAM_X_LINK_ID) HT_LINK_P_COUNT
} ht_link_param_id_t;

/* The table's defaults. */
void ht_link_params_default(fw_link_params_t *p);
/* The table's row of a parameter, or NULL. */
const ht_param_info_t *ht_link_param_info(ht_link_param_id_t id);
const char *ht_link_param_name(ht_link_param_id_t id);
/* The first row outside its bounds (table order), or HT_LINK_P_NONE. p must
 * not be NULL. */
ht_link_param_id_t ht_link_first_bad(const fw_link_params_t *p);

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
    uint8_t frame; /* MAV_FRAME_GLOBAL_INT or MAV_FRAME_GLOBAL_RELATIVE_ALT_INT */
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
} fw_link_counters_t;

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
    uint8_t apply_pending; /* an accepted list waits for the home position */
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
    /* mission */
    fw_link_mission_t mission;
    fw_link_item_t items[FW_LINK_MAX_WAYPOINTS];  /* the active list (download answers it) */
    fw_link_item_t upload[FW_LINK_MAX_WAYPOINTS]; /* an upload in progress */
    uint16_t item_count;
    ht_waypoint_t waypoints[FW_LINK_MAX_WAYPOINTS]; /* the active list in the guidance's frame */
    /* board */
    fw_link_save_fn save;
    void *save_ctx;
    fw_link_counters_t count;
} fw_link_t;

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

/* --- flight modes as HEARTBEAT.custom_mode (fw_link_command.c) ----------- */

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

/* --- the parameter table as MAVLink sees it (fw_link_param_table.c) ------- */

/* Parameters on the link: every row of every group of params.def. */
uint16_t fw_link_param_count(void);
/* The MAVLink param_id of row index (0-based): 16 characters at most,
 * NUL-terminated in id[17]; 0, or -1 for an index out of range ("" then). */
int fw_link_param_id(uint16_t index, char id[17]);
/* The index of a param_id (at most 16 characters, need not be terminated),
 * or -1. */
int32_t fw_link_param_find(const char *id);
/* A row's value in its stored format, and its table row. 0, or -1. */
int fw_link_param_get(const fw_link_t *l, uint16_t index, int32_t *raw,
                      const ht_param_info_t **row);
/* Set a row to raw (stored format): range-checked by the row, then the
 * group's joint checks and its block's init; applied to the live
 * configuration and the running controllers (the estimator and the flight
 * state are kept). 0 = applied; else nothing changed. */
int fw_link_param_set(fw_link_t *l, uint16_t index, int32_t raw);
/* The same rows in a configuration that is not flown (a board's stored set,
 * before fw_init): a row's value and table row from cfg (link_params for
 * the LINK group); raw may be NULL (cfg and link_params then may be too).
 * 0, or -1 for an index out of range or a NULL struct. */
int fw_link_param_get_cfg(const fw_config_t *cfg, const fw_link_params_t *link_params,
                          uint16_t index, int32_t *raw, const ht_param_info_t **row);
/* Put raw (stored format) into row index of cfg / link_params, checked
 * against the row's own range only: no joint check, no re-initialisation
 * (the caller runs the blocks' checks once every row is put, e.g. fw_init
 * and ht_link_first_bad). 0 = put; 1 = outside the row's range (nothing
 * changed); -1 = index out of range or a NULL struct. */
int fw_link_param_put_cfg(fw_config_t *cfg, fw_link_params_t *link_params, uint16_t index,
                          int32_t raw);

/* --- IEEE-754 binary32 bit patterns without float (fw_link_f32.c) -------- */

/* num / den (den > 0), rounded to nearest, ties to even. |num| < 2^62,
 * den < 2^31. */
uint32_t fw_f32_from_ratio(int64_t num, uint32_t den);
/* The binary32 value f times scale (1 .. 2^20), rounded to nearest (ties
 * away from zero), into *out. 0 = exact or rounded; 1 = saturated to
 * INT32_MIN / INT32_MAX; -1 = NaN or infinity (*out untouched). */
int fw_f32_to_fixed(uint32_t f, int32_t scale, int32_t *out);

#ifdef __cplusplus
}
#endif

#endif /* HT_FW_LINK_H */
