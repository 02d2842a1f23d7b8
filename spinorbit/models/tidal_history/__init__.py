"""The Earth-Moon system over the Moon's age: orbit-averaged tidal equations that keep the angular momentum
(``equations``), the secular tidal exchange for any tidal response (``secular``), the tidal responses
(``response``), today's rates and the one-parameter fits (``calibration``), the precession constant and the
Milankovitch periods (``milankovitch``)."""
