/*
 * fw_link_text.c - STATUSTEXT at a bounded rate and the text builder
 * (fw_link_text.h).
 */
#include "link/fw_link_text.h"

#include "link/fw_link_tx.h"

void fw_link_text_start(fw_link_text_t *t, const char *s)
{
    t->n = 0u;
    t->s[0] = '\0';
    fw_link_text_str(t, s);
}

/* the decimal digits, by value: a digit without arithmetic on characters */
static const char DIGITS[10] = {'0', '1', '2', '3', '4', '5', '6', '7', '8', '9'};

static void put(fw_link_text_t *t, char c)
{
    if (t->n < FW_LINK_TEXT_MAX) {
        t->s[t->n] = c;
        t->n = (uint8_t)(t->n + 1u);
        t->s[t->n] = '\0';
    }
}

void fw_link_text_str(fw_link_text_t *t, const char *s)
{
    for (const char *p = s; *p != '\0'; ++p) {
        put(t, *p);
    }
}

static void put_u64(fw_link_text_t *t, uint64_t v)
{
    char d[20];
    unsigned k = 0u;
    uint64_t x = v;
    do {
        d[k] = DIGITS[x % 10u];
        ++k;
        x /= 10u;
    } while ((x != 0u) && (k < sizeof d));
    while (k > 0u) {
        --k;
        put(t, d[k]);
    }
}

void fw_link_text_int(fw_link_text_t *t, int32_t v)
{
    if (v < 0) {
        put(t, '-');
        put_u64(t, (uint64_t)(-(int64_t)v));
    } else {
        put_u64(t, (uint64_t)v);
    }
}

void fw_link_text_fixed(fw_link_text_t *t, int32_t raw, int32_t scale)
{
    unsigned digits;
    uint64_t pow10;
    if (scale <= 1) {
        fw_link_text_int(t, raw);
        return;
    }
    if (scale == 100) {
        digits = 2u;
        pow10 = 100u;
    } else if (scale == 1000) {
        digits = 3u;
        pow10 = 1000u;
    } else {
        digits = 5u; /* 2^-16 = 0.0000153: five digits tell every Q14 / Q16 bound apart */
        pow10 = 100000u;
    }
    const uint64_t mag = (raw < 0) ? (uint64_t)(-(int64_t)raw) : (uint64_t)raw;
    const uint64_t s = (uint64_t)scale;
    const uint64_t scaled = ((mag * pow10) + (s / 2u)) / s; /* half away from zero */
    if ((raw < 0) && (scaled != 0u)) {
        put(t, '-');
    }
    put_u64(t, scaled / pow10);
    uint64_t frac = scaled % pow10;
    if (frac == 0u) {
        return;
    }
    while ((frac % 10u) == 0u) {
        frac /= 10u;
        --digits;
        pow10 /= 10u;
    }
    put(t, '.');
    for (uint64_t p = pow10 / 10u; p > 0u; p /= 10u) {
        put(t, DIGITS[(frac / p) % 10u]);
    }
}

int fw_link_statustext(fw_link_t *l, uint8_t severity, const fw_link_text_t *t)
{
    /* refill: one text per FW_LINK_TEXT_REFILL_MS since the last refill */
    const uint32_t since = l->now_ms - l->text_refill_ms;
    if (since >= FW_LINK_TEXT_REFILL_MS) {
        const uint32_t add = since / FW_LINK_TEXT_REFILL_MS;
        const uint32_t room = (uint32_t)FW_LINK_TEXT_BURST - (uint32_t)l->text_tokens;
        l->text_tokens = (uint8_t)(l->text_tokens + ((add < room) ? add : room));
        l->text_refill_ms += add * FW_LINK_TEXT_REFILL_MS;
    }
    if (l->text_tokens == 0u) {
        fw_link_count(&l->count.tx_text_dropped);
        return 1;
    }
    mavlink_statustext_t st;
    (void)memset(&st, 0, sizeof st);
    st.severity = severity;
    (void)memcpy(st.text, t->s, t->n); /* <= 50: not terminated at 50 (the spec) */
    if (FW_LINK_QUEUE(l, STATUSTEXT, st) != 0) {
        fw_link_count(&l->count.tx_text_dropped);
        return 1;
    }
    l->text_tokens = (uint8_t)(l->text_tokens - 1u);
    return 0;
}
