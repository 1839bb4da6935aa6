/*
 * matek_param_blob.h - the stored parameter set of the Matek F405-WING
 * image: the law's (ht_params_t) and the estimator's (ht_dcm_params_t)
 * parameters as one versioned blob for the parameter store
 * (boards/common/param_store.h), and the boot-time load that puts them into
 * the firmware configuration.
 *
 * The blob is a list of fields, each little-endian at a fixed offset, in the
 * order of the table in matek_param_blob.c: one line per parameter, so that
 * the table can later be generated from the project's single parameter
 * table. A change of the list is a new MATEK_PARAM_SCHEMA_VERSION (the store
 * then reports SCHEMA_MISMATCH and the image boots on its defaults).
 *
 * Layout (bytes), schema 0x4D57 ("WM"), version 1, 92 bytes:
 *     0 law.kp_aileron .. 32 law.kd_rudder   9 x q16 (int32)
 *    36 law.v_ref_cm_s   40 law.v_min_cm_s    int32
 *    44 law.max_tilt (q16)   48 law.schedule (u8)   49 law.pitch_mode (u8)
 *    50 dcm.imu_rate_hz (u16)
 *    52 dcm.kp_rollpitch, ki_rollpitch, kp_yaw, ki_yaw, gyro_bias_max_rad_s,
 *       gyro_limit_rad_s, accel_limit_g, accel_band_g   8 x q16
 *    84 dcm.gps_min_speed_cm_s (int16)   86 dcm.gps_latency_ms (u16)
 *    88 dcm.centripetal (u8)   89..91 zero (padding to a word)
 */
#ifndef HT_MATEK_PARAM_BLOB_H
#define HT_MATEK_PARAM_BLOB_H

#include <stdint.h>

#include "fw_step.h"
#include "param_store.h"

#define MATEK_PARAM_SCHEMA_ID      0x4D57u
#define MATEK_PARAM_SCHEMA_VERSION 1u
#define MATEK_PARAM_BLOB_BYTES     92u

/* The blob from the two structs (padding bytes 0). */
void matek_param_blob_encode(const ht_params_t *law, const ht_dcm_params_t *dcm,
                             uint8_t blob[MATEK_PARAM_BLOB_BYTES]);
/* The two structs from the blob (fields not in the blob are left as they were). */
void matek_param_blob_decode(const uint8_t blob[MATEK_PARAM_BLOB_BYTES], ht_params_t *law,
                             ht_dcm_params_t *dcm);

/* The store's description of this blob on a flash. */
void matek_param_store(const param_flash_t *flash, param_store_t *out);

/* What the boot-time load did. */
typedef enum {
    MATEK_PARAMS_LOADED = 0,              /* the stored set is flown */
    MATEK_PARAMS_BLANK = 1,               /* nothing stored: defaults */
    MATEK_PARAMS_CORRUPT = 2,             /* no valid record: defaults */
    MATEK_PARAMS_MISMATCH = 3,            /* another schema or version stored: defaults */
    MATEK_PARAMS_REFUSED = 4,             /* stored values fail the law's or estimator's checks, or
                                             change the IMU rate this image is built for: defaults */
    MATEK_PARAMS_LOADED_OTHER_CORRUPT = 5 /* loaded, but the other slot is corrupt */
} matek_params_result_t;

typedef struct {
    uint8_t result;    /* matek_params_result_t */
    uint8_t slot;      /* when loaded */
    uint32_t sequence; /* when loaded */
    int32_t bad_field; /* REFUSED: the ht_param_id_t (law) or 1000 + ht_dcm_param_id_t,
                          or 2000 for the IMU rate */
} matek_params_report_t;

/*
 * Load the store on flash and, when a valid record of this schema passes
 * ht_init and ht_dcm_init and keeps cfg->dcm.imu_rate_hz, replace cfg->law
 * and cfg->dcm with it. Otherwise cfg is untouched (the defaults fly) and
 * rep says why.
 */
void matek_params_load(const param_flash_t *flash, fw_config_t *cfg, matek_params_report_t *rep);

#endif /* HT_MATEK_PARAM_BLOB_H */
