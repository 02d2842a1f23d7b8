"""The lunar model (layer 2): figure torques of degree 2-4, fluid core, tidal and rotational distortion.

Four levels, each adding physics to the one before:

1. Euler's model: a rigid degree-2 Moon, Earth and Sun as point masses
   (Euler ch. 16 P91, §815: N = 3 GM/r^5 r x I r);
2. + the Moon's degree-3 and degree-4 gravity field acting with every point mass:
   N = -M_A r x grad U_Moon(r) (Williams, Boggs & Folkner 2008; Folkner et al. 2014);
3. + a fluid core with an oblate core-mantle boundary, coupled by friction and by the
   fluid's pressure on the boundary; the tidal and rotational distortion of the mantle's
   moment of inertia; and the Earth's J2 acting on the Moon's degree-2 figure
   (Folkner et al. 2014, IPN PR 42-196, §III "Lunar orientation": mantle and core
   equations (34)-(35), moments of inertia (36)-(41), point-mass torque (43), figure-
   figure torque (44), equation numbers as cited by PlanetaryEphemeris.jl; I_m as in
   Pavlov, Williams & Suvorkin 2016, CMDA 126:61, eq. (15) with the zz element
   corrected in Pavlov & Williams 2019, doi:10.1007/s10569-019-9939-8):

   I_m = I~ - I_c - k2 (M_E/M) (R^3/r^5) [x_i x_j - r^2 d_ij/3]
               + k2 R^3/(3 GM) [w_i w_j - d_ij (w^2 - n^2)/3, zz: w_z^2 - (w^2 + 2 n^2)/3]
   I_c = diag(A_c, A_c, C_c),  A_c = C_c (1 - f_c)
   d(I_m w_m)/dt + w_m x I_m w_m = N_figure + N_figM-figE + N_cmb
   N_cmb = k_v (w_c - w_m) + (C_c - A_c) (z . w_c) (z x w_c)
   I_c dw_c/dt + w_m x I_c w_c = -N_cmb                 (w_c in mantle axes, z = (0, 0, 1))
   N_figM-figE = 15 GM_E J2E R_E^2 / (2 r^5) [(1 - 7 s^2) u x I u
                 + 2 s (u x I p + p x I u) - (2/5) p x I p]   (u = r/r, p = Earth pole, s = u.p)

   x = the Earth's position in the mantle frame at t - tau (the tide raised a time
   tau earlier, carried round with the mantle); w in the rotational term is taken at t.
   The torques act with the whole Moon's distorted I; the mantle turns with I - I_c.

   What limited the pole (measured against DE421 over 1900-2050, benchmarks/RESULTS.md):
   DE421's core is oblate (header COBLAT, f_c = 3.8e-4).  Its pressure torque couples
   the core's free precession (~200 yr) to the mantle; with a spherical core the pole
   is off by 1.24" (0.82" rms), with the oblate core and the Earth's J2 (0.16" alone)
   by 0.0036" (0.0021" rms), longitude 0.0005".  From DE421's own epoch (JDEPOC,
   where the header gives the core state) to 2050: 0.003".  The published forms
   matter: the uncorrected zz element (w^2 - n^2) or leaving out dI/dt w moves the
   pole by 3.3"; the rotational term as a whole by 0.07".
4. (optional) further point masses (planets) acting on the figure.

Units: km, rad/day, GM km^3/day^2, moments in units of M R^2 (R = gravity reference
radius).  State y = [q (4), w_m (3)] or [q, w_m, w_c (3)] with a core.
"""
import math

import numpy as np
from numba import njit

from .linker import link, template
from .rotations import cross3, diag3, dot3, mat_t_vec3, matrix_from_quat, matvec3, put, quat_rate, solve3

# Layout of the float vector ``consts`` in the parameters (see moon_params).
R_KM, K2_MASS_RATIO, K2_ROT, TAU_D, KV, C_CORE, N_MEAN, F_CORE, J2E_GM_R2 = range(9)


@njit(cache=True)
def harmonic_gradient(r, radius, c_nm, s_nm, n_min, n_max):
    """grad W at r (body axes, km) for W = (1/r) sum (R/r)^n P_nm (C cos + S sin): 1/km^2.

    W is the potential per unit GM of the body, degrees n_min..n_max, unnormalised
    coefficients (C_n0 = -J_n).  Cartesian V_nm/W_nm recursion, free of polar
    singularities (Montenbruck & Gill 2000, §3.2.4-3.2.5).
    """
    top = n_max + 1
    x, y, z = r[0], r[1], r[2]
    r2 = x * x + y * y + z * z
    rho = radius * radius / r2
    x0, y0, z0 = radius * x / r2, radius * y / r2, radius * z / r2
    v = np.zeros((top + 1, top + 1))
    w = np.zeros((top + 1, top + 1))
    v[0, 0] = radius / math.sqrt(r2)
    for m in range(top + 1):
        if m > 0:
            v[m, m] = (2 * m - 1) * (x0 * v[m - 1, m - 1] - y0 * w[m - 1, m - 1])
            w[m, m] = (2 * m - 1) * (x0 * w[m - 1, m - 1] + y0 * v[m - 1, m - 1])
        if m < top:
            v[m + 1, m] = (2 * m + 1) * z0 * v[m, m]
            w[m + 1, m] = (2 * m + 1) * z0 * w[m, m]
        for n in range(m + 2, top + 1):
            v[n, m] = ((2 * n - 1) * z0 * v[n - 1, m] - (n + m - 1) * rho * v[n - 2, m]) / (n - m)
            w[n, m] = ((2 * n - 1) * z0 * w[n - 1, m] - (n + m - 1) * rho * w[n - 2, m]) / (n - m)
    ax = ay = az = 0.0
    for n in range(n_min, n_max + 1):
        c = c_nm[n, 0]
        ax -= c * v[n + 1, 1]
        ay -= c * w[n + 1, 1]
        az -= (n + 1) * c * v[n + 1, 0]
        for m in range(1, n + 1):
            c, s = c_nm[n, m], s_nm[n, m]
            fac = (n - m + 2) * (n - m + 1)
            ax += 0.5 * (-c * v[n + 1, m + 1] - s * w[n + 1, m + 1]
                         + fac * (c * v[n + 1, m - 1] + s * w[n + 1, m - 1]))
            ay += 0.5 * (-c * w[n + 1, m + 1] + s * v[n + 1, m + 1]
                         + fac * (-c * w[n + 1, m - 1] + s * v[n + 1, m - 1]))
            az += (n - m + 1) * (-c * v[n + 1, m] - s * w[n + 1, m])
    r_ref2 = radius * radius
    return np.array([ax / r_ref2, ay / r_ref2, az / r_ref2])


@njit(cache=True)
def figure_torque(inertia, r_body, gm):
    """Degree-2 torque 3 GM/r^5 r x (I r) of a point mass (Euler ch. 16 P91, §815), any I tensor."""
    r2 = r_body[0] ** 2 + r_body[1] ** 2 + r_body[2] ** 2
    return 3.0 * gm / (r2 * r2 * math.sqrt(r2)) * cross3(r_body, matvec3(inertia, r_body))


@njit(cache=True)
def oblate_earth_torque(inertia, r_body, pole_body, gm_j2_r2):
    """Torque of the Earth's J2 on a degree-2 figure I (Folkner et al. 2014, N_figM-figE), per M R^2.

    r_body: the Earth's position (km) and pole_body its unit pole, both in body axes;
    gm_j2_r2 = GM_E J2E R_E^2 (km^5/d^2).  The torque -int x x grad U_J2 dm of the
    Earth's degree-2 potential's gradient across the body (its Hessian against I).
    """
    r2 = dot3(r_body, r_body)
    r = math.sqrt(r2)
    u = r_body / r
    s = dot3(u, pole_body)
    iu, ip = matvec3(inertia, u), matvec3(inertia, pole_body)
    return 7.5 * gm_j2_r2 / (r2 * r2 * r) * ((1.0 - 7.0 * s * s) * cross3(u, iu)
                                             + 2.0 * s * (cross3(u, ip) + cross3(pole_body, iu))
                                             - 0.4 * cross3(pole_body, ip))


@njit(cache=True)
def interpolate_pole(t, pole):
    """Unit vector at TDB day t, linear in a table pole = (grid [t0, h], (m, 3) samples)."""
    grid, samples = pole
    s = min(max((t - grid[0]) / grid[1], 0.0), samples.shape[0] - 1.000001)
    k = int(s)
    v = samples[k] + (s - k) * (samples[k + 1] - samples[k])
    return v / math.sqrt(dot3(v, v))


@njit(cache=True)
def harmonic_torque(r_body, gm, radius, c_nm, s_nm, n_min, n_max):
    """Torque per unit M R^2 of a point mass GM at r_body on the body's degree n_min..n_max field.

    N = -M_A r x grad U_body(r); divided by M R^2: -(GM/R^2) r x grad W.
    """
    return -gm / (radius * radius) * cross3(r_body, harmonic_gradient(r_body, radius, c_nm, s_nm, n_min, n_max))


@njit(cache=True)
def rotate_about(v, axis, angle):
    """Rodrigues: v rotated right-handedly by ``angle`` about the unit vector ``axis``."""
    c, s = math.cos(angle), math.sin(angle)
    return v * c + cross3(axis, v) * s + axis * dot3(axis, v) * (1.0 - c)


@njit(cache=True)
def distortion(omega, r_del, v_del, consts):
    """Tidal + rotational change of the mantle inertia (M R^2) and its rate (tidal part), body axes.

    r_del, v_del: the Earth's position (km) and its rate of change in mantle axes (km/d)
    at t - tau.  The rotational part's rate (w varies by 1e-4 of n) is below 1e-12 M R^2/d
    and is left out.
    """
    k_tide = consts[K2_MASS_RATIO] * consts[R_KM] ** 3
    r2 = dot3(r_del, r_del)
    f = k_tide / (r2 * r2 * math.sqrt(r2))
    rv = dot3(r_del, v_del)
    w2, n2 = dot3(omega, omega), consts[N_MEAN] ** 2
    delta, delta_rate = np.empty((3, 3)), np.empty((3, 3))
    for i in range(3):                     # the module docstring's I_m terms, element (i, j)
        for j in range(3):
            d_ij = 1.0 if i == j else 0.0
            xx = r_del[i] * r_del[j]
            xx_rate = v_del[i] * r_del[j] + r_del[i] * v_del[j]
            tide = -f * (xx - r2 / 3.0 * d_ij)
            delta_rate[i, j] = -f * (xx_rate - 2.0 * rv / 3.0 * d_ij) + 5.0 * f * rv / r2 * (xx - r2 / 3.0 * d_ij)
            rot = omega[i] * omega[j] - (w2 - n2) / 3.0 * d_ij
            if i == 2 and j == 2:
                rot = omega[2] * omega[2] - (w2 + 2.0 * n2) / 3.0
            delta[i, j] = tide + consts[K2_ROT] * rot
    return delta, delta_rate


@njit(cache=True)
def external_torque(t, inertia, rot, r_all, gm, c_nm, s_nm, consts, pole, n_max):
    """Body-frame torque (per M R^2) of the point masses at ``r_all`` (km, ICRF) on the Moon.

    ``rot``: the body-to-ICRF matrix (its transpose takes ICRF vectors to body axes).
    The degree-2 figure torque of each mass (Euler ch. 16 P91, §815, with the
    instantaneous inertia), the Moon's degree 3..n_max field, and the Earth's
    J2 (body 0) acting on the lunar figure when its constant is nonzero.
    """
    torque = np.zeros(3)
    for i in range(gm.shape[0]):
        r_b = mat_t_vec3(rot, r_all[i])
        torque += figure_torque(inertia, r_b, gm[i])
        if n_max >= 3:
            torque += harmonic_torque(r_b, gm[i], consts[R_KM], c_nm, s_nm, 3, n_max)
    if consts[J2E_GM_R2] != 0.0:
        torque += oblate_earth_torque(inertia, mat_t_vec3(rot, r_all[0]), mat_t_vec3(rot, interpolate_pole(t, pole)),
                                      consts[J2E_GM_R2])
    return torque


@template("positions", "N_MAX")
def rigid_moon_torque(t, y, p):
    """Body-frame torque (per M R^2) on a rigid Moon (no core, no distortion); p = moon_params(...)."""
    moments, gm, data, c_nm, s_nm, consts, pole = p
    return external_torque(t, diag3(moments), matrix_from_quat(y[:4]), positions(t, data), gm, c_nm, s_nm, consts,
                           pole, N_MAX)


def make_rigid_moon_torque(positions, degree=2):
    """torque(t, y, p) of a rigid Moon (no core, no distortion), p = moon_params(...).

    The same terms as make_moon_rhs; exposed so that splitting integrators can
    alternate the free flow with torque kicks (levels 1-2).
    """
    return link(rigid_moon_torque, positions=positions, N_MAX=int(degree))


_DT_DIFF = 1e-3        # days, central difference for the Earth's velocity at t - tau


@template("positions", "N_MAX", "WITH_CORE", "WITH_TIDES")
def moon_rhs(t, y, p):
    """dy/dt of the lunar model; y = [q, w_m] or [q, w_m, w_c]; p = moon_params(...)."""
    moments, gm, data, c_nm, s_nm, consts, pole = p
    q, omega = y[:4], y[4:7]
    rot = matrix_from_quat(q)                 # body -> ICRF; mat_t_vec3(rot, v) takes v to body axes
    inertia = diag3(moments)
    inertia_rate = np.zeros((3, 3))
    if WITH_TIDES:
        tau = consts[TAU_D]
        wn = math.sqrt(dot3(omega, omega))
        axis = omega / wn
        r_del = rotate_about(mat_t_vec3(rot, positions(t - tau, data)[0]), axis, wn * tau)
        vel_i = (positions(t - tau + _DT_DIFF, data)[0] - positions(t - tau - _DT_DIFF, data)[0]) / (2 * _DT_DIFF)
        v_del = rotate_about(mat_t_vec3(rot, vel_i), axis, wn * tau) - cross3(omega, r_del)
        delta, inertia_rate = distortion(omega, r_del, v_del, consts)
        inertia = inertia + delta
    torque = external_torque(t, inertia, rot, positions(t, data), gm, c_nm, s_nm, consts, pole, N_MAX)
    dy = np.empty_like(y)
    put(dy[:4], quat_rate(q, omega))
    if WITH_CORE:                  # torques act with the whole Moon's I; the mantle turns with I - I_c
        c_core = consts[C_CORE]
        core_moments = np.array([c_core * (1.0 - consts[F_CORE]), c_core * (1.0 - consts[F_CORE]), c_core])
        inertia = inertia - diag3(core_moments)
        omega_c = y[7:10]
        n_cmb = consts[KV] * (omega_c - omega) + (c_core - core_moments[0]) * omega_c[2] * np.array(
            [-omega_c[1], omega_c[0], 0.0])
        torque += n_cmb
        put(dy[7:10], (-cross3(omega, core_moments * omega_c) - n_cmb) / core_moments)
    rhs_vec = torque - cross3(omega, matvec3(inertia, omega)) - matvec3(inertia_rate, omega)
    put(dy[4:7], solve3(inertia, rhs_vec))
    return dy


def make_moon_rhs(positions, degree=2, core=False, tides=False):
    """Compiled rhs(t, y, p) of the lunar model.

    ``positions(t, data) -> (n, 3)``: attracting bodies relative to the Moon, km, ICRF;
    body 0 must be the Earth (it raises the tide and carries J2).  ``degree``: 2, 3
    or 4 (highest degree of the Moon's field); ``core``: fluid core, y has 10
    components; ``tides``: tidal and rotational distortion.  p = moon_params(...);
    the Earth's J2 acts on the figure when its constant is nonzero.
    """
    return link(moon_rhs, positions=positions, N_MAX=int(degree), WITH_CORE=bool(core), WITH_TIDES=bool(tides))


NO_POLE = (np.array([0.0, 1.0]), np.array([[0.0, 0.0, 1.0], [0.0, 0.0, 1.0]]))


def moon_params(moments, gm, data, c_nm, s_nm, radius_km, k2=0.0, gm_moon=1.0, tau_d=0.0,
                kv_over_c=0.0, core_c_over_c=0.0, n_mean=0.0, core_flattening=0.0,
                earth_j2_gm_r2=0.0, earth_pole=NO_POLE):
    """Parameter tuple of make_moon_rhs.

    moments: (A, B, C) of the whole undistorted Moon, M R^2; gm (n,) km^3/d^2 (gm[0] = Earth);
    data: the orbit kernel's data; c_nm, s_nm (5, 5) unnormalised; k2, tau_d (days);
    kv_over_c: k_v / C (1/day); core_c_over_c: C_core / C; n_mean: mean motion, rad/day;
    core_flattening: f_c = (C_c - A_c)/C_c; earth_j2_gm_r2: GM_E J2E R_E^2 (km^5/d^2, 0 = off);
    earth_pole: (grid [t0, h] TDB days, (m, 3) unit vectors ICRF), read by interpolate_pole.
    """
    moments = np.asarray(moments, dtype=float)
    c_total = moments[2]
    consts = np.zeros(9)
    consts[R_KM] = radius_km
    consts[K2_MASS_RATIO] = k2 * gm[0] / gm_moon
    consts[K2_ROT] = k2 * radius_km**3 / (3.0 * gm_moon)
    consts[TAU_D] = tau_d
    consts[KV] = kv_over_c * c_total
    consts[C_CORE] = core_c_over_c * c_total
    consts[N_MEAN] = n_mean
    consts[F_CORE] = core_flattening
    consts[J2E_GM_R2] = earth_j2_gm_r2
    pole = (np.asarray(earth_pole[0], dtype=float), np.ascontiguousarray(earth_pole[1], dtype=float))
    return (moments, np.asarray(gm, dtype=float), data, np.ascontiguousarray(c_nm, dtype=float),
            np.ascontiguousarray(s_nm, dtype=float), consts, pole)
