/*
 * param_rows.h - a row of one group of the parameter table by its id, and
 * its name (src/params/param_rows.c): what each group's *_param_info and
 * *_param_name share. The rows themselves are declared once, in
 * helical/params.def; their type is helical/params.h's ht_param_info_t.
 */
#ifndef HELICAL_PARAMS_PARAM_ROWS_H
#define HELICAL_PARAMS_PARAM_ROWS_H

#include "helical/params.h"

/* Row id (1 .. count) of a group's table (ids start at 1, after *_NONE), or
 * NULL for any other id or a NULL table. */
const ht_param_info_t *ht_param_row(const ht_param_info_t *table, int count, int id);

/* A row's name; "" for NULL. */
const char *ht_param_row_name(const ht_param_info_t *row);

#endif /* HELICAL_PARAMS_PARAM_ROWS_H */
