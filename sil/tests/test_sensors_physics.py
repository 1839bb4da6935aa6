"""The ideal sensors (sensor_truth.py) against physics, on real JSBSim runs:
level flight reads 1 g up, a steady coordinated turn n = 1/cos(phi) along -Z,
and the specific force equals the finite-differenced inertial acceleration
minus gravity in a manoeuvre. The numbers quoted in sil/README.md come from
`pytest -s` of this file (each test prints its measurement)."""

from __future__ import annotations

import math

import jsbsim
import numpy as np
import pytest

from helical_sil.sensors import frames
from helical_sil.sensors import truth as st
from helical_sil.sim.lockstep import _quiet_stdout

FT = frames.FT
OMEGA_EARTH = 7.292115e-5  # rad/s


def _trimmed(model: str, airspeed_m_s: float, phi_deg: float = 0.0, lat_deg: float = 0.0,
             mode: int = 1) -> jsbsim.FGFDMExec:
    """JSBSim trimmed at 1500 m: mode 1 = full trim (level), mode 5 = the
    trim's steady turn at bank ic/phi-deg (turn rate g tan(phi) / V)."""
    with _quiet_stdout():
        fdm = jsbsim.FGFDMExec(None)
        fdm.set_debug_level(0)
        assert fdm.load_model(model)
        fdm.set_dt(1.0 / 120.0)
        fdm["ic/h-sl-ft"] = 1500.0 / FT
        fdm["ic/vt-fps"] = airspeed_m_s / FT
        fdm["ic/gamma-deg"] = 0.0
        fdm["ic/phi-deg"] = phi_deg
        fdm["ic/lat-geod-deg"] = lat_deg
        assert fdm.run_ic()
        fdm["propulsion/set-running"] = -1
        fdm["simulation/do_simple_trim"] = mode
    return fdm


def _g_eff(lat_deg: float, fdm: jsbsim.FGFDMExec) -> float:
    """The local apparent gravity (m/s^2): JSBSim's gravitation minus the
    centrifugal term of the Earth's rotation (its vertical part)."""
    lat = math.radians(lat_deg)
    r = st.WGS84_A_M + fdm["position/h-sl-ft"] * FT
    return fdm["accelerations/gravity-ft_sec2"] * FT - OMEGA_EARTH**2 * r * math.cos(lat) ** 2


@pytest.mark.parametrize("model,airspeed", [("c172p", 50.0), ("T37", 110.0)])
def test_level_flight_reads_one_g_up(model: str, airspeed: float) -> None:
    fdm = _trimmed(model, airspeed)
    acc, gyr = [], []
    for _ in range(240):  # 2 s
        fdm.run()
        s = st.read_fdm_state(fdm)
        acc.append(st.ideal_accel_g(s))
        gyr.append(st.ideal_gyro_rad_s(s))
    a = np.mean(acc, axis=0)
    row = np.array(frames.dcm_bottom_row(fdm["attitude/phi-rad"], fdm["attitude/theta-rad"]))
    want = -_g_eff(0.0, fdm) / st.G0 * row  # -g_eff along earth-down, in body axes
    print(f"\n{model} level: accel {a} g, |a| {np.linalg.norm(a):.5f}, want {want}, "
          f"theta {fdm['attitude/theta-deg']:.2f} deg, max |gyro| {np.abs(gyr).max():.2e}")
    # the exact physics: gravity's reaction along -down, local g
    assert np.allclose(a, want, atol=2e-4), (a, want)
    # the brief's figure: ~[0, 0, -1] g (the trim pitch puts sin(theta) on Y,
    # the equator's apparent gravity is 0.9969 g)
    assert abs(a[0]) < 2e-3 and abs(a[1]) < 0.05 and abs(a[2] + 1.0) < 5e-3, a
    assert np.abs(gyr).max() < 1e-3


@pytest.mark.parametrize("phi_deg", [30.0, 45.0, -45.0, 60.0])
def test_coordinated_turn_reads_n_along_minus_z(phi_deg: float) -> None:
    fdm = _trimmed("c172p", 50.0, phi_deg=phi_deg, mode=5)
    acc, phis, gyr, thetas, exact = [], [], [], [], []
    for _ in range(360):  # 3 s of the trimmed turn
        fdm.run()
        s = st.read_fdm_state(fdm)
        acc.append(st.ideal_accel_g(s))
        gyr.append(st.ideal_gyro_rad_s(s))
        phis.append(s.phi_rad)
        thetas.append(s.theta_rad)
        # the exact load of a level turn: |f| = hypot(g_eff, psi_dot V)
        exact.append(math.hypot(_g_eff(0.0, fdm), fdm["velocities/psidot-rad_sec"] * s.vt_m_s))
    a = np.mean(acc, axis=0)
    phi = float(np.mean(phis))
    theta = float(np.mean(thetas))
    n = 1.0 / math.cos(phi)
    g_ratio = _g_eff(0.0, fdm) / st.G0
    mag = float(np.linalg.norm(a))
    want = float(np.mean(exact)) / st.G0
    print(f"\nturn phi {math.degrees(phi):.2f} deg: accel {a} g, |a| {mag:.5f} "
          f"(exact {want:.5f}), n = 1/cos(phi) {n:.5f}, n g_eff/g0 {n * g_ratio:.5f}, "
          f"-Z/n {-a[2] / n:.5f}, lateral {a[0]:.5f} g, theta {math.degrees(theta):.2f} deg")
    assert math.isclose(mag, want, rel_tol=1e-4)
    # 1/cos(phi) is that load only where psi_dot = g_eff tan(phi) / V; JSBSim's
    # turn trim sets psi_dot with the gravitation (0.34 % above g_eff at the
    # equator), so its turn is 0.26 % tighter at 60 deg: within 0.5 %
    assert math.isclose(mag, n * g_ratio, rel_tol=5e-3)
    assert math.isclose(-a[2], n, rel_tol=0.01)  # "within a few percent": 1 %
    assert abs(a[0]) < 0.005  # no lateral component (the trim's sideslip < 1 deg)
    # forward: thrust = drag in a steady turn, so f is normal to the airflow,
    # tilted forward of -Z by the angle of attack
    alpha = fdm["aero/alpha-rad"]
    assert abs(a[1] - mag * math.sin(alpha)) < 0.005, (a[1], mag * math.sin(alpha))
    # the gyro sees the turn rate about earth-down: omega . [X, Y, Z] = g tan(phi) / V
    omega_d = float(np.mean([np.dot(g, frames.dcm_bottom_row(p, t))
                             for g, p, t in zip(gyr, phis, thetas)]))
    want = _g_eff(0.0, fdm) * math.tan(phi) / (fdm["velocities/vt-fps"] * FT)
    assert math.isclose(omega_d, want, rel_tol=0.02), (omega_d, want)


def test_specific_force_is_inertial_acceleration_minus_gravity() -> None:
    """In a manoeuvre (all three surfaces swept), the ideal accelerometer equals
    d(v_NED)/dt + 2 Omega x v - g_eff down, rotated into the body: the chosen
    property is the specific force at the CG and is not a frame late."""
    lat = 47.0
    fdm = _trimmed("c172p", 50.0, lat_deg=lat)
    rows = []
    for k in range(720):  # 6 s
        t = k / 120.0
        fdm["fcs/aileron-cmd-norm"] = 0.5 * math.sin(2 * math.pi * 0.5 * t)
        fdm["fcs/elevator-cmd-norm"] = -0.3 * math.sin(2 * math.pi * 0.3 * t)
        fdm["fcs/rudder-cmd-norm"] = 0.3 * math.sin(2 * math.pi * 0.7 * t)
        fdm.run()
        s = st.read_fdm_state(fdm)
        tl2b = np.asarray(fdm.get_propagate().get_Tl2b())
        n_lag = np.array([fdm["accelerations/Nx"], fdm["accelerations/Ny"],
                          -fdm["accelerations/Nz"]])
        rows.append((tl2b, np.array(s.v_ned_m_s), np.array(s.f_frd_m_s2) / st.G0,
                     _g_eff(fdm["position/lat-geod-deg"], fdm), n_lag))
    la = math.radians(lat)
    omega = OMEGA_EARTH * np.array([math.cos(la), 0.0, -math.sin(la)])
    err, err_lag, fz = [], [], []
    for k in range(1, len(rows) - 1):
        tl2b, v, f, g, _ = rows[k]
        dv = (rows[k + 1][1] - rows[k - 1][1]) * 60.0  # central difference, 120 Hz
        ref = tl2b @ (dv + 2.0 * np.cross(omega, v) - np.array([0.0, 0.0, g])) / st.G0
        err.append(ref - f)
        err_lag.append(ref - rows[k][4])
        fz.append(f[2])
    e, el = np.array(err), np.array(err_lag)
    rms, mx = np.sqrt((e**2).mean(axis=0)), np.abs(e).max(axis=0)
    print(f"\nmanoeuvre: f_z {min(fz):.3f}..{max(fz):.3f} g; error RMS {rms} g, max {mx} g; "
          f"accelerations/N* RMS {np.sqrt((el**2).mean(axis=0))} g")
    assert min(fz) < -1.8 and max(fz) > -0.2  # it did manoeuvre
    assert np.all(rms < 3e-4) and np.all(mx < 3e-3), (rms, mx)
    # the one-frame lag of accelerations/N* is 30 times larger: the reason not to use it
    assert np.sqrt((el**2).mean(axis=0))[2] > 10.0 * rms[2]


def test_rates_position_airspeed_and_baro_from_the_fdm() -> None:
    fdm = _trimmed("c172p", 50.0, lat_deg=47.0)
    fdm["fcs/aileron-cmd-norm"] = 0.3
    for _ in range(120):
        fdm.run()
    s = st.read_fdm_state(fdm)
    p, q, r = fdm["velocities/p-rad_sec"], fdm["velocities/q-rad_sec"], fdm["velocities/r-rad_sec"]
    assert abs(p) > 0.05  # rolling
    assert st.ideal_gyro_rad_s(s) == (-q, p, r)  # README's frames table
    assert s.lat_deg == fdm["position/lat-geod-deg"] and s.lon_deg == fdm["position/long-gc-deg"]
    assert math.isclose(s.alt_msl_m, fdm["position/h-sl-ft"] * FT, rel_tol=1e-15)
    # the pitot's ideal pressure inverts to JSBSim's true airspeed
    assert math.isclose(math.sqrt(2.0 * st.ideal_dynamic_pressure_pa(s) / s.rho_kg_m3), s.vt_m_s,
                        rel_tol=1e-12)
    assert math.isclose(st.ideal_dynamic_pressure_pa(s), fdm["aero/qbar-psf"] * st.PSF,
                        rel_tol=1e-6)
    # the ISA altimeter on JSBSim's static pressure gives its altitude back
    h = st.ideal_baro_altitude_m(s)
    print(f"\nbaro {h:.4f} m (QNH {st.pressure_altitude_m(s.p_static_pa, 2116.228 * st.PSF):.4f}), h-sl {s.alt_msl_m:.4f} m, "
          f"pressure-altitude {fdm['atmosphere/pressure-altitude'] * FT:.4f} m")
    # JSBSim's sea-level pressure is 2116.228 psf = 101325.56 Pa, not the
    # ICAO 101325 Pa: with it as the altimeter setting the two agree to 1 cm;
    # with the ICAO value the baro reads 4.7 cm low
    h_jsb = st.ideal_baro_altitude_m(s, qnh_pa=2116.228 * st.PSF)
    assert abs(h_jsb - fdm["atmosphere/pressure-altitude"] * FT) < 0.01
    assert abs(h - s.alt_msl_m) < 0.06


def test_pressure_altitude_against_isa_table() -> None:
    # ISA (ICAO Doc 7488) pressures at geopotential altitudes 0, 1, 5, 11, 15 km
    for h_geopot, p in [(0.0, 101325.0), (1000.0, 89874.6), (5000.0, 54019.9),
                        (11000.0, 22632.1), (15000.0, 12044.6)]:
        z = st.EARTH_R_GEOPOT_M * h_geopot / (st.EARTH_R_GEOPOT_M - h_geopot)
        assert abs(st.pressure_altitude_m(p) - z) < 0.1, (h_geopot, st.pressure_altitude_m(p))
    # an altimeter set 1 hPa high reads ~8.4 m higher at sea level
    assert 8.0 < st.pressure_altitude_m(101325.0, 101425.0) < 8.8
    with pytest.raises(ValueError, match="pressure must be > 0"):
        st.pressure_altitude_m(0.0)


def test_full_model_in_a_jsbsim_loop() -> None:
    """The integrator's loop: read the state after every frame, IMU at the sim
    rate (120 Hz), GPS at 5 Hz with 0.1 s latency, default errors."""
    from helical_sil.sensors.models import ImuConfig, SensorConfig, SensorModel

    fdm = _trimmed("c172p", 50.0, lat_deg=47.0)
    model = SensorModel(SensorConfig(imu=ImuConfig(rate_hz=120.0)), seed=1)
    acc, fixes, alt = [], [], []
    for k in range(1, 1201):  # 10 s
        fdm.run()
        t = k / 120.0
        s = st.read_fdm_state(fdm)
        acc.append(model.imu(s, t).accel_g)
        g = model.gps(s, t)
        if g.fresh:
            fixes.append(g)
        alt.append(model.baro(s, t).altitude_m - s.alt_msl_m)
    a = np.mean(acc, axis=0)
    # 1 g up within the default (calibrated) 3-sigma bias, scale and cross-axis errors
    assert np.all(np.abs(a - [0.0, 0.022, -0.997]) < 0.005), a
    # epochs 0, 0.2 ... 9.8 s, each 0.1 s later (epoch 0 sampled at the first
    # call, 1/120 s: labelled so)
    assert len(fixes) == 50
    assert fixes[0].t_valid_s == 1.0 / 120.0 and fixes[1].t_valid_s == pytest.approx(0.2)
    assert all(abs(f.t_s - f.t_valid_s - 0.1) < 1e-9 for f in fixes)
    assert abs(float(np.mean(alt))) < 0.5  # baro: noise 0.1 m, ISA offset 4.7 cm
