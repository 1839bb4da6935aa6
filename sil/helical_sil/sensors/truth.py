"""The ideal sensors: what a perfect IMU, GPS, pitot and baro would read,
as pure functions of one JSBSim state snapshot (``FdmState``).

The error models of models.py are applied on top of these values; keeping
this part pure lets tests/test_sensors_physics.py check it against physics
(1 g in level flight, n = 1/cos(phi) in a coordinated turn, the specific force
against the finite-differenced inertial velocity).

Where the numbers come from (checked numerically in test_sensors_physics.py):

- Specific force (what an accelerometer reads) at the CG:
  ``forces/fb{x,y,z}-total-lbs / inertia/mass-slugs``: the sum of the
  aerodynamic, propulsive, gear and external forces in FRD body axes, i.e.
  everything except gravity. It matches d(v_NED)/dt + Coriolis - g_eff rotated
  into the body to 1e-4 g RMS in a manoeuvre. JSBSim's ``accelerations/Nx,
  Ny, Nz`` hold the same vector in standard g (Nz positive up) but one
  integration frame late (FGAuxiliary runs before the forces of the frame),
  and ``accelerations/a-pilot-*`` is at the pilot's eye point (lever-arm
  terms of several 0.01 g in a manoeuvre). The IMU sits at the CG.
- Body rates: ``velocities/p,q,r-rad_sec`` (FRD) -> library axes by
  frames.body_rates_lib.
- JSBSim flies a rotating WGS84 Earth: in level flight the specific force is
  the gravitation minus the centrifugal term, 9.776 m/s^2 = 0.9969 g at the
  equator at 1500 m, not 1 g. An accelerometer reports in standard g
  (9.80665 m/s^2), so it reads that ratio.
- Static pressure ``atmosphere/P-psf``, density ``atmosphere/rho-slugs_ft3``,
  true airspeed ``velocities/vt-fps``, position ``position/lat-geod-deg``,
  ``position/long-gc-deg`` (geocentric and geodetic longitude coincide),
  ``position/h-sl-ft``, velocity ``velocities/v-{north,east,down}-fps``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import jsbsim

from helical_sil.sensors import frames

G0 = 9.80665  # m/s^2: the unit "g" of an accelerometer (standard gravity)
FT = frames.FT
PSF = 47.880258980336  # Pa per lbf/ft^2
SLUG_FT3 = 515.378818  # kg/m^3 per slug/ft^3
LBF = 4.4482216152605  # N per lbf
SLUG = 14.5939029372  # kg per slug

# International Standard Atmosphere (troposphere and lower stratosphere), the
# pressure -> altitude law of a barometric altimeter
ISA_P0_PA = 101325.0
ISA_T0_K = 288.15
ISA_LAPSE_K_M = 0.0065
ISA_R = 287.05287  # J/(kg K), dry air
ISA_H11_M = 11000.0  # geopotential altitude of the tropopause
ISA_T11_K = ISA_T0_K - ISA_LAPSE_K_M * ISA_H11_M
EARTH_R_GEOPOT_M = 6356766.0  # the radius of the US 1976 geopotential conversion
RHO0_KG_M3 = 1.225  # ISA sea-level density: indicated airspeed's reference


@dataclass(frozen=True)
class FdmState:
    """Everything the ideal sensors need, SI units, JSBSim's frames (body FRD,
    local NED). ``read_fdm_state`` fills it from a running FGFDMExec; tests
    can build one by hand."""

    phi_rad: float
    theta_rad: float
    psi_rad: float
    pqr_rad_s: tuple[float, float, float]  # body rates, FRD
    f_frd_m_s2: tuple[float, float, float]  # specific force at the CG, FRD
    lat_deg: float  # geodetic
    lon_deg: float
    alt_msl_m: float
    v_ned_m_s: tuple[float, float, float]  # ground velocity
    vt_m_s: float  # true airspeed
    rho_kg_m3: float  # ambient density
    p_static_pa: float  # ambient static pressure


def read_fdm_state(fdm: jsbsim.FGFDMExec) -> FdmState:
    """The snapshot of the FDM's current state (after fdm.run())."""
    m_slug = fdm["inertia/mass-slugs"]
    # written out, no generator: the flight loop reads one state per control step
    f = (fdm["forces/fbx-total-lbs"] / m_slug * FT, fdm["forces/fby-total-lbs"] / m_slug * FT,
         fdm["forces/fbz-total-lbs"] / m_slug * FT)
    return FdmState(
        phi_rad=fdm["attitude/phi-rad"], theta_rad=fdm["attitude/theta-rad"],
        psi_rad=fdm["attitude/psi-rad"],
        pqr_rad_s=(fdm["velocities/p-rad_sec"], fdm["velocities/q-rad_sec"],
                   fdm["velocities/r-rad_sec"]),
        f_frd_m_s2=f,
        lat_deg=fdm["position/lat-geod-deg"], lon_deg=fdm["position/long-gc-deg"],
        alt_msl_m=fdm["position/h-sl-ft"] * FT,
        v_ned_m_s=(fdm["velocities/v-north-fps"] * FT, fdm["velocities/v-east-fps"] * FT,
                   fdm["velocities/v-down-fps"] * FT),
        vt_m_s=fdm["velocities/vt-fps"] * FT,
        rho_kg_m3=fdm["atmosphere/rho-slugs_ft3"] * SLUG_FT3,
        p_static_pa=fdm["atmosphere/P-psf"] * PSF,
    )


def ideal_gyro_rad_s(s: FdmState) -> tuple[float, float, float]:
    """Body rates in library axes (X left wing, Y forward, Z down), rad/s."""
    return frames.body_rates_lib(*s.pqr_rad_s)


def ideal_accel_g(s: FdmState) -> tuple[float, float, float]:
    """Specific force in library axes, standard g: level flight ~[0, 0, -1]."""
    x, y, z = frames.frd_to_lib(s.f_frd_m_s2)
    return (x / G0, y / G0, z / G0)


def ideal_dynamic_pressure_pa(s: FdmState) -> float:
    """What a pitot-static differential sensor sees: q = rho V^2 / 2 (the
    incompressible relation; the compressible impact pressure is 0.25 M^2
    larger, < 3 % below M 0.33, and the same relation inverts it)."""
    return 0.5 * s.rho_kg_m3 * s.vt_m_s * s.vt_m_s


def pressure_altitude_m(p_pa: float, p_ref_pa: float = ISA_P0_PA) -> float:
    """Geometric altitude (m) of static pressure p in the ISA whose sea-level
    pressure is p_ref (a barometric altimeter set to p_ref). Troposphere and
    the isothermal layer above it (to 20 km)."""
    if not (p_pa > 0.0 and p_ref_pa > 0.0):
        raise ValueError(f"pressure must be > 0 Pa, got p={p_pa!r}, p_ref={p_ref_pa!r}")
    expo = ISA_R * ISA_LAPSE_K_M / G0
    h = ISA_T0_K / ISA_LAPSE_K_M * (1.0 - (p_pa / p_ref_pa) ** expo)
    if h > ISA_H11_M:
        p11 = p_ref_pa * (ISA_T11_K / ISA_T0_K) ** (1.0 / expo)
        h = ISA_H11_M + ISA_R * ISA_T11_K / G0 * math.log(p11 / p_pa)
    # geopotential -> geometric
    return EARTH_R_GEOPOT_M * h / (EARTH_R_GEOPOT_M - h)


def ideal_baro_altitude_m(s: FdmState, qnh_pa: float = ISA_P0_PA) -> float:
    return pressure_altitude_m(s.p_static_pa, qnh_pa)


# WGS84, for turning north/east metres into degrees
WGS84_A_M = 6378137.0
WGS84_E2 = 6.69437999014e-3


def metres_per_degree(lat_deg: float, alt_m: float) -> tuple[float, float]:
    """(north, east) metres per degree of latitude / longitude at lat, alt."""
    s = math.sin(math.radians(lat_deg))
    w = 1.0 - WGS84_E2 * s * s
    m_merid = WGS84_A_M * (1.0 - WGS84_E2) / w ** 1.5
    n_prime = WGS84_A_M / math.sqrt(w)
    k = math.pi / 180.0
    return ((m_merid + alt_m) * k, (n_prime + alt_m) * math.cos(math.radians(lat_deg)) * k)
