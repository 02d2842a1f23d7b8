"""Named units for test tolerances (radians per unit), as in skyfield's tests."""
import math

arcsec = math.pi / (180 * 3600)
mas = arcsec / 1000
deg = math.pi / 180
