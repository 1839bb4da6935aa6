"""Hand-made FdmState snapshots for the sensor-model tests."""

from __future__ import annotations

import dataclasses

from helical_sil.sensors.truth import G0, FdmState

# level flight at 1500 m ISA (84 556 Pa, 1.0581 kg/m^3), 50 m/s north
LEVEL = FdmState(phi_rad=0.0, theta_rad=0.0, psi_rad=0.0, pqr_rad_s=(0.0, 0.0, 0.0),
                 f_frd_m_s2=(0.0, 0.0, -G0), lat_deg=47.0, lon_deg=8.0, alt_msl_m=1500.0,
                 v_ned_m_s=(50.0, 0.0, 0.0), vt_m_s=50.0, rho_kg_m3=1.0581,
                 p_static_pa=84556.0)


def state(**kw: object) -> FdmState:
    return dataclasses.replace(LEVEL, **kw)  # type: ignore[arg-type]
