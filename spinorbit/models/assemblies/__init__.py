"""Every model the scenes integrate, written as data: bodies, motion, interactions (spinorbit.models).

``moon``: the Moon's libration levels on an ephemeris; ``earth``: the rigid Earth's precession and nutation;
``earth_moon``: the Earth-Moon system integrated as one, in the solar system or closed; ``planet``: any rigid
planet from its constants (GM, J2, C22, C/MR^2, satellites as rings, geodesic precession: Mars); ``idealised``:
the free body and a rigid body under point masses (Euler's problems, the stress cases).
"""
