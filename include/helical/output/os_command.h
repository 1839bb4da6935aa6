/*
 * os_command.h - what the mixes work on: the output functions (which mix
 * feeds a channel) and the command (the law's surfaces and the throttle).
 * The mixer (mixer.h) and its rules (src/output/mix_inline.h) build on
 * these. Sign conventions: mixer.h.
 */
#ifndef HELICAL_OS_COMMAND_H
#define HELICAL_OS_COMMAND_H

#include <stdint.h>

#include "helical/math/q14.h"

#ifdef __cplusplus
extern "C" {
#endif

/* What an output channel drives, i.e. which mix feeds it. */
typedef enum {
    OS_FN_NONE = 0,         /* unused: command 0 (the channel sits at centre + trim) */
    OS_FN_AILERON = 1,      /* aileron, + = roll right */
    OS_FN_AILERON2 = 2,     /* second aileron servo: the same roll command; a
                               mirror-mounted servo sets `reversed` */
    OS_FN_ELEVATOR = 3,     /* + = nose up */
    OS_FN_RUDDER = 4,       /* + = nose right */
    OS_FN_THROTTLE = 5,     /* [0, 1]: 0 = idle */
    OS_FN_VTAIL_LEFT = 6,   /* left ruddervator  = pitch + yaw */
    OS_FN_VTAIL_RIGHT = 7,  /* right ruddervator = pitch - yaw */
    OS_FN_ELEVON_LEFT = 8,  /* left elevon  = pitch - roll */
    OS_FN_ELEVON_RIGHT = 9, /* right elevon = pitch + roll */
    OS_FN_COUNT = 10
} os_function_t;

/* The commands the mixer works from. */
typedef struct {
    q14_t aileron;  /* [-1, 1]; outside values are clamped */
    q14_t elevator; /* [-1, 1] */
    q14_t rudder;   /* [-1, 1] */
    q14_t throttle; /* [0, 1]; below 0 reads as 0, above 1 as 1 */
} os_command_t;

#ifdef __cplusplus
}
#endif

#endif /* HELICAL_OS_COMMAND_H */
