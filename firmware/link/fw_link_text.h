/*
 * fw_link_text.h - STATUSTEXT (fw_link_text.c): the reason of every refusal
 * and the events a pilot must see, at a bounded rate, and a small text
 * builder (no printf: the link's path has no libc formatting).
 *
 * Rate: a bucket of FW_LINK_TEXT_BURST texts, refilled by one every
 * FW_LINK_TEXT_REFILL_MS; a text with the bucket empty is not sent and is
 * counted in fw_link_t.count.tx_text_dropped (a flood of bad input cannot
 * starve the telemetry or the parameter answers).
 */
#ifndef HT_FW_LINK_TEXT_H
#define HT_FW_LINK_TEXT_H

#include <stdint.h>

#include "link/fw_link_types.h"

#define FW_LINK_TEXT_MAX 50u /* STATUSTEXT.text: 50 characters, not terminated at 50 */

/* A text being built: always terminated, cut at FW_LINK_TEXT_MAX. */
typedef struct {
    char s[FW_LINK_TEXT_MAX + 1u];
    uint8_t n;
} fw_link_text_t;

void fw_link_text_start(fw_link_text_t *t, const char *s);
void fw_link_text_str(fw_link_text_t *t, const char *s);
/* a decimal integer */
void fw_link_text_int(fw_link_text_t *t, int32_t v);
/* raw / scale (scale 1, 100, 1000, 16384 or 65536) as a decimal number,
 * rounded half away from zero to the digits scale needs: 0 for 1, 2 for
 * 100, 3 for 1000, 5 for the binary formats; trailing zeros removed */
void fw_link_text_fixed(fw_link_text_t *t, int32_t raw, int32_t scale);

/* Queue STATUSTEXT (severity MAV_SEVERITY_*) if the rate allows. 0 = queued;
 * 1 = dropped (rate or a full queue; counted). */
int fw_link_statustext(fw_link_t *l, uint8_t severity, const fw_link_text_t *t);

#endif /* HT_FW_LINK_TEXT_H */
