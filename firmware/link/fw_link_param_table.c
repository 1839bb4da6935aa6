/*
 * fw_link_param_table.c - the one parameter table (params.def) as the
 * MAVLink parameter protocol sees it: one flat index over every group's
 * rows, a <= 16-character param_id per row, and reading / setting a row's
 * stored value in the live configuration with its block re-initialised.
 *
 * param_id rule (docs/mavlink.md): the group's 4-character prefix (LAW_,
 * DCM_, GDE_, ALT_, SPD_, MOD_, FBW_, NAV_, AOA_, LNK_) and the row's ID
 * column; while longer than 16 characters, the last vowel of the ID part
 * that does not begin a word (a word follows '_') is removed; if none is
 * left, the ID part is cut to 12. test_fw_link_params proves every id fits
 * and is unique.
 *
 * Setting a row re-initialises only what depends on it, from the live
 * configuration: the law's two controllers (and the modes, which copy two
 * of the law's limits), the estimator's gains (its state is kept: the
 * attitude, the bias), the guidance's trim gains, or the modes with their
 * holds, fly-by-wire, waypoint guidance and AoA model (their states are
 * kept). The flight continues on the new value at the next step.
 */
#include <stddef.h>
#include <string.h>

#include "link/fw_link_param_table.h"
#include "link/fw_link_tx.h" /* the MAV_PARAM_TYPE constants */

typedef enum {
    G_LAW = 0,
    G_DCM,
    G_GUIDE,
    G_ALT,
    G_SPEED,
    G_MODES,
    G_FBW,
    G_NAV,
    G_AOA,
    G_LINK,
    G_COUNT
} group_t;

/* how a format is stored */
typedef enum { K_I32 = 0, K_I16, K_U16, K_U8 } kind_t;
#define KIND_Q16  K_I32
#define KIND_CM32 K_I32
#define KIND_CM16 K_I16
#define KIND_U8   K_U8
#define KIND_U16  K_U16
#define KIND_Q14  K_I16
#define KIND_MS16 K_U16
#define KIND_I16  K_I16
#define KIND_I32  K_I32

typedef struct {
    const char *id;  /* the ID column */
    uint16_t offset; /* in fw_config_t (LINK: in fw_link_params_t) */
    uint8_t kind;    /* kind_t */
} row_t;

/* clang-format off */
#define ROW_IN(base, id, field, fmt) {#id, (uint16_t)offsetof(base, field), (uint8_t)KIND_##fmt},
#define ROW_LAW(id, name, field, unit, fmt, lo, hi, def, desc)   ROW_IN(fw_config_t, id, law.field, fmt)
#define ROW_DCM(id, name, field, unit, fmt, lo, hi, def, desc)   ROW_IN(fw_config_t, id, dcm.field, fmt)
#define ROW_GUIDE(id, name, field, unit, fmt, lo, hi, def, desc) ROW_IN(fw_config_t, id, guide.field, fmt)
#define ROW_ALT(id, name, field, unit, fmt, lo, hi, def, desc)   ROW_IN(fw_config_t, id, modes.alt.field, fmt)
#define ROW_SPEED(id, name, field, unit, fmt, lo, hi, def, desc) ROW_IN(fw_config_t, id, modes.speed.field, fmt)
#define ROW_MODES(id, name, field, unit, fmt, lo, hi, def, desc) ROW_IN(fw_config_t, id, modes.field, fmt)
#define ROW_FBW(id, name, field, unit, fmt, lo, hi, def, desc)   ROW_IN(fw_config_t, id, modes.fbw.field, fmt)
#define ROW_NAV(id, name, field, unit, fmt, lo, hi, def, desc)   ROW_IN(fw_config_t, id, modes.nav.field, fmt)
#define ROW_AOA(id, name, field, unit, fmt, lo, hi, def, desc)   ROW_IN(fw_config_t, id, modes.aoa.field, fmt)
#define ROW_LINK(id, name, field, unit, fmt, lo, hi, def, desc)  ROW_IN(fw_link_params_t, id, field, fmt)
/* clang-format on */

static const row_t rows[] = {
    HT_PARAMS_LAW(ROW_LAW) HT_PARAMS_DCM(ROW_DCM) HT_PARAMS_GUIDE(ROW_GUIDE) HT_PARAMS_ALT(ROW_ALT)
        HT_PARAMS_SPEED(ROW_SPEED) HT_PARAMS_MODES(ROW_MODES) HT_PARAMS_FBW(ROW_FBW)
            HT_PARAMS_NAV(ROW_NAV) HT_PARAMS_AOA(ROW_AOA) HT_PARAMS_LINK(ROW_LINK)};

#define ROW_COUNT ((uint16_t)(sizeof rows / sizeof rows[0]))

/* rows per group, unsigned constants */
#define ROW_PLUS_ONE(id, name, field, unit, fmt, lo, hi, def, desc)                                \
    +1U /* NOLINT(bugprone-macro-parentheses): a sum's term */
static const uint16_t group_count[G_COUNT] = {
    0U HT_PARAMS_LAW(ROW_PLUS_ONE),   0U HT_PARAMS_DCM(ROW_PLUS_ONE),
    0U HT_PARAMS_GUIDE(ROW_PLUS_ONE), 0U HT_PARAMS_ALT(ROW_PLUS_ONE),
    0U HT_PARAMS_SPEED(ROW_PLUS_ONE), 0U HT_PARAMS_MODES(ROW_PLUS_ONE),
    0U HT_PARAMS_FBW(ROW_PLUS_ONE),   0U HT_PARAMS_NAV(ROW_PLUS_ONE),
    0U HT_PARAMS_AOA(ROW_PLUS_ONE),   0U HT_PARAMS_LINK(ROW_PLUS_ONE)};

static const char *const group_prefix[G_COUNT] = {"LAW_", "DCM_", "GDE_", "ALT_", "SPD_",
                                                  "MOD_", "FBW_", "NAV_", "AOA_", "LNK_"};

/* The group of a flat index and the row's 1-based id in it. */
static group_t group_of(uint16_t index, int *id)
{
    uint32_t start = 0u;
    for (unsigned g = 0u; g < (unsigned)G_COUNT; ++g) {
        const uint32_t end = start + group_count[g];
        if ((uint32_t)index < end) {
            const uint32_t in_group = (uint32_t)index - start;
            *id = (int)in_group + 1;
            return (group_t)g;
        }
        start = end;
    }
    *id = 0;
    return G_COUNT;
}

static const ht_param_info_t *row_info(group_t g, int id)
{
    switch (g) {
    case G_LAW:
        return ht_param_info((ht_param_id_t)id);
    case G_DCM:
        return ht_dcm_param_info((ht_dcm_param_id_t)id);
    case G_GUIDE:
        return ht_guide_param_info((ht_guide_param_id_t)id);
    case G_ALT:
        return ht_alt_hold_param_info((ht_alt_param_id_t)id);
    case G_SPEED:
        return ht_speed_hold_param_info((ht_speed_param_id_t)id);
    case G_MODES:
        return ht_modes_param_info((ht_modes_param_id_t)id);
    case G_FBW:
        return ht_fbw_param_info((ht_fbw_param_id_t)id);
    case G_NAV:
        return ht_nav_param_info((ht_nav_param_id_t)id);
    case G_AOA:
        return ht_aoa_param_info((ht_aoa_param_id_t)id);
    case G_LINK:
        return ht_link_param_info((ht_link_param_id_t)id);
    default:
        return NULL;
    }
}

uint16_t fw_link_param_count(void)
{
    return ROW_COUNT;
}

static int is_vowel(char c)
{
    return ((c == 'A') || (c == 'E') || (c == 'I') || (c == 'O') || (c == 'U')) ? 1 : 0;
}

int fw_link_param_id(uint16_t index, char id[17])
{
    if (id == NULL) {
        return -1;
    }
    id[0] = '\0';
    int gid = 0;
    const group_t g = group_of(index, &gid);
    if (g == G_COUNT) {
        return -1;
    }
    char body[48] = {0};
    size_t n = 0u;
    for (const char *c = rows[index].id; (*c != '\0') && (n < (sizeof body - 1u)); ++c) {
        body[n] = *c;
        ++n;
    }
    while ((4u + n) > 16u) {
        size_t i = n;
        while ((i > 1u) && !((is_vowel(body[i - 1u]) != 0) && (body[i - 2u] != '_'))) {
            --i;
        }
        if (i <= 1u) {
            n = 12u; /* no vowel left to remove */
        } else {
            (void)memmove(&body[i - 1u], &body[i], n - i);
            --n;
        }
    }
    (void)memcpy(id, group_prefix[g], 4u);
    (void)memcpy(&id[4], body, n);
    id[4u + n] = '\0';
    return 0;
}

int32_t fw_link_param_find(const char *id)
{
    if (id == NULL) {
        return -1;
    }
    char want[17];
    size_t n = 0u;
    while ((n < 16u) && (id[n] != '\0')) {
        want[n] = id[n];
        ++n;
    }
    want[n] = '\0';
    for (uint16_t i = 0u; i < ROW_COUNT; ++i) {
        char have[17];
        if ((fw_link_param_id(i, have) == 0) && (strcmp(have, want) == 0)) {
            return (int32_t)i;
        }
    }
    return -1;
}

/* the row's field, through its bytes (character pointers: any object) */
static const uint8_t *field_ro(const fw_config_t *cfg, const fw_link_params_t *lp, group_t g,
                               uint16_t index)
{
    const uint8_t *const base = (g == G_LINK) ? (const uint8_t *)lp : (const uint8_t *)cfg;
    return &base[rows[index].offset];
}

static uint8_t *field_rw(fw_config_t *cfg, fw_link_params_t *lp, group_t g, uint16_t index)
{
    uint8_t *const base = (g == G_LINK) ? (uint8_t *)lp : (uint8_t *)cfg;
    return &base[rows[index].offset];
}

static int32_t load(const uint8_t *p, uint8_t kind)
{
    switch ((kind_t)kind) {
    case K_I32: {
        int32_t v;
        // cppcheck-suppress misra-c2012-21.15 ; D-LINK-BYTES: the row's field read through its
        // bytes
        (void)memcpy(&v, p, sizeof v);
        return v;
    }
    case K_I16: {
        int16_t v;
        // cppcheck-suppress misra-c2012-21.15 ; D-LINK-BYTES: the row's field read through its
        // bytes
        (void)memcpy(&v, p, sizeof v);
        return (int32_t)v;
    }
    case K_U16: {
        uint16_t v;
        // cppcheck-suppress misra-c2012-21.15 ; D-LINK-BYTES: the row's field read through its
        // bytes
        (void)memcpy(&v, p, sizeof v);
        return (int32_t)v;
    }
    default:
        return (int32_t)*p;
    }
}

/* raw is within the row's bounds, which fit the kind */
static void store(uint8_t *p, uint8_t kind, int32_t raw)
{
    switch ((kind_t)kind) {
    case K_I32:
        // cppcheck-suppress misra-c2012-21.15 ; D-LINK-BYTES: the row's field written through its
        // bytes
        (void)memcpy(p, &raw, sizeof raw);
        break;
    case K_I16: {
        const int16_t v = (int16_t)raw;
        // cppcheck-suppress misra-c2012-21.15 ; D-LINK-BYTES: the row's field written through its
        // bytes
        (void)memcpy(p, &v, sizeof v);
        break;
    }
    case K_U16: {
        const uint16_t v = (uint16_t)raw;
        // cppcheck-suppress misra-c2012-21.15 ; D-LINK-BYTES: the row's field written through its
        // bytes
        (void)memcpy(p, &v, sizeof v);
        break;
    }
    default:
        *p = (uint8_t)raw;
        break;
    }
}

// cppcheck-suppress misra-c2012-8.7 ; D-8.7: the link's API (the Matek parameter blob, its test)
int fw_link_param_get_cfg(const fw_config_t *cfg, const fw_link_params_t *link_params,
                          uint16_t index, int32_t *raw, const ht_param_info_t **row)
{
    int gid = 0;
    const group_t g = group_of(index, &gid);
    if (g == G_COUNT) {
        return -1;
    }
    if (raw != NULL) {
        if ((cfg == NULL) || (link_params == NULL)) {
            return -1;
        }
        *raw = load(field_ro(cfg, link_params, g, index), rows[index].kind);
    }
    if (row != NULL) {
        *row = row_info(g, gid);
    }
    return 0;
}

uint8_t fw_link_param_mav_type(uint16_t index)
{
    int gid = 0;
    const group_t g = group_of(index, &gid);
    const ht_param_info_t *info = (g == G_COUNT) ? NULL : row_info(g, gid);
    if (info == NULL) {
        return 0u;
    }
    if (info->scale != 1) {
        return (uint8_t)MAV_PARAM_TYPE_REAL32;
    }
    switch (rows[index].kind) {
    case K_U8:
        return (uint8_t)MAV_PARAM_TYPE_UINT8;
    case K_U16:
        return (uint8_t)MAV_PARAM_TYPE_UINT16;
    case K_I16:
        return (uint8_t)MAV_PARAM_TYPE_INT16;
    default:
        return (uint8_t)MAV_PARAM_TYPE_INT32;
    }
}

int fw_link_param_get(const fw_link_t *l, uint16_t index, int32_t *raw, const ht_param_info_t **row)
{
    if ((l == NULL) || (l->cfg == NULL)) {
        return -1;
    }
    return fw_link_param_get_cfg(l->cfg, &l->params, index, raw, row);
}

int fw_link_param_put_cfg(fw_config_t *cfg, fw_link_params_t *link_params, uint16_t index,
                          int32_t raw)
{
    int gid = 0;
    const group_t g = group_of(index, &gid);
    if ((cfg == NULL) || (link_params == NULL) || (g == G_COUNT)) {
        return -1;
    }
    const ht_param_info_t *info = row_info(g, gid);
    if ((info == NULL) || (raw < info->min_raw) || (raw > info->max_raw)) {
        return 1;
    }
    store(field_rw(cfg, link_params, g, index), rows[index].kind, raw);
    return 0;
}

/* The modes (and their holds, fly-by-wire, guidance, AoA model) from the
 * live configuration and the current controller. */
static int reinit_modes(fw_link_t *l)
{
    fw_t *fw = l->fw;
    const fw_config_t *cfg = l->cfg;
    const uint8_t pm = (cfg->modes_pitch_mode != 0u) ? 1u : 0u;
    return ht_modes_init(&fw->modes, &cfg->modes, &fw->law[pm], cfg->waypoints, cfg->waypoint_count,
                         &fw->modes_bad);
}

static int reinit_law(fw_link_t *l)
{
    for (uint8_t mode = 0u; mode < 2u; ++mode) {
        ht_params_t p = l->cfg->law;
        p.pitch_mode = mode;
        if (ht_init(&l->fw->law[mode], &p, NULL) != HT_OK) {
            return 1;
        }
    }
    return reinit_modes(l);
}

/* Re-initialise the group's block from the live configuration. 0 = OK. */
static int reinit_group(fw_link_t *l, group_t g)
{
    fw_t *fw = l->fw;
    const fw_config_t *cfg = l->cfg;
    switch (g) {
    case G_LAW:
        return reinit_law(l);
    case G_DCM:
        /* the step's timing is built on the IMU rate: it is not changed here */
        if ((uint32_t)cfg->modes.rate_hz * cfg->control_divider != cfg->dcm.imu_rate_hz) {
            return 1;
        }
        return ht_dcm_init(&fw->dcm, &cfg->dcm, NULL);
    case G_GUIDE:
        return ht_guide_init(&fw->guide, &cfg->guide, cfg->modes.rate_hz, NULL);
    case G_LINK:
        return (ht_link_first_bad(&l->params) == HT_LINK_P_NONE) ? 0 : 1;
    case G_COUNT:
        return 1;
    default: /* the modes' own rows, the holds, fly-by-wire, waypoints, AoA */
        return reinit_modes(l);
    }
}

/* "<PARAM_ID><tail>" into the refusal text (49 characters at most) */
static void refusal_of_row(fw_link_t *l, uint16_t index, const char *tail)
{
    char id[17];
    (void)fw_link_param_id(index, id);
    size_t n = 0u;
    for (const char *c = id; (*c != '\0') && (n < 16u); ++c) {
        l->param_refusal[n] = *c;
        ++n;
    }
    for (const char *c = tail; (*c != '\0') && ((n + 1u) < sizeof l->param_refusal); ++c) {
        l->param_refusal[n] = *c;
        ++n;
    }
    l->param_refusal[n] = '\0';
}

int fw_link_param_set(fw_link_t *l, uint16_t index, int32_t raw)
{
    int gid = 0;
    const group_t g = group_of(index, &gid);
    if ((l == NULL) || (l->cfg == NULL) || (l->fw == NULL) || (g == G_COUNT)) {
        return -1;
    }
    l->param_refusal[0] = '\0';
    const ht_param_info_t *info = row_info(g, gid);
    if ((info == NULL) || (raw < info->min_raw) || (raw > info->max_raw)) {
        refusal_of_row(l, index, " out of range");
        return 1;
    }
    uint8_t *p = field_rw(l->cfg, &l->params, g, index);
    const int32_t old = load(p, rows[index].kind);
    store(p, rows[index].kind, raw);
    if (reinit_group(l, g) != 0) {
        /* the reason before the old value's re-init clears it: the modes
         * name the joint rule (config_check.h) or their block's field */
        if (l->fw->modes_bad.field != HT_MODES_P_NONE) {
            ht_modes_bad_name(&l->fw->modes_bad, l->param_refusal,
                              (unsigned)sizeof l->param_refusal);
        } else {
            refusal_of_row(l, index, " refused by a joint limit");
        }
        store(p, rows[index].kind, old); /* refused whole: as it was */
        (void)reinit_group(l, g);
        return 2;
    }
    return 0;
}
