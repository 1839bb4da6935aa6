/*
 * How many good frames the HIL decoder loses per corrupted frame, by kind of
 * corruption (issue 18, item 4). Each trial sends a stream of good frames
 * (known ids, lengths 2..64, payloads seeded at random with some 0xA5 0x5A
 * pairs inside), corrupts one of them (the victim) and counts, by comparing
 * what the decoder delivered with what was sent:
 *
 *   - intact frames lost: frames whose bytes are all in the stream, in a row,
 *     but were not delivered (the victim too when the corruption left an
 *     intact copy of it: a dropped byte equal to the byte after the frame, an
 *     inserted byte before the sync byte);
 *   - merges: trials where the victim's intact copy overlaps the next frame
 *     (its last byte is the next frame's first): only one of two overlapping
 *     frames can be delivered, and the first to end is;
 *   - phantom frames (delivered but never sent);
 *   - late frames (delivered at a later byte than their own last byte).
 *
 * It prints the table and requires, for the decoder in src/protocols/hil_frame.c: no
 * intact frame lost except the one frame of each merge, no phantom, nothing late, and the byte
 * accounting of hil_stats_t to add up. The seeds are fixed, so the figures are too.
 *
 * The same file measured the decoder before the fix (the "before" figures of
 * the report), built by hand against the old sources with the assertions off:
 *
 *   mkdir -p /tmp/old/helical
 *   git show 877ec22:src/protocols/hil_frame.c > /tmp/old/hil_frame.c
 *   git show 877ec22:include/helical/protocols/hil_frame.h > /tmp/old/helical/hil_frame.h
 *   cc -std=c11 -O2 -DHIL_RESYNC_REPORT_ONLY -I/tmp/old -Itests/vendor/unity \
 *      -DUNITY_INCLUDE_DOUBLE tests/unit/test_hil_resync.c /tmp/old/hil_frame.c \
 *      tests/vendor/unity/unity.c -o /tmp/old/resync && /tmp/old/resync
 */
#include <stdio.h>
#include <string.h>

#include "helical/protocols/hil_frame.h"
#include "unity.h"

/* ids 0..5: 0 and 3 any length, the others one length each. */
static const uint8_t lengths[6] = {0xFF, 8, 2, 0xFF, 41, 64};
static const hil_msg_table_t table = {lengths, 6};

#define FRAMES     24 /* per stream */
#define STREAM_MAX (FRAMES * HIL_FRAME_MAX + 16)

typedef enum {
    K_TRUNCATED, /* the frame cut short at a random byte; the next follows */
    K_DROPPED,   /* one byte of the frame missing */
    K_LENGTH,    /* the length byte changed (every other value in turn) */
    K_BITS,      /* 1 to 3 bits flipped anywhere in the frame */
    K_INSERTED,  /* one random byte inserted inside the frame */
    K_COUNT
} kind_t;

static const char *const kind_name[K_COUNT] = {"truncation", "dropped byte", "changed length",
                                               "bit flips (1-3)", "inserted byte"};

#define TRIALS 2000 /* per kind */

/* splitmix64: a small, seedable generator local to this test. */
static uint64_t rng_next(uint64_t *s)
{
    uint64_t z = (*s += 0x9E3779B97F4A7C15u);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9u;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBu;
    return z ^ (z >> 31);
}

static unsigned rng_below(uint64_t *s, unsigned n)
{
    return (unsigned)(rng_next(s) % n);
}

typedef struct {
    uint8_t frame[HIL_FRAME_MAX];
    size_t size;
    size_t end; /* one past its last byte in the stream; 0: not intact in it */
    size_t start;
} sent_t;

typedef struct {
    long trials, intact_lost, merges, phantoms, late;
    long worst_trial_loss; /* most frames lost in one trial, victim included */
    long lost_total;       /* every frame not delivered, victim included */
    long expected_lost;    /* 1 per trial, 0 where an intact copy of the victim stands alone */
} tally_t;

void setUp(void) {}
void tearDown(void) {}

/* One random good frame with sequence number seq in its first two bytes. */
static void make_frame(uint64_t *rng, unsigned seq, sent_t *f)
{
    uint8_t id = (uint8_t)rng_below(rng, 6);
    uint8_t len = lengths[id] != 0xFFu ? lengths[id] : (uint8_t)(2u + rng_below(rng, 63));
    uint8_t p[HIL_PAYLOAD_MAX];
    for (unsigned i = 0; i < len; i++) {
        p[i] = (uint8_t)rng_next(rng);
    }
    /* sync pairs inside payloads: the decoder must not look for frames there
     * while the frame is good, and must when it is not */
    if (len >= 6u && rng_below(rng, 3) == 0u) {
        unsigned at = 2u + rng_below(rng, len - 3u);
        p[at] = HIL_SYNC1;
        p[at + 1u] = HIL_SYNC2;
    }
    hil_put_u16(p, (uint16_t)seq);
    f->size = hil_encode(id, p, len, f->frame, sizeof f->frame);
}

/* Corrupt f (size m) into out; returns the new size. */
static size_t corrupt(uint64_t *rng, kind_t kind, long trial, const sent_t *f, uint8_t *out)
{
    size_t m = f->size;
    memcpy(out, f->frame, m);
    switch (kind) {
    case K_TRUNCATED:
        return 1u + rng_below(rng, (unsigned)m - 1u);
    case K_DROPPED: {
        size_t at = rng_below(rng, (unsigned)m);
        memmove(&out[at], &out[at + 1u], m - at - 1u);
        return m - 1u;
    }
    case K_LENGTH: {
        uint8_t v = (uint8_t)(trial % 255);
        out[2] = (uint8_t)(v >= f->frame[2] ? v + 1u : v); /* every other value */
        return m;
    }
    case K_BITS: {
        unsigned flips = 1u + rng_below(rng, 3);
        unsigned done[3] = {0};
        for (unsigned k = 0; k < flips; k++) {
            unsigned bit;
            int again;
            do { /* distinct bits, or two flips could cancel */
                bit = rng_below(rng, (unsigned)m * 8u);
                again = 0;
                for (unsigned j = 0; j < k; j++) {
                    again |= done[j] == bit;
                }
            } while (again);
            done[k] = bit;
            out[bit / 8u] ^= (uint8_t)(1u << (bit % 8u));
        }
        return m;
    }
    case K_INSERTED:
    default: {
        size_t at = 1u + rng_below(rng, (unsigned)m - 1u);
        memmove(&out[at + 1u], &out[at], m - at);
        out[at] = (uint8_t)rng_next(rng);
        return m + 1u;
    }
    }
}

static int same_frame(const hil_decoder_t *d, const sent_t *f)
{
    return d->id == f->frame[3] && d->len == f->frame[2] &&
           memcmp(d->payload, &f->frame[4], d->len) == 0;
}

/* One trial: returns the frames lost in it (victim included). */
static long run_trial(kind_t kind, long trial, tally_t *t)
{
    uint64_t rng = 0x5EED0000u + (uint64_t)kind * 1000003u + (uint64_t)trial;
    static sent_t sent[FRAMES];
    static uint8_t stream[STREAM_MAX];
    unsigned victim = 1u + rng_below(&rng, FRAMES - 2u);
    size_t n = 0;
    for (unsigned k = 0; k < FRAMES; k++) {
        make_frame(&rng, k, &sent[k]);
        sent[k].start = n;
        if (k == victim) {
            n += corrupt(&rng, kind, trial, &sent[k], &stream[n]);
            sent[k].end = 0;
        } else {
            memcpy(&stream[n], sent[k].frame, sent[k].size);
            n += sent[k].size;
            sent[k].end = n;
        }
    }

    /* Did the corruption leave an intact copy of the victim (shifted by one
     * byte at most)? The next frame starts at sent[victim + 1].start. */
    const sent_t *v = &sent[victim];
    int merged = 0;
    for (size_t o = v->start > 0 ? v->start - 1u : 0; o <= v->start + 1u; o++) {
        if (o + v->size <= n && memcmp(&stream[o], v->frame, v->size) == 0) {
            sent[victim].end = o + v->size;
            merged = sent[victim].end > sent[victim + 1u].start;
        }
    }
    t->merges += merged;
    t->expected_lost += (sent[victim].end != 0u && !merged) ? 0 : 1;

    hil_decoder_t d;
    hil_decoder_init(&d, table);
    int delivered[FRAMES] = {0};
    unsigned next = 0; /* frames arrive in order: search from the last match */
    for (size_t i = 0; i < n; i++) {
        if (!hil_decoder_push(&d, stream[i])) {
            continue;
        }
        unsigned k = next;
        while (k < FRAMES && !same_frame(&d, &sent[k])) {
            k++;
        }
        if (k == FRAMES) {
            t->phantoms++;
            continue;
        }
        delivered[k] = 1;
        next = k + 1u;
        if (sent[k].end != 0u && sent[k].end != i + 1u) {
            t->late++;
        }
    }
#ifndef HIL_RESYNC_REPORT_ONLY
    /* Every byte is accounted for (hil_stats_t). */
    long framed = 0;
    for (unsigned k = 0; k < FRAMES; k++) {
        framed += delivered[k] ? (long)sent[k].size : 0;
    }
    long sum = framed + d.stats.bad_crc + d.stats.bad_length + d.stats.skipped_bytes + d.held;
    TEST_ASSERT_EQUAL_INT(0, d.stats.unknown_id); /* none sent */
    TEST_ASSERT_EQUAL_INT_MESSAGE((long)n, sum, "bytes fed != bytes accounted for");
#endif
    long lost = 0;
    for (unsigned k = 0; k < FRAMES; k++) {
        lost += !delivered[k];
        if (sent[k].end != 0u && !delivered[k]) {
            t->intact_lost++;
#ifndef HIL_RESYNC_REPORT_ONLY
            /* the one loss a merge allows: the frame the victim's copy overlaps */
            TEST_ASSERT_TRUE_MESSAGE(merged && k == victim + 1u && delivered[victim],
                                     "an intact frame was lost");
#endif
        }
    }
    t->trials++;
    t->lost_total += lost;
    if (lost > t->worst_trial_loss) {
        t->worst_trial_loss = lost;
    }
    return lost;
}

static tally_t tallies[K_COUNT];

static void test_frames_lost_per_corruption(void)
{
    for (int k = 0; k < (int)K_COUNT; k++) {
        tally_t *t = &tallies[k];
        memset(t, 0, sizeof *t);
        for (long trial = 0; trial < TRIALS; trial++) {
            (void)run_trial((kind_t)k, trial, t);
        }
    }
    printf("\nframes lost per corrupted frame (%d trials per kind, %d frames per stream)\n", TRIALS,
           FRAMES);
    printf("%-16s %10s %6s %12s %7s %9s %5s\n", "corruption", "lost/trial", "worst", "intact lost",
           "merges", "phantoms", "late");
    for (int k = 0; k < (int)K_COUNT; k++) {
        const tally_t *t = &tallies[k];
        printf("%-16s %10.3f %6ld %12ld %7ld %9ld %5ld\n", kind_name[k],
               (double)t->lost_total / (double)t->trials, t->worst_trial_loss, t->intact_lost,
               t->merges, t->phantoms, t->late);
    }
#ifndef HIL_RESYNC_REPORT_ONLY
    for (int k = 0; k < (int)K_COUNT; k++) {
        const tally_t *t = &tallies[k];
        TEST_ASSERT_EQUAL_INT_MESSAGE(t->merges, t->intact_lost, kind_name[k]);
        TEST_ASSERT_EQUAL_INT_MESSAGE(0, t->phantoms, kind_name[k]);
        TEST_ASSERT_EQUAL_INT_MESSAGE(0, t->late, kind_name[k]);
        /* one frame lost per trial: the victim, or in a merge the frame after
         * it; none when the corruption left the victim intact on its own */
        TEST_ASSERT_EQUAL_INT_MESSAGE(t->expected_lost, t->lost_total, kind_name[k]);
        TEST_ASSERT_EQUAL_INT_MESSAGE(1, t->worst_trial_loss, kind_name[k]);
    }
#endif
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_frames_lost_per_corruption);
    return UNITY_END();
}
