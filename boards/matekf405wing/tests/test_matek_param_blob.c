/*
 * test_matek_param_blob.c - the Matek F405-WING parameter blob and its
 * boot-time load, on the simulated flash of boards/common/tests.
 *
 * Worked layout (matek_param_blob.h), little-endian:
 *   law.kp_aileron = 1.0 = Q16 65536 = 0x00010000 -> bytes 0..3: 00 00 01 00
 *   law.v_ref_cm_s = 1500 = 0x5DC                  -> bytes 36..39: DC 05 00 00
 *   law.max_tilt = 4.0 = 0x40000                   -> bytes 44..47: 00 00 04 00
 *   dcm.imu_rate_hz = 200 = 0xC8                   -> bytes 50..51: C8 00
 *   dcm.kp_rollpitch = 0.2 = Q16 13107 = 0x3333    -> bytes 52..55: 33 33 00 00
 *   dcm.gps_min_speed_cm_s = -2 (a test value)     -> bytes 84..85: FE FF
 *   dcm.centripetal = 2                            -> byte 88: 02; 89..91: 00
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

void setUp(void)
{
    memset(mem, 0xFF, sizeof mem);
    sim_flash_init(&sim, mem, SLOT, 2u, 4u);
    sim_flash_bind(&sim, &flash);
    fw_config_default(&cfg);
}

void tearDown(void) {}

static void test_layout_bytes(void)
{
    ht_params_t law = cfg.law;
    ht_dcm_params_t dcm = cfg.dcm;
    law.kp_aileron = 65536;
    law.v_ref_cm_s = 1500;
    law.max_tilt = 0x40000;
    dcm.imu_rate_hz = 200u;
    dcm.kp_rollpitch = 13107;
    dcm.gps_min_speed_cm_s = -2;
    dcm.centripetal = 2u;
    uint8_t blob[MATEK_PARAM_BLOB_BYTES];
    memset(blob, 0xEE, sizeof blob);
    matek_param_blob_encode(&law, &dcm, blob);
    const uint8_t kp[4] = {0x00, 0x00, 0x01, 0x00};
    const uint8_t vref[4] = {0xDC, 0x05, 0x00, 0x00};
    const uint8_t tilt[4] = {0x00, 0x00, 0x04, 0x00};
    const uint8_t rate[2] = {0xC8, 0x00};
    const uint8_t kprp[4] = {0x33, 0x33, 0x00, 0x00};
    const uint8_t gmin[2] = {0xFE, 0xFF};
    const uint8_t tail[4] = {0x02, 0x00, 0x00, 0x00};
    TEST_ASSERT_EQUAL_HEX8_ARRAY(kp, &blob[0], 4);
    TEST_ASSERT_EQUAL_HEX8_ARRAY(vref, &blob[36], 4);
    TEST_ASSERT_EQUAL_HEX8_ARRAY(tilt, &blob[44], 4);
    TEST_ASSERT_EQUAL_HEX8_ARRAY(rate, &blob[50], 2);
    TEST_ASSERT_EQUAL_HEX8_ARRAY(kprp, &blob[52], 4);
    TEST_ASSERT_EQUAL_HEX8_ARRAY(gmin, &blob[84], 2);
    TEST_ASSERT_EQUAL_HEX8_ARRAY(tail, &blob[88], 4);
}

static void test_round_trip(void)
{
    ht_params_t law = cfg.law;
    ht_dcm_params_t dcm = cfg.dcm;
    law.kd_rudder = -12345;
    law.schedule = 1u;
    dcm.gps_latency_ms = 321u;
    dcm.accel_band_g = 0x12345;
    uint8_t blob[MATEK_PARAM_BLOB_BYTES];
    matek_param_blob_encode(&law, &dcm, blob);
    ht_params_t law2;
    ht_dcm_params_t dcm2;
    memset(&law2, 0, sizeof law2);
    memset(&dcm2, 0, sizeof dcm2);
    matek_param_blob_decode(blob, &law2, &dcm2);
    TEST_ASSERT_EQUAL_INT32(-12345, law2.kd_rudder);
    TEST_ASSERT_EQUAL_UINT8(1u, law2.schedule);
    TEST_ASSERT_EQUAL_INT32(law.v_min_cm_s, law2.v_min_cm_s);
    TEST_ASSERT_EQUAL_UINT8(law.pitch_mode, law2.pitch_mode);
    TEST_ASSERT_EQUAL_UINT16(321u, dcm2.gps_latency_ms);
    TEST_ASSERT_EQUAL_INT32(0x12345, dcm2.accel_band_g);
    TEST_ASSERT_EQUAL_UINT16(dcm.imu_rate_hz, dcm2.imu_rate_hz);
    TEST_ASSERT_EQUAL_UINT8(dcm.centripetal, dcm2.centripetal);
}

static void test_blank_store_keeps_defaults(void)
{
    const fw_config_t before = cfg;
    matek_params_report_t rep;
    matek_params_load(&flash, &cfg, &rep);
    TEST_ASSERT_EQUAL_UINT8(MATEK_PARAMS_BLANK, rep.result);
    TEST_ASSERT_EQUAL_MEMORY(&before.law, &cfg.law, sizeof cfg.law);
}

static void save(const ht_params_t *law, const ht_dcm_params_t *dcm)
{
    uint8_t blob[MATEK_PARAM_BLOB_BYTES];
    param_store_t store;
    matek_param_blob_encode(law, dcm, blob);
    matek_param_store(&flash, &store);
    TEST_ASSERT_EQUAL(PARAM_STORE_OK, param_store_save(&store, blob, NULL, NULL));
}

static void test_stored_set_is_loaded(void)
{
    ht_params_t law = cfg.law;
    law.kp_aileron = 2 * 65536;
    save(&law, &cfg.dcm);
    matek_params_report_t rep;
    matek_params_load(&flash, &cfg, &rep);
    TEST_ASSERT_EQUAL_UINT8(MATEK_PARAMS_LOADED, rep.result);
    TEST_ASSERT_EQUAL_UINT32(1u, rep.sequence);
    TEST_ASSERT_EQUAL_INT32(2 * 65536, cfg.law.kp_aileron);
}

static void test_corrupt_store_keeps_defaults(void)
{
    save(&cfg.law, &cfg.dcm);
    mem[30] ^= 0x01u; /* a payload bit: the CRC fails */
    ht_params_t law_before = cfg.law;
    matek_params_report_t rep;
    matek_params_load(&flash, &cfg, &rep);
    TEST_ASSERT_EQUAL_UINT8(MATEK_PARAMS_CORRUPT, rep.result);
    TEST_ASSERT_EQUAL_MEMORY(&law_before, &cfg.law, sizeof cfg.law);
}

static void test_other_schema_keeps_defaults(void)
{
    uint8_t blob[MATEK_PARAM_BLOB_BYTES];
    memset(blob, 0, sizeof blob);
    param_store_t store;
    matek_param_store(&flash, &store);
    store.schema_version = 2u;
    TEST_ASSERT_EQUAL(PARAM_STORE_OK, param_store_save(&store, blob, NULL, NULL));
    matek_params_report_t rep;
    matek_params_load(&flash, &cfg, &rep);
    TEST_ASSERT_EQUAL_UINT8(MATEK_PARAMS_MISMATCH, rep.result);
}

static void test_out_of_range_values_are_refused(void)
{
    ht_params_t law = cfg.law;
    law.v_min_cm_s = 50; /* below the law's 100 cm/s floor */
    save(&law, &cfg.dcm);
    matek_params_report_t rep;
    matek_params_load(&flash, &cfg, &rep);
    TEST_ASSERT_EQUAL_UINT8(MATEK_PARAMS_REFUSED, rep.result);
    TEST_ASSERT_EQUAL_INT32((int32_t)HT_P_V_MIN, rep.bad_field);
    TEST_ASSERT_NOT_EQUAL(50, cfg.law.v_min_cm_s);
}

static void test_other_imu_rate_is_refused(void)
{
    ht_dcm_params_t dcm = cfg.dcm;
    dcm.imu_rate_hz = 100u; /* valid for the estimator, not for this image's tick */
    save(&cfg.law, &dcm);
    matek_params_report_t rep;
    matek_params_load(&flash, &cfg, &rep);
    TEST_ASSERT_EQUAL_UINT8(MATEK_PARAMS_REFUSED, rep.result);
    TEST_ASSERT_EQUAL_INT32(2000, rep.bad_field);
    TEST_ASSERT_EQUAL_UINT16(200u, cfg.dcm.imu_rate_hz);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_layout_bytes);
    RUN_TEST(test_round_trip);
    RUN_TEST(test_blank_store_keeps_defaults);
    RUN_TEST(test_stored_set_is_loaded);
    RUN_TEST(test_corrupt_store_keeps_defaults);
    RUN_TEST(test_other_schema_keeps_defaults);
    RUN_TEST(test_out_of_range_values_are_refused);
    RUN_TEST(test_other_imu_rate_is_refused);
    return UNITY_END();
}
