"""The real-ships measurement's own arithmetic (``blender_scripts/measure_ships.py``): a
point's distance from a triangle mesh is exact even where the nearest triangle is long and
its centroid far away."""

import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "blender_scripts"))
from measure_ships import CANDIDATES, surface_distance  # noqa: E402


def test_the_nearest_triangle_counts_even_when_its_centroid_is_far():
    # A long thin triangle 1 mm under the point, its centroid 60 m away, and more small
    # triangles than the bound searches 10 mm under it, their centroids close by.
    long = [[-10.0, -1.0, -0.001], [170.0, -1.0, -0.001], [10.0, 1.0, -0.001]]
    small = [
        [[x - 0.1, -0.1, -0.01], [x + 0.1, -0.1, -0.01], [x, 0.1, -0.01]]
        for x in np.linspace(-0.5, 0.5, 2 * CANDIDATES)
    ]
    tris = np.array([long, *small])
    d = surface_distance(np.zeros((1, 3)), tris)
    assert abs(d[0] - 0.001) < 1e-12, f"the long triangle is the nearest: got {d[0]} m"


def test_distances_from_a_fine_mesh_of_a_plane_are_the_heights():
    xs = np.linspace(0.0, 10.0, 21)
    grid = [
        [[a, b, 0.0], [c, b, 0.0], [a, d, 0.0]]
        for a, c in zip(xs[:-1], xs[1:], strict=True)
        for b, d in zip(xs[:-1], xs[1:], strict=True)
    ]
    points = np.array([[3.3, 7.1, 0.25], [0.0, 0.0, -2.0], [9.9, 0.1, 0.0]])
    d = surface_distance(points, np.array(grid))
    assert np.allclose(d, [0.25, 2.0, 0.0], atol=1e-12), d
