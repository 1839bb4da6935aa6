/*
 * The README's "Calling it from C", as a program the host build compiles and
 * ctest runs, so that the snippet stays true. A 0.2 rad/s right turn at
 * 22 m/s from level flight: the aileron must be positive (roll right).
 */
#include <stdio.h>

#include "helical/law/helical_turn.h"

static void report(const char *field)
{
    fprintf(stderr, "bad parameter: %s\n", field);
}

int main(void)
{
    const q14_t r6 = 0, r7 = 0, r8 = Q14_ONE; /* the DCM bottom row: level */
    const q11_t gx = 0, gy = 0, gz = 0;       /* gyros: still */

    static const ht_params_t params = {/* physical units, integers: no float on the board */
                                       .kp_aileron = Q16_FROM_REAL(3.0),
                                       .kp_elevator = Q16_FROM_REAL(6.0),
                                       .kp_rudder = Q16_FROM_REAL(0.3),
                                       .kd_aileron = Q16_FROM_REAL(0.5),
                                       .kd_elevator = Q16_FROM_REAL(1.0),
                                       .kd_rudder = Q16_FROM_REAL(1.0),
                                       .kff_elevator = Q16_FROM_REAL(1.0),
                                       .kff_rudder = Q16_FROM_REAL(0.5),
                                       .v_ref_cm_s = 5000,
                                       .v_min_cm_s = 500,
                                       .max_tilt = 4 * Q16_ONE};
    ht_controller_t ctl; /* caller-owned, read-only after init */
    ht_param_id_t bad;
    if (ht_init(&ctl, &params, &bad) != HT_OK) {
        report(ht_param_name(bad));
        return 1;
    }
    ht_input_t in = {.x = r6,
                     .y = r7,
                     .z = r8,
                     .turn_rate_rad_s = Q11_FROM_REAL(0.2),
                     .pitch_ratio = 0,
                     .airspeed_cm_s = 2200,
                     .gyro_rad_s = {gx, gy, gz}};
    ht_output_t out; /* surfaces and every intermediate, for logging */
    ht_step(&ctl, &in, &out);
    printf("aileron %.4f elevator %.4f rudder %.4f\n", out.aileron / 16384.0,
           out.elevator / 16384.0, out.rudder / 16384.0);
    return (out.aileron > 0) ? 0 : 1;
}
