/*
 * upset_guard.h - nose-low inverted upset recovery in the outer loop: the
 * classic order "unload, roll upright, then pull".
 *
 * Why: commanded to upright flight from inverted with the nose steeply down,
 * the law saturates its roll error (ROLL_BEYOND_90) and, in the earth-frame
 * pitch method, pushes the nose toward the (inverted) horizon at the same
 * time; with the fuselage near vertical the two cancel and the aircraft stays
 * in a rolling dive (fault campaign, sil/README.md). The law is a fixed
 * contract (control-law.md), so the guard acts on its pitch-ratio input:
 *
 *   engage  when the command is upright, the aircraft is inverted (Z < 0) and
 *           the nose is down beyond engage_sin (Y > engage_sin; nose down by
 *           theta gives Y = +sin(theta));
 *   while engaged, replace the pitch ratio by the MEASURED one,
 *           -Y / sqrt(X^2 + Z^2) (clamped to +-HT_UG_RATIO_MAX): the law's
 *           pitch error is then zero (unload) and its roll error rolls the
 *           aircraft upright about the fuselage;
 *   release when the aircraft is upright within the release bank
 *           (Z > 0 and Z >= release_cos_bank * sqrt(X^2 + Z^2)), or the nose
 *           has come up to release_sin (Y < release_sin: the law alone
 *           handles a shallow inverted attitude), or the command turns
 *           inverted. After the release the hold's pitch ratio pulls the
 *           aircraft out of the (now upright) dive with positive load factor.
 *
 * The hysteresis is release_sin < engage_sin. Integer only; the caller owns
 * the state; no global mutable state.
 */
#ifndef HELICAL_UPSET_GUARD_H
#define HELICAL_UPSET_GUARD_H

#include <stdint.h>

#include "helical/math/q14.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Limit on |the measured pitch ratio| given to the law (Q16): 16 (86.4 deg). */
#define HT_UG_RATIO_MAX (16L * 65536L)

typedef struct {
    q14_t engage_sin;       /* engage: nose down beyond asin(this), (release_sin, 1] */
    q14_t release_sin;      /* release: nose down less than asin(this), (0, engage_sin) */
    q14_t release_cos_bank; /* release: upright within acos(this) of bank, (0, 1] */
} ht_upset_guard_params_t;

/* Engage beyond 60 deg nose down, release below 30 deg nose down or within
 * 45 deg of wings level upright. */
#define HT_UPSET_GUARD_PARAMS_DEFAULT                                                              \
    {                                                                                              \
        14189, 8192, 11585                                                                         \
    }

typedef enum {
    HT_UG_OK = 0,
    HT_UG_ERR_NULL = 1, /* a NULL pointer */
    HT_UG_ERR_PARAM = 2 /* a parameter out of range */
} ht_upset_guard_status_t;

typedef struct {
    uint8_t engaged; /* 1 while the guard replaces the pitch ratio */
} ht_upset_guard_state_t;

/* Check the parameters; HT_UG_OK when every field is in range. */
ht_upset_guard_status_t ht_upset_guard_check(const ht_upset_guard_params_t *p);

/* Disengage. */
void ht_upset_guard_reset(ht_upset_guard_state_t *s);

/*
 * One step: the pitch ratio (Q16) to give the law: pitch_q16 unchanged unless
 * the guard is engaged (above). x, y, z: the DCM bottom row (Q14) the law is
 * given; inverted_cmd: the law's inverted input (nonzero = inverted).
 * NULL pointers or out-of-range parameters give pitch_q16 and disengage (call
 * ht_upset_guard_check once at start-up).
 */
q16_t ht_upset_guard_step(const ht_upset_guard_params_t *p, ht_upset_guard_state_t *s, q14_t x,
                          q14_t y, q14_t z, uint8_t inverted_cmd, q16_t pitch_q16);

#ifdef __cplusplus
}
#endif

#endif /* HELICAL_UPSET_GUARD_H */
