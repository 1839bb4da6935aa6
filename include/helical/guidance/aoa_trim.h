/*
 * aoa_trim.h - the angle-of-attack and elevator-trim model ("Helical Turns",
 * Part 3): the wing needs more angle of attack, and the elevator more trim,
 * the more it is loaded. Both are modelled as linear functions of the
 * relative wing loading
 *
 *     w = |load| * (v_ref / V)^2,     load = Z + X * (X / Z)
 *
 * where [X, Y, Z] is the DCM bottom row (the tilt) and V the airspeed. The
 * load is the load factor of a coordinated level turn at that bank
 * (1 / cos(bank)), computed from the tilt and NOT from the accelerometers:
 * measured load would feed back (more AoA -> more load -> more AoA) into a
 * stall. Its sign is the sign of Z: Z < 0 (the wing loaded towards the body
 * +Z side: inverted) selects the inverted coefficients.
 *
 *     aoa  = aoa0[o] + aoa_slope[o] * w     (body frame, + = nose towards body -Z)
 *     trim = trim0[o] + trim_slope[o] * w   (elevator command, + = nose up)
 *
 * o = normal (Z >= 0) or inverted (Z < 0). The coefficients are body-frame
 * quantities, so an aircraft that flies inverted at a negative body AoA and
 * with down elevator has negative inverted coefficients.
 *
 * How they are used (modes.c does it): the AoA offset adjusts the target
 * pitch ratio, projected by Z: pitch += aoa_rad * Z (small-angle: the nose
 * must sit aoa above the flight path, and only the Z share of a body-frame
 * angle shows as earth-frame pitch; upright Z > 0 and inverted Z < 0 with a
 * negative AoA both raise the nose). The trim is added to the law's elevator.
 *
 * Below v_enable the model is off: offset 0, trim 0 (also when `enabled` is 0).
 *
 * Integer only, no state; the parameters are converted once by
 * ht_aoa_init().
 */
#ifndef HELICAL_AOA_TRIM_H
#define HELICAL_AOA_TRIM_H

#include <stdint.h>

#include "helical/params.h"
#include "helical/guidance/mode_params.h"
#include "helical/math/q14.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The parameters (ht_aoa_params_t) and their ids: mode_params.h. */

/* The converted model. Read-only after ht_aoa_init. */
typedef struct {
    uint8_t enabled;
    int16_t v_ref_cm_s, v_enable_cm_s;
    q16_t load_max;
    q16_t aoa0_rad[2], aoa1_rad[2]; /* [0] normal, [1] inverted, rad (Q16) */
    q14_t trim0[2], trim1[2];
    uint8_t ready;
} ht_aoa_t;

/* 0 = OK, 1 = NULL, 2 = a parameter out of range (named in *bad_field). */
int ht_aoa_init(ht_aoa_t *m, const ht_aoa_params_t *p, ht_aoa_param_id_t *bad_field);

typedef struct {
    q16_t load;          /* signed load from the tilt, |load| <= load_max (Q16) */
    q16_t loading;       /* w = |load| (v_ref / V)^2 (Q16) */
    q16_t aoa_rad;       /* body-frame AoA of the model (Q16 rad) */
    q16_t pitch_offset;  /* aoa_rad * Z: add to the target pitch ratio (Q16) */
    q14_t elevator_trim; /* add to the elevator, [-1, 1] */
    uint8_t active;      /* 1 when enabled and V >= v_enable */
    uint8_t inverted;    /* 1 when the inverted coefficients were used (Z < 0) */
} ht_aoa_output_t;

/*
 * The model for one step. x, z: the tilt (DCM bottom row) as given; Z = 0 is
 * read as upright with |load| = load_max. Every input is accepted; NULL or an
 * uninitialised model gives an all-zero output.
 */
void ht_aoa_step(const ht_aoa_t *m, q14_t x, q14_t z, int16_t airspeed_cm_s, ht_aoa_output_t *out);

#ifdef __cplusplus
}
#endif

#endif /* HELICAL_AOA_TRIM_H */
