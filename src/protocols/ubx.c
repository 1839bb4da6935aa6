/*
 * ubx.c - UBX frame decoder: NAV-PVT and ACK-ACK / ACK-NAK, and the frame
 * checksum (the encoders in ubx_encode.c use it too). See ubx.h.
 */
#include "helical/protocols/ubx.h"

#include "protocols/frame_scan.h"

static uint32_t get_u32(const uint8_t *p)
{
    return (uint32_t)p[0] | ((uint32_t)p[1] << 8u) | ((uint32_t)p[2] << 16u) |
           ((uint32_t)p[3] << 24u);
}

static int32_t get_i32(const uint8_t *p)
{
    /* two's complement on every target this library builds for */
    return (int32_t)get_u32(p);
}

uint16_t ubx_checksum(const uint8_t *data, size_t n)
{
    uint8_t a = 0u;
    uint8_t b = 0u;
    for (size_t i = 0u; i < n; i++) {
        a = (uint8_t)(a + data[i]);
        b = (uint8_t)(b + a);
    }
    return (uint16_t)((uint16_t)a | ((uint16_t)b << 8u));
}

static fs_cand_t ubx_classify(const uint8_t *w, size_t n, size_t *size)
{
    if (w[0] != UBX_SYNC1 || (n >= 2u && w[1] != UBX_SYNC2)) {
        return FS_NONE;
    }
    if (n < 6u) {
        return FS_OPEN;
    }
    const size_t len = (size_t)w[4] | ((size_t)w[5] << 8u);
    if (len > UBX_PAYLOAD_MAX) {
        return FS_BAD_LENGTH;
    }
    *size = len + UBX_OVERHEAD;
    return (n < *size) ? FS_OPEN : FS_ENDED;
}

static bool ubx_check(const uint8_t *f, size_t size)
{
    const uint16_t ck = ubx_checksum(&f[2], size - 4u);
    return f[size - 2u] == (uint8_t)(ck & 0xFFu) && f[size - 1u] == (uint8_t)(ck >> 8u);
}

static const fs_proto_t ubx_proto = {ubx_classify, ubx_check, false, NULL};

void ubx_init(ubx_decoder_t *d)
{
    if (d != NULL) {
        ubx_decoder_t zero = {0};
        *d = zero;
    }
}

static void decode_pvt(const uint8_t *p, ubx_nav_pvt_t *out)
{
    out->itow_ms = get_u32(&p[0]);
    out->fix_type = p[20];
    out->flags = p[21];
    out->gnss_fix_ok = (p[21] & UBX_PVT_FLAG_GNSS_FIX_OK) != 0u;
    out->num_sv = p[23];
    out->lon_e7 = get_i32(&p[24]);
    out->lat_e7 = get_i32(&p[28]);
    out->height_mm = get_i32(&p[32]);
    out->hmsl_mm = get_i32(&p[36]);
    out->h_acc_mm = get_u32(&p[40]);
    out->v_acc_mm = get_u32(&p[44]);
    out->vel_n_mm_s = get_i32(&p[48]);
    out->vel_e_mm_s = get_i32(&p[52]);
    out->vel_d_mm_s = get_i32(&p[56]);
    out->ground_speed_mm_s = get_i32(&p[60]);
    out->head_mot_e5 = get_i32(&p[64]);
    out->s_acc_mm_s = get_u32(&p[68]);
}

/* A frame with a good checksum: decode it if its class, id and length are
 * known. */
static ubx_result_t decode_frame(ubx_decoder_t *d, const uint8_t *f, size_t size, ubx_msg_t *out)
{
    const uint8_t cls = f[2];
    const uint8_t id = f[3];
    const size_t len = size - UBX_OVERHEAD;
    const uint8_t *p = &f[6];
    ubx_result_t r = UBX_NONE;
    if (cls == UBX_CLASS_NAV && id == UBX_ID_NAV_PVT) {
        if (len == UBX_NAV_PVT_BYTES) {
            decode_pvt(p, &out->pvt);
            r = UBX_NAV_PVT;
        } else {
            fs_count(&d->counts.wrong_length);
        }
    } else if (cls == UBX_CLASS_ACK && (id == UBX_ID_ACK_ACK || id == UBX_ID_ACK_NAK)) {
        if (len == 2u) {
            out->ack.cls = p[0];
            out->ack.id = p[1];
            r = (id == UBX_ID_ACK_ACK) ? UBX_ACK_ACK : UBX_ACK_NAK;
        } else {
            fs_count(&d->counts.wrong_length);
        }
    } else {
        fs_count(&d->counts.unknown_type);
    }
    if (r != UBX_NONE) {
        fs_count(&d->counts.frames_ok);
    }
    return r;
}

ubx_result_t ubx_push(ubx_decoder_t *d, uint8_t byte, ubx_msg_t *out)
{
    if (d == NULL || out == NULL) {
        return UBX_ERR_NULL;
    }
    size_t start = 0u;
    size_t size = fs_push(&ubx_proto, d->window, UBX_FRAME_MAX, &d->held, &d->counts, byte, &start);
    if (size == 0u) {
        return UBX_NONE;
    }
    return decode_frame(d, &d->window[start], size, out);
}

size_t ubx_feed(ubx_decoder_t *d, const uint8_t *bytes, size_t n, ubx_msg_t *out,
                ubx_result_t *result)
{
    if (result == NULL) {
        return 0u;
    }
    if (d == NULL || out == NULL || (bytes == NULL && n != 0u)) {
        *result = UBX_ERR_NULL;
        return 0u;
    }
    *result = UBX_NONE;
    size_t i = 0u;
    while (i < n && *result == UBX_NONE) {
        *result = ubx_push(d, bytes[i], out);
        i++;
    }
    return i;
}
