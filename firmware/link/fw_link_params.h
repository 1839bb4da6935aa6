/*
 * fw_link_params.h - the link's own parameters (params.def HT_PARAMS_LINK:
 * rates, system id, the mission protocol's timing) and their table rows
 * (fw_link_params.c).
 */
#ifndef HT_FW_LINK_PARAMS_H
#define HT_FW_LINK_PARAMS_H

#include "helical/params.h"

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

#ifdef __cplusplus
}
#endif

#endif /* HT_FW_LINK_PARAMS_H */
