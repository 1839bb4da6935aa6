/*
 * param_store.h - a power-cut proof parameter store in two flash slots.
 *
 * The store keeps one opaque blob (the caller serialises its parameters
 * into it) tagged with a schema id, a schema version and its length, in
 * whichever of two equal flash slots (erase units) holds the newer record.
 * A save always goes into the other slot, so the last good record is never
 * erased or written while a new one is being made; load takes the valid
 * record with the higher sequence number. See docs/drivers/param_store.md.
 *
 * Record layout in a slot (all fields little-endian, offsets in bytes):
 *    0  u32 magic           PARAM_STORE_MAGIC ("HTPS")
 *    4  u16 format          PARAM_STORE_FORMAT (this layout)
 *    6  u16 schema_id       the caller's: what the blob is
 *    8  u16 schema_version  the caller's: which revision of it
 *   10  u16 reserved        0
 *   12  u32 sequence        one more than the record it replaces (wraps)
 *   16  u32 length          payload bytes
 *   20  payload             length bytes, then 0x00 up to a multiple of 4
 *   P   u32 crc             CRC-32/ISO-HDLC of bytes 0 .. P-1 (P = 20 + padded length)
 *   P+4 u32 commit          PARAM_STORE_COMMIT, programmed last of all
 * The rest of the slot stays erased (0xFF).
 *
 * A slot is valid when magic, format, length (fits the slot), commit and CRC
 * all agree; blank when every byte reads 0xFF; corrupt otherwise.
 *
 * No float, no allocation, no state of its own: the caller owns
 * param_store_t and the payload buffers. Stack use is bounded (a 64-byte
 * chunk buffer); flash reads are chunked.
 */
#ifndef HT_PARAM_STORE_H
#define HT_PARAM_STORE_H

#include <stddef.h>
#include <stdint.h>

#define PARAM_STORE_MAGIC    0x53505448u /* bytes 'H' 'T' 'P' 'S' */
#define PARAM_STORE_FORMAT   1u
#define PARAM_STORE_COMMIT   0x54494D43u /* bytes 'C' 'M' 'I' 'T' */
#define PARAM_STORE_HEADER   20u         /* bytes before the payload */
#define PARAM_STORE_TRAILER  8u          /* crc + commit */
#define PARAM_STORE_OVERHEAD (PARAM_STORE_HEADER + PARAM_STORE_TRAILER)
#define PARAM_STORE_ALIGN    4u /* every program call: offset and length multiples of this */
#define PARAM_STORE_SLOTS    2u

/*
 * The flash under the store. Each call returns 0 on success, anything else
 * on failure. Slots are 0 and 1, each slot_size bytes (a multiple of 4),
 * erasable on their own; erase leaves every byte 0xFF; program only clears
 * bits and is always called with offset and n multiples of
 * PARAM_STORE_ALIGN; read takes any offset and length inside the slot.
 */
typedef struct {
    void *ctx;
    uint32_t slot_size;
    int (*erase)(void *ctx, uint32_t slot);
    int (*program)(void *ctx, uint32_t slot, uint32_t offset, const uint8_t *bytes, uint32_t n);
    int (*read)(void *ctx, uint32_t slot, uint32_t offset, uint8_t *bytes, uint32_t n);
} param_flash_t;

/* The store, owned by the caller: the flash and the blob it expects. */
typedef struct {
    const param_flash_t *flash;
    uint16_t schema_id;
    uint16_t schema_version;
    uint32_t length; /* payload bytes of this schema */
} param_store_t;

typedef enum {
    PARAM_STORE_OK = 0,              /* load: the newest record is loaded, the other slot is fine */
    PARAM_STORE_BLANK = 1,           /* load: both slots erased; nothing loaded: use defaults */
    PARAM_STORE_CORRUPT = 2,         /* load: a slot is neither blank nor valid (see loaded) */
    PARAM_STORE_SCHEMA_MISMATCH = 3, /* load: the newest record has another schema, version or
                                        length; nothing loaded: use defaults */
    PARAM_STORE_ERR_ARG = 4,         /* NULL pointer, bad slot size, length over the maximum */
    PARAM_STORE_ERR_FLASH = 5,       /* save: an erase or program call failed */
    PARAM_STORE_ERR_VERIFY = 6       /* save: the slot did not read back as written */
} param_store_status_t;

typedef enum {
    PARAM_SLOT_BLANK = 0,   /* every byte 0xFF */
    PARAM_SLOT_VALID = 1,   /* a complete record (of any schema) */
    PARAM_SLOT_CORRUPT = 2, /* anything else: a torn write, a torn erase, a failed read */
} param_slot_state_t;

/* What a slot holds, as load and save found it. */
typedef struct {
    param_slot_state_t state;
    uint16_t schema_id; /* the record's, when VALID */
    uint16_t schema_version;
    uint32_t sequence;
    uint32_t length;
} param_slot_info_t;

typedef struct {
    param_store_status_t status;
    uint8_t loaded;    /* 1: payload holds the record; 0: the caller must use its defaults */
    uint8_t slot;      /* the newest valid record's slot (when one was found) */
    uint32_t sequence; /* its sequence number */
    param_slot_info_t slots[PARAM_STORE_SLOTS];
} param_store_load_t;

/* Largest payload a slot of slot_size bytes takes (0 if none). */
uint32_t param_store_max_payload(uint32_t slot_size);

/*
 * Serial-number order of two sequence numbers (RFC 1982 style, 32 bits):
 * 1 when a is newer than b, i.e. a - b (mod 2^32) is in 1 .. 2^31 - 1.
 * So 0 is newer than 0xFFFFFFFF (the wrap), and two numbers exactly 2^31
 * apart are unordered (0 both ways). Saves only ever step by one.
 */
int param_store_seq_newer(uint32_t a, uint32_t b);

/*
 * Read both slots and take the newest valid record. If it matches the
 * store's schema id, version and length, copy its payload into payload
 * (store->length bytes) and set loaded = 1; status OK, or CORRUPT when the
 * other slot is corrupt (booting on the good one, and saying so).
 * Otherwise loaded = 0 and payload is unspecified (may be overwritten):
 * BLANK (both slots erased), CORRUPT (no valid record and at least one
 * corrupt slot) or SCHEMA_MISMATCH (the newest valid record is another
 * schema's: an older record of this schema is not used, as it would bring
 * back settings the newer record replaced). out must not be NULL.
 */
param_store_status_t param_store_load(const param_store_t *store, uint8_t *payload,
                                      param_store_load_t *out);

/*
 * Save store->length bytes of payload as a new record: read both slots,
 * then into the slot NOT holding the newest valid record (slot 0 when
 * neither is valid) with that record's sequence + 1 (1 when none): erase,
 * check blank, program header, payload, CRC; read back and compare; program
 * the commit word; check that the slot now holds exactly this record.
 * Returns OK (and *slot_out, *sequence_out if not NULL), or an error with
 * the other slot untouched. A failed save leaves a corrupt slot, which the
 * next load reports and the next save overwrites.
 */
param_store_status_t param_store_save(const param_store_t *store, const uint8_t *payload,
                                      uint8_t *slot_out, uint32_t *sequence_out);

#endif /* HT_PARAM_STORE_H */
