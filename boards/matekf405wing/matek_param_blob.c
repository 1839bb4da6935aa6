/*
 * matek_param_blob.c - the parameter blob from the link's table, its
 * fingerprint and the boot-time load (see matek_param_blob.h for the layout).
 */
#include "matek_param_blob.h"

#include <stddef.h>
#include <string.h>

#include "crc32.h"
#include "helical/guidance/config_check.h"

static uint32_t rd32(const uint8_t *p)
{
    return (uint32_t)p[0] | ((uint32_t)p[1] << 8) | ((uint32_t)p[2] << 16) | ((uint32_t)p[3] << 24);
}

static void wr32(uint8_t *p, uint32_t v)
{
    for (uint32_t b = 0u; b < 4u; ++b) {
        p[b] = (uint8_t)((v >> (8u * b)) & 0xFFu);
    }
}

static size_t text_len(const char *s, size_t max)
{
    size_t n = 0u;
    while ((n < max) && (s[n] != '\0')) {
        ++n;
    }
    return n;
}

uint32_t matek_param_fingerprint(void)
{
    uint32_t crc = 0u;
    const uint16_t count = fw_link_param_count();
    for (uint16_t i = 0u; i < count; ++i) {
        char id[17];
        const ht_param_info_t *row = NULL;
        (void)fw_link_param_id(i, id);
        (void)fw_link_param_get_cfg(NULL, NULL, i, NULL, &row);
        crc = crc32_iso_hdlc(crc, (const uint8_t *)id, text_len(id, 16u) + 1u);
        const char *fmt = ((row != NULL) && (row->format != NULL)) ? row->format : "";
        crc = crc32_iso_hdlc(crc, (const uint8_t *)fmt, text_len(fmt, 32u) + 1u);
    }
    return crc;
}

uint32_t matek_param_blob_bytes(void)
{
    return MATEK_PARAM_HEAD_BYTES + (4u * (uint32_t)fw_link_param_count());
}

int matek_param_blob_encode(const fw_config_t *cfg, const fw_link_params_t *link_params,
                            uint8_t blob[MATEK_PARAM_BLOB_MAX_BYTES])
{
    const uint16_t count = fw_link_param_count();
    if ((cfg == NULL) || (link_params == NULL) || (blob == NULL) ||
        ((uint32_t)count > MATEK_PARAM_MAX_ROWS)) {
        return -1;
    }
    (void)memset(blob, 0, MATEK_PARAM_BLOB_MAX_BYTES);
    blob[0] = (uint8_t)(count & 0xFFu);
    blob[1] = (uint8_t)(count >> 8);
    wr32(&blob[4], matek_param_fingerprint());
    for (uint16_t i = 0u; i < count; ++i) {
        int32_t raw = 0;
        if (fw_link_param_get_cfg(cfg, link_params, i, &raw, NULL) != 0) {
            return -1;
        }
        wr32(&blob[MATEK_PARAM_HEAD_BYTES + (4u * (uint32_t)i)], (uint32_t)raw);
    }
    return 0;
}

void matek_param_store(const param_flash_t *flash, param_store_t *out)
{
    out->flash = flash;
    out->schema_id = (uint16_t)MATEK_PARAM_SCHEMA_ID;
    out->schema_version = (uint16_t)MATEK_PARAM_SCHEMA_VERSION;
    out->length = matek_param_blob_bytes();
}

/* The link row whose table row is info, or -1. */
static int32_t index_of(const ht_param_info_t *info)
{
    const uint16_t count = fw_link_param_count();
    for (uint16_t i = 0u; (info != NULL) && (i < count); ++i) {
        const ht_param_info_t *row = NULL;
        if ((fw_link_param_get_cfg(NULL, NULL, i, NULL, &row) == 0) && (row == info)) {
            return (int32_t)i;
        }
    }
    return -1;
}

/* The table row of the modes' refusal (theirs, or a sub-module's). */
/* The row a joint rule names (config_check.h), or NULL (the sticks: not rows) */
static const ht_param_info_t *joint_row(ht_cfg_status_t s)
{
    const ht_param_info_t *row;
    switch (s) {
    case HT_CFG_MODE_ABSENT:
    case HT_CFG_MODE_ON_STICK:
        row = ht_modes_param_info(HT_MODES_P_MODE_INPUT);
        break;
    case HT_CFG_INVERTED_ABSENT:
    case HT_CFG_INVERTED_ON_STICK:
    case HT_CFG_INVERTED_ON_MODE:
        row = ht_fbw_param_info(HT_FBW_P_INVERTED_INPUT);
        break;
    case HT_CFG_INVERTED_THRESHOLD:
        row = ht_fbw_param_info(HT_FBW_P_INVERTED_THRESHOLD);
        break;
    case HT_CFG_ARRIVAL_RADIUS:
        row = ht_nav_param_info(HT_NAV_P_ARRIVAL_RADIUS);
        break;
    default:
        row = NULL;
        break;
    }
    return row;
}

static const ht_param_info_t *modes_row(const ht_modes_bad_t *bad)
{
    const ht_param_info_t *row;
    switch (bad->field) {
    case HT_MODES_P_FBW:
        row = ht_fbw_param_info((ht_fbw_param_id_t)bad->sub);
        break;
    case HT_MODES_P_NAV:
        row = ht_nav_param_info((ht_nav_param_id_t)bad->sub);
        break;
    case HT_MODES_P_AOA:
        row = ht_aoa_param_info((ht_aoa_param_id_t)bad->sub);
        break;
    case HT_MODES_P_ALT_HOLD:
        row = ht_alt_hold_param_info((ht_alt_param_id_t)bad->sub);
        break;
    case HT_MODES_P_SPEED_HOLD:
        row = ht_speed_hold_param_info((ht_speed_param_id_t)bad->sub);
        break;
    case HT_MODES_P_JOINT:
        row = joint_row((ht_cfg_status_t)bad->sub);
        break;
    default:
        row = ht_modes_param_info(bad->field);
        break;
    }
    return row;
}

/* The table row fw_init's refusal names, or NULL (a block without rows). */
static const ht_param_info_t *refused_row(const fw_t *fw)
{
    const ht_param_info_t *row;
    switch ((fw_bad_block_t)fw->bad) {
    case FW_BAD_DCM:
        row = ht_dcm_param_info((ht_dcm_param_id_t)fw->bad_sub);
        break;
    case FW_BAD_LAW:
        row = ht_param_info((ht_param_id_t)fw->bad_sub);
        break;
    case FW_BAD_GUIDE:
        row = ht_guide_param_info((ht_guide_param_id_t)fw->bad_sub);
        break;
    case FW_BAD_MODES:
        row = modes_row(&fw->modes_bad);
        break;
    default:
        row = NULL;
        break;
    }
    return row;
}

static void refuse(matek_params_report_t *rep, matek_params_bad_t why, int32_t index)
{
    rep->result = (uint8_t)MATEK_PARAMS_REFUSED;
    rep->bad = (uint8_t)why;
    rep->bad_index = (index < 0) ? -1 : index;
    if ((index < 0) || (fw_link_param_id((uint16_t)index, rep->bad_id) != 0)) {
        rep->bad_id[0] = '\0';
    }
}

/* Scratch for the load and its checks (file-static: this is the image, not
 * the library; used once, at boot, before the firmware's own fw_init). */
static uint8_t blob[MATEK_PARAM_BLOB_MAX_BYTES];
static fw_config_t put_cfg;
static fw_link_params_t put_link;

/* Put every row of blob into put_cfg / put_link (copies of cfg /
 * link_params); run the checks. 1 = accepted; 0 = rep says why. */
static int put_and_check(const fw_config_t *cfg, const fw_link_params_t *link_params,
                         matek_params_report_t *rep)
{
    static fw_t check_fw; /* fw_init's scratch: the checks are fw_init's own */
    const uint16_t count = fw_link_param_count();
    put_cfg = *cfg;
    put_link = *link_params;
    int32_t rate_row = -1;
    for (uint16_t i = 0u; i < count; ++i) {
        const int32_t raw = (int32_t)rd32(&blob[MATEK_PARAM_HEAD_BYTES + (4u * (uint32_t)i)]);
        if (fw_link_param_put_cfg(&put_cfg, &put_link, i, raw) != 0) {
            refuse(rep, MATEK_BAD_RANGE, (int32_t)i);
            return 0;
        }
        if ((rate_row < 0) && (put_cfg.dcm.imu_rate_hz != cfg->dcm.imu_rate_hz)) {
            rate_row = (int32_t)i;
        }
    }
    if (rate_row >= 0) {
        /* the board's tick, the decimation and the control divider are
         * built for this rate */
        refuse(rep, MATEK_BAD_IMU_RATE, rate_row);
        return 0;
    }
    if (fw_init(&check_fw, &put_cfg) == 0) {
        rep->bad_block = check_fw.bad;
        rep->bad_sub = ((fw_bad_block_t)check_fw.bad == FW_BAD_MODES)
                           ? (int32_t)check_fw.modes_bad.sub
                           : check_fw.bad_sub;
        if ((fw_bad_block_t)check_fw.bad == FW_BAD_MODES) {
            ht_modes_bad_name(&check_fw.modes_bad, rep->reason, (unsigned)sizeof rep->reason);
        }
        refuse(rep, MATEK_BAD_INIT, index_of(refused_row(&check_fw)));
        return 0;
    }
    const ht_link_param_id_t bad_link = ht_link_first_bad(&put_link);
    if (bad_link != HT_LINK_P_NONE) {
        rep->bad_sub = (int32_t)bad_link;
        refuse(rep, MATEK_BAD_LINK, index_of(ht_link_param_info(bad_link)));
        return 0;
    }
    return 1;
}

void matek_params_load(const param_flash_t *flash, fw_config_t *cfg, fw_link_params_t *link_params,
                       matek_params_report_t *rep)
{
    param_store_t store;
    param_store_load_t info;
    (void)memset(rep, 0, sizeof *rep);
    rep->result = (uint8_t)MATEK_PARAMS_CORRUPT;
    rep->bad_index = -1;
    if ((uint32_t)fw_link_param_count() > MATEK_PARAM_MAX_ROWS) {
        rep->result = (uint8_t)MATEK_PARAMS_MISMATCH; /* this image cannot hold its table */
        return;
    }
    matek_param_store(flash, &store);
    const param_store_status_t st = param_store_load(&store, blob, &info);
    if (info.loaded == 0u) {
        if (st == PARAM_STORE_BLANK) {
            rep->result = (uint8_t)MATEK_PARAMS_BLANK;
        } else if (st == PARAM_STORE_SCHEMA_MISMATCH) {
            rep->result = (uint8_t)MATEK_PARAMS_MISMATCH;
        } else {
            rep->result = (uint8_t)MATEK_PARAMS_CORRUPT;
        }
        return;
    }
    const uint32_t stored_count = (uint32_t)blob[0] | ((uint32_t)blob[1] << 8);
    if ((stored_count != (uint32_t)fw_link_param_count()) || (blob[2] != 0u) || (blob[3] != 0u) ||
        (rd32(&blob[4]) != matek_param_fingerprint())) {
        rep->result = (uint8_t)MATEK_PARAMS_MISMATCH; /* another table's rows */
        return;
    }
    if (put_and_check(cfg, link_params, rep) == 0) {
        return;
    }
    *cfg = put_cfg;
    *link_params = put_link;
    rep->result =
        (uint8_t)((st == PARAM_STORE_OK) ? MATEK_PARAMS_LOADED : MATEK_PARAMS_LOADED_OTHER_CORRUPT);
    rep->slot = info.slot;
    rep->sequence = info.sequence;
}
