/*
 * param_rows.c - a row of one group of the parameter table by its id, and
 * its name: what ht_param_info / ht_dcm_param_info / ht_guide_param_info and
 * their _name twins share (include/helical/params/param_rows.h).
 */
#include <stddef.h>

#include "helical/params/param_rows.h"

const ht_param_info_t *ht_param_row(const ht_param_info_t *table, int count, int id)
{
    if (table == NULL || id <= 0 || id > count) {
        return NULL;
    }
    return &table[id - 1];
}

const char *ht_param_row_name(const ht_param_info_t *row)
{
    return (row != NULL) ? row->name : "";
}
