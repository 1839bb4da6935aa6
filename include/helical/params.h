/*
 * params.h - the expansion side of the parameter table (params.def): the
 * storage formats and the macros that turn one row into a struct field, an
 * id, a name, a default or a range check. docs/parameters.md.
 *
 * Floating point appears only inside HT_PARAM_RAW_*, on constants: every use
 * folds to an integer constant at compile time (the cortex-m0 build checks
 * that no float routine reaches the object code, boards/common).
 */
#ifndef HELICAL_PARAMS_H
#define HELICAL_PARAMS_H

#include <stdint.h>

#include "helical/math/q14.h"

#include "helical/params.def"

/* The storage formats: C type, scale from the engineering unit, wire bytes
 * (little-endian on the HIL link), and the name messages show. */
#define HT_PFMT_TYPE_Q16  q16_t
#define HT_PFMT_TYPE_CM32 int32_t
#define HT_PFMT_TYPE_CM16 int16_t
#define HT_PFMT_TYPE_U8   uint8_t
#define HT_PFMT_TYPE_U16  uint16_t
#define HT_PFMT_TYPE_Q14  q14_t
#define HT_PFMT_TYPE_MS16 uint16_t
#define HT_PFMT_TYPE_I16  int16_t
#define HT_PFMT_TYPE_I32  int32_t

#define HT_PFMT_SCALE_Q16  65536.0
#define HT_PFMT_SCALE_CM32 100.0
#define HT_PFMT_SCALE_CM16 100.0
#define HT_PFMT_SCALE_U8   1.0
#define HT_PFMT_SCALE_U16  1.0
#define HT_PFMT_SCALE_Q14  16384.0
#define HT_PFMT_SCALE_MS16 1000.0
#define HT_PFMT_SCALE_I16  1.0
#define HT_PFMT_SCALE_I32  1.0

#define HT_PFMT_ISCALE_Q16  65536
#define HT_PFMT_ISCALE_CM32 100
#define HT_PFMT_ISCALE_CM16 100
#define HT_PFMT_ISCALE_U8   1
#define HT_PFMT_ISCALE_U16  1
#define HT_PFMT_ISCALE_Q14  16384
#define HT_PFMT_ISCALE_MS16 1000
#define HT_PFMT_ISCALE_I16  1
#define HT_PFMT_ISCALE_I32  1

#define HT_PFMT_BYTES_Q16  4u
#define HT_PFMT_BYTES_CM32 4u
#define HT_PFMT_BYTES_CM16 2u
#define HT_PFMT_BYTES_U8   1u
#define HT_PFMT_BYTES_U16  2u
#define HT_PFMT_BYTES_Q14  2u
#define HT_PFMT_BYTES_MS16 2u
#define HT_PFMT_BYTES_I16  2u
#define HT_PFMT_BYTES_I32  4u

#define HT_PFMT_NAME_Q16  "Q16"
#define HT_PFMT_NAME_CM32 "int32 x100"
#define HT_PFMT_NAME_CM16 "int16 x100"
#define HT_PFMT_NAME_U8   "uint8"
#define HT_PFMT_NAME_U16  "uint16"
#define HT_PFMT_NAME_Q14  "Q14"
#define HT_PFMT_NAME_MS16 "uint16 x1000"
#define HT_PFMT_NAME_I16  "int16"
#define HT_PFMT_NAME_I32  "int32"

/* An engineering value as the field stores it, rounded half away from zero
 * (as Q16_FROM_REAL). Only for the table's constants. One macro per format,
 * so that an expander pastes the format token at once (HT_PARAM_RAW_##fmt):
 * a token passed on unpasted would be macro-expanded first, and a user's
 * "#define Q16 65536.0" would then break the expansion. */
#define HT_PARAM_RAW_(type, scale, v) ((type)(((v) * (scale)) + (((v) >= 0) ? 0.5 : -0.5)))
#define HT_PARAM_RAW_Q16(v)           HT_PARAM_RAW_(q16_t, 65536.0, v)
#define HT_PARAM_RAW_CM32(v)          HT_PARAM_RAW_(int32_t, 100.0, v)
#define HT_PARAM_RAW_CM16(v)          HT_PARAM_RAW_(int16_t, 100.0, v)
#define HT_PARAM_RAW_U8(v)            HT_PARAM_RAW_(uint8_t, 1.0, v)
#define HT_PARAM_RAW_U16(v)           HT_PARAM_RAW_(uint16_t, 1.0, v)
#define HT_PARAM_RAW_Q14(v)           HT_PARAM_RAW_(q14_t, 16384.0, v)
#define HT_PARAM_RAW_MS16(v)          HT_PARAM_RAW_(uint16_t, 1000.0, v)
#define HT_PARAM_RAW_I16(v)           HT_PARAM_RAW_(int16_t, 1.0, v)
#define HT_PARAM_RAW_I32(v)           HT_PARAM_RAW_(int32_t, 1.0, v)

/* --- row expanders (X of HT_PARAMS_LAW / HT_PARAMS_DCM) ------------------- */

/* a struct field */
#define HT_PARAM_X_FIELD(id, name, field, unit, fmt, lo, hi, def, desc) HT_PFMT_TYPE_##fmt field;
/* an initializer element: the default */
#define HT_PARAM_X_DEFAULT(id, name, field, unit, fmt, lo, hi, def, desc) HT_PARAM_RAW_##fmt(def),
/* the name, as a string */
#define HT_PARAM_X_NAME(id, name, field, unit, fmt, lo, hi, def, desc) #name,
/* one per row: the count */
#define HT_PARAM_X_ONE(id, name, field, unit, fmt, lo, hi, def, desc)                              \
    +1 /* NOLINT: a sum's term                                                                     \
        */
/* the bytes a row takes on the HIL link */
#define HT_PARAM_X_BYTES(id, name, field, unit, fmt, lo, hi, def, desc)                            \
    +HT_PFMT_BYTES_##fmt /* NOLINT(bugprone-macro-parentheses): a sum's term */

/* In a function with a parameter pointer p: set the row's field to its
 * default (folded to an integer constant). */
#define HT_PARAM_X_SET_DEFAULT(id, name, field, unit, fmt, lo, hi, def, desc)                      \
    p->field = HT_PARAM_RAW_##fmt(def);
/* In a function with p and two ints, row = 0 and bad = 0 before the list:
 * bad becomes the 1-based row of the first field outside its bounds. */
#define HT_PARAM_X_FIRST_BAD(id, name, field, unit, fmt, lo, hi, def, desc)                        \
    ++row;                                                                                         \
    if ((bad == 0) && (((int32_t)p->field < (int32_t)HT_PARAM_RAW_##fmt(lo)) ||                    \
                       ((int32_t)p->field > (int32_t)HT_PARAM_RAW_##fmt(hi)))) {                   \
        bad = row;                                                                                 \
    }

/* The descriptions cost about 1.5 KB of flash: a target build leaves them out
 * ("") unless HT_PARAM_DESCRIPTIONS=1; the host build defines it
 * (src/CMakeLists.txt) for ht_replay, the SIL and the tests. */
#ifndef HT_PARAM_DESCRIPTIONS
#define HT_PARAM_DESCRIPTIONS 0
#endif
#if HT_PARAM_DESCRIPTIONS
#define HT_PARAM_DESC_(d) d
#else
#define HT_PARAM_DESC_(d) ""
#endif

/* an ht_param_info_t initializer */
#define HT_PARAM_X_INFO(id, name, field, unit, fmt, lo, hi, def, desc)                             \
    {#name,                                                                                        \
     unit,                                                                                         \
     HT_PFMT_NAME_##fmt,                                                                           \
     HT_PARAM_DESC_(desc),                                                                         \
     HT_PARAM_RAW_##fmt(lo),                                                                       \
     HT_PARAM_RAW_##fmt(hi),                                                                       \
     HT_PARAM_RAW_##fmt(def),                                                                      \
     HT_PFMT_ISCALE_##fmt,                                                                         \
     HT_PFMT_BYTES_##fmt},

/* Parameters per group (integer constant expressions). */
#define HT_PARAM_LAW_COUNT   (0 HT_PARAMS_LAW(HT_PARAM_X_ONE))
#define HT_PARAM_DCM_COUNT   (0 HT_PARAMS_DCM(HT_PARAM_X_ONE))
#define HT_PARAM_GUIDE_COUNT (0 HT_PARAMS_GUIDE(HT_PARAM_X_ONE))
#define HT_PARAM_ALT_COUNT   (0 HT_PARAMS_ALT(HT_PARAM_X_ONE))
#define HT_PARAM_SPEED_COUNT (0 HT_PARAMS_SPEED(HT_PARAM_X_ONE))
#define HT_PARAM_MODES_COUNT (0 HT_PARAMS_MODES(HT_PARAM_X_ONE))
#define HT_PARAM_FBW_COUNT   (0 HT_PARAMS_FBW(HT_PARAM_X_ONE))
#define HT_PARAM_NAV_COUNT   (0 HT_PARAMS_NAV(HT_PARAM_X_ONE))
#define HT_PARAM_AOA_COUNT   (0 HT_PARAMS_AOA(HT_PARAM_X_ONE))

/* What one row says, for tools, messages and the cross-checks of the tests
 * (ht_param_info, ht_dcm_param_info). Bounds and default as stored. */
typedef struct {
    const char *name;
    const char *unit;
    const char *format; /* HT_PFMT_NAME_* */
    const char *description;
    int32_t min_raw, max_raw, default_raw;
    int32_t scale; /* stored = engineering value * scale: 65536, 16384, 1000, 100 or 1 */
    uint8_t bytes; /* HT_PFMT_BYTES_* */
} ht_param_info_t;

/* A row by its id and its name: helical/params/param_rows.h. */

#endif /* HELICAL_PARAMS_H */
