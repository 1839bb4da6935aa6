/*
 * matek_param_blob.c - the parameter blob's field table, its encoding and
 * the boot-time load (see matek_param_blob.h for the layout).
 */
#include "matek_param_blob.h"

#include <stddef.h>
#include <string.h>

#include "helical/dcm.h"
#include "helical/helical_turn.h"

typedef enum { BLOB_LAW = 0, BLOB_DCM = 1, BLOB_PAD = 2 } blob_struct_t;

/* One parameter: which struct, where in it, how wide (1, 2 or 4 bytes). */
typedef struct {
    uint8_t in;
    uint8_t size;
    uint16_t offset;
} blob_field_t;

#define LAW(f)                                                                                     \
    {                                                                                              \
        (uint8_t) BLOB_LAW, (uint8_t)sizeof(((ht_params_t *)0)->f),                                \
            (uint16_t)offsetof(ht_params_t, f)                                                     \
    }
#define DCM(f)                                                                                     \
    {                                                                                              \
        (uint8_t) BLOB_DCM, (uint8_t)sizeof(((ht_dcm_params_t *)0)->f),                            \
            (uint16_t)offsetof(ht_dcm_params_t, f)                                                 \
    }

/* The blob, in order: one line per parameter. */
static const blob_field_t fields[] = {
    LAW(kp_aileron),     LAW(kp_elevator),         LAW(kp_rudder),
    LAW(kff_aileron),    LAW(kff_elevator),        LAW(kff_rudder),
    LAW(kd_aileron),     LAW(kd_elevator),         LAW(kd_rudder),
    LAW(v_ref_cm_s),     LAW(v_min_cm_s),          LAW(max_tilt),
    LAW(schedule),       LAW(pitch_mode),          DCM(imu_rate_hz),
    DCM(kp_rollpitch),   DCM(ki_rollpitch),        DCM(kp_yaw),
    DCM(ki_yaw),         DCM(gyro_bias_max_rad_s), DCM(gyro_limit_rad_s),
    DCM(accel_limit_g),  DCM(accel_band_g),        DCM(gps_min_speed_cm_s),
    DCM(gps_latency_ms), DCM(centripetal),         {(uint8_t)BLOB_PAD, 3u, 0u},
};
#define FIELD_COUNT (sizeof fields / sizeof fields[0])

/* The field's bytes inside its struct (NULL for padding). */
static uint8_t *field_ptr(const blob_field_t *f, ht_params_t *law, ht_dcm_params_t *dcm)
{
    if (f->in == (uint8_t)BLOB_LAW) {
        return (uint8_t *)law + f->offset;
    }
    if (f->in == (uint8_t)BLOB_DCM) {
        return (uint8_t *)dcm + f->offset;
    }
    return NULL;
}

void matek_param_blob_encode(const ht_params_t *law, const ht_dcm_params_t *dcm,
                             uint8_t blob[MATEK_PARAM_BLOB_BYTES])
{
    ht_params_t l = *law; /* field_ptr takes non-const structs */
    ht_dcm_params_t d = *dcm;
    uint32_t at = 0u;
    for (size_t i = 0u; i < FIELD_COUNT; ++i) {
        const uint8_t *p = field_ptr(&fields[i], &l, &d);
        uint32_t v = 0u; /* padding: zeros */
        if (p != NULL && fields[i].size == 4u) {
            memcpy(&v, p, 4u);
        } else if (p != NULL && fields[i].size == 2u) {
            uint16_t h = 0u;
            memcpy(&h, p, 2u);
            v = h;
        } else if (p != NULL) {
            v = *p;
        } else {
            /* padding */
        }
        for (uint32_t b = 0u; b < fields[i].size; ++b) {
            blob[at + b] = (uint8_t)((v >> (8u * b)) & 0xFFu); /* little-endian */
        }
        at += fields[i].size;
    }
}

void matek_param_blob_decode(const uint8_t blob[MATEK_PARAM_BLOB_BYTES], ht_params_t *law,
                             ht_dcm_params_t *dcm)
{
    uint32_t at = 0u;
    for (size_t i = 0u; i < FIELD_COUNT; ++i) {
        uint8_t *p = field_ptr(&fields[i], law, dcm);
        uint32_t v = 0u;
        for (uint32_t b = 0u; b < fields[i].size; ++b) {
            v |= (uint32_t)blob[at + b] << (8u * b);
        }
        if (p != NULL) {
            if (fields[i].size == 4u) {
                memcpy(p, &v, 4u);
            } else if (fields[i].size == 2u) {
                const uint16_t h = (uint16_t)(v & 0xFFFFu);
                memcpy(p, &h, 2u);
            } else {
                *p = (uint8_t)(v & 0xFFu);
            }
        }
        at += fields[i].size;
    }
}

void matek_param_store(const param_flash_t *flash, param_store_t *out)
{
    out->flash = flash;
    out->schema_id = (uint16_t)MATEK_PARAM_SCHEMA_ID;
    out->schema_version = (uint16_t)MATEK_PARAM_SCHEMA_VERSION;
    out->length = MATEK_PARAM_BLOB_BYTES;
}

/* Scratch for the checks (file-static: this is the image, not the library). */
static ht_controller_t check_law;
static ht_dcm_t check_dcm;

void matek_params_load(const param_flash_t *flash, fw_config_t *cfg, matek_params_report_t *rep)
{
    static uint8_t blob[MATEK_PARAM_BLOB_BYTES];
    param_store_t store;
    param_store_load_t info;
    rep->result = (uint8_t)MATEK_PARAMS_CORRUPT;
    rep->slot = 0u;
    rep->sequence = 0u;
    rep->bad_field = 0;
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
    ht_params_t law = cfg->law;
    ht_dcm_params_t dcm = cfg->dcm;
    matek_param_blob_decode(blob, &law, &dcm);
    ht_param_id_t bad_law = HT_P_NONE;
    ht_dcm_param_id_t bad_dcm = (ht_dcm_param_id_t)0;
    if (ht_init(&check_law, &law, &bad_law) != HT_OK) {
        rep->result = (uint8_t)MATEK_PARAMS_REFUSED;
        rep->bad_field = (int32_t)bad_law;
        return;
    }
    if (ht_dcm_init(&check_dcm, &dcm, &bad_dcm) != 0) {
        rep->result = (uint8_t)MATEK_PARAMS_REFUSED;
        rep->bad_field = 1000 + (int32_t)bad_dcm;
        return;
    }
    if (dcm.imu_rate_hz != cfg->dcm.imu_rate_hz) {
        /* the board's tick, the decimation and the control divider are
         * built for this rate */
        rep->result = (uint8_t)MATEK_PARAMS_REFUSED;
        rep->bad_field = 2000;
        return;
    }
    cfg->law = law;
    cfg->dcm = dcm;
    rep->result =
        (uint8_t)((st == PARAM_STORE_OK) ? MATEK_PARAMS_LOADED : MATEK_PARAMS_LOADED_OTHER_CORRUPT);
    rep->slot = info.slot;
    rep->sequence = info.sequence;
}
