/*
 * matek_param_blob.h - the stored parameter set of the Matek F405-WING
 * image: every row the MAVLink link exposes (firmware/link/fw_link.h: every row
 * of every group of include/helical/params.def, LINK included) as one
 * versioned blob for the parameter store (boards/common/param_store.h), and
 * the boot-time load that puts it into the firmware configuration and the
 * link's parameters.
 *
 * The blob is generated from the one table, not from a hand list: for each
 * link index i in [0, fw_link_param_count()), the row's stored value
 * (fw_link_param_get_cfg) as a little-endian int32. A fingerprint of the
 * table's layout (the row count and a CRC-32 over every row's param_id and
 * format name) heads it, so that an image with another table (a row added,
 * removed, moved, renamed or re-formatted) reads a stored set as MISMATCH
 * and boots on its defaults rather than putting values into the wrong rows.
 *
 * Layout (bytes), schema 0x4D57 ("WM"), version 2, 8 + 4 * rows bytes:
 *     0 u16 row count     2 u16 zero
 *     4 u32 fingerprint (matek_param_fingerprint)
 *     8 int32 row 0 .. 8 + 4 * (count - 1) int32 row count - 1
 * Schema 1 (the law's first 14 rows and the estimator's, 92 bytes) is no
 * longer decoded: a schema-1 record reads as MISMATCH (defaults fly) until
 * the next MAV_CMD_PREFLIGHT_STORAGE writes a schema-2 one.
 */
#ifndef HT_MATEK_PARAM_BLOB_H
#define HT_MATEK_PARAM_BLOB_H

#include <stdint.h>

#include "link/fw_link.h"
#include "fw_step.h"
#include "param_store.h"

#define MATEK_PARAM_SCHEMA_ID      0x4D57u
#define MATEK_PARAM_SCHEMA_VERSION 2u
#define MATEK_PARAM_HEAD_BYTES     8u
/* Rows the blob has room for (the table has 97); a table over this is not
 * stored (save fails, load reads MISMATCH). */
#define MATEK_PARAM_MAX_ROWS       128u
#define MATEK_PARAM_BLOB_MAX_BYTES (MATEK_PARAM_HEAD_BYTES + (4u * MATEK_PARAM_MAX_ROWS))

/* The table's fingerprint: CRC-32 over each row's param_id and format
 * name, each with its terminating NUL, in index order. */
uint32_t matek_param_fingerprint(void);
/* This image's blob length (8 + 4 * fw_link_param_count()). */
uint32_t matek_param_blob_bytes(void);

/* The blob from a configuration and the link's parameters (the bytes past
 * matek_param_blob_bytes() are 0). 0, or -1 (more rows than the blob holds,
 * a NULL pointer). */
int matek_param_blob_encode(const fw_config_t *cfg, const fw_link_params_t *link_params,
                            uint8_t blob[MATEK_PARAM_BLOB_MAX_BYTES]);

/* The store's description of this blob on a flash. */
void matek_param_store(const param_flash_t *flash, param_store_t *out);

/* What the boot-time load did. */
typedef enum {
    MATEK_PARAMS_LOADED = 0,              /* the stored set is flown */
    MATEK_PARAMS_BLANK = 1,               /* nothing stored: defaults */
    MATEK_PARAMS_CORRUPT = 2,             /* no valid record: defaults */
    MATEK_PARAMS_MISMATCH = 3,            /* another schema, version or table stored: defaults */
    MATEK_PARAMS_REFUSED = 4,             /* stored values fail a row's range, a block's checks,
                                             or change the IMU rate this image is built for:
                                             defaults */
    MATEK_PARAMS_LOADED_OTHER_CORRUPT = 5 /* loaded, but the other slot is corrupt */
} matek_params_result_t;

/* Why a stored set was refused. */
typedef enum {
    MATEK_BAD_NONE = 0,
    MATEK_BAD_RANGE = 1,    /* bad_index: the row is outside its own range */
    MATEK_BAD_IMU_RATE = 2, /* bad_index: the IMU rate row differs from this image's */
    MATEK_BAD_INIT = 3,     /* fw_init refused: bad_block (fw_bad_block_t), bad_sub */
    MATEK_BAD_LINK = 4      /* ht_link_first_bad: bad_sub (ht_link_param_id_t) */
} matek_params_bad_t;

typedef struct {
    uint8_t result;    /* matek_params_result_t */
    uint8_t slot;      /* when loaded */
    uint32_t sequence; /* when loaded */
    uint8_t bad;       /* REFUSED: matek_params_bad_t */
    uint8_t bad_block; /* MATEK_BAD_INIT: fw_bad_block_t */
    int32_t bad_sub;   /* MATEK_BAD_INIT: the block's field id (modes: ht_modes_bad_t.sub when
                          the field is a sub-module's); MATEK_BAD_LINK: the link's id */
    int32_t bad_index; /* REFUSED: the link row (0-based) the check names, or -1 */
    char bad_id[17];   /* its param_id ("" when bad_index is -1) */
    char reason[50];   /* MATEK_BAD_INIT of the modes: ht_modes_bad_name, e.g. the joint
                          rule "joint.mode_input is a stick channel" (config_check.h) */
} matek_params_report_t;

/*
 * Load the store on flash and, when a valid record of this schema and
 * table puts every row in range (fw_link_param_put_cfg), passes fw_init's
 * checks (estimator, both law controllers, rate divider, modes with their
 * holds, fly-by-wire, waypoint guidance and AoA model, turn guidance) and
 * ht_link_first_bad, and keeps cfg->dcm.imu_rate_hz, replace *cfg and
 * *link_params with it. Otherwise both are untouched (the defaults fly)
 * and rep says why.
 */
void matek_params_load(const param_flash_t *flash, fw_config_t *cfg, fw_link_params_t *link_params,
                       matek_params_report_t *rep);

#endif /* HT_MATEK_PARAM_BLOB_H */
