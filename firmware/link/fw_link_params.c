/*
 * fw_link_params.c - the link's parameters from the table (params.def
 * HT_PARAMS_LINK): defaults, rows, names and the range checks. The rows'
 * bounds are all there is: no joint limit (a rate beyond what the control
 * rate reaches is simply reached at the control rate: docs/mavlink.md).
 */
#include "link/fw_link_params.h"
#include "helical/params/param_rows.h"

#include <stddef.h>

// cppcheck-suppress misra-c2012-10.8 ; D-10.8-FROM-REAL: the table's bounds, folded constants
static const ht_param_info_t link_rows[HT_PARAM_LINK_COUNT] = {HT_PARAMS_LINK(HT_PARAM_X_INFO)};

void ht_link_params_default(fw_link_params_t *p)
{
    if (p != NULL) {
        // cppcheck-suppress misra-c2012-10.8 ; D-10.8-FROM-REAL: the table's defaults, folded
        // constants
        HT_PARAMS_LINK(HT_PARAM_X_SET_DEFAULT)
    }
}

const ht_param_info_t *ht_link_param_info(ht_link_param_id_t id)
{
    return ht_param_row(link_rows, HT_PARAM_LINK_COUNT, (int)id);
}

const char *ht_link_param_name(ht_link_param_id_t id)
{
    return ht_param_row_name(ht_link_param_info(id));
}

ht_link_param_id_t ht_link_first_bad(const fw_link_params_t *p)
{
    int row = 0;
    int bad = 0;
    // cppcheck-suppress misra-c2012-10.8 ; D-10.8-FROM-REAL: the table's bounds, folded constants
    HT_PARAMS_LINK(HT_PARAM_X_FIRST_BAD)
    (void)row;
    return (ht_link_param_id_t)bad;
}
