/*
 * param_parse.h - "--param NAME=VALUE" to ht_params_t for ht_replay.
 *
 * Names, units, formats and ranges are those of the parameter table
 * (include/helical/params.def, the law's rows; docs/control-law.md's
 * parameter table plus pitch_mode):
 *   kp_*, kff_*, kd_* (aileron, elevator, rudder)  gain, stored as Q16
 *   v_ref, v_min                                   m/s, stored as cm/s
 *   schedule                                       0 or 1
 *   max_tilt                                       ratio, stored as Q16
 *   pitch_mode                                     earth | cross | 0 | 1
 *
 * This layer checks the syntax and that a value fits the field's format
 * (a gain of 1e6 does not fit Q16; an integer field takes an integer of its
 * range). Whether a value is allowed by the law (a gain in [0, 64], v_min >=
 * 1 m/s, the joint limits) is decided by ht_init, whose per-field ranges are
 * the same table's, so the tool and the library cannot disagree; the tool
 * quotes the table's bounds when ht_init refuses (ht_param_format_range).
 */
#ifndef HT_REPLAY_PARAM_PARSE_H
#define HT_REPLAY_PARAM_PARSE_H

#include <stddef.h>
#include <stdio.h>

#include "helical/law/helical_turn.h"

/*
 * Apply one "NAME=VALUE" to *p. Returns 0 and writes the parameter to *id
 * (may be NULL); or -1 with a message naming the parameter (or the whole
 * argument when there is no name) written to msg, *p unchanged.
 */
int ht_param_parse(ht_params_t *p, const char *arg, ht_param_id_t *id, char *msg, size_t size);

/* The tool's name of a parameter (the control-law.md name), or "" if id is
 * not a parameter. Kept here rather than taken from ht_param_name so that the
 * parser does not depend on the core's object code; a unit test checks the
 * two tables agree. */
const char *ht_param_tool_name(ht_param_id_t id);

/* Write the value of parameter id in *p, in --param units ("1.5", "15",
 * "earth"), to buf. Returns 0, or -1 (and "?") if id is not a parameter. */
int ht_param_format_value(const ht_params_t *p, ht_param_id_t id, char *buf, size_t size);

/* Room for a value shown in a message: longer ones are cut, ending in "...". */
#define HT_PARAM_SHOWN_MAX 72

/* A value's text as the user gave it, for a message: bytes outside printable
 * ASCII as '?', cut with "..." to fit buf (size >= 4). */
void ht_param_show_text(const char *text, char *buf, size_t size);

/* Print one line per parameter: name, unit and the value in *p, in the
 * units of --param (used by --help with the defaults). */
void ht_param_print_table(FILE *out, const ht_params_t *p);

/* "kp_aileron in [0, 64] per unit error (Q16)": the table's range of id in
 * --param units. Returns 0, or -1 (and "?") if id is not a parameter. */
int ht_param_format_range(ht_param_id_t id, char *buf, size_t size);

/* Print one such line per parameter (--help). */
void ht_param_print_ranges(FILE *out);

#endif /* HT_REPLAY_PARAM_PARSE_H */
