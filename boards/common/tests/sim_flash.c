/*
 * sim_flash.c - the simulated NOR flash (see sim_flash.h). Host tests only.
 */
#include "sim_flash.h"

#include <stddef.h>
#include <string.h>

void sim_flash_init(sim_flash_t *s, uint8_t *mem, uint32_t slot_size, uint32_t slots,
                    uint32_t align)
{
    memset(s, 0, sizeof *s);
    s->mem = mem;
    s->slot_size = slot_size;
    s->slots = slots;
    s->align = (align == 0u) ? 1u : align;
    s->powered = 1u;
    memset(mem, 0xFF, (size_t)slot_size * slots);
}

void sim_flash_cut_program(sim_flash_t *s, uint32_t after, uint8_t torn_mask)
{
    s->cut = SIM_CUT_PROGRAM;
    s->cut_at = s->programmed + after;
    s->torn_mask = torn_mask;
}

void sim_flash_cut_erase(sim_flash_t *s, sim_erase_model_t model, uint32_t at)
{
    s->cut = SIM_CUT_ERASE;
    s->erase_model = model;
    s->cut_at = at;
}

void sim_flash_power_on(sim_flash_t *s)
{
    s->cut = SIM_CUT_NONE;
    s->powered = 1u;
    s->programmed = 0u;
}

void sim_flash_bind(sim_flash_t *s, param_flash_t *out)
{
    out->ctx = s;
    out->slot_size = s->slot_size;
    out->erase = sim_flash_erase;
    out->program = sim_flash_program;
    out->read = sim_flash_read;
}

static int span_ok(const sim_flash_t *s, uint32_t slot, uint32_t offset, uint32_t n)
{
    return slot < s->slots && offset <= s->slot_size && n <= s->slot_size - offset;
}

static uint32_t xorshift32(uint32_t *x)
{
    uint32_t v = *x;
    v ^= v << 13;
    v ^= v >> 17;
    v ^= v << 5;
    *x = v;
    return v;
}

int sim_flash_erase(void *ctx, uint32_t slot)
{
    sim_flash_t *s = ctx;
    if (!s->powered) {
        return SIM_FLASH_ERR_POWER;
    }
    if (slot >= s->slots) {
        s->range_violations++;
        return SIM_FLASH_ERR_RANGE;
    }
    uint8_t *m = &s->mem[(size_t)slot * s->slot_size];
    s->erases++;
    if (s->cut != SIM_CUT_ERASE) {
        memset(m, 0xFF, s->slot_size);
        return 0;
    }
    const uint32_t k = (s->cut_at < s->slot_size) ? s->cut_at : s->slot_size;
    uint32_t x = (s->cut_at != 0u) ? s->cut_at : 1u;
    switch (s->erase_model) {
    case SIM_ERASE_PREFIX:
        memset(m, 0xFF, k);
        break;
    case SIM_ERASE_SUFFIX:
        memset(&m[s->slot_size - k], 0xFF, k);
        break;
    case SIM_ERASE_NOISE:
    default:
        for (uint32_t i = 0u; i < s->slot_size; ++i) {
            m[i] = (uint8_t)(m[i] | (xorshift32(&x) & 0xFFu));
        }
        break;
    }
    s->powered = 0u;
    s->cut = SIM_CUT_NONE;
    return SIM_FLASH_ERR_POWER;
}

int sim_flash_program(void *ctx, uint32_t slot, uint32_t offset, const uint8_t *bytes, uint32_t n)
{
    sim_flash_t *s = ctx;
    if (!s->powered) {
        return SIM_FLASH_ERR_POWER;
    }
    if (!span_ok(s, slot, offset, n) || (bytes == NULL && n != 0u)) {
        s->range_violations++;
        return SIM_FLASH_ERR_RANGE;
    }
    if ((offset % s->align) != 0u || (n % s->align) != 0u) {
        s->align_violations++;
        return SIM_FLASH_ERR_ALIGN;
    }
    s->program_calls++;
    uint8_t *m = &s->mem[(size_t)slot * s->slot_size + offset];
    for (uint32_t i = 0u; i < n; ++i) {
        if (s->cut == SIM_CUT_PROGRAM && s->programmed == s->cut_at) {
            /* clear only the torn_mask part of the bits this byte needed cleared */
            const uint8_t clear = (uint8_t)(m[i] & (uint8_t)~bytes[i] & s->torn_mask);
            m[i] = (uint8_t)(m[i] & (uint8_t)~clear);
            s->powered = 0u;
            s->cut = SIM_CUT_NONE;
            return SIM_FLASH_ERR_POWER;
        }
        const uint8_t old = m[i];
        m[i] = (uint8_t)(old & bytes[i]);
        s->programmed++;
        if ((uint8_t)(old & bytes[i]) != bytes[i]) {
            s->nor_violations++;
            return SIM_FLASH_ERR_NOR;
        }
    }
    return 0;
}

int sim_flash_read(void *ctx, uint32_t slot, uint32_t offset, uint8_t *bytes, uint32_t n)
{
    sim_flash_t *s = ctx;
    if (!s->powered) {
        return SIM_FLASH_ERR_POWER;
    }
    if (!span_ok(s, slot, offset, n) || (bytes == NULL && n != 0u)) {
        s->range_violations++;
        return SIM_FLASH_ERR_RANGE;
    }
    s->read_calls++;
    if (n != 0u) {
        memcpy(bytes, &s->mem[(size_t)slot * s->slot_size + offset], n);
    }
    return 0;
}
