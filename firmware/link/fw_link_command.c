/*
 * fw_link_command.c - commands: COMMAND_LONG and COMMAND_INT (the same
 * commands, params 1..4 as floats; COMMAND_INT's x, y are integers), and
 * SET_MODE, each answered with one COMMAND_ACK (ACCEPTED, DENIED,
 * UNSUPPORTED or FAILED: never silence); a DENIED or FAILED one also with a
 * STATUSTEXT naming the reason (fw_link_text.h).
 *
 *   MAV_CMD_DO_SET_MODE, MAV_CMD_NAV_RETURN_TO_LAUNCH    the flight modes
 *   MAV_CMD_COMPONENT_ARM_DISARM                         DENIED: no arming yet
 *   MAV_CMD_PREFLIGHT_STORAGE                            param1 = 1, on the ground
 *   MAV_CMD_SET_MESSAGE_INTERVAL, GET_MESSAGE_INTERVAL   the streams
 *   MAV_CMD_REQUEST_MESSAGE, REQUEST_AUTOPILOT_CAPABILITIES
 *
 * A ground-station mode reaches the flight modes through fw_t.gcs_mode: the
 * step puts the pulse that selects it in place of the mode switch's
 * (fw_step.c), so the modes' own rules hold: the RC-loss failsafe still
 * wins (return home), and the pilot takes the mode back by moving the
 * switch. Modes: custom_mode = fw_link_custom_mode_t (ArduPlane's numbers,
 * fw_link_modes.h); without MAV_MODE_FLAG_CUSTOM_MODE_ENABLED the base
 * mode's flags choose (AUTO: waypoint, STABILIZE: fly-by-wire, else manual).
 * A mode number that is not an exact integer is refused (10.4 is not AUTO).
 */
#include "link/fw_link_command.h"

#include "helical/math/f32_bits.h"
#include "link/fw_link_modes.h"
#include "link/fw_link_telemetry.h"
#include "link/fw_link_text.h"
#include "link/fw_link_tx.h"

/* SET_MESSAGE_INTERVAL's bounds on the heartbeat: 50 Hz (LNK_HEARTBEAT_HZ's
 * top) to 1 Hz (its bottom: a ground station drops a link silent for a few
 * seconds) */
#define HEARTBEAT_MIN_US 20000
#define HEARTBEAT_MAX_US 1000000

/* One command, from either message. */
typedef struct {
    uint16_t command;
    uint32_t param_bits[4]; /* params 1..4, binary32 */
} command_t;

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

/* the reason of a refusal: "<what> refused: <why>" */
static void refusal(fw_link_t *l, const char *what, const char *why)
{
    fw_link_text_t t;
    fw_link_text_start(&t, what);
    fw_link_text_str(&t, " refused: ");
    fw_link_text_str(&t, why);
    (void)fw_link_statustext(l, (uint8_t)MAV_SEVERITY_WARNING, &t);
}

/* param k (1..4) as an exact integer: 0, or -1 (NaN, infinity, a fraction,
 * beyond int32) */
static int param_exact(const command_t *c, unsigned k, int32_t *v)
{
    const uint32_t bits = c->param_bits[k - 1u];
    int32_t r = 0;
    if (ht_f32_to_fixed(bits, 1, &r) != 0) {
        return -1; /* NaN, infinity or saturated */
    }
    /* exact when the integer converts back to the same number (-0 is 0) */
    if ((ht_f32_from_ratio((int64_t)r, 1u) != bits) && !((r == 0) && (bits == 0x80000000u))) {
        return -1;
    }
    *v = r;
    return 0;
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
        refusal(l, "mode", "no such mode (MANUAL 0 FBWA 5 AUTO 10 RTL 11)");
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
                     (uint64_t)MAV_PROTOCOL_CAPABILITY_PARAM_ENCODE_C_CAST |
                     (uint64_t)MAV_PROTOCOL_CAPABILITY_COMMAND_INT |
                     (uint64_t)MAV_PROTOCOL_CAPABILITY_MAVLINK2;
    (void)FW_LINK_QUEUE(l, AUTOPILOT_VERSION, v);
}

/* the aircraft may be flying: the airspeed or the ground speed at or above
 * the law's airspeed floor (LAW_V_MIN), the speed below which it does not
 * fly; until the first control step nothing says so */
static int flying(const fw_link_t *l)
{
    if (l->have_output == 0u) {
        return 0;
    }
    const int64_t v = l->cfg->law.v_min_cm_s;
    const int64_t vn = l->last.nav.vel_north_cm_s;
    const int64_t ve = l->last.nav.vel_east_cm_s;
    return (((int64_t)l->last.nav.airspeed_cm_s >= v) || (((vn * vn) + (ve * ve)) >= (v * v))) ? 1
                                                                                               : 0;
}

static uint8_t storage(fw_link_t *l, const command_t *c)
{
    int32_t op = 0;
    if ((param_exact(c, 1u, &op) != 0) || (op != 1)) {
        return (uint8_t)MAV_RESULT_UNSUPPORTED; /* only "write" */
    }
    if (l->save == NULL) {
        return (uint8_t)MAV_RESULT_UNSUPPORTED;
    }
    /* the board's write is a flash erase that stalls the loop (up to 0.5 s
     * on the Matek): on the ground only; once arming exists, disarmed only */
    if (flying(l) != 0) {
        refusal(l, "storage", "flying (speed >= LAW_V_MIN)");
        return (uint8_t)MAV_RESULT_DENIED;
    }
    if (l->save(l->save_ctx, l->cfg, &l->params) != 0) {
        refusal(l, "storage", "the board's write failed");
        return (uint8_t)MAV_RESULT_FAILED;
    }
    return (uint8_t)MAV_RESULT_ACCEPTED;
}

static uint8_t message_interval(fw_link_t *l, const command_t *c)
{
    int32_t id = 0;
    int32_t us = 0;
    if ((param_exact(c, 1u, &id) != 0) || (param_exact(c, 2u, &us) != 0) || (id < 0)) {
        refusal(l, "interval", "message id and interval must be integers");
        return (uint8_t)MAV_RESULT_DENIED;
    }
    const fw_link_stream_t s = fw_link_stream_of((uint32_t)id);
    if (s == FW_LINK_S_COUNT) {
        return (uint8_t)MAV_RESULT_UNSUPPORTED; /* a message the link does not stream */
    }
    if (us < -1) {
        refusal(l, "interval", "below -1");
        return (uint8_t)MAV_RESULT_DENIED;
    }
    if ((s == FW_LINK_S_HEARTBEAT) && (us != 0) &&
        ((us < HEARTBEAT_MIN_US) || (us > HEARTBEAT_MAX_US))) {
        refusal(l, "interval", "HEARTBEAT only 20000..1000000 us");
        return (uint8_t)MAV_RESULT_DENIED; /* never off, never slower than 1 Hz */
    }
    l->interval_override_us[s] = us;
    l->next_ms[s] = l->now_ms;
    return (uint8_t)MAV_RESULT_ACCEPTED;
}

static uint8_t get_interval(fw_link_t *l, const mavlink_message_t *msg, const command_t *c)
{
    int32_t id = 0;
    if ((param_exact(c, 1u, &id) != 0) || (id < 0) || (id > 0xFFFF)) {
        refusal(l, "interval", "message id must be an integer");
        return (uint8_t)MAV_RESULT_DENIED;
    }
    const fw_link_stream_t s = fw_link_stream_of((uint32_t)id);
    mavlink_message_interval_t mi;
    (void)memset(&mi, 0, sizeof mi);
    mi.message_id = (uint16_t)id;
    /* the spec: -1 not available, 0 off */
    mi.interval_us = (s == FW_LINK_S_COUNT) ? -1 : fw_link_stream_interval_us(l, s);
    (void)msg;
    (void)FW_LINK_QUEUE(l, MESSAGE_INTERVAL, mi);
    return (uint8_t)MAV_RESULT_ACCEPTED;
}

static uint8_t request_message(fw_link_t *l, const command_t *c)
{
    int32_t id = 0;
    if ((param_exact(c, 1u, &id) != 0) || (id < 0)) {
        refusal(l, "request", "message id must be an integer");
        return (uint8_t)MAV_RESULT_DENIED;
    }
    if (id == (int32_t)MAVLINK_MSG_ID_AUTOPILOT_VERSION) {
        autopilot_version(l);
        return (uint8_t)MAV_RESULT_ACCEPTED;
    }
    const fw_link_stream_t s = fw_link_stream_of((uint32_t)id);
    if (s == FW_LINK_S_COUNT) {
        return (uint8_t)MAV_RESULT_UNSUPPORTED; /* a message the link cannot send */
    }
    l->request_now[s] = 1u; /* with the next step's values */
    return (uint8_t)MAV_RESULT_ACCEPTED;
}

static uint8_t do_set_mode(fw_link_t *l, const command_t *c)
{
    int32_t base = 0;
    int32_t custom = 0;
    if ((param_exact(c, 1u, &base) != 0) || (param_exact(c, 2u, &custom) != 0) || (base < 0) ||
        (custom < 0)) {
        refusal(l, "mode", "base and custom mode must be integers >= 0");
        return (uint8_t)MAV_RESULT_DENIED;
    }
    return set_mode(l, mode_of((uint32_t)base, (uint32_t)custom));
}

static void command(fw_link_t *l, const mavlink_message_t *msg, const command_t *c)
{
    uint8_t result;
    switch (c->command) {
    case MAV_CMD_DO_SET_MODE:
        result = do_set_mode(l, c);
        break;
    case MAV_CMD_NAV_RETURN_TO_LAUNCH:
        result = set_mode(l, (int32_t)HT_MODE_RTH);
        break;
    case MAV_CMD_COMPONENT_ARM_DISARM:
        /* the image is live from power-up (fw_link_armed): nothing to arm
         * or disarm until the arming work exists */
        refusal(l, "arm", "not implemented, always armed");
        result = (uint8_t)MAV_RESULT_DENIED;
        break;
    case MAV_CMD_PREFLIGHT_STORAGE:
        result = storage(l, c);
        break;
    case MAV_CMD_SET_MESSAGE_INTERVAL:
        result = message_interval(l, c);
        break;
    case MAV_CMD_GET_MESSAGE_INTERVAL:
        result = get_interval(l, msg, c);
        break;
    case MAV_CMD_REQUEST_MESSAGE:
        result = request_message(l, c);
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
    command_ack(l, msg, c->command, result);
}

/* param1..param4: four consecutive binary32 fields (4 bytes each) at the
 * start of COMMAND_LONG and of COMMAND_INT */
static void four_params(const void *payload, size_t param1, uint32_t bits[4])
{
    for (size_t i = 0u; i < 4u; ++i) {
        bits[i] = fw_link_get_f32(payload, param1 + (4u * i));
    }
}

void fw_link_command_rx(fw_link_t *l, const mavlink_message_t *msg)
{
    command_t c;
    (void)memset(&c, 0, sizeof c);
    if (msg->msgid == (uint32_t)MAVLINK_MSG_ID_COMMAND_LONG) {
        mavlink_command_long_t cl;
        mavlink_msg_command_long_decode(msg, &cl);
        c.command = cl.command;
        four_params(&cl, offsetof(mavlink_command_long_t, param1), c.param_bits);
        command(l, msg, &c);
    } else if (msg->msgid == (uint32_t)MAVLINK_MSG_ID_COMMAND_INT) {
        mavlink_command_int_t ci;
        mavlink_msg_command_int_decode(msg, &ci);
        c.command = ci.command;
        four_params(&ci, offsetof(mavlink_command_int_t, param1), c.param_bits);
        command(l, msg, &c);
    } else if (msg->msgid == (uint32_t)MAVLINK_MSG_ID_SET_MODE) {
        mavlink_set_mode_t sm;
        mavlink_msg_set_mode_decode(msg, &sm);
        const uint8_t result = set_mode(l, mode_of(sm.base_mode, sm.custom_mode));
        if (result != (uint8_t)MAV_RESULT_ACCEPTED) {
            fw_link_count(&l->count.rx_bad_content);
        }
        command_ack(l, msg, (uint16_t)MAV_CMD_DO_SET_MODE, result);
    } else {
        /* not a command */
    }
}
