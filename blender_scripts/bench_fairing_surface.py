"""Surface fairing through families of sections (seed 003) beside Taubin lambda|mu smoothing of
the surface mesh (the paper's discrete peer, Taubin 1995), on the same noisy input.

The paper's test (Pla et al. 1998, section 5): a clean hull's stations and waterlines are moved
along their normals by noise uniform in +-30 % of the tolerance (10 mm), carried along at the
nodes so the network stays exact (``batten_native.section_noise``), then faired within the
tolerance (``batten_native.fair_sections``, both families). Hulls: the Wigley lines
(examples/wigley_lines.json), the frigate (examples/frigate_network.json), the Wigley hull at 21
stations and 8 waterlines (examples/wigley.py) and, when
../shared/hulls is there, KCS as ``api.import_sections`` builds it.

Reported per hull: the largest distance from the clean hull (curves at equal parameters; for
the meshes, vertex to vertex of the same tessellation), the hull's curvature variation
Sigma int kappa'^2 ds over its sections and their inflections (clean, noisy, faired), the change of
the enclosed volume against the clean hull, the fairing time (best of 3; run the release
build); then Taubin's smoothing of the noisy surface mesh (lambda = 0.5, mu = -0.53, boundary
vertices kept, the pass count that brings it nearest the clean hull, at most 50, and 10
passes) beside batten's faired surface mesh: largest distance from the clean mesh and the
mesh's curvature variation (the summed squared differences of the umbrella Laplacian's length across edges);
distances from a mesh are to the tangent plane at its nearest vertex, with the share of the
vertices within the tolerance of the clean mesh.

    PYTHONPATH=build/native/release:addon .venv/bin/python blender_scripts/bench_fairing_surface.py
"""

from __future__ import annotations

import os
import sys
import time
from pathlib import Path

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import batten_native as bn
import numpy as np
from scipy.spatial import cKDTree

ROOT = Path(__file__).resolve().parent.parent
KCS = ROOT.parent / "shared" / "hulls" / "kcs" / "network.json"
TOL = 0.01
NOISE = 0.3 * TOL
SEED = 3
TAUBIN_LAMBDA, TAUBIN_MU, TAUBIN_PASSES = 0.5, -0.53, 50
#: Passes of Taubin's smoothing for its second row: a smoothing a user would see.
TAUBIN_FIXED_PASSES = 10
#: Intervals per patch side of the meshes compared (dense enough that vertex-to-nearest-vertex
#: distances are distances to the surface within a fraction of a millimetre on the Wigley).
MESH_RESOLUTION = 16


def best(fn, repeat=3):
    out, times = None, []
    for _ in range(repeat):
        t0 = time.perf_counter()
        out = fn()
        times.append(time.perf_counter() - t0)
    return out, min(times)


def apart(a: list, b: list) -> float:
    """Largest distance between two lists of curves at equal parameters."""
    worst = 0.0
    for ca, cb in zip(a, b, strict=True):
        t = np.linspace(*ca.domain, 201)
        worst = max(
            worst,
            float(np.linalg.norm(np.asarray(ca.evaluate(t)) - np.asarray(cb.evaluate(t)), axis=1).max()),
        )
    return worst


def figures(curves: list, fixed: list) -> dict:
    """The hull's fairness figures as fair_sections measures them (no round made)."""
    return bn.fair_sections(curves, tolerance=TOL, fixed_curves=fixed, max_rounds=0)[1]["before"]


def mesh(curves: list, model_tolerance: float):
    (positions, corners, sizes, _), report, _ = bn.build_hull_model(curves, model_tolerance, MESH_RESOLUTION)
    return np.asarray(positions), np.asarray(corners), np.asarray(sizes), report["volume"]


def face_edges(corners, sizes) -> np.ndarray:
    """Every side of every face as a sorted vertex pair (a shared edge twice)."""
    starts = np.concatenate([[0], np.cumsum(sizes)[:-1]])
    pairs = []
    for s, n in zip(starts, sizes, strict=True):
        f = corners[s : s + n]
        pairs.append(np.column_stack([f, np.roll(f, -1)]))
    return np.sort(np.concatenate(pairs), axis=1)


def edges_of(corners, sizes) -> np.ndarray:
    return np.unique(face_edges(corners, sizes), axis=0)


def umbrella(p, edges, n) -> np.ndarray:
    """The umbrella Laplacian: the mean of a vertex's neighbours minus the vertex."""
    total = np.zeros_like(p)
    count = np.zeros(n)
    np.add.at(total, edges[:, 0], p[edges[:, 1]])
    np.add.at(total, edges[:, 1], p[edges[:, 0]])
    np.add.at(count, edges[:, 0], 1)
    np.add.at(count, edges[:, 1], 1)
    return total / count[:, None] - p


def boundary(corners, sizes, n) -> np.ndarray:
    """The vertices on the mesh's open boundary (edges of one face)."""
    uniq, count = np.unique(face_edges(corners, sizes), axis=0, return_counts=True)
    fixed = np.zeros(n, dtype=bool)
    fixed[uniq[count == 1].ravel()] = True
    return fixed


def mesh_variation(p, edges) -> float:
    h = np.linalg.norm(umbrella(p, edges, len(p)), axis=1)
    return float(np.sum((h[edges[:, 0]] - h[edges[:, 1]]) ** 2))


class Surface:
    """A mesh as the surface it stands for: a point's distance from it is the distance to the
    tangent plane at the nearest vertex (area-weighted normal), which a dense mesh gives within
    a fraction of a millimetre for points near it, whether they slid along it or not."""

    def __init__(self, p, corners, sizes):
        self.tree = cKDTree(p)
        self.p = p
        normals = np.zeros_like(p)
        starts = np.concatenate([[0], np.cumsum(sizes)[:-1]])
        for s, n in zip(starts, sizes, strict=True):
            f = corners[s : s + n]
            a = np.cross(p[f[1]] - p[f[0]], p[f[-1]] - p[f[0]])
            normals[f] += a
        self.n = normals / np.maximum(np.linalg.norm(normals, axis=1), 1e-300)[:, None]

    def distances(self, q) -> np.ndarray:
        """The distances of the points ``q`` from the surface."""
        i = self.tree.query(q)[1]
        return np.abs(np.einsum("ij,ij->i", q - self.p[i], self.n[i]))

    def distance(self, q) -> float:
        """The largest distance of the points ``q`` from the surface."""
        return float(self.distances(q).max())

    def share_within(self, q, limit: float) -> float:
        """The share of the points ``q`` within ``limit`` of the surface."""
        return float(np.mean(self.distances(q) <= limit))


def taubin(p, edges, fixed, clean: Surface):
    """Taubin's lambda|mu passes on the free vertices: the pass nearest the clean surface (and
    how many passes that was), and the mesh after ``TAUBIN_FIXED_PASSES``."""
    q = p.copy()
    best_q, best_d, best_k, fixed_q = q.copy(), clean.distance(q), 0, None
    for k in range(1, TAUBIN_PASSES + 1):
        for f in (TAUBIN_LAMBDA, TAUBIN_MU):
            step = f * umbrella(q, edges, len(q))
            step[fixed] = 0.0
            q = q + step
        d = clean.distance(q)
        if d < best_d:
            best_q, best_d, best_k = q.copy(), d, k
        if k == TAUBIN_FIXED_PASSES:
            fixed_q = q.copy()
    return best_q, best_d, best_k, fixed_q


def kcs_curves():
    """KCS as api.import_sections draws it (needs bpy)."""
    import batten.api as api

    coll, _ = api.import_sections(KCS)
    return api.read_curves(coll)


def run(name: str, clean: list, model_tolerance: float = bn.DEFAULT_TOLERANCE, fixed=()) -> None:
    fixed = list(fixed)
    noisy = bn.section_noise(clean, NOISE, SEED, fixed_curves=fixed, model_tolerance=model_tolerance)
    (faired, report), seconds = best(
        lambda: bn.fair_sections(noisy, tolerance=TOL, fixed_curves=fixed, model_tolerance=model_tolerance)
    )
    fc, fn, ff = figures(clean, fixed), report["before"], report["after"]
    print(
        f"\n== {name}: {report['sections']}, {report['moves']} moves in {report['rounds']} rounds, "
        f"converged {report['converged']}, {seconds * 1e3:.0f} ms"
    )
    print(
        f"  from the clean hull: noisy {apart(clean, noisy) * 1e3:.2f} mm,"
        f" faired {apart(clean, faired) * 1e3:.2f} mm;"
        f" from the noisy input {report['max_deviation'] * 1e3:.2f} mm (tolerance {TOL * 1e3:.0f} mm)"
    )
    kc, kn, kf = (f["curvature_variation"] for f in (fc, fn, ff))
    print(
        f"  Sigma int kappa'^2 ds: clean {kc:.4g}, noisy {kn:.4g}, faired {kf:.4g}"
        f" (noisy/faired {kn / kf:.1f}x, faired/clean {kf / kc:.2f}x)"
    )
    print(f"  inflections: clean {fc['inflections']}, noisy {fn['inflections']}, faired {ff['inflections']}")
    try:
        pc, corners, sizes, vc = mesh(clean, model_tolerance)
        pn, corners_n, sizes_n, vn = mesh(noisy, model_tolerance)
        pf, corners_f, sizes_f, vf = mesh(faired, model_tolerance)
    except bn.BattenError as e:
        print(f"  (no surface: {e})")
        return
    print(
        f"  enclosed volume: noisy {100 * (vn - vc) / vc:+.4f} %,"
        f" faired {100 * (vf - vc) / vc:+.4f} % of the clean"
    )
    tc, tn = Surface(pc, corners, sizes), Surface(pn, corners_n, sizes_n)
    edges = edges_of(corners_n, sizes_n)
    fixed = boundary(corners_n, sizes_n, len(pn))
    pt, dt, kt, p10 = taubin(pn, edges, fixed, tc)
    fedges = edges_of(corners_f, sizes_f)
    mc, mn, mf, mt = (
        mesh_variation(pc, edges_of(corners, sizes)),
        mesh_variation(pn, edges),
        mesh_variation(pf, fedges),
        mesh_variation(pt, edges),
    )
    within = f"within {TOL * 1e3:.0f} mm of clean"
    print(f"  surface mesh        from clean   from noisy   curvature variation   {within}")
    print(
        f"    noisy              {tc.distance(pn) * 1e3:7.2f} mm                 {mn:<20.4g}"
        f"  {tc.share_within(pn, TOL):.2%}"
    )
    print(
        f"    batten (sections)  {tc.distance(pf) * 1e3:7.2f} mm   {tn.distance(pf) * 1e3:7.2f} mm"
        f"   {mf:<20.4g}  {tc.share_within(pf, TOL):.2%}"
    )
    print(
        f"    Taubin, {kt:2d} passes  {dt * 1e3:7.2f} mm   {tn.distance(pt) * 1e3:7.2f} mm"
        f"   {mt:<20.4g}  {tc.share_within(pt, TOL):.2%}"
    )
    m10 = mesh_variation(p10, edges)
    d10, n10 = tc.distance(p10), tn.distance(p10)
    print(
        f"    Taubin, {TAUBIN_FIXED_PASSES} passes  {d10 * 1e3:7.2f} mm   {n10 * 1e3:7.2f} mm"
        f"   {m10:<20.4g}  {tc.share_within(p10, TOL):.2%}"
    )
    print(f"    clean                                         {mc:.4g}")


def fine_wigley() -> list:
    """The Wigley hull of examples/wigley.py with 21 stations at L/22 and 8 waterlines at T/8."""
    import json

    sys.path.insert(0, str(ROOT / "examples"))
    import wigley

    xs = [wigley.L * k / 22.0 for k in range(-10, 11)]
    zs = [wigley.T * k / 8.0 for k in range(1, 9)]
    return bn.network_from_json(json.dumps(wigley.network(xs, zs, "wigley 21x8")))[1]


def main() -> None:
    for file in ("wigley_lines.json", "frigate_network.json"):
        _, curves, _ = bn.network_from_json((ROOT / "examples" / file).read_text())
        run(file, curves)
    run("Wigley, 21 stations x 8 waterlines", fine_wigley())
    if KCS.exists() and "--no-kcs" not in sys.argv:
        try:
            import bpy  # noqa: F401
        except ImportError:
            print("\n(KCS needs bpy for api.import_sections)")
            return
        curves = kcs_curves()
        # The profile, the upper edge and the chines are the outline: fixed by name (the drawn
        # objects of import_sections carry role free).
        outline = [c.name for c in curves if c.name.startswith(("profile", "deck", "chine"))]
        run("KCS (import_sections)", curves, fixed=outline)


if __name__ == "__main__":
    main()
