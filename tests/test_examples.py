"""Example networks: the committed JSON is what its generator writes, and it loads."""

import importlib.util

import batten.api as api
import pytest


@pytest.mark.parametrize("name", ["wigley", "hard_chine"])
def test_example_json_matches_its_generator(examples_dir, name):
    spec = importlib.util.spec_from_file_location(name, examples_dir / f"{name}.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    assert (examples_dir / f"{name}.json").read_text() == module.text()


def test_wigley_sections_are_exact(examples_dir):
    import numpy as np

    name, curves = api.read_network(examples_dir / "wigley.json")
    L, B, T = 100.0, 10.0, 6.25
    for c in curves:
        if not c.name.startswith("station"):
            continue
        p = c.evaluate(np.linspace(0, 1, 50))  # the underwater parabola
        x, y, z = p[:, 0], p[:, 1], p[:, 2]
        exact = B / 2 * (1 - (2 * x / L) ** 2) * (1 - ((T - z) / T) ** 2)
        np.testing.assert_allclose(y, exact, atol=1e-12)
