/*
 * fw_link_param_table.h - the parameter table as MAVLink sees it
 * (fw_link_param_table.c): one flat index over every row of params.def.
 */
#ifndef HT_FW_LINK_PARAM_TABLE_H
#define HT_FW_LINK_PARAM_TABLE_H

#include <stdint.h>

#include "fw_step.h"
#include "helical/params.h"
#include "link/fw_link_params.h"
#include "link/fw_link_types.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Parameters on the link: every row of every group of params.def. */
uint16_t fw_link_param_count(void);
/* The MAVLink param_id of row index (0-based): 16 characters at most,
 * NUL-terminated in id[17]; 0, or -1 for an index out of range ("" then). */
int fw_link_param_id(uint16_t index, char id[17]);
/* The index of a param_id (at most 16 characters, need not be terminated),
 * or -1. */
int32_t fw_link_param_find(const char *id);
/* The MAV_PARAM_TYPE a row travels as: the integer formats (U8, U16, I16,
 * I32: scale 1) as MAV_PARAM_TYPE_UINT8 / UINT16 / INT16 / INT32, the
 * fixed-point ones as MAV_PARAM_TYPE_REAL32; 0 for an index out of range. */
uint8_t fw_link_param_mav_type(uint16_t index);
/* A row's value in its stored format, and its table row. 0, or -1. */
int fw_link_param_get(const fw_link_t *l, uint16_t index, int32_t *raw,
                      const ht_param_info_t **row);
/* Set a row to raw (stored format): range-checked by the row, then the
 * group's joint checks and its block's init; applied to the live
 * configuration and the running controllers (the estimator and the flight
 * state are kept). 0 = applied; else nothing changed, and l->param_refusal
 * says why in at most 49 characters: "<PARAM_ID> out of range", the joint
 * rule of the modes (helical/guidance/config_check.h, as ht_modes_bad_name
 * gives it: "joint.mode_input is a stick channel") or the block's first bad
 * field ("speed.throttle_max"), or "<PARAM_ID> refused by a joint limit". */
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

#ifdef __cplusplus
}
#endif

#endif /* HT_FW_LINK_PARAM_TABLE_H */
