"""Frame conversions and surface signs, checked against JSBSim itself."""

from __future__ import annotations

import math

import jsbsim
import numpy as np
import pytest

from helical_sil.sensors import frames
from helical_sil.sim.lockstep import _quiet_stdout

ATTITUDES = [  # phi, theta, psi in degrees
    (0.0, 0.0, 0.0), (30.0, 0.0, 10.0), (-45.0, 10.0, 200.0), (0.0, -20.0, 90.0),
    (170.0, 5.0, 45.0), (-179.0, -15.0, 300.0), (90.0, 30.0, 0.0), (60.0, -60.0, 135.0),
]


def _fdm(phi: float = 0.0, theta: float = 0.0, psi: float = 0.0, p: float = 0.0,
         q: float = 0.0, r: float = 0.0, trim: bool = False) -> jsbsim.FGFDMExec:
    with _quiet_stdout():
        fdm = jsbsim.FGFDMExec(None)
        fdm.set_debug_level(0)
        assert fdm.load_model("c172p")
        fdm.set_dt(1.0 / 120.0)
        fdm["ic/h-sl-ft"] = 5000.0
        fdm["ic/vt-fps"] = 50.0 / frames.FT
        fdm["ic/phi-deg"] = phi
        fdm["ic/theta-deg"] = theta
        fdm["ic/psi-true-deg"] = psi
        fdm["ic/p-rad_sec"] = p
        fdm["ic/q-rad_sec"] = q
        fdm["ic/r-rad_sec"] = r
        assert fdm.run_ic()
        if trim:
            fdm["propulsion/set-running"] = -1
            fdm["simulation/do_simple_trim"] = 1
    return fdm


@pytest.mark.parametrize("phi,theta,psi", ATTITUDES)
def test_dcm_bottom_row_matches_jsbsim_matrix(phi: float, theta: float, psi: float) -> None:
    fdm = _fdm(phi, theta, psi)
    tl2b = np.asarray(fdm.get_propagate().get_Tl2b())
    # third column of local-to-body = earth-down in FRD body axes
    want = frames.frd_to_lib(tl2b[:, 2])
    got = frames.dcm_bottom_row(fdm["attitude/phi-rad"], fdm["attitude/theta-rad"])
    assert np.allclose(got, want, atol=1e-12), (got, want)
    assert math.isclose(sum(c * c for c in got), 1.0, abs_tol=1e-12)


def test_dcm_signs_of_the_control_law_doc() -> None:
    # level: [0, 0, 1]; right bank: X = -sin(phi); nose up: Y = -sin(theta); inverted: Z = -1
    assert np.allclose(frames.dcm_bottom_row(0.0, 0.0), (0.0, 0.0, 1.0))
    x, _, _ = frames.dcm_bottom_row(math.radians(30), 0.0)
    assert math.isclose(x, -0.5, abs_tol=1e-12)
    _, y, _ = frames.dcm_bottom_row(0.0, math.radians(30))
    assert math.isclose(y, -0.5, abs_tol=1e-12)
    _, _, z = frames.dcm_bottom_row(math.pi, 0.0)
    assert math.isclose(z, -1.0, abs_tol=1e-12)


@pytest.mark.parametrize("phi,theta,psi", ATTITUDES[:5])
def test_earth_turn_rate_matches_jsbsim(phi: float, theta: float, psi: float) -> None:
    fdm = _fdm(phi, theta, psi, p=0.1, q=-0.05, r=0.2)
    pqr = np.array([fdm["velocities/p-rad_sec"], fdm["velocities/q-rad_sec"],
                    fdm["velocities/r-rad_sec"]])
    tb2l = np.asarray(fdm.get_propagate().get_Tl2b()).T
    want = float((tb2l @ pqr)[2])  # earth-down component = clockwise from above
    got = frames.earth_turn_rate(*pqr, fdm["attitude/phi-rad"], fdm["attitude/theta-rad"])
    assert math.isclose(got, want, abs_tol=1e-12)
    # and it equals the law's omega_d = omega . [X, Y, Z] in library axes
    row = frames.dcm_bottom_row(fdm["attitude/phi-rad"], fdm["attitude/theta-rad"])
    g = frames.body_rates_lib(*pqr)
    assert math.isclose(sum(a * b for a, b in zip(row, g)), want, abs_tol=1e-12)


def test_body_rates_map_to_library_axes() -> None:
    # p = omega_Y, q = -omega_X, r = omega_Z
    assert frames.body_rates_lib(1.0, 2.0, 3.0) == (-2.0, 1.0, 3.0)


@pytest.mark.parametrize("surface,axis,sign", [
    ("aileron", 1, +1.0),   # + rolls right: rotation about +Y
    ("elevator", 0, -1.0),  # + nose up: rotation about -X (X is the left wing)
    ("rudder", 2, +1.0),    # + nose right: rotation about +Z
])
def test_surface_signs_through_jsbsim(surface: str, axis: int, sign: float) -> None:
    fdm = _fdm(trim=True)
    base = {"aileron": 0.0, "elevator": 0.0, "rudder": 0.0}
    trim = (fdm["fcs/aileron-cmd-norm"], fdm["fcs/elevator-cmd-norm"],
            fdm["fcs/rudder-cmd-norm"])
    base[surface] = 0.3
    cmd = frames.surfaces_to_jsbsim(base["aileron"], base["elevator"], base["rudder"])
    fdm["fcs/aileron-cmd-norm"] = trim[0] + cmd[0]
    fdm["fcs/elevator-cmd-norm"] = trim[1] + cmd[1]
    fdm["fcs/rudder-cmd-norm"] = trim[2] + cmd[2]
    for _ in range(30):  # 0.25 s
        fdm.run()
    g = frames.body_rates_lib(fdm["velocities/p-rad_sec"], fdm["velocities/q-rad_sec"],
                              fdm["velocities/r-rad_sec"])
    assert sign * g[axis] > 0.02, (surface, g)
    assert abs(g[axis]) == max(abs(c) for c in g), (surface, g)


def test_surface_mapping_is_its_own_inverse() -> None:
    v = (0.1, -0.2, 0.3)
    assert frames.surfaces_from_jsbsim(*frames.surfaces_to_jsbsim(*v)) == v
