/*
 * air_data.c - true airspeed from indicated airspeed, pressure altitude and
 * temperature (include/helical/estimator/air_data.h).
 */
#include "helical/estimator/air_data.h"

#include "helical/math/q14.h"

#define AIR_NODES   85u
#define AIR_STEP_CM ((int32_t)25000) /* 250 m */

/* TAS / IAS of the ISA at -1000 + 250 k m, Q14: scripts/gen_tas_table.py */
static const uint16_t tas_per_ias_q14[AIR_NODES] = {
    15624u, 15809u, 15998u, 16189u, 16384u, 16582u, 16784u, 16990u, 17199u, 17412u, 17629u,
    17850u, 18075u, 18304u, 18538u, 18776u, 19019u, 19266u, 19518u, 19774u, 20036u, 20303u,
    20575u, 20853u, 21136u, 21424u, 21719u, 22020u, 22326u, 22639u, 22959u, 23285u, 23618u,
    23958u, 24306u, 24660u, 25023u, 25393u, 25772u, 26159u, 26554u, 26958u, 27372u, 27795u,
    28227u, 28670u, 29122u, 29586u, 30060u, 30658u, 31269u, 31891u, 32526u, 33173u, 33834u,
    34507u, 35194u, 35895u, 36609u, 37338u, 38081u, 38839u, 39612u, 40401u, 41205u, 42026u,
    42862u, 43715u, 44586u, 45473u, 46378u, 47302u, 48243u, 49204u, 50183u, 51182u, 52201u,
    53240u, 54300u, 55381u, 56483u, 57608u, 58754u, 59924u, 61117u,
};

/* The ISA temperature at a pressure altitude (already clamped), centi-kelvin:
 * 288.15 K - 6.5 K/km up to the tropopause at 11 km, 216.65 K above. */
static int32_t isa_temp_ck(int32_t alt_cm)
{
    if (alt_cm >= (int32_t)1100000) {
        return 21665;
    }
    return 28815 - ((65 * alt_cm) / 10000); /* |65 alt| <= 1.3e8: no overflow */
}

uint32_t ht_tas_per_ias_q14(int32_t pressure_alt_cm, int16_t temp_cdeg, uint8_t temp_valid)
{
    const int32_t h = q_clamp32(pressure_alt_cm, HT_AIR_ALT_MIN_CM, HT_AIR_ALT_MAX_CM);
    const int32_t from_base = h - HT_AIR_ALT_MIN_CM; /* [0, 2.1e6] */
    const int32_t node = from_base / AIR_STEP_CM;
    uint32_t k = (uint32_t)node;
    if (k >= (AIR_NODES - 1u)) {
        k = AIR_NODES - 2u; /* the top node: interpolate in the last interval */
    }
    const int32_t frac = from_base - ((int32_t)k * AIR_STEP_CM); /* [0, 25000] */
    const int32_t lo = (int32_t)tas_per_ias_q14[k];
    const int32_t span = (int32_t)tas_per_ias_q14[k + 1u] - lo; /* < 1200 */
    /* span * frac < 3e7: int32 */
    const int32_t f = lo + (((span * frac) + (AIR_STEP_CM / 2)) / AIR_STEP_CM);
    if ((temp_valid == 0u) || (temp_cdeg < HT_AIR_TEMP_MIN_CDEG) ||
        (temp_cdeg > HT_AIR_TEMP_MAX_CDEG)) {
        return (uint32_t)f;
    }
    /* sigma scales with 1 / T: TAS / IAS with sqrt(T / T_isa) */
    const int32_t t_ck_s = (int32_t)temp_cdeg + 27315; /* [19315, 35815] */
    const uint32_t t_ck = (uint32_t)t_ck_s;
    const uint32_t isa_ck = (uint32_t)isa_temp_ck(h);               /* [21665, 29465] */
    const uint32_t r_q16 = ((t_ck << 16) + (isa_ck / 2u)) / isa_ck; /* < 2.35e9 + : uint32 */
    const uint32_t s_q14 = q_isqrt32_round(r_q16 << 12);            /* sqrt of Q28: Q14 */
    return (((uint32_t)f * s_q14) + 8192u) >> 14;                   /* 61117 x 22300 < 2^31 */
}

int16_t ht_true_airspeed_cm_s(int16_t ias_cm_s, int32_t pressure_alt_cm, int16_t temp_cdeg,
                              uint8_t temp_valid)
{
    if (ias_cm_s <= 0) {
        return 0;
    }
    const uint32_t f = ht_tas_per_ias_q14(pressure_alt_cm, temp_cdeg, temp_valid);
    /* 32767 x 78800 < 2^32 */
    const uint32_t tas = (((uint32_t)ias_cm_s * f) + 8192u) >> 14;
    if (tas > (uint32_t)INT16_MAX) {
        return (int16_t)INT16_MAX;
    }
    return (int16_t)tas;
}
