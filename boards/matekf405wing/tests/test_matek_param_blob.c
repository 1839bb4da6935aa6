/*
 * test_matek_param_blob.c - the Matek F405-WING parameter blob (schema 2:
 * every row the MAVLink link exposes) and its boot-time load, on the
 * simulated flash of boards/common/tests.
 *
 * Worked layout (matek_param_blob.h), little-endian: bytes 0..1 the row
 * count (97 = 61 00), 2..3 zero, 4..7 the table's fingerprint, then row i
 * at 8 + 4 i; e.g. row 0 (LAW_KP_AILERON) = Q16 65536 -> 00 00 01 00.
 */
#include "unity.h"

#include "matek_param_blob.h"
#include "sim_flash.h"

#include <string.h>

#define SLOT 1024u

static uint8_t mem[2u * SLOT];
static sim_flash_t sim;
static param_flash_t flash;
static fw_config_t cfg;
static fw_link_params_t lp;
static fw_config_t live_cfg;
static fw_t fw;
static fw_link_t link;
static uint8_t blob[MATEK_PARAM_BLOB_MAX_BYTES];

void setUp(void)
{
    memset(mem, 0xFF, sizeof mem);
    sim_flash_init(&sim, mem, SLOT, 2u, 4u);
    sim_flash_bind(&sim, &flash);
    fw_config_default(&cfg);
    ht_link_params_default(&lp);
}

void tearDown(void) {}

static uint16_t index_of_id(const char *id)
{
    const int32_t i = fw_link_param_find(id);
    TEST_ASSERT_TRUE_MESSAGE(i >= 0, id);
    return (uint16_t)i;
}

static void save_blob(void)
{
    param_store_t store;
    matek_param_store(&flash, &store);
    TEST_ASSERT_EQUAL(PARAM_STORE_OK, param_store_save(&store, blob, NULL, NULL));
}

/* The defaults' blob with row index set to raw (any value: no check here). */
static void save_with(uint16_t index, int32_t raw)
{
    TEST_ASSERT_EQUAL_INT(0, matek_param_blob_encode(&cfg, &lp, blob));
    const uint32_t at = MATEK_PARAM_HEAD_BYTES + 4u * index;
    for (uint32_t b = 0u; b < 4u; ++b) {
        blob[at + b] = (uint8_t)(((uint32_t)raw >> (8u * b)) & 0xFFu);
    }
    save_blob();
}

static void assert_untouched(const fw_config_t *before, const fw_link_params_t *lp_before)
{
    TEST_ASSERT_EQUAL_MEMORY(before, &cfg, sizeof cfg);
    TEST_ASSERT_EQUAL_MEMORY(lp_before, &lp, sizeof lp);
}

static void test_layout_bytes(void)
{
    const uint16_t n = fw_link_param_count();
    TEST_ASSERT_EQUAL_UINT16(97u, n);
    TEST_ASSERT_TRUE(n <= MATEK_PARAM_MAX_ROWS);
    TEST_ASSERT_EQUAL_UINT32(8u + 4u * 97u, matek_param_blob_bytes());
    cfg.law.kp_aileron = 65536;
    memset(blob, 0xEE, sizeof blob);
    TEST_ASSERT_EQUAL_INT(0, matek_param_blob_encode(&cfg, &lp, blob));
    const uint8_t head[4] = {0x61, 0x00, 0x00, 0x00};
    TEST_ASSERT_EQUAL_HEX8_ARRAY(head, blob, 4);
    const uint32_t fp = matek_param_fingerprint();
    TEST_ASSERT_EQUAL_HEX32(fp, (uint32_t)blob[4] | ((uint32_t)blob[5] << 8) |
                                    ((uint32_t)blob[6] << 16) | ((uint32_t)blob[7] << 24));
    const uint8_t kp[4] = {0x00, 0x00, 0x01, 0x00};
    TEST_ASSERT_EQUAL_HEX8_ARRAY(kp, &blob[8], 4);
    char id[17];
    TEST_ASSERT_EQUAL_INT(0, fw_link_param_id(0u, id));
    TEST_ASSERT_EQUAL_STRING("LAW_KP_AILERON", id);
    for (uint16_t i = 0u; i < n; ++i) { /* every row, sign-extended int32 */
        int32_t raw = 0;
        TEST_ASSERT_EQUAL_INT(0, fw_link_param_get_cfg(&cfg, &lp, i, &raw, NULL));
        const uint8_t *p = &blob[8u + 4u * i];
        const uint32_t v = (uint32_t)p[0] | ((uint32_t)p[1] << 8) | ((uint32_t)p[2] << 16) |
                           ((uint32_t)p[3] << 24);
        TEST_ASSERT_EQUAL_INT32(raw, (int32_t)v);
    }
    for (uint32_t b = matek_param_blob_bytes(); b < MATEK_PARAM_BLOB_MAX_BYTES; ++b) {
        TEST_ASSERT_EQUAL_HEX8(0u, blob[b]);
    }
    TEST_ASSERT_NOT_EQUAL(0u, fp);
}

static void test_put_cfg(void)
{
    const uint16_t i = index_of_id("LAW_V_MIN");
    const ht_param_info_t *row = NULL;
    TEST_ASSERT_EQUAL_INT(0, fw_link_param_get_cfg(NULL, NULL, i, NULL, &row));
    TEST_ASSERT_NOT_NULL(row);
    const fw_config_t before = cfg;
    TEST_ASSERT_EQUAL_INT(1, fw_link_param_put_cfg(&cfg, &lp, i, row->min_raw - 1));
    TEST_ASSERT_EQUAL_INT(1, fw_link_param_put_cfg(&cfg, &lp, i, row->max_raw + 1));
    TEST_ASSERT_EQUAL_MEMORY(&before, &cfg, sizeof cfg);
    TEST_ASSERT_EQUAL_INT(0, fw_link_param_put_cfg(&cfg, &lp, i, row->max_raw));
    TEST_ASSERT_EQUAL_INT32(row->max_raw, cfg.law.v_min_cm_s); /* no joint check */
    TEST_ASSERT_EQUAL_INT(-1, fw_link_param_put_cfg(&cfg, &lp, fw_link_param_count(), 0));
    TEST_ASSERT_EQUAL_INT(-1, fw_link_param_put_cfg(NULL, &lp, i, 0));
    TEST_ASSERT_EQUAL_INT(-1, fw_link_param_get_cfg(NULL, &lp, i, &(int32_t){0}, NULL));
}

/* Each row to a legal value other than its default through the link (the
 * joint checks of its block may refuse some candidates), save, boot-load
 * into a fresh configuration: every row comes back. */
static void test_round_trip_every_row(void)
{
    fw_config_default(&live_cfg);
    TEST_ASSERT_EQUAL_INT(1, fw_init(&fw, &live_cfg));
    TEST_ASSERT_EQUAL_INT(0, fw_link_init(&link, &fw, &live_cfg, 0u, 1u));
    const uint16_t n = fw_link_param_count();
    unsigned changed = 0u;
    for (uint16_t i = 0u; i < n; ++i) {
        int32_t def = 0;
        const ht_param_info_t *row = NULL;
        TEST_ASSERT_EQUAL_INT(0, fw_link_param_get(&link, i, &def, &row));
        const int32_t cand[6] = {def + 1,
                                 def - 1,
                                 row->max_raw,
                                 row->min_raw,
                                 def + (row->max_raw - def) / 2,
                                 def - (def - row->min_raw) / 2};
        for (unsigned c = 0u; c < 6u; ++c) {
            if ((cand[c] != def) && (fw_link_param_set(&link, i, cand[c]) == 0)) {
                ++changed;
                break;
            }
        }
    }
    /* only the IMU rate is fixed by this image (divider rule) */
    TEST_ASSERT_EQUAL_UINT(n - 1u, changed);
    TEST_ASSERT_EQUAL_INT(0, matek_param_blob_encode(&live_cfg, &link.params, blob));
    save_blob();
    matek_params_report_t rep;
    matek_params_load(&flash, &cfg, &lp, &rep);
    TEST_ASSERT_EQUAL_UINT8(MATEK_PARAMS_LOADED, rep.result);
    TEST_ASSERT_EQUAL_UINT32(1u, rep.sequence);
    unsigned differ_from_default = 0u;
    fw_config_t defaults;
    fw_config_default(&defaults);
    fw_link_params_t lp_def;
    ht_link_params_default(&lp_def);
    for (uint16_t i = 0u; i < n; ++i) {
        int32_t want = 0;
        int32_t got = 0;
        int32_t def = 0;
        TEST_ASSERT_EQUAL_INT(0, fw_link_param_get(&link, i, &want, NULL));
        TEST_ASSERT_EQUAL_INT(0, fw_link_param_get_cfg(&cfg, &lp, i, &got, NULL));
        TEST_ASSERT_EQUAL_INT(0, fw_link_param_get_cfg(&defaults, &lp_def, i, &def, NULL));
        TEST_ASSERT_EQUAL_INT32(want, got);
        differ_from_default += (got != def) ? 1u : 0u;
    }
    TEST_ASSERT_TRUE(differ_from_default >= n / 2u); /* the set is really not the defaults */
    fw_t check;
    TEST_ASSERT_EQUAL_INT(1, fw_init(&check, &cfg)); /* flyable */
}

static void test_blank_store_keeps_defaults(void)
{
    const fw_config_t before = cfg;
    const fw_link_params_t lp_before = lp;
    matek_params_report_t rep;
    matek_params_load(&flash, &cfg, &lp, &rep);
    TEST_ASSERT_EQUAL_UINT8(MATEK_PARAMS_BLANK, rep.result);
    assert_untouched(&before, &lp_before);
}

static void test_corrupt_store_keeps_defaults(void)
{
    save_with(0u, 2 * 65536);
    mem[30] ^= 0x01u; /* a payload bit: the CRC fails */
    const fw_config_t before = cfg;
    const fw_link_params_t lp_before = lp;
    matek_params_report_t rep;
    matek_params_load(&flash, &cfg, &lp, &rep);
    TEST_ASSERT_EQUAL_UINT8(MATEK_PARAMS_CORRUPT, rep.result);
    assert_untouched(&before, &lp_before);
}

static void test_other_table_is_a_mismatch(void)
{
    const fw_config_t before = cfg;
    const fw_link_params_t lp_before = lp;
    matek_params_report_t rep;
    /* another fingerprint (a renamed or re-formatted row) */
    TEST_ASSERT_EQUAL_INT(0, matek_param_blob_encode(&cfg, &lp, blob));
    blob[5] ^= 0x10u;
    save_blob();
    matek_params_load(&flash, &cfg, &lp, &rep);
    TEST_ASSERT_EQUAL_UINT8(MATEK_PARAMS_MISMATCH, rep.result);
    assert_untouched(&before, &lp_before);
    /* another row count, same fingerprint */
    TEST_ASSERT_EQUAL_INT(0, matek_param_blob_encode(&cfg, &lp, blob));
    blob[0] = 96u;
    save_blob();
    matek_params_load(&flash, &cfg, &lp, &rep);
    TEST_ASSERT_EQUAL_UINT8(MATEK_PARAMS_MISMATCH, rep.result);
    assert_untouched(&before, &lp_before);
}

static void test_schema_1_record_is_a_mismatch(void)
{
    uint8_t old[92];
    memset(old, 0, sizeof old);
    param_store_t store;
    matek_param_store(&flash, &store);
    store.schema_version = 1u;
    store.length = 92u;
    TEST_ASSERT_EQUAL(PARAM_STORE_OK, param_store_save(&store, old, NULL, NULL));
    const fw_config_t before = cfg;
    const fw_link_params_t lp_before = lp;
    matek_params_report_t rep;
    matek_params_load(&flash, &cfg, &lp, &rep);
    TEST_ASSERT_EQUAL_UINT8(MATEK_PARAMS_MISMATCH, rep.result);
    assert_untouched(&before, &lp_before);
}

static void assert_refused(uint8_t why, const char *id)
{
    const fw_config_t before = cfg;
    const fw_link_params_t lp_before = lp;
    matek_params_report_t rep;
    matek_params_load(&flash, &cfg, &lp, &rep);
    TEST_ASSERT_EQUAL_UINT8(MATEK_PARAMS_REFUSED, rep.result);
    TEST_ASSERT_EQUAL_UINT8(why, rep.bad);
    TEST_ASSERT_EQUAL_INT32((int32_t)index_of_id(id), rep.bad_index);
    TEST_ASSERT_EQUAL_STRING(id, rep.bad_id);
    assert_untouched(&before, &lp_before);
}

static void test_row_out_of_range_is_refused(void)
{
    const ht_param_info_t *row = ht_param_info(HT_P_V_MIN);
    save_with(index_of_id("LAW_V_MIN"), row->min_raw - 1);
    assert_refused(MATEK_BAD_RANGE, "LAW_V_MIN");
    /* a late group's row: the navigation's, and the link's own */
    const uint16_t nav = index_of_id("NAV_L1");
    const ht_param_info_t *nrow = NULL;
    TEST_ASSERT_EQUAL_INT(0, fw_link_param_get_cfg(NULL, NULL, nav, NULL, &nrow));
    save_with(nav, nrow->max_raw + 1);
    assert_refused(MATEK_BAD_RANGE, "NAV_L1");
    const uint16_t lnk = (uint16_t)(fw_link_param_count() - 1u);
    const ht_param_info_t *lrow = NULL;
    char lid[17];
    TEST_ASSERT_EQUAL_INT(0, fw_link_param_get_cfg(NULL, NULL, lnk, NULL, &lrow));
    TEST_ASSERT_EQUAL_INT(0, fw_link_param_id(lnk, lid));
    TEST_ASSERT_EQUAL_MEMORY("LNK_", lid, 4);
    save_with(lnk, lrow->max_raw + 1);
    assert_refused(MATEK_BAD_RANGE, lid);
}

static void test_joint_limit_is_refused(void)
{
    /* v_ref below v_min: each in its range, the law's joint check refuses */
    const ht_param_info_t *row = ht_param_info(HT_P_V_REF);
    const int32_t v_ref = cfg.law.v_min_cm_s - 1;
    TEST_ASSERT_TRUE(v_ref >= row->min_raw);
    save_with(index_of_id("LAW_V_REF"), v_ref);
    const fw_config_t before = cfg;
    matek_params_report_t rep;
    matek_params_load(&flash, &cfg, &lp, &rep);
    TEST_ASSERT_EQUAL_UINT8(MATEK_PARAMS_REFUSED, rep.result);
    TEST_ASSERT_EQUAL_UINT8(MATEK_BAD_INIT, rep.bad);
    TEST_ASSERT_EQUAL_UINT8(FW_BAD_LAW, rep.bad_block);
    TEST_ASSERT_EQUAL_INT32((int32_t)HT_P_V_REF, rep.bad_sub);
    TEST_ASSERT_EQUAL_STRING("LAW_V_REF", rep.bad_id);
    TEST_ASSERT_EQUAL_MEMORY(&before, &cfg, sizeof cfg);
}

static void test_other_imu_rate_is_refused(void)
{
    /* 100 Hz is in the estimator's range, not this image's tick */
    const uint16_t i = (uint16_t)index_of_id("DCM_IMU_RATE");
    save_with(i, 100);
    assert_refused(MATEK_BAD_IMU_RATE, "DCM_IMU_RATE");
    TEST_ASSERT_EQUAL_UINT16(200u, cfg.dcm.imu_rate_hz);
    /* the same rate stored: loaded */
    save_with(i, 200);
    matek_params_report_t rep;
    matek_params_load(&flash, &cfg, &lp, &rep);
    TEST_ASSERT_EQUAL_UINT8(MATEK_PARAMS_LOADED, rep.result);
}

/* A stored set each of whose rows is in range but that breaks the joint
 * rule (config_check.h: the mode switch on the aileron stick, the inverted
 * switch on a stick, its threshold at the stick centre) is refused whole at
 * boot, the defaults kept, the row and the rule named (issue 33: on main it
 * was loaded, and the aircraft booted with the aileron stick switching
 * modes). */
static void test_jointly_unsafe_set_is_refused(void)
{
    static const struct {
        const char *id;
        int32_t raw;
        const char *reason;
    } cases[] = {
        {"MOD_MODE_INPUT", 0, "joint.mode_input is a stick channel"},
        {"FBW_INVERTD_INPT", 1, "joint.inverted_input is a stick channel"},
        {"FBW_INVRTD_THRSH", 1500, "joint.inverted_threshold_us not in (centre, full]"},
    };
    for (unsigned i = 0u; i < sizeof cases / sizeof cases[0]; ++i) {
        setUp();
        save_with(index_of_id(cases[i].id), cases[i].raw);
        const fw_config_t before = cfg;
        matek_params_report_t rep;
        matek_params_load(&flash, &cfg, &lp, &rep);
        TEST_ASSERT_EQUAL_UINT8(MATEK_PARAMS_REFUSED, rep.result);
        TEST_ASSERT_EQUAL_UINT8(MATEK_BAD_INIT, rep.bad);
        TEST_ASSERT_EQUAL_UINT8(FW_BAD_MODES, rep.bad_block);
        TEST_ASSERT_EQUAL_STRING(cases[i].id, rep.bad_id);
        TEST_ASSERT_EQUAL_STRING(cases[i].reason, rep.reason);
        TEST_ASSERT_EQUAL_MEMORY(&before, &cfg, sizeof cfg);
    }
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_layout_bytes);
    RUN_TEST(test_put_cfg);
    RUN_TEST(test_round_trip_every_row);
    RUN_TEST(test_blank_store_keeps_defaults);
    RUN_TEST(test_corrupt_store_keeps_defaults);
    RUN_TEST(test_other_table_is_a_mismatch);
    RUN_TEST(test_schema_1_record_is_a_mismatch);
    RUN_TEST(test_row_out_of_range_is_refused);
    RUN_TEST(test_joint_limit_is_refused);
    RUN_TEST(test_other_imu_rate_is_refused);
    RUN_TEST(test_jointly_unsafe_set_is_refused);
    return UNITY_END();
}
