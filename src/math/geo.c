/*
 * geo.c - latitude/longitude to local north/east (see geo.h). Integer only.
 */
#include "helical/math/geo.h"

#include <stddef.h>

#define E7_PER_DEG ((int32_t)10000000)
#define LAT_MAX_E7 ((int32_t)900000000)
#define LON_MAX_E7 ((int32_t)1800000000)

/* cos(d deg) * 2^14 rounded, d = 0..91 (the last entry for interpolation). */
static const int16_t cos_deg_q14[92] = {
    16384, 16382, 16374, 16362, 16344, 16322, 16294, 16262, 16225, 16182, 16135, 16083,
    16026, 15964, 15897, 15826, 15749, 15668, 15582, 15491, 15396, 15296, 15191, 15082,
    14968, 14849, 14726, 14598, 14466, 14330, 14189, 14044, 13894, 13741, 13583, 13421,
    13255, 13085, 12911, 12733, 12551, 12365, 12176, 11982, 11786, 11585, 11381, 11174,
    10963, 10749, 10531, 10311, 10087, 9860,  9630,  9397,  9162,  8923,  8682,  8438,
    8192,  7943,  7692,  7438,  7182,  6924,  6664,  6402,  6138,  5872,  5604,  5334,
    5063,  4790,  4516,  4240,  3964,  3686,  3406,  3126,  2845,  2563,  2280,  1997,
    1713,  1428,  1143,  857,   572,   286,   0,     -286};

/* WGS84: a (1 - e^2) and a in cm per 1e-7 deg, Q16; 1.5 e^2 and 0.5 e^2 in Q30. */
#define K_NORTH0_Q16 ((int32_t)72466)
#define K_EAST0_Q16  ((int32_t)72954)
#define E2_3_2_Q30   ((int32_t)10782054)
#define E2_1_2_Q30   ((int32_t)3594018)
#define ONE_Q30      ((int32_t)1073741824)

q14_t ht_geo_cos_lat_q14(int32_t lat_e7)
{
    /* |lat| clamped to 90 deg before the sign is dropped: no overflow */
    const int32_t c =
        (lat_e7 > LAT_MAX_E7) ? LAT_MAX_E7 : ((lat_e7 < -LAT_MAX_E7) ? -LAT_MAX_E7 : lat_e7);
    const int32_t a = (c < 0) ? -c : c; /* [0, 90 deg] */
    const int32_t deg = a / E7_PER_DEG;
    /* the fraction of a degree in 1e-5 deg: the table's slope (at most 286
     * LSB per degree) times it stays below 2^25, and 1e-5 deg moves cos by
     * less than 0.003 LSB */
    const int32_t frac = (a - deg * E7_PER_DEG) / 100; /* [0, 100000) */
    const int32_t c0 = cos_deg_q14[deg];
    const int32_t c1 = cos_deg_q14[deg + 1];
    const int32_t num = (c1 - c0) * frac;            /* <= 0 */
    const int32_t step = -((-num + 50000) / 100000); /* rounded, ties away from zero */
    return (q14_t)(c0 + step);
}

int ht_geo_origin_set(ht_geo_origin_t *o, int32_t lat_e7, int32_t lon_e7)
{
    if (o == NULL) {
        return 1;
    }
    if (lat_e7 < -LAT_MAX_E7 || lat_e7 > LAT_MAX_E7 || lon_e7 < -LON_MAX_E7 ||
        lon_e7 > LON_MAX_E7) {
        o->set = 0u;
        return 1;
    }
    const int32_t c = ht_geo_cos_lat_q14(lat_e7);       /* Q14 */
    const int32_t one_q28 = (int32_t)268435456;         /* 2^28 */
    const int32_t s2_q28 = one_q28 - (c * c);           /* sin^2, Q28 */
    const int32_t s2_q14 = q_rshift_round(s2_q28, 14u); /* Q14 */
    /* M = a (1 - e^2) (1 + 1.5 e^2 sin^2), N = a (1 + 0.5 e^2 sin^2) */
    const int32_t m_corr_q30 = ONE_Q30 + q_mul32(E2_3_2_Q30, s2_q14, 14u);
    const int32_t n_corr_q30 = ONE_Q30 + q_mul32(E2_1_2_Q30, s2_q14, 14u);
    o->k_north_q16 = q_mul32(K_NORTH0_Q16, m_corr_q30, 30u);
    o->k_east_q16 = q_mul32(q_mul32(K_EAST0_Q16, n_corr_q30, 30u), c, 14u);
    o->lat0_e7 = lat_e7;
    o->lon0_e7 = lon_e7;
    o->set = 1u;
    return 0;
}

static int32_t clamp_e7(int32_t v, int32_t lim)
{
    return (v > lim) ? lim : ((v < -lim) ? -lim : v);
}

/* a - b for angles in 1e-7 deg within +/-180 deg, the short way round. The
 * plain difference may reach +/-360 deg (beyond int32), so the wrapped cases
 * are formed from two terms that each fit and whose sum is the result. */
static int32_t lon_diff_e7(int32_t a, int32_t b)
{
    const int32_t half = a / 2 - b / 2; /* the difference / 2, +/-1 */
    if (half > LON_MAX_E7 / 2) {        /* a - b > 180 deg: a - b - 360 deg */
        return (a - LON_MAX_E7) + (-LON_MAX_E7 - b);
    }
    if (half < -LON_MAX_E7 / 2) { /* a - b < -180 deg: a - b + 360 deg */
        return (a + LON_MAX_E7) + (LON_MAX_E7 - b);
    }
    return a - b;
}

void ht_geo_to_local(const ht_geo_origin_t *o, int32_t lat_e7, int32_t lon_e7, int32_t *north_cm,
                     int32_t *east_cm)
{
    int32_t n = 0;
    int32_t e = 0;
    if (o != NULL && o->set != 0u) {
        const int32_t dlat = clamp_e7(lat_e7, LAT_MAX_E7) - o->lat0_e7; /* |d| <= 180 deg */
        const int32_t dlon = lon_diff_e7(clamp_e7(lon_e7, LON_MAX_E7), o->lon0_e7);
        n = q_mul32(dlat, o->k_north_q16, 16u);
        e = q_mul32(dlon, o->k_east_q16, 16u);
    }
    if (north_cm != NULL) {
        *north_cm = n;
    }
    if (east_cm != NULL) {
        *east_cm = e;
    }
}
