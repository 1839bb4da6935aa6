/*
 * fw_link_command.c - commands: COMMAND_LONG (MAV_CMD_DO_SET_MODE,
 * MAV_CMD_NAV_RETURN_TO_LAUNCH, MAV_CMD_PREFLIGHT_STORAGE,
 * MAV_CMD_REQUEST_MESSAGE, MAV_CMD_SET_MESSAGE_INTERVAL,
 * MAV_CMD_REQUEST_AUTOPILOT_CAPABILITIES) and SET_MODE, each answered with
 * COMMAND_ACK.
 *
 * A ground-station mode reaches the flight modes through fw_t.gcs_mode: the
 * step puts the pulse that selects it in place of the mode switch's
 * (fw_step.c), so the modes' own rules hold: the RC-loss failsafe still
 * wins (return home), and the pilot takes the mode back by moving the
 * switch. Modes: custom_mode = fw_link_custom_mode_t (fw_link_modes.h: 0
 * manual, 5 fly-by-wire, 10 waypoint, 11 return-to-home); without
 * MAV_MODE_FLAG_CUSTOM_MODE_ENABLED the base mode's flags choose (AUTO:
 * waypoint, STABILIZE: fly-by-wire, else manual).
 */
#include "link/fw_link_command.h"

#include "link/fw_link_f32.h"
#include "link/fw_link_modes.h"
#include "link/fw_link_telemetry.h"
#include "link/fw_link_tx.h"

static void command_ack(fw_link_t *l, const mavlink_message_t *msg, uint16_t command,
                        uint8_t result)
{
    mavlink_command_ack_t a;
    (void)memset(&a, 0, sizeof a);
    a.command = command;
    a.result = result;
    a.target_system = msg->sysid;
    a.target_component = msg->compid;
    (void)FW_LINK_QUEUE(l, COMMAND_ACK, a);
}

/* the ht_mode_t a base / custom mode pair asks for, or -1 */
static int32_t mode_of(uint32_t base, uint32_t custom)
{
    if ((base & (uint32_t)MAV_MODE_FLAG_CUSTOM_MODE_ENABLED) != 0u) {
        return fw_link_mode_of_custom(custom);
    }
    if ((base & (uint32_t)MAV_MODE_FLAG_AUTO_ENABLED) != 0u) {
        return (int32_t)HT_MODE_WAYPOINT;
    }
    if ((base & (uint32_t)MAV_MODE_FLAG_STABILIZE_ENABLED) != 0u) {
        return (int32_t)HT_MODE_FBW;
    }
    return (int32_t)HT_MODE_MANUAL;
}

static uint8_t set_mode(fw_link_t *l, int32_t mode)
{
    if ((mode < 0) || (mode >= (int32_t)HT_MODE_COUNT)) {
        return (uint8_t)MAV_RESULT_DENIED;
    }
    const uint8_t m8 = (uint8_t)mode; /* [0, 3] */
    l->fw->gcs_mode = (uint8_t)(m8 + 1u);
    l->fw->gcs_switch = UINT8_MAX; /* the switch's position is read at the next step */
    return (uint8_t)MAV_RESULT_ACCEPTED;
}

static void autopilot_version(fw_link_t *l)
{
    mavlink_autopilot_version_t v;
    (void)memset(&v, 0, sizeof v);
    v.capabilities = (uint64_t)MAV_PROTOCOL_CAPABILITY_MISSION_INT |
                     (uint64_t)MAV_PROTOCOL_CAPABILITY_PARAM_FLOAT |
                     (uint64_t)MAV_PROTOCOL_CAPABILITY_MAVLINK2;
    (void)FW_LINK_QUEUE(l, AUTOPILOT_VERSION, v);
}

/* a float parameter of a command as an integer; -1 for NaN / infinity */
static int32_t param_int(const mavlink_command_long_t *c, size_t offset, int32_t *v)
{
    return (fw_f32_to_fixed(fw_link_get_f32(c, offset), 1, v) < 0) ? -1 : 0;
}

static uint8_t storage(fw_link_t *l, const mavlink_command_long_t *c)
{
    int32_t op = 0;
    if ((param_int(c, offsetof(mavlink_command_long_t, param1), &op) != 0) || (op != 1)) {
        return (uint8_t)MAV_RESULT_UNSUPPORTED; /* only "write" */
    }
    if (l->save == NULL) {
        return (uint8_t)MAV_RESULT_UNSUPPORTED;
    }
    return (l->save(l->save_ctx, l->cfg, &l->params) == 0) ? (uint8_t)MAV_RESULT_ACCEPTED
                                                           : (uint8_t)MAV_RESULT_FAILED;
}

static uint8_t message_interval(fw_link_t *l, const mavlink_command_long_t *c)
{
    int32_t id = 0;
    int32_t us = 0;
    if ((param_int(c, offsetof(mavlink_command_long_t, param1), &id) != 0) ||
        (param_int(c, offsetof(mavlink_command_long_t, param2), &us) != 0) || (id < 0)) {
        return (uint8_t)MAV_RESULT_DENIED;
    }
    const fw_link_stream_t s = fw_link_stream_of((uint32_t)id);
    if ((s == FW_LINK_S_COUNT) || (us < -1) || ((s == FW_LINK_S_HEARTBEAT) && (us == -1))) {
        return (uint8_t)MAV_RESULT_DENIED; /* the heartbeat is never turned off */
    }
    l->interval_override_us[s] = us;
    l->next_ms[s] = l->now_ms;
    return (uint8_t)MAV_RESULT_ACCEPTED;
}

static uint8_t request_message(fw_link_t *l, const mavlink_command_long_t *c)
{
    int32_t id = 0;
    if ((param_int(c, offsetof(mavlink_command_long_t, param1), &id) != 0) || (id < 0)) {
        return (uint8_t)MAV_RESULT_DENIED;
    }
    if (id == (int32_t)MAVLINK_MSG_ID_AUTOPILOT_VERSION) {
        autopilot_version(l);
        return (uint8_t)MAV_RESULT_ACCEPTED;
    }
    const fw_link_stream_t s = fw_link_stream_of((uint32_t)id);
    if (s == FW_LINK_S_COUNT) {
        return (uint8_t)MAV_RESULT_DENIED;
    }
    l->request_now[s] = 1u; /* with the next step's values */
    return (uint8_t)MAV_RESULT_ACCEPTED;
}

static void command_long(fw_link_t *l, const mavlink_message_t *msg)
{
    mavlink_command_long_t c;
    mavlink_msg_command_long_decode(msg, &c);
    uint8_t result;
    switch (c.command) {
    case MAV_CMD_DO_SET_MODE: {
        int32_t base = 0;
        int32_t custom = 0;
        if ((param_int(&c, offsetof(mavlink_command_long_t, param1), &base) != 0) ||
            (param_int(&c, offsetof(mavlink_command_long_t, param2), &custom) != 0) || (base < 0) ||
            (custom < 0)) {
            result = (uint8_t)MAV_RESULT_DENIED;
        } else {
            result = set_mode(l, mode_of((uint32_t)base, (uint32_t)custom));
        }
        break;
    }
    case MAV_CMD_NAV_RETURN_TO_LAUNCH:
        result = set_mode(l, (int32_t)HT_MODE_RTH);
        break;
    case MAV_CMD_PREFLIGHT_STORAGE:
        result = storage(l, &c);
        break;
    case MAV_CMD_SET_MESSAGE_INTERVAL:
        result = message_interval(l, &c);
        break;
    case MAV_CMD_REQUEST_MESSAGE:
        result = request_message(l, &c);
        break;
    case MAV_CMD_REQUEST_AUTOPILOT_CAPABILITIES:
        autopilot_version(l);
        result = (uint8_t)MAV_RESULT_ACCEPTED;
        break;
    default:
        result = (uint8_t)MAV_RESULT_UNSUPPORTED;
        break;
    }
    if (result != (uint8_t)MAV_RESULT_ACCEPTED) {
        fw_link_count(&l->count.rx_bad_content);
    }
    command_ack(l, msg, c.command, result);
}

void fw_link_command_rx(fw_link_t *l, const mavlink_message_t *msg)
{
    if (msg->msgid == (uint32_t)MAVLINK_MSG_ID_COMMAND_LONG) {
        command_long(l, msg);
    } else if (msg->msgid == (uint32_t)MAVLINK_MSG_ID_SET_MODE) {
        mavlink_set_mode_t sm;
        mavlink_msg_set_mode_decode(msg, &sm);
        const uint8_t result = set_mode(l, mode_of(sm.base_mode, sm.custom_mode));
        command_ack(l, msg, (uint16_t)MAV_CMD_DO_SET_MODE, result);
    } else {
        /* not a command */
    }
}
