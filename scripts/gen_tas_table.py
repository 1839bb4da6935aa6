#!/usr/bin/env python3
"""Print the table of src/estimator/air_data.c: TAS / IAS = 1 / sqrt(sigma) of
the ICAO standard atmosphere at every 250 m of pressure altitude from
-1000 m to 20000 m, in Q14 (x 16384, rounded), for the integer-only
piecewise-linear lookup of ht_true_airspeed_cm_s.

sigma = rho / rho0 = delta / theta with, in the troposphere (h <= 11 000 m),
theta = 1 - L h / T0 and delta = theta ** (g0 / (R L)), and above it (the
lower stratosphere, isothermal at 216.65 K) theta = 216.65 / 288.15 and
delta = delta(11 000 m) * exp(-g0 (h - 11 000) / (R 216.65)).
T0 = 288.15 K, L = 0.0065 K/m, g0 = 9.80665 m/s^2, R = 287.05287 J/(kg K)
(ICAO Doc 7488, ISO 2533:1975: the constants of scripts/gen_baro_alt_table.py).

Usage: scripts/gen_tas_table.py   (paste the output over the table)
"""
import math

T0_K = 288.15
LAPSE_K_M = 0.0065
G0_M_S2 = 9.80665
R_J_KGK = 287.05287
H_TROPO_M = 11000.0
T_TROPO_K = T0_K - LAPSE_K_M * H_TROPO_M  # 216.65

BASE_M = -1000
STEP_M = 250
NODES = 85  # -1000 + 84 * 250 = 20000 m


def theta_delta(h_m: float) -> tuple[float, float]:
    n = G0_M_S2 / (R_J_KGK * LAPSE_K_M)
    if h_m <= H_TROPO_M:
        theta = 1.0 - LAPSE_K_M * h_m / T0_K
        return theta, theta ** n
    d11 = (T_TROPO_K / T0_K) ** n
    return T_TROPO_K / T0_K, d11 * math.exp(-G0_M_S2 * (h_m - H_TROPO_M) / (R_J_KGK * T_TROPO_K))


def tas_per_ias(h_m: float) -> float:
    theta, delta = theta_delta(h_m)
    return 1.0 / math.sqrt(delta / theta)


def main() -> None:
    vals = [round(tas_per_ias(BASE_M + i * STEP_M) * 16384.0) for i in range(NODES)]
    print("static const uint16_t tas_per_ias_q14[AIR_NODES] = {")
    for i in range(0, NODES, 8):
        print("    " + ", ".join(f"{v}u" for v in vals[i:i + 8]) + ",")
    print("};")


if __name__ == "__main__":
    main()
