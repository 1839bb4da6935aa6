/*
 * log_df.c - the DataFlash record table and the field encoders. The format
 * characters used (DFReader's sizes): Q uint64, i int32, I uint32, h int16,
 * H uint16, B uint8, M uint8 (a flight mode), L int32 degrees * 1e7,
 * e int32 * 0.01, c int16 * 0.01, C uint16 * 0.01, f binary32, N char[16],
 * Z char[64]. GPS carries GMS and GWk (the GPS time of week) because
 * DFReader takes a GPS record without them for an old-style one and fails;
 * the board seam has no GPS time, so both are 0 (DFReader then keeps the
 * TimeUS clock). Fixed-point fields are logged raw (their Q format in the
 * label's documentation, docs/flight-log.md) so a replay gets the exact bits.
 */
#include "log/log_df.h"

/* Lengths are the header (3) plus the fields; tests/test_fw_log.c checks
 * each against its format string. */
static const fw_log_format_t k_formats[FW_LOG_KIND_COUNT] = {
    {0x81u, 31u, "PARM", "QNf", "TimeUS,Name,Value"},
    {0x82u, 75u, "MSG", "QZ", "TimeUS,Message"},
    {0x83u, 35u, "IMU", "Qiiiiii", "TimeUS,GyrX,GyrY,GyrZ,AccX,AccY,AccZ"},
    {0x84u, 42u, "GPS", "QBIHLLeeee", "TimeUS,Status,GMS,GWk,Lat,Lng,Alt,VelN,VelE,VelD"},
    {0x85u, 16u, "BARO", "QeB", "TimeUS,Alt,Fresh"},
    {0x86u, 14u, "ARSP", "QcB", "TimeUS,Airspeed,Fresh"},
    {0x87u, 23u, "ATT", "QccChhh", "TimeUS,Roll,Pitch,Yaw,DX,DY,DZ"},
    {0x88u, 37u, "HTIN", "QhhhhihhhhhhBB",
     "TimeUS,X,Y,Z,Turn,Pitch,Asp,GX,GY,GZ,TAcc,ALat,Inv,PMod"},
    {0x89u, 40u, "HTO", "QhihhhhhhhhhhhB",
     "TimeUS,TrnU,Tilt,TX,TY,TZ,REr,PEr,Ail,Elv,Rud,RIn,Fade,Slip,Flg"},
    {0x8Au, 22u, "CTRL", "QihBBBBB", "TimeUS,PCmd,Thr,Ctl,IFs,RcFs,Guard,Clamp"},
    {0x8Bu, 27u, "RCOU", "QHHHHHHHH", "TimeUS,C1,C2,C3,C4,C5,C6,C7,C8"},
    {0x8Cu, 14u, "MODE", "QMBB", "TimeUS,Mode,ModeNum,Rsn"},
    {0x8Du, 12u, "EV", "QB", "TimeUS,Id"},
};

const fw_log_format_t *fw_log_format(fw_log_kind_t kind)
{
    if ((unsigned)kind >= (unsigned)FW_LOG_KIND_COUNT) {
        return NULL;
    }
    return &k_formats[kind];
}

void fw_log_rec_begin(fw_log_rec_t *r, uint8_t *buf, uint8_t type)
{
    r->p = buf;
    r->p[0] = FW_LOG_HEAD1;
    r->p[1] = FW_LOG_HEAD2;
    r->p[2] = type;
    r->n = 3u;
}

void fw_log_put_u8(fw_log_rec_t *r, uint8_t v)
{
    r->p[r->n] = v;
    r->n += 1u;
}

void fw_log_put_u16(fw_log_rec_t *r, uint16_t v)
{
    fw_log_put_u8(r, (uint8_t)(v & 0xFFu));
    fw_log_put_u8(r, (uint8_t)(v >> 8u));
}

void fw_log_put_i16(fw_log_rec_t *r, int16_t v)
{
    fw_log_put_u16(r, (uint16_t)v); /* two's complement, as the reader unpacks */
}

void fw_log_put_u32(fw_log_rec_t *r, uint32_t v)
{
    fw_log_put_u16(r, (uint16_t)(v & 0xFFFFu));
    fw_log_put_u16(r, (uint16_t)(v >> 16u));
}

void fw_log_put_i32(fw_log_rec_t *r, int32_t v)
{
    fw_log_put_u32(r, (uint32_t)v);
}

void fw_log_put_u64(fw_log_rec_t *r, uint64_t v)
{
    fw_log_put_u32(r, (uint32_t)(v & 0xFFFFFFFFu));
    fw_log_put_u32(r, (uint32_t)(v >> 32u));
}

void fw_log_put_text(fw_log_rec_t *r, const char *s, size_t width)
{
    size_t i = 0u;
    if (s != NULL) {
        while ((i < width) && (s[i] != '\0')) {
            r->p[r->n + i] = (uint8_t)s[i];
            ++i;
        }
    }
    while (i < width) {
        r->p[r->n + i] = 0u;
        ++i;
    }
    r->n += width;
}

int fw_log_fmt_record(fw_log_kind_t kind, uint8_t buf[FW_LOG_FMT_LEN])
{
    const fw_log_format_t *f = fw_log_format(kind);
    if ((f == NULL) || (buf == NULL)) {
        return -1;
    }
    fw_log_rec_t r;
    fw_log_rec_begin(&r, buf, FW_LOG_TYPE_FMT);
    fw_log_put_u8(&r, f->type);
    fw_log_put_u8(&r, f->length);
    fw_log_put_text(&r, f->name, 4u);
    fw_log_put_text(&r, f->format, 16u);
    fw_log_put_text(&r, f->labels, 64u);
    return 0;
}
