/*
 * param_store.c - the two-slot parameter store (see param_store.h and
 * docs/drivers/param_store.md for the power-cut argument).
 */
#include "param_store.h"

#include "crc32.h"

#define CHUNK 64u /* bytes read per flash call while scanning */

#define OFF_MAGIC    0u
#define OFF_FORMAT   4u
#define OFF_SCHEMA   6u
#define OFF_VERSION  8u
#define OFF_RESERVED 10u
#define OFF_SEQUENCE 12u
#define OFF_LENGTH   16u

static uint32_t get32(const uint8_t *p)
{
    const uint32_t b0 = p[0];
    const uint32_t b1 = p[1];
    const uint32_t b2 = p[2];
    const uint32_t b3 = p[3];
    return b0 | (b1 << 8) | (b2 << 16) | (b3 << 24);
}

static uint16_t get16(const uint8_t *p)
{
    const uint32_t b0 = p[0];
    const uint32_t b1 = p[1];
    const uint32_t v = b0 | (b1 << 8);
    return (uint16_t)v;
}

static void put32(uint8_t *p, uint32_t v)
{
    p[0] = (uint8_t)(v & 0xFFu);
    p[1] = (uint8_t)((v >> 8) & 0xFFu);
    p[2] = (uint8_t)((v >> 16) & 0xFFu);
    p[3] = (uint8_t)((v >> 24) & 0xFFu);
}

static void put16(uint8_t *p, uint16_t v)
{
    const uint32_t w = v;
    p[0] = (uint8_t)(w & 0xFFu);
    p[1] = (uint8_t)((w >> 8) & 0xFFu);
}

/* Payload bytes rounded up to the program unit; callers bound n first. */
static uint32_t padded(uint32_t n)
{
    return (n + (PARAM_STORE_ALIGN - 1u)) & ~(PARAM_STORE_ALIGN - 1u);
}

uint32_t param_store_max_payload(uint32_t slot_size)
{
    if (slot_size < PARAM_STORE_OVERHEAD) {
        return 0u;
    }
    return (slot_size - PARAM_STORE_OVERHEAD) & ~(PARAM_STORE_ALIGN - 1u);
}

int param_store_seq_newer(uint32_t a, uint32_t b)
{
    const uint32_t d = a - b; /* unsigned: wraps by definition */
    return (d != 0u && d < 0x80000000u) ? 1 : 0;
}

static int flash_ok(const param_flash_t *f)
{
    return f != NULL && f->erase != NULL && f->program != NULL && f->read != NULL &&
           f->slot_size >= PARAM_STORE_OVERHEAD && (f->slot_size % PARAM_STORE_ALIGN) == 0u;
}

static int store_ok(const param_store_t *s)
{
    return s != NULL && flash_ok(s->flash) &&
           s->length <= param_store_max_payload(s->flash->slot_size);
}

/* Every byte of the slot reads 0xFF (a failed read is not blank). */
static int slot_blank(const param_flash_t *f, uint32_t slot)
{
    uint8_t buf[CHUNK];
    for (uint32_t at = 0u; at < f->slot_size; at += CHUNK) {
        const uint32_t left = f->slot_size - at;
        const uint32_t n = (left < CHUNK) ? left : CHUNK;
        if (f->read(f->ctx, slot, at, buf, n) != 0) {
            return 0;
        }
        for (uint32_t i = 0u; i < n; ++i) {
            if (buf[i] != 0xFFu) {
                return 0;
            }
        }
    }
    return 1;
}

/* CRC-32 of the slot's first n bytes; 0 on a failed read (*ok = 0). */
static uint32_t slot_crc(const param_flash_t *f, uint32_t slot, uint32_t n, int *ok)
{
    uint8_t buf[CHUNK];
    uint32_t crc = 0u;
    for (uint32_t at = 0u; at < n; at += CHUNK) {
        const uint32_t left = n - at;
        const uint32_t len = (left < CHUNK) ? left : CHUNK;
        if (f->read(f->ctx, slot, at, buf, len) != 0) {
            *ok = 0;
            return 0u;
        }
        crc = crc32_iso_hdlc(crc, buf, len);
    }
    *ok = 1;
    return crc;
}

/* A complete record: magic, format, a length that fits, the commit word
 * (programmed last) and the CRC over header and padded payload. */
static int slot_valid(const param_flash_t *f, uint32_t slot, param_slot_info_t *info)
{
    uint8_t h[PARAM_STORE_HEADER];
    uint8_t t[PARAM_STORE_TRAILER];
    if (f->read(f->ctx, slot, 0u, h, PARAM_STORE_HEADER) != 0) {
        return 0;
    }
    if (get32(&h[OFF_MAGIC]) != PARAM_STORE_MAGIC || get16(&h[OFF_FORMAT]) != PARAM_STORE_FORMAT) {
        return 0;
    }
    const uint32_t length = get32(&h[OFF_LENGTH]);
    if (length > param_store_max_payload(f->slot_size)) {
        return 0;
    }
    const uint32_t body = PARAM_STORE_HEADER + padded(length);
    if (f->read(f->ctx, slot, body, t, PARAM_STORE_TRAILER) != 0) {
        return 0;
    }
    if (get32(&t[4]) != PARAM_STORE_COMMIT) {
        return 0;
    }
    int ok = 0;
    const uint32_t crc = slot_crc(f, slot, body, &ok);
    if (!ok || crc != get32(&t[0])) {
        return 0;
    }
    info->schema_id = get16(&h[OFF_SCHEMA]);
    info->schema_version = get16(&h[OFF_VERSION]);
    info->sequence = get32(&h[OFF_SEQUENCE]);
    info->length = length;
    return 1;
}

static void scan_slot(const param_flash_t *f, uint32_t slot, param_slot_info_t *info)
{
    info->schema_id = 0u;
    info->schema_version = 0u;
    info->sequence = 0u;
    info->length = 0u;
    if (slot_valid(f, slot, info) != 0) {
        info->state = PARAM_SLOT_VALID;
    } else if (slot_blank(f, slot) != 0) {
        info->state = PARAM_SLOT_BLANK;
    } else {
        info->state = PARAM_SLOT_CORRUPT;
    }
}

/* The slot of the newest valid record, or PARAM_STORE_SLOTS when none.
 * Equal (or unordered) sequence numbers, which saves never make, give 0. */
static uint32_t newest(const param_slot_info_t s[PARAM_STORE_SLOTS])
{
    const uint8_t v0 = (s[0].state == PARAM_SLOT_VALID) ? 1u : 0u;
    const uint8_t v1 = (s[1].state == PARAM_SLOT_VALID) ? 1u : 0u;
    if (v0 != 0u && v1 != 0u) {
        return (param_store_seq_newer(s[1].sequence, s[0].sequence) != 0) ? 1u : 0u;
    }
    if (v0 != 0u) {
        return 0u;
    }
    if (v1 != 0u) {
        return 1u;
    }
    return PARAM_STORE_SLOTS;
}

/* Header, payload and padding as they will be (or were) programmed. */
static void make_header(const param_store_t *s, uint32_t sequence, uint8_t h[PARAM_STORE_HEADER])
{
    put32(&h[OFF_MAGIC], PARAM_STORE_MAGIC);
    put16(&h[OFF_FORMAT], (uint16_t)PARAM_STORE_FORMAT);
    put16(&h[OFF_SCHEMA], s->schema_id);
    put16(&h[OFF_VERSION], s->schema_version);
    put16(&h[OFF_RESERVED], 0u);
    put32(&h[OFF_SEQUENCE], sequence);
    put32(&h[OFF_LENGTH], s->length);
}

static uint32_t record_crc(const uint8_t h[PARAM_STORE_HEADER], const uint8_t *payload,
                           uint32_t length)
{
    static const uint8_t zeros[PARAM_STORE_ALIGN] = {0u, 0u, 0u, 0u};
    uint32_t crc = crc32_iso_hdlc(0u, h, PARAM_STORE_HEADER);
    crc = crc32_iso_hdlc(crc, payload, length);
    return crc32_iso_hdlc(crc, zeros, padded(length) - length);
}

param_store_status_t param_store_load(const param_store_t *store, uint8_t *payload,
                                      param_store_load_t *out)
{
    if (out == NULL) {
        return PARAM_STORE_ERR_ARG;
    }
    out->loaded = 0u;
    out->slot = 0u;
    out->sequence = 0u;
    for (uint32_t i = 0u; i < PARAM_STORE_SLOTS; ++i) {
        out->slots[i].state = PARAM_SLOT_CORRUPT;
        out->slots[i].schema_id = 0u;
        out->slots[i].schema_version = 0u;
        out->slots[i].sequence = 0u;
        out->slots[i].length = 0u;
    }
    if (!store_ok(store) || (payload == NULL && store->length != 0u)) {
        out->status = PARAM_STORE_ERR_ARG;
        return out->status;
    }
    const param_flash_t *f = store->flash;
    scan_slot(f, 0u, &out->slots[0]);
    scan_slot(f, 1u, &out->slots[1]);
    const uint8_t corrupt =
        (out->slots[0].state == PARAM_SLOT_CORRUPT || out->slots[1].state == PARAM_SLOT_CORRUPT)
            ? 1u
            : 0u;
    const uint32_t n = newest(out->slots);
    if (n >= PARAM_STORE_SLOTS) {
        out->status = (corrupt != 0u) ? PARAM_STORE_CORRUPT : PARAM_STORE_BLANK;
        return out->status;
    }
    const param_slot_info_t *rec = &out->slots[n];
    out->slot = (uint8_t)n;
    out->sequence = rec->sequence;
    if (rec->schema_id != store->schema_id || rec->schema_version != store->schema_version ||
        rec->length != store->length) {
        out->status = PARAM_STORE_SCHEMA_MISMATCH;
        return out->status;
    }
    /* Copy, then check the copy against the stored CRC once more: what the
     * caller gets is what was checked. */
    uint8_t h[PARAM_STORE_HEADER];
    uint8_t c[4];
    const uint32_t body = PARAM_STORE_HEADER + padded(store->length);
    if ((store->length != 0u &&
         f->read(f->ctx, n, PARAM_STORE_HEADER, payload, store->length) != 0) ||
        f->read(f->ctx, n, 0u, h, PARAM_STORE_HEADER) != 0 ||
        f->read(f->ctx, n, body, c, 4u) != 0 || record_crc(h, payload, store->length) != get32(c)) {
        out->slots[n].state = PARAM_SLOT_CORRUPT;
        out->status = PARAM_STORE_CORRUPT;
        return out->status;
    }
    out->loaded = 1u;
    out->status = (corrupt != 0u) ? PARAM_STORE_CORRUPT : PARAM_STORE_OK;
    return out->status;
}

/* The slot's bytes at offset equal expect (n bytes). */
static int slot_equals(const param_flash_t *f, uint32_t slot, uint32_t offset,
                       const uint8_t *expect, uint32_t n)
{
    uint8_t buf[CHUNK];
    for (uint32_t at = 0u; at < n; at += CHUNK) {
        const uint32_t left = n - at;
        const uint32_t len = (left < CHUNK) ? left : CHUNK;
        if (f->read(f->ctx, slot, offset + at, buf, len) != 0) {
            return 0;
        }
        for (uint32_t i = 0u; i < len; ++i) {
            if (buf[i] != expect[at + i]) {
                return 0;
            }
        }
    }
    return 1;
}

param_store_status_t param_store_save(const param_store_t *store, const uint8_t *payload,
                                      uint8_t *slot_out, uint32_t *sequence_out)
{
    if (!store_ok(store) || (payload == NULL && store->length != 0u)) {
        return PARAM_STORE_ERR_ARG;
    }
    const param_flash_t *f = store->flash;
    param_slot_info_t s[PARAM_STORE_SLOTS];
    scan_slot(f, 0u, &s[0]);
    scan_slot(f, 1u, &s[1]);
    const uint32_t n = newest(s);
    const uint32_t target = (n < PARAM_STORE_SLOTS) ? (1u - n) : 0u;
    const uint32_t sequence = (n < PARAM_STORE_SLOTS) ? (s[n].sequence + 1u) : 1u;

    if (f->erase(f->ctx, target) != 0) {
        return PARAM_STORE_ERR_FLASH;
    }
    if (!slot_blank(f, target)) {
        return PARAM_STORE_ERR_VERIFY;
    }

    const uint32_t length = store->length;
    const uint32_t body = length & ~(PARAM_STORE_ALIGN - 1u); /* whole words */
    const uint32_t tail = length - body;                      /* 0..3 bytes */
    const uint32_t crc_at = PARAM_STORE_HEADER + padded(length);
    uint8_t h[PARAM_STORE_HEADER];
    uint8_t last[PARAM_STORE_ALIGN] = {0u, 0u, 0u, 0u}; /* the tail, zero padded */
    uint8_t c[4];
    uint8_t commit[4];
    make_header(store, sequence, h);
    for (uint32_t i = 0u; i < tail; ++i) {
        last[i] = payload[body + i];
    }
    put32(c, record_crc(h, payload, length));
    put32(commit, PARAM_STORE_COMMIT);

    /* Everything but the commit word, in address order. */
    if (f->program(f->ctx, target, 0u, h, PARAM_STORE_HEADER) != 0) {
        return PARAM_STORE_ERR_FLASH;
    }
    if (body != 0u && f->program(f->ctx, target, PARAM_STORE_HEADER, payload, body) != 0) {
        return PARAM_STORE_ERR_FLASH;
    }
    if (tail != 0u &&
        f->program(f->ctx, target, PARAM_STORE_HEADER + body, last, PARAM_STORE_ALIGN) != 0) {
        return PARAM_STORE_ERR_FLASH;
    }
    if (f->program(f->ctx, target, crc_at, c, 4u) != 0) {
        return PARAM_STORE_ERR_FLASH;
    }
    /* Only a record that reads back right gets its commit word. */
    if (!slot_equals(f, target, 0u, h, PARAM_STORE_HEADER) ||
        (body != 0u && !slot_equals(f, target, PARAM_STORE_HEADER, payload, body)) ||
        (tail != 0u &&
         !slot_equals(f, target, PARAM_STORE_HEADER + body, last, PARAM_STORE_ALIGN)) ||
        !slot_equals(f, target, crc_at, c, 4u)) {
        return PARAM_STORE_ERR_VERIFY;
    }
    if (f->program(f->ctx, target, crc_at + 4u, commit, 4u) != 0) {
        return PARAM_STORE_ERR_FLASH;
    }
    param_slot_info_t done;
    scan_slot(f, target, &done);
    if (done.state != PARAM_SLOT_VALID || done.sequence != sequence ||
        done.schema_id != store->schema_id || done.schema_version != store->schema_version ||
        done.length != length) {
        return PARAM_STORE_ERR_VERIFY;
    }
    if (slot_out != NULL) {
        *slot_out = (uint8_t)target;
    }
    if (sequence_out != NULL) {
        *sequence_out = sequence;
    }
    return PARAM_STORE_OK;
}
