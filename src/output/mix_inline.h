/*
 * mix_inline.h - the mixer's rules as static inline functions, shared by
 * os_mix (mixer.c) and os_compute (output_stage.c). os_compute clamps the
 * command once per control step and then picks each channel's value without
 * a call; os_mix does both steps for one function. One place for each rule,
 * so the two cannot drift apart.
 * int32_t throughout: correct on 16-bit-int targets (XC16) as well.
 */
#ifndef HELICAL_MIX_INLINE_H
#define HELICAL_MIX_INLINE_H

#include <stdint.h>

#include "helical/math/q14.h"
#include "helical/output/os_command.h"

/* The command with each input clamped to its range. */
typedef struct {
    int32_t ail, ele, rud, thr;
} mix_inputs_t;

/* A surface command or a sum of two, saturated to [-1, 1]: the mix saturates,
 * it does not rescale. x is within [-2, 2]. In flight x is nearly always in
 * range already: one unsigned compare decides that for both bounds. */
static inline int32_t mix_surface(int32_t x)
{
    int32_t r = x;
    if (((uint32_t)x + (uint32_t)Q14_ONE) > (2u * (uint32_t)Q14_ONE)) {
        r = (x < 0) ? -(int32_t)Q14_ONE : (int32_t)Q14_ONE;
    }
    return r;
}

/* The throttle, clamped to [0, 1]; the same single compare when in range. */
static inline int32_t mix_unipolar(int32_t x)
{
    int32_t r = x;
    if ((uint32_t)x > (uint32_t)Q14_ONE) {
        r = (x < 0) ? 0 : (int32_t)Q14_ONE;
    }
    return r;
}

/* Clamp each input first, so that an out-of-range input cannot push a sum
 * further than a full-scale one would. cmd must not be NULL. */
static inline mix_inputs_t mix_inputs(const os_command_t *cmd)
{
    mix_inputs_t in;
    in.ail = mix_surface(cmd->aileron);
    in.ele = mix_surface(cmd->elevator);
    in.rud = mix_surface(cmd->rudder);
    in.thr = mix_unipolar(cmd->throttle);
    return in;
}

/* The command for one output function, in [-1, 1] (throttle [0, 1]);
 * OS_FN_NONE and unknown functions give 0 (neutral). */
static inline int32_t mix_pick(const mix_inputs_t *in, uint8_t function)
{
    int32_t out;
    switch (function) {
    case OS_FN_NONE:
        out = 0; /* unused channel: centre + trim */
        break;
    case OS_FN_AILERON:
    case OS_FN_AILERON2:
        out = in->ail;
        break;
    case OS_FN_ELEVATOR:
        out = in->ele;
        break;
    case OS_FN_RUDDER:
        out = in->rud;
        break;
    case OS_FN_THROTTLE:
        out = in->thr;
        break;
    case OS_FN_VTAIL_LEFT:
        out = mix_surface(in->ele + in->rud);
        break;
    case OS_FN_VTAIL_RIGHT:
        out = mix_surface(in->ele - in->rud);
        break;
    case OS_FN_ELEVON_LEFT:
        out = mix_surface(in->ele - in->ail);
        break;
    case OS_FN_ELEVON_RIGHT:
        out = mix_surface(in->ele + in->ail);
        break;
    default:
        out = 0; /* unknown function: neutral */
        break;
    }
    return out;
}

#endif /* HELICAL_MIX_INLINE_H */
