/*
 * geo.h - GPS latitude/longitude to the local north/east frame the guidance
 * flies in, in integers.
 *
 * Local tangent plane around an origin (the home point, the first 3-D fix):
 *   north_cm = (lat - lat0) * k_north,  east_cm = wrap(lon - lon0) * k_east
 * with the WGS84 radii of curvature at the origin's latitude (meridian M and
 * prime vertical N, to first order in e^2) in cm per 1e-7 degree:
 *   k_north = M * pi / 180e7 * 100,  k_east = N * cos(lat0) * pi / 180e7 * 100.
 * cos is a 1-degree table with linear interpolation (0.6 LSB of Q14). The
 * plane's error grows with the square of the distance: about 8 cm at 1 km and
 * 8 m at 10 km from home, below a GPS's own error within the range of a
 * model aeroplane. Results saturate at +/-INT32_MAX cm (beyond +/-21 000 km).
 */
#ifndef HELICAL_GEO_H
#define HELICAL_GEO_H

#include <stdint.h>

#include "helical/math/q14.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct {
    int32_t lat0_e7, lon0_e7;
    int32_t k_north_q16; /* cm per 1e-7 deg, Q16 */
    int32_t k_east_q16;
    uint8_t set;
} ht_geo_origin_t;

/* cos(lat) in Q14 for a latitude in 1e-7 deg (any int32: clamped to +/-90 deg). */
q14_t ht_geo_cos_lat_q14(int32_t lat_e7);

/* Set the origin. Returns 0, or 1 for a latitude beyond +/-90 deg or a
 * longitude beyond +/-180 deg (origin left unset). */
int ht_geo_origin_set(ht_geo_origin_t *o, int32_t lat_e7, int32_t lon_e7);

/* The local position of (lat, lon), cm. An unset origin gives 0, 0. */
void ht_geo_to_local(const ht_geo_origin_t *o, int32_t lat_e7, int32_t lon_e7, int32_t *north_cm,
                     int32_t *east_cm);

#ifdef __cplusplus
}
#endif

#endif /* HELICAL_GEO_H */
