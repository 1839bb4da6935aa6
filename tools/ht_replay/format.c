/* format.c - ht_replay's output rows; see format.h. */
#include "format.h"

double ht_q14_to_real(q14_t v)
{
    return (double)v / 16384.0;
}

double ht_q11_to_real(q11_t v)
{
    return (double)v / 2048.0;
}

double ht_q16_to_real(q16_t v)
{
    return (double)v / 65536.0;
}

void ht_format_header(FILE *out)
{
    (void)fputs("turn_rate_used,tilt_x,tilt_y,tilt_z,rate_x,rate_y,rate_z,roll_dot,roll_cross,"
                "roll_error,pitch_error,pitch_body_x,pitch_body_z,aileron,elevator,rudder,"
                "tilt_ratio,flags\n",
                out);
}

void ht_format_row(FILE *out, const ht_output_t *o)
{
    const double v[17] = {
        ht_q11_to_real(o->turn_rate_used_rad_s),
        ht_q14_to_real(o->tilt_x),
        ht_q14_to_real(o->tilt_y),
        ht_q14_to_real(o->tilt_z),
        ht_q11_to_real(o->rate_x_rad_s),
        ht_q11_to_real(o->rate_y_rad_s),
        ht_q11_to_real(o->rate_z_rad_s),
        ht_q14_to_real(o->roll_dot),
        ht_q14_to_real(o->roll_cross),
        ht_q14_to_real(o->roll_error),
        ht_q14_to_real(o->pitch_error),
        ht_q14_to_real(o->pitch_body_x),
        ht_q14_to_real(o->pitch_body_z),
        ht_q14_to_real(o->aileron),
        ht_q14_to_real(o->elevator),
        ht_q14_to_real(o->rudder),
        ht_q16_to_real(o->tilt_ratio),
    };
    for (size_t i = 0; i < sizeof v / sizeof v[0]; i++) {
        (void)fprintf(out, "%.6f,", v[i]);
    }
    (void)fprintf(out, "%u\n", (unsigned)o->flags);
}
