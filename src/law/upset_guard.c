/*
 * upset_guard.c - nose-low inverted upset recovery in the outer loop (see
 * upset_guard.h). Integer only: no float, no libm, no allocation, no
 * recursion, no global mutable state.
 */
#include "helical/law/upset_guard.h"

#include <stdbool.h>
#include <stddef.h>

ht_upset_guard_status_t ht_upset_guard_check(const ht_upset_guard_params_t *p)
{
    if (p == NULL) {
        return HT_UG_ERR_NULL;
    }
    if (p->engage_sin > Q14_ONE || p->release_sin <= 0 || p->release_sin >= p->engage_sin ||
        p->release_cos_bank <= 0 || p->release_cos_bank > Q14_ONE) {
        return HT_UG_ERR_PARAM;
    }
    return HT_UG_OK;
}

void ht_upset_guard_reset(ht_upset_guard_state_t *s)
{
    if (s != NULL) {
        s->engaged = 0u;
    }
}

q16_t ht_upset_guard_step(const ht_upset_guard_params_t *p, ht_upset_guard_state_t *s, q14_t x,
                          q14_t y, q14_t z, uint8_t inverted_cmd, q16_t pitch_q16)
{
    if (s == NULL) {
        return pitch_q16;
    }
    if (ht_upset_guard_check(p) != HT_UG_OK || inverted_cmd != 0u) {
        s->engaged = 0u;
        return pitch_q16;
    }
    const int32_t xi = x;
    const int32_t yi = y;
    const int32_t zi = z;
    /* |X|, |Z| <= 2^15: each square <= 2^30, the sum < 2^32 */
    const int32_t x_abs = (xi < 0) ? -xi : xi;
    const int32_t z_abs = (zi < 0) ? -zi : zi;
    const uint32_t ux = (uint32_t)x_abs;
    const uint32_t uz = (uint32_t)z_abs;
    const uint32_t h2 = (ux * ux) + (uz * uz);
    const int32_t h = (int32_t)q_isqrt32(h2); /* sqrt(X^2 + Z^2), Q14, <= 46341 */
    if (s->engaged == 0u) {
        if (zi < 0 && yi > p->engage_sin) {
            s->engaged = 1u;
        }
    } else {
        /* z * 2^14 <= 2^29 and cos * h <= 2^14 * 46341 < 2^31 */
        const bool upright = (zi > 0) && ((zi * 16384) >= (p->release_cos_bank * h));
        if (upright || yi < p->release_sin) {
            s->engaged = 0u;
        }
    }
    if (s->engaged == 0u) {
        return pitch_q16;
    }
    /* the measured pitch ratio -Y / h, clamped to +-HT_UG_RATIO_MAX */
    const int32_t y_abs = (yi < 0) ? -yi : yi;
    if (y_abs >= 16 * h) {
        return (yi > 0) ? -HT_UG_RATIO_MAX : HT_UG_RATIO_MAX;
    }
    /* |Y| < 16 h: |Y| * 2^14 <= 2^29, the quotient < 2^18 (Q14), * 4 = Q16 */
    return (-yi * 16384 / h) * 4;
}
