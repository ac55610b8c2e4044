"""The one-bounce estimate of python/translucency_pixel_bins.py on a case with a closed form."""

import numpy as np

from translucency_pixel_bins import bounce_estimate


def test_one_source_pixel_lights_a_facing_pixel_by_the_inverse_square_law():
    # A 3 × 3 patch of pixels 1 mm apart on z = 0 facing +z, radiance 1; only its middle pixel
    # has four covered neighbours, so it is the one source, of area 1 mm². The receiver, 5 mm
    # above it and facing it, gets E = L · dA / r² = 1/25.
    size = 6
    covered = np.zeros((size, size), bool)
    p = np.zeros((size, size, 3))
    n = np.zeros((size, size, 3))
    r = np.zeros((size, size, 3))
    for y in range(1, 4):
        for x in range(1, 4):
            covered[y, x] = True
            p[y, x] = (x, y, 0.0)
            n[y, x] = (0, 0, 1)
            r[y, x] = 1.0
    covered[4, 4] = True
    p[4, 4] = (2, 2, 5.0)
    n[4, 4] = (0, 0, -1)
    albedo = np.array([0.6, 0.35, 0.2])
    bounce = bounce_estimate(covered, r, n, p, albedo)
    np.testing.assert_allclose(bounce[4, 4], albedo / 25.0 / np.pi, rtol=1e-9)
    # The sources, side by side in one plane, light each other not at all, and turning the
    # receiver away from the source leaves it dark.
    assert np.all(bounce[2, 2] == 0)
    n[4, 4] = (0, 0, 1)
    assert np.all(bounce_estimate(covered, r, n, p, albedo)[4, 4] == 0)
