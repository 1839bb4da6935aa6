/*
 * frame_scan.c - the candidate-window frame search shared by the UBX, CRSF
 * and SBUS decoders. See frame_scan.h.
 */
#include "protocols/frame_scan.h"

void fs_count(uint32_t *counter)
{
    if (*counter != UINT32_MAX) {
        (*counter)++;
    }
}

/* Count the start byte of a candidate that is dropped, by its state. */
static void count_dropped(const fs_proto_t *p, ht_frame_counts_t *c, fs_cand_t k)
{
    switch (k) {
    case FS_NONE:
        fs_count(&c->discarded_bytes);
        break;
    case FS_BAD_LENGTH:
        fs_count(&c->bad_length);
        break;
    case FS_OPEN:
        fs_count(&c->truncated);
        break;
    default: /* FS_ENDED without being taken: its check failed */
        if (p->check_is_end_byte) {
            fs_count(&c->bad_end);
        } else {
            fs_count(&c->bad_checksum);
        }
        break;
    }
}

/* w[0..end) precede a good frame: each byte is counted once, as the start
 * of a dropped candidate or as discarded. */
static void drop_before(const fs_proto_t *p, const uint8_t *w, size_t n, size_t end,
                        ht_frame_counts_t *c)
{
    for (size_t i = 0u; i < end; i++) {
        size_t size = 0u;
        count_dropped(p, c, p->classify(&w[i], n - i, &size));
    }
}

/* While the oldest candidate (at w[0]) cannot be a frame any more, count it
 * and move the window down to the next byte that can start one, so that
 * every byte after a failed start byte is searched again. Each pass drops at
 * least one byte, so the loop ends. */
static void drop_failed(const fs_proto_t *p, uint8_t *w, uint8_t *held, ht_frame_counts_t *c)
{
    size_t n = *held;
    while (n > 0u) {
        size_t size = 0u;
        fs_cand_t k = p->classify(w, n, &size);
        if (k == FS_OPEN) {
            break;
        }
        count_dropped(p, c, k);
        size_t next = 1u;
        while (next < n && p->classify(&w[next], 1u, &size) == FS_NONE) {
            fs_count(&c->discarded_bytes);
            next++;
        }
        for (size_t j = next; j < n; j++) {
            w[j - next] = w[j];
        }
        n -= next;
    }
    *held = (uint8_t)n;
}

size_t fs_push(const fs_proto_t *p, uint8_t *w, size_t cap, uint8_t *held, ht_frame_counts_t *c,
               uint8_t byte, size_t *start)
{
    size_t size = 0u;
    if ((size_t)*held >= cap) {
        /* Cannot happen (the oldest candidate is open, so it is shorter than
         * cap); a corrupted state is dropped rather than overrun. */
        fs_drop_held(held, c);
    }
    if (*held == 0u && p->classify(&byte, 1u, &size) == FS_NONE) {
        fs_count(&c->discarded_bytes);
        return 0u;
    }
    w[*held] = byte;
    const size_t n = (size_t)*held + 1u;
    *held = (uint8_t)n;

    /* The earliest candidate that this byte completes with a good check is
     * the frame; the later ones lie inside it. */
    for (size_t i = 0u; i < n; i++) {
        fs_cand_t k = p->classify(&w[i], n - i, &size);
        if (k == FS_ENDED && size == n - i && p->check(&w[i], size) &&
            (i == 0u || p->decodes == NULL || p->decodes(&w[i], size))) {
            drop_before(p, w, n, i, c);
            c->frame_bytes = (c->frame_bytes > UINT32_MAX - (uint32_t)size)
                                 ? UINT32_MAX
                                 : (c->frame_bytes + (uint32_t)size);
            *held = 0u;
            *start = i;
            return size;
        }
    }
    drop_failed(p, w, held, c);
    return 0u;
}

void fs_drop_held(uint8_t *held, ht_frame_counts_t *c)
{
    if (*held > 0u) {
        fs_count(&c->truncated);
        for (size_t i = 1u; i < (size_t)*held; i++) {
            fs_count(&c->discarded_bytes);
        }
    }
    *held = 0u;
}
