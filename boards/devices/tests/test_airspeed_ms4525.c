/*
 * test_airspeed_ms4525.c - the MS4525DO driver against its datasheet's
 * transfer function and the simulated sensor (sim_ms4525.c).
 *
 * Worked values (MS4525DO datasheet: output type A, 10 %..90 % of 16383
 * counts over -1..+1 psi for the 001PD; 1 psi = 6894.757 Pa):
 *   P = (2 counts - 16383) * 6894.757 Pa / 13106.4 = (2 counts - 16383) * 526.0603 mPa
 *   counts 14745 (90 %, 0.9 * 16383 = 14744.7): 13107 * 526.0603 = +6 895 073 mPa
 *   counts  1638 (10 %):                                           -6 895 073 mPa
 *   counts  8192 / 8191 (mid-scale 8191.5):                         +526 / -526 mPa
 *   counts 0 / 16383 (rails): -/+16383 * 526.0603 =               -/+8 618 447 mPa
 * Indicated airspeed v = sqrt(2 q / 1.225 kg/m^3):
 *   q = 61.25 Pa -> 10.00 m/s; 245 Pa -> 20.00 m/s; 1531.25 Pa -> 50.00 m/s;
 *   6894.757 Pa (1 psi) -> 106.098 m/s -> 10610 cm/s
 * Temperature T = counts * 200 / 2047 - 50: 25 degC -> counts round(767.6) =
 *   768 -> 25.0366 degC -> 2504 (0.01 degC)
 * Through the sim, each of the reading and the zero is rounded to a count
 * (1.052 Pa): dp within +/-1.05 Pa, so v within 1.05 Pa / (rho v):
 *   +/-8.6 cm/s at 10 m/s, 4.3 at 20 m/s, 1.7 at 50 m/s (+0.5 for the root's rounding).
 * Back-off after NACKs: skip 1, 2, 4, 8, 16, 32, 64, 64 calls: probes at calls
 *   1, 3, 6, 11, 20, 37, 70, 135, 200 -> 9 transactions in 200 calls.
 */
#include "unity.h"

#include "airspeed_ms4525.h"
#include "sim_ms4525.h"

#include <string.h>

static sim_ms4525_t sim;
static ms4525_t pitot;
static i2c_bus_t bus;

void setUp(void)
{
    sim_ms4525_init(&sim, MS4525_ADDR_I);
    bus = sim_ms4525_bus(&sim);
    memset(&pitot, 0, sizeof pitot);
    TEST_ASSERT_EQUAL(MS4525_OK, ms4525_init(&pitot, &bus, MS4525_ADDR_I));
}

void tearDown(void) {}

static void zero_at_rest(void)
{
    sim_ms4525_set(&sim, 0.0, 20.0);
    for (unsigned i = 0; i < MS4525_ZERO_SAMPLES; ++i) {
        TEST_ASSERT_EQUAL(MS4525_NO_DATA, ms4525_update(&pitot));
    }
    TEST_ASSERT_EQUAL_UINT8(1u, pitot.zeroed);
}

static void test_transfer_function(void)
{
    TEST_ASSERT_EQUAL_INT32(6895073, ms4525_counts_to_mpa(14745u));
    TEST_ASSERT_EQUAL_INT32(-6895073, ms4525_counts_to_mpa(1638u));
    TEST_ASSERT_EQUAL_INT32(526, ms4525_counts_to_mpa(8192u));
    TEST_ASSERT_EQUAL_INT32(-526, ms4525_counts_to_mpa(8191u));
    TEST_ASSERT_EQUAL_INT32(-8618447, ms4525_counts_to_mpa(0u));
    TEST_ASSERT_EQUAL_INT32(8618447, ms4525_counts_to_mpa(16383u));
    /* the status bits are not pressure */
    TEST_ASSERT_EQUAL_INT32(8618447, ms4525_counts_to_mpa(0xFFFFu));
}

static void test_airspeed_formula(void)
{
    TEST_ASSERT_EQUAL_INT16(1000, ms4525_airspeed_cm_s(61250));
    TEST_ASSERT_EQUAL_INT16(2000, ms4525_airspeed_cm_s(245000));
    TEST_ASSERT_EQUAL_INT16(5000, ms4525_airspeed_cm_s(1531250));
    TEST_ASSERT_EQUAL_INT16(10610, ms4525_airspeed_cm_s(6894757));
    TEST_ASSERT_EQUAL_INT16(0, ms4525_airspeed_cm_s(0));
    TEST_ASSERT_EQUAL_INT16(0, ms4525_airspeed_cm_s(-245000));
    TEST_ASSERT_EQUAL_INT16(INT16_MAX, ms4525_airspeed_cm_s(INT32_MAX));
}

static void test_zero_removes_the_offset(void)
{
    sim.zero_error_pa = 20.0; /* at rest the part says +20 Pa (5.7 m/s) */
    zero_at_rest();
    TEST_ASSERT_EQUAL(MS4525_OK, ms4525_update(&pitot));
    TEST_ASSERT_EQUAL_INT32(0, pitot.dp_mpa);
    TEST_ASSERT_EQUAL_INT16(0, pitot.airspeed_cm_s);
    sim_ms4525_set(&sim, 61.25, 20.0);
    TEST_ASSERT_EQUAL(MS4525_OK, ms4525_update(&pitot));
    TEST_ASSERT_INT16_WITHIN(9, 1000, pitot.airspeed_cm_s);
    sim_ms4525_set(&sim, 245.0, 20.0);
    TEST_ASSERT_EQUAL(MS4525_OK, ms4525_update(&pitot));
    TEST_ASSERT_INT16_WITHIN(5, 2000, pitot.airspeed_cm_s);
    TEST_ASSERT_INT32_WITHIN(1060, 245000, pitot.dp_mpa);
    sim_ms4525_set(&sim, 1531.25, 20.0);
    TEST_ASSERT_EQUAL(MS4525_OK, ms4525_update(&pitot));
    TEST_ASSERT_INT16_WITHIN(3, 5000, pitot.airspeed_cm_s);
    /* a negative pressure (ports swapped, a gust from behind) reads 0 */
    sim_ms4525_set(&sim, -1000.0, 20.0);
    TEST_ASSERT_EQUAL(MS4525_OK, ms4525_update(&pitot));
    TEST_ASSERT_INT32_WITHIN(1060, -1000000, pitot.dp_mpa);
    TEST_ASSERT_EQUAL_INT16(0, pitot.airspeed_cm_s);
}

static void test_temperature(void)
{
    sim_ms4525_set(&sim, 0.0, 25.0);
    TEST_ASSERT_EQUAL(MS4525_NO_DATA, ms4525_update(&pitot)); /* zeroing, but T is read */
    TEST_ASSERT_EQUAL_INT16(2504, pitot.temp_cdeg);
    sim_ms4525_set(&sim, 0.0, -40.0); /* counts round(102.35) = 102 -> -40.034 */
    (void)ms4525_update(&pitot);
    TEST_ASSERT_EQUAL_INT16(-4003, pitot.temp_cdeg);
}

static void test_not_fresh_while_zeroing(void)
{
    sim_ms4525_set(&sim, 245.0, 20.0); /* (flying would be refused: see below) */
    sim_ms4525_set(&sim, 0.0, 20.0);
    for (unsigned i = 0; i + 1u < MS4525_ZERO_SAMPLES; ++i) {
        TEST_ASSERT_EQUAL(MS4525_NO_DATA, ms4525_update(&pitot));
        TEST_ASSERT_EQUAL_UINT8(0u, pitot.zeroed);
    }
    TEST_ASSERT_EQUAL(MS4525_NO_DATA, ms4525_update(&pitot));
    TEST_ASSERT_EQUAL_UINT8(1u, pitot.zeroed);
    TEST_ASSERT_EQUAL(MS4525_OK, ms4525_update(&pitot));
    ms4525_rezero(&pitot);
    TEST_ASSERT_EQUAL(MS4525_NO_DATA, ms4525_update(&pitot));
    ms4525_rezero(NULL);
}

static void test_implausible_zero_is_refused(void)
{
    sim.zero_error_pa = 1000.0; /* 950 counts off mid-scale: more than 655 */
    sim_ms4525_set(&sim, 0.0, 20.0);
    for (unsigned i = 0; i + 1u < MS4525_ZERO_SAMPLES; ++i) {
        TEST_ASSERT_EQUAL(MS4525_NO_DATA, ms4525_update(&pitot));
    }
    TEST_ASSERT_EQUAL(MS4525_ERR_ZERO, ms4525_update(&pitot));
    TEST_ASSERT_EQUAL_UINT8(0u, pitot.zeroed);
    TEST_ASSERT_EQUAL_UINT16(1u, pitot.zero_errors);
    /* 600 Pa (570 counts) is accepted */
    sim.zero_error_pa = 600.0;
    zero_at_rest();
    TEST_ASSERT_EQUAL(MS4525_OK, ms4525_update(&pitot));
    TEST_ASSERT_EQUAL_INT16(0, pitot.airspeed_cm_s);
}

static void test_stale_and_fault(void)
{
    zero_at_rest();
    sim.auto_update = 0u;
    sim_ms4525_set(&sim, 245.0, 20.0);
    TEST_ASSERT_EQUAL(MS4525_OK, ms4525_update(&pitot));
    const int16_t v = pitot.airspeed_cm_s;
    TEST_ASSERT_EQUAL(MS4525_NO_DATA, ms4525_update(&pitot)); /* already fetched */
    TEST_ASSERT_EQUAL_UINT16(1u, pitot.stale);
    TEST_ASSERT_EQUAL_INT16(v, pitot.airspeed_cm_s);
    sim.fault = 1u;
    sim_ms4525_set(&sim, 1531.25, 20.0);
    TEST_ASSERT_EQUAL(MS4525_ERR_FAULT, ms4525_update(&pitot));
    TEST_ASSERT_EQUAL_UINT16(1u, pitot.faults);
    TEST_ASSERT_EQUAL_INT16(v, pitot.airspeed_cm_s); /* not taken */
    sim.fault = 0u;
    sim_ms4525_set(&sim, 1531.25, 20.0);
    TEST_ASSERT_EQUAL(MS4525_OK, ms4525_update(&pitot));
    TEST_ASSERT_INT16_WITHIN(3, 5000, pitot.airspeed_cm_s);
}

static void test_absent_backs_off(void)
{
    sim.absent = 1u;
    unsigned probes = 0u;
    for (unsigned call = 1u; call <= 200u; ++call) {
        const unsigned before = sim.transactions;
        TEST_ASSERT_EQUAL(MS4525_ABSENT, ms4525_update(&pitot));
        if (sim.transactions != before) {
            probes++;
        }
        if (call == 135u || call == 200u) {
            TEST_ASSERT_EQUAL_UINT(before + 1u, sim.transactions); /* a probe here */
        }
    }
    TEST_ASSERT_EQUAL_UINT(9u, probes);
    TEST_ASSERT_EQUAL_UINT16(9u, pitot.absent);
    TEST_ASSERT_EQUAL_UINT8(0u, pitot.present);
    /* plugged in: found at the next probe (call 265), then zeroing starts */
    sim.absent = 0u;
    unsigned call = 201u;
    while (ms4525_update(&pitot) == MS4525_ABSENT) {
        call++;
        TEST_ASSERT_TRUE(call <= 265u);
    }
    TEST_ASSERT_EQUAL_UINT(265u, call);
    TEST_ASSERT_EQUAL_UINT8(1u, pitot.present);
    TEST_ASSERT_EQUAL_UINT8(0u, pitot.backoff_len);
}

static void test_address_variants_and_bus_errors(void)
{
    sim_ms4525_init(&sim, MS4525_ADDR_J); /* a "J" part at 0x36 */
    TEST_ASSERT_EQUAL(MS4525_ABSENT, ms4525_update(&pitot));
    TEST_ASSERT_EQUAL(MS4525_OK, ms4525_init(&pitot, &bus, MS4525_ADDR_J));
    TEST_ASSERT_EQUAL(MS4525_NO_DATA, ms4525_update(&pitot));
    TEST_ASSERT_EQUAL_UINT8(1u, pitot.present);
    /* a bus error is counted, not backed off: the next call reads again */
    sim.fail_next = I2C_BUS_ERR_TIMEOUT;
    TEST_ASSERT_EQUAL(MS4525_ERR_BUS, ms4525_update(&pitot));
    TEST_ASSERT_EQUAL_UINT16(1u, pitot.bus_errors);
    const unsigned before = sim.transactions;
    TEST_ASSERT_EQUAL(MS4525_NO_DATA, ms4525_update(&pitot));
    TEST_ASSERT_EQUAL_UINT(before + 1u, sim.transactions);
    TEST_ASSERT_EQUAL(MS4525_ERR_NULL, ms4525_update(NULL));
    TEST_ASSERT_EQUAL(MS4525_ERR_NULL, ms4525_init(NULL, &bus, MS4525_ADDR_I));
    TEST_ASSERT_EQUAL(MS4525_ERR_NULL, ms4525_init(&pitot, NULL, MS4525_ADDR_I));
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_transfer_function);
    RUN_TEST(test_airspeed_formula);
    RUN_TEST(test_zero_removes_the_offset);
    RUN_TEST(test_temperature);
    RUN_TEST(test_not_fresh_while_zeroing);
    RUN_TEST(test_implausible_zero_is_refused);
    RUN_TEST(test_stale_and_fault);
    RUN_TEST(test_absent_backs_off);
    RUN_TEST(test_address_variants_and_bus_errors);
    return UNITY_END();
}
