/*
 * test_fw_log.c - the log writer (fw_log.c): the record table against its
 * own format characters, the header (FMT, MSG, PARM in order, values as
 * binary32), the step's records with the step's numbers, the byte budget
 * per call, a full sink (drops counted, never a torn record), a slow sink,
 * decimation, and the refused configurations.
 */
#include "unity.h"

#include "log/fw_log.h"

#include <stdint.h>
#include <stdio.h>
#include <string.h>

void setUp(void) {}
void tearDown(void) {}

/* DFReader's sizes of the format characters the table uses. */
static size_t char_size(char c)
{
    switch (c) {
    case 'Q':
        return 8u;
    case 'i':
    case 'I':
    case 'L':
    case 'e':
    case 'f':
        return 4u;
    case 'h':
    case 'H':
    case 'c':
    case 'C':
        return 2u;
    case 'B':
    case 'M':
        return 1u;
    case 'N':
        return 16u;
    case 'Z':
        return 64u;
    default:
        return 0u;
    }
}

/* A file-like sink: takes up to `take` bytes per call (SIZE_MAX: all),
 * into a big buffer. */
typedef struct {
    uint8_t data[1u << 20];
    size_t n;
    size_t take;
    size_t calls;
} sink_t;

static sink_t g_sink;

static size_t sink_write(void *ctx, const uint8_t *b, size_t n)
{
    sink_t *s = ctx;
    size_t k = (n < s->take) ? n : s->take;
    if (k > sizeof s->data - s->n) {
        k = sizeof s->data - s->n;
    }
    memcpy(&s->data[s->n], b, k);
    s->n += k;
    ++s->calls;
    return k;
}

/* Three rows: a Q16 gain, a cm/s speed, a plain count. */
static int param_rows(void *ctx, uint16_t index, char name[17], int32_t *raw, int32_t *scale)
{
    (void)ctx;
    static const char *names[] = {"KP_AILERON", "V_REF_SIXTEEN_CH", "IMU_RATE"};
    static const int32_t raws[] = {98304, 1500, 200};
    static const int32_t scales[] = {65536, 100, 1};
    if (index >= 3u) {
        return -1;
    }
    (void)snprintf(name, 17u, "%s", names[index]);
    *raw = raws[index];
    *scale = scales[index];
    return 0;
}

static uint8_t g_ring[4096];

static fw_log_config_t config(uint32_t ring_size, uint32_t budget)
{
    fw_log_config_t c = {g_ring, ring_size, budget, 1u, sink_write, &g_sink, param_rows, NULL};
    return c;
}

static void reset_sink(size_t take)
{
    memset(&g_sink, 0, sizeof g_sink);
    g_sink.take = take;
}

/* The length of the record at p per the table (FMT 89), 0 for a bad
 * header or an unknown type. */
static size_t record_len(const uint8_t *p)
{
    if ((p[0] != FW_LOG_HEAD1) || (p[1] != FW_LOG_HEAD2)) {
        return 0u;
    }
    if (p[2] == FW_LOG_TYPE_FMT) {
        return FW_LOG_FMT_LEN;
    }
    for (int k = 0; k < (int)FW_LOG_KIND_COUNT; ++k) {
        if (fw_log_format((fw_log_kind_t)k)->type == p[2]) {
            return fw_log_format((fw_log_kind_t)k)->length;
        }
    }
    return 0u;
}

/* Walk the sink's bytes record by record: the count, or -1 at a torn or
 * unknown record. types[] gets the type of each (up to cap). */
static int walk(const uint8_t *d, size_t n, uint8_t *types, size_t cap)
{
    size_t off = 0u;
    int count = 0;
    while (off < n) {
        if (n - off < 3u) {
            return -1;
        }
        const size_t len = record_len(&d[off]);
        if ((len == 0u) || (off + len > n)) {
            return -1;
        }
        if ((size_t)count < cap) {
            types[count] = d[off + 2u];
        }
        ++count;
        off += len;
    }
    return count;
}

static fw_t g_fw; /* the step's state: only its (absent) configuration is read */
static fw_inputs_t g_in;
static fw_output_t g_out;

static void some_step(int k)
{
    memset(&g_in, 0, sizeof g_in);
    memset(&g_out, 0, sizeof g_out);
    g_in.sensors.imu.gyro_rad_s[0] = -65536 * 3 + k;
    g_in.sensors.imu.accel_g[2] = -65536;
    g_in.sensors.gps.fix = 3u;
    g_in.sensors.gps.lat_e7 = 473977420;
    g_in.sensors.gps.lon_e7 = 85455940;
    g_in.sensors.baro_alt_cm = 48812;
    g_in.sensors.airspeed_cm_s = 1523;
    g_out.control_ran = 1u;
    g_out.pulse_count = 4u;
    g_out.pulse_us[0] = 1000u;
    g_out.pulse_us[3] = 2000u;
    g_out.pulse_us[5] = 1234u; /* beyond pulse_count: logged as 0 */
    g_out.law_in.x = -16384;
    g_out.law_in.turn_rate_rad_s = (int16_t)(-2048 + k);
    g_out.law_in.pitch_ratio = 65536 * 3;
    g_out.law.aileron = 8192;
    g_out.law.tilt_ratio = -123456;
    g_out.law.flags = 5u;
    g_out.est.roll_cdeg = -17999;
    g_out.est.yaw_cdeg = 35999u;
    g_out.modes.mode = 1u;
}

static uint32_t le32(const uint8_t *p)
{
    return (uint32_t)p[0] | ((uint32_t)p[1] << 8u) | ((uint32_t)p[2] << 16u) |
           ((uint32_t)p[3] << 24u);
}

static void test_table_matches_its_format_characters(void)
{
    for (int k = 0; k < (int)FW_LOG_KIND_COUNT; ++k) {
        const fw_log_format_t *f = fw_log_format((fw_log_kind_t)k);
        TEST_ASSERT_NOT_NULL(f);
        size_t len = 3u;
        size_t fields = 0u;
        for (const char *c = f->format; *c != '\0'; ++c) {
            TEST_ASSERT_NOT_EQUAL_MESSAGE(0u, char_size(*c), f->name);
            len += char_size(*c);
            ++fields;
        }
        TEST_ASSERT_EQUAL_MESSAGE(len, f->length, f->name);
        size_t labels = 1u;
        for (const char *c = f->labels; *c != '\0'; ++c) {
            labels += (*c == ',') ? 1u : 0u;
        }
        TEST_ASSERT_EQUAL_MESSAGE(fields, labels, f->name);
        TEST_ASSERT_TRUE(strlen(f->name) <= 4u);
        TEST_ASSERT_TRUE(strlen(f->format) <= 16u);
        TEST_ASSERT_TRUE(strlen(f->labels) <= 64u);
        TEST_ASSERT_TRUE(f->length <= FW_LOG_REC_MAX);
        TEST_ASSERT_EQUAL_INT(0, strncmp(f->labels, "TimeUS,", 7u));
        TEST_ASSERT_EQUAL_INT('Q', f->format[0]);
        for (int j = 0; j < k; ++j) {
            TEST_ASSERT_NOT_EQUAL(fw_log_format((fw_log_kind_t)j)->type, f->type);
        }
    }
    TEST_ASSERT_NULL(fw_log_format(FW_LOG_KIND_COUNT));
}

static void test_header_then_steps_with_the_steps_numbers(void)
{
    reset_sink(SIZE_MAX);
    fw_log_t log;
    fw_log_config_t c = config(sizeof g_ring, 100000u);
    TEST_ASSERT_EQUAL_INT(0, fw_log_init(&log, &c));
    some_step(0);
    fw_log_step(&log, &g_fw, 25000u, &g_in, &g_out);
    uint8_t types[64];
    const int n = walk(g_sink.data, g_sink.n, types, 64u);
    /* 13 FMT, MSG, 3 PARM, MODE, IMU GPS BARO ARSP ATT HTIN HTO CTRL RCOU */
    TEST_ASSERT_EQUAL_INT(13 + 1 + 3 + 1 + 9, n);
    for (int k = 0; k < 13; ++k) {
        TEST_ASSERT_EQUAL_HEX8(FW_LOG_TYPE_FMT, types[k]);
    }
    TEST_ASSERT_EQUAL_HEX8(fw_log_format(FW_LOG_MSG)->type, types[13]);
    TEST_ASSERT_EQUAL_HEX8(fw_log_format(FW_LOG_PARM)->type, types[14]);
    TEST_ASSERT_EQUAL_HEX8(fw_log_format(FW_LOG_MODE)->type, types[17]);
    /* the first FMT: PARM's, as DFReader reads it */
    const uint8_t *f = &g_sink.data[0];
    TEST_ASSERT_EQUAL_HEX8(0x81u, f[3]);
    TEST_ASSERT_EQUAL_UINT8(31u, f[4]);
    TEST_ASSERT_EQUAL_STRING_LEN("PARM", (const char *)&f[5], 4);
    TEST_ASSERT_EQUAL_STRING("QNf", (const char *)&f[9]);
    TEST_ASSERT_EQUAL_STRING("TimeUS,Name,Value", (const char *)&f[25]);
    /* the PARMs: 1.5 (Q16), 15.0 (cm/s / 100), 200 as binary32, and a
     * 16-character name with no terminator in the record */
    const size_t parm0 = 13u * FW_LOG_FMT_LEN + 75u;
    const uint8_t *p = &g_sink.data[parm0];
    TEST_ASSERT_EQUAL_STRING("KP_AILERON", (const char *)&p[11]);
    TEST_ASSERT_EQUAL_HEX32(0x3FC00000u, le32(&p[27]));
    TEST_ASSERT_EQUAL_INT(0, memcmp(&p[31 + 11], "V_REF_SIXTEEN_CH", 16u));
    TEST_ASSERT_EQUAL_HEX32(0x41700000u, le32(&p[31 + 27]));
    TEST_ASSERT_EQUAL_HEX32(0x43480000u, le32(&p[62 + 27]));
    /* the step's records follow the MODE record (14 bytes) */
    const uint8_t *imu = &p[3u * 31u + 14u];
    TEST_ASSERT_EQUAL_HEX8(0x83u, imu[2]);
    TEST_ASSERT_EQUAL_UINT32(25000u, le32(&imu[3]));
    TEST_ASSERT_EQUAL_INT32(-65536 * 3, (int32_t)le32(&imu[11]));
    TEST_ASSERT_EQUAL_INT32(-65536, (int32_t)le32(&imu[11 + 20]));
    const uint8_t *gps = &imu[35];
    TEST_ASSERT_EQUAL_UINT8(3u, gps[11]);
    TEST_ASSERT_EQUAL_INT32(473977420, (int32_t)le32(&gps[18]));
    const uint8_t *rcou = &g_sink.data[g_sink.n - 27u];
    TEST_ASSERT_EQUAL_HEX8(0x8Bu, rcou[2]);
    TEST_ASSERT_EQUAL_UINT16(1000u, (uint16_t)(rcou[11] | (rcou[12] << 8)));
    TEST_ASSERT_EQUAL_UINT16(2000u, (uint16_t)(rcou[17] | (rcou[18] << 8)));
    TEST_ASSERT_EQUAL_UINT16(0u, (uint16_t)(rcou[21] | (rcou[22] << 8)));
    TEST_ASSERT_EQUAL_UINT32(0u, log.dropped);
    /* a second step with the same mode: no MODE record, 9 records more */
    const size_t before = g_sink.n;
    some_step(1);
    fw_log_step(&log, &g_fw, 50000u, &g_in, &g_out);
    TEST_ASSERT_EQUAL_INT(9, walk(&g_sink.data[before], g_sink.n - before, types, 64u));
    /* an RC-loss failsafe: MODE (reason 1) and EV 3 come first */
    const size_t before2 = g_sink.n;
    some_step(2);
    g_out.modes.mode = 3u;
    g_out.modes.failsafe = 1u;
    fw_log_step(&log, &g_fw, 75000u, &g_in, &g_out);
    TEST_ASSERT_EQUAL_INT(11, walk(&g_sink.data[before2], g_sink.n - before2, types, 64u));
    TEST_ASSERT_EQUAL_HEX8(0x8Cu, types[0]);
    TEST_ASSERT_EQUAL_UINT8(3u, g_sink.data[before2 + 11u]);
    TEST_ASSERT_EQUAL_UINT8(1u, g_sink.data[before2 + 13u]);
    TEST_ASSERT_EQUAL_HEX8(0x8Du, types[1]);
    TEST_ASSERT_EQUAL_UINT8(FW_LOG_EV_RC_FAILSAFE_ON, g_sink.data[before2 + 14u + 11u]);
}

/* Each call gives the sink at most budget bytes; all of it arrives, whole. */
static void test_budget_bounds_every_call(void)
{
    reset_sink(SIZE_MAX);
    fw_log_t log;
    fw_log_config_t c = config(sizeof g_ring, 200u);
    TEST_ASSERT_EQUAL_INT(0, fw_log_init(&log, &c));
    size_t prev = 0u;
    for (int k = 0; k < 400; ++k) {
        some_step(k);
        fw_log_step(&log, &g_fw, (uint64_t)k * 25000u, &g_in, &g_out);
        TEST_ASSERT_TRUE(g_sink.n - prev <= 200u);
        prev = g_sink.n;
    }
    /* 200 bytes per 40 Hz step is less than the 256 bytes a step makes:
     * the ring fills and drops whole records */
    TEST_ASSERT_TRUE(log.dropped > 0u);
    TEST_ASSERT_EQUAL_UINT32(0u, fw_log_flush(&log));
    uint8_t types[1];
    const int n = walk(g_sink.data, g_sink.n, types, 0u);
    TEST_ASSERT_TRUE(n > 0);
    TEST_ASSERT_EQUAL_UINT32(log.records, (uint32_t)n);
    TEST_ASSERT_EQUAL_UINT32(log.written, (uint32_t)g_sink.n);
}

/* A sink that takes nothing (a card pulled): the ring fills, every later
 * record is dropped and counted, the calls return; the card back, the log
 * goes on with whole records only. */
static void test_full_sink_drops_whole_records(void)
{
    reset_sink(SIZE_MAX);
    fw_log_t log;
    fw_log_config_t c = config(1000u, 100000u);
    TEST_ASSERT_EQUAL_INT(0, fw_log_init(&log, &c));
    for (int k = 0; k < 10; ++k) {
        some_step(k);
        fw_log_step(&log, &g_fw, (uint64_t)k * 25000u, &g_in, &g_out);
    }
    TEST_ASSERT_EQUAL_UINT32(0u, log.dropped);
    g_sink.take = 0u; /* pulled */
    for (int k = 10; k < 110; ++k) {
        some_step(k);
        fw_log_step(&log, &g_fw, (uint64_t)k * 25000u, &g_in, &g_out);
        TEST_ASSERT_TRUE(log.used <= 1000u);
    }
    TEST_ASSERT_TRUE(log.dropped > 800u); /* 100 steps x 9 records, minus what fit */
    TEST_ASSERT_TRUE(log.stalls >= 100u);
    g_sink.take = SIZE_MAX; /* back */
    for (int k = 110; k < 120; ++k) {
        some_step(k);
        fw_log_step(&log, &g_fw, (uint64_t)k * 25000u, &g_in, &g_out);
    }
    (void)fw_log_flush(&log);
    uint8_t types[1];
    TEST_ASSERT_EQUAL_INT((int)log.records, walk(g_sink.data, g_sink.n, types, 0u));
}

/* A slow sink (7 bytes a call, records cut anywhere by the sink): the bytes
 * still join into whole records in order. */
static void test_slow_sink_keeps_the_stream_whole(void)
{
    reset_sink(7u);
    fw_log_t log;
    fw_log_config_t c = config(sizeof g_ring, 100000u);
    TEST_ASSERT_EQUAL_INT(0, fw_log_init(&log, &c));
    for (int k = 0; k < 50; ++k) {
        some_step(k);
        fw_log_step(&log, &g_fw, (uint64_t)k * 25000u, &g_in, &g_out);
    }
    TEST_ASSERT_TRUE(log.dropped > 0u);
    g_sink.take = SIZE_MAX;
    (void)fw_log_flush(&log);
    uint8_t types[1];
    TEST_ASSERT_EQUAL_INT((int)log.records, walk(g_sink.data, g_sink.n, types, 0u));
}

static void test_decimation_logs_every_nth_step_and_every_event(void)
{
    reset_sink(SIZE_MAX);
    fw_log_t log;
    fw_log_config_t c = config(sizeof g_ring, 100000u);
    c.decimation = 4u;
    TEST_ASSERT_EQUAL_INT(0, fw_log_init(&log, &c));
    uint8_t types[256];
    for (int k = 0; k < 8; ++k) {
        some_step(k);
        g_out.guard_engaged = (uint8_t)(k == 2); /* on at 2, off at 3 */
        fw_log_step(&log, &g_fw, (uint64_t)k * 25000u, &g_in, &g_out);
    }
    const int n = walk(g_sink.data, g_sink.n, types, 256u);
    /* header 17, MODE, 2 x 9 step records, 2 EV */
    TEST_ASSERT_EQUAL_INT(17 + 1 + 18 + 2, n);
}

static void test_refused_configurations(void)
{
    fw_log_t log;
    fw_log_config_t c = config(sizeof g_ring, 100u);
    TEST_ASSERT_EQUAL_INT(-1, fw_log_init(NULL, &c));
    TEST_ASSERT_EQUAL_INT(-1, fw_log_init(&log, NULL));
    c.ring_size = 2u * FW_LOG_REC_MAX - 1u;
    TEST_ASSERT_EQUAL_INT(-1, fw_log_init(&log, &c));
    c = config(sizeof g_ring, 0u);
    TEST_ASSERT_EQUAL_INT(-1, fw_log_init(&log, &c));
    c = config(sizeof g_ring, 100u);
    c.decimation = 0u;
    TEST_ASSERT_EQUAL_INT(-1, fw_log_init(&log, &c));
    c = config(sizeof g_ring, 100u);
    c.write = NULL;
    TEST_ASSERT_EQUAL_INT(-1, fw_log_init(&log, &c));
    /* a refused log writes nothing and the calls are harmless */
    reset_sink(SIZE_MAX);
    some_step(0);
    fw_log_step(&log, &g_fw, 0u, &g_in, &g_out);
    TEST_ASSERT_EQUAL_UINT32(0u, fw_log_flush(&log));
    TEST_ASSERT_EQUAL_UINT32(0u, (uint32_t)g_sink.n);
    fw_log_step(NULL, &g_fw, 0u, &g_in, &g_out);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_table_matches_its_format_characters);
    RUN_TEST(test_header_then_steps_with_the_steps_numbers);
    RUN_TEST(test_budget_bounds_every_call);
    RUN_TEST(test_full_sink_drops_whole_records);
    RUN_TEST(test_slow_sink_keeps_the_stream_whole);
    RUN_TEST(test_decimation_logs_every_nth_step_and_every_event);
    RUN_TEST(test_refused_configurations);
    return UNITY_END();
}
