"""Mesh hydrostatics beside navaltoolbox and trimesh: one 1,000,000-triangle hull, one draft.

The hull: a closed Wigley hull (L = 100 m, B = 10 m, T = 6.25 m; y = B/2 (1 - (2x/L)^2)
(1 - ((T - z)/T)^2) below the waterline, wall-sided above it to a flat deck at 1.5 T), both
sides, triangulated on a 1,036 x 241 grid per side (998,704 side triangles and the deck's
strip; the waterline at T falls between grid rows). Its vertices are rounded to float32,
because navaltoolbox reads the mesh from a binary STL file: both tools then get the identical
polyhedron.

batten, at draft T about AP = -L/2, FP = L/2: ``MeshHull.hydrostatics`` on the hull built
once (as navaltoolbox's calculator is timed on its loaded hull), and ``mesh_hydrostatics``
from the numpy arrays in one call (building the hull included: validation, free edges, runs).
navaltoolbox (PyPI, AGPL-3.0: used only here, never by batten; install it apart, e.g.
``pip install --target /tmp/ntb navaltoolbox``, and put /tmp/ntb on PYTHONPATH after batten's
own paths) gets the STL, AP and FP, and ``HydrostaticsCalculator(...).from_draft(T)`` is timed
with the hull already loaded. trimesh: the mass properties (signed tetrahedra) of the
submerged polyhedron, cut here in numpy: each triangle clipped at z = T, the waterplane closed
by a fan from midships.

Reported: best-of-N times and their ratio, and volume, LCB, KB, BMt, Awp from each with the
relative differences (the issue asks for 1e-6).

    PYTHONPATH=build/native/release:/tmp/ntb .venv/bin/python blender_scripts/bench_hydrostatics.py
"""

from __future__ import annotations

import os
import sys
import tempfile
import time
from pathlib import Path

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import batten_native as bn
import numpy as np
import trimesh

L, B, T = 100.0, 10.0, 6.25
DEPTH = 1.5 * T
NX, NZ = 1036, 241  # no grid row at z = T = (2/3) DEPTH: the water cuts triangles
RHO = 1.025  # t/m^3 (navaltoolbox: kg/m^3)


def best(fn, repeat):
    out, times = None, []
    for _ in range(repeat):
        t0 = time.perf_counter()
        out = fn()
        times.append(time.perf_counter() - t0)
    return out, min(times)


def wigley(nx=NX, nz=NZ):
    """The closed Wigley hull: vertices (float64) and outward triangles. The keel (z = 0) and
    the stem and stern (x = +-L/2) lie on y = 0 and are shared by both sides."""
    rows = nz
    xs = np.linspace(-L / 2, L / 2, nx + 1)
    zs = np.linspace(0.0, DEPTH, nz + 1)
    xg, zg = np.meshgrid(xs, zs, indexing="ij")
    depth = np.clip((T - zg) / T, 0.0, None)
    yg = 0.5 * B * (1 - (2 * xg / L) ** 2) * (1 - depth**2)
    on_centre = (np.arange(nx + 1)[:, None] % nx == 0) | (np.arange(rows + 1)[None, :] == 0)
    on_centre = np.broadcast_to(on_centre, xg.shape)
    n_port = xg.size
    port = np.arange(n_port).reshape(xg.shape)
    star = np.full(xg.shape, -1)
    star[~on_centre] = n_port + np.arange(np.count_nonzero(~on_centre))
    star[on_centre] = port[on_centre]
    yg[on_centre] = 0.0
    pts = np.stack([xg, yg, zg], axis=-1).reshape(-1, 3)
    pts_star = pts[port[~on_centre]] * (1.0, -1.0, 1.0)
    positions = np.vstack([pts, pts_star])

    def quads(ix):
        a, b = ix[:-1, :-1], ix[1:, :-1]
        c, d = ix[1:, 1:], ix[:-1, 1:]
        return a.ravel(), b.ravel(), c.ravel(), d.ravel()

    a, b, c, d = quads(port)
    port_tris = np.concatenate([np.stack([a, c, b], 1), np.stack([a, d, c], 1)])  # outward +y
    a, b, c, d = quads(star)
    star_tris = np.concatenate([np.stack([a, b, c], 1), np.stack([a, c, d], 1)])  # outward -y
    p, s = port[:, -1], star[:, -1]
    deck = np.concatenate([np.stack([s[:-1], s[1:], p[1:]], 1), np.stack([s[:-1], p[1:], p[:-1]], 1)])
    triangles = np.concatenate([port_tris, star_tris, deck])
    # Leave out triangles with a repeated corner (the deck's ends) and those lying wholly in the
    # centreplane (at the stem's foot, where keel and stem meet: the same on both sides).
    keep = (
        (triangles[:, 0] != triangles[:, 1])
        & (triangles[:, 1] != triangles[:, 2])
        & (triangles[:, 2] != triangles[:, 0])
        & np.any(positions[triangles][:, :, 1] != 0.0, axis=1)
    )
    return positions, triangles[keep]


def submerged(positions, triangles, draft):
    """The polyhedron below z = ``draft`` as a triangle soup: every triangle clipped there (one
    or two wet pieces, the winding kept) and the waterplane closed by a fan of triangles from
    (0, 0, draft) to each piece's waterline segment."""
    p, z = positions[triangles], positions[triangles][:, :, 2] - draft
    wet = z <= 0
    n = wet.sum(axis=1)
    centre = np.array([0.0, 0.0, draft])

    def rotated(sel, first):
        k = np.flatnonzero(sel)
        i = first[k]
        pick = [p[k, (i + s) % 3] for s in range(3)]
        zz = [z[k, (i + s) % 3][:, None] for s in range(3)]
        return pick, zz

    def cut(a, b, za, zb):
        return a + (b - a) * (za / (za - zb))

    pieces = [p[n == 3]]
    (a, b, c), (za, zb, zc) = rotated(n == 1, np.argmax(wet, axis=1))
    ab, ac = cut(a, b, za, zb), cut(a, c, za, zc)
    pieces += [np.stack([a, ab, ac], 1), np.stack([np.broadcast_to(centre, ac.shape), ac, ab], 1)]
    (a, b, c), (za, zb, zc) = rotated(n == 2, np.argmin(wet, axis=1))
    ab, ca = cut(a, b, za, zb), cut(c, a, zc, za)
    pieces += [np.stack([ab, b, c], 1), np.stack([ab, c, ca], 1)]
    pieces += [np.stack([np.broadcast_to(centre, ab.shape), ab, ca], 1)]
    soup = np.concatenate(pieces)
    return trimesh.Trimesh(soup.reshape(-1, 3), np.arange(3 * len(soup)).reshape(-1, 3), process=False)


def write_stl(path, positions, triangles):
    """A binary STL (float32, as the format is)."""
    corners = positions[triangles].astype(np.float32)
    normals = np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0])
    normals /= np.maximum(np.linalg.norm(normals, axis=1, keepdims=True), 1e-30)
    record = np.dtype([("n", "<f4", 3), ("v", "<f4", (3, 3)), ("attr", "<u2")])
    data = np.zeros(len(triangles), dtype=record)
    data["n"], data["v"] = normals, corners
    with open(path, "wb") as f:
        f.write(b"batten bench_hydrostatics".ljust(80, b" "))
        f.write(np.uint32(len(triangles)).tobytes())
        f.write(data.tobytes())


def rel(a, b):
    return abs(a - b) / max(abs(b), 1e-300)


def main():
    positions, triangles = wigley()
    positions = positions.astype(np.float32).astype(np.float64)  # what the STL holds
    print(f"Wigley hull: {len(triangles):,} triangles, {len(positions):,} vertices, draft {T} m")
    closed = trimesh.Trimesh(positions, triangles, process=False)
    print(f"  closed: {closed.is_watertight}, winding consistent: {closed.is_winding_consistent}")

    t0 = time.perf_counter()
    hull = bn.MeshHull(positions, triangles)
    t_build = time.perf_counter() - t0
    h, t_batten = best(lambda: hull.hydrostatics(T, lpp=L, fp=L / 2), 10)
    _, t_once = best(lambda: bn.mesh_hydrostatics(positions, triangles, T, lpp=L, fp=L / 2), 5)
    rows = {"batten": h}
    print(
        f"batten MeshHull.hydrostatics: {t_batten * 1e3:.1f} ms (best of 10;"
        f" building it {t_build * 1e3:.0f} ms)"
    )
    print(f"batten mesh_hydrostatics from the arrays: {t_once * 1e3:.1f} ms (best of 5)")

    wet = submerged(positions, triangles, T)
    rows["trimesh"] = {
        "volume": wet.volume,
        "displacement": RHO * wet.volume,
        "lcb": wet.center_mass[0],
        "vcb": wet.center_mass[2],
    }

    try:
        import navaltoolbox as ntb
    except ImportError:
        ntb = None
        print("navaltoolbox is not installed: `pip install --target /tmp/ntb navaltoolbox` and")
        print("  put /tmp/ntb on PYTHONPATH (AGPL: never into batten's requirements)")
    if ntb is not None:
        with tempfile.TemporaryDirectory() as tmp:
            stl = Path(tmp) / "wigley.stl"
            write_stl(stl, positions, triangles)
            t0 = time.perf_counter()
            vessel = ntb.Vessel(ntb.Hull(str(stl)))
            t_load = time.perf_counter() - t0
        vessel.ap, vessel.fp = -L / 2, L / 2
        calc = ntb.HydrostaticsCalculator(vessel, water_density=RHO * 1000.0)
        state, t_ntb = best(lambda: calc.from_draft(T), 3)
        print(
            f"navaltoolbox from_draft: {t_ntb * 1e3:.1f} ms (best of 3; loading the STL {t_load:.2f} s more)"
        )
        print(f"ratio, per draft on the built hull: batten is {t_ntb / t_batten:.0f}x faster")
        print(f"ratio, batten from the arrays in one call: {t_ntb / t_once:.0f}x faster")
        rows["navaltoolbox"] = {
            "volume": state.volume,
            "displacement": state.displacement / 1000.0,
            "lcb": state.lcb,
            "vcb": state.vcb,
            "bmt": state.bmt,
            "bml": state.bml,
            "waterplane_area": state.waterplane_area,
            "lcf": state.lcf,
            "wetted_area": state.wetted_surface_area,
        }

    keys = ["volume", "displacement", "lcb", "vcb", "bmt", "bml", "waterplane_area", "lcf", "wetted_area"]
    analytic = {
        "volume": 4 / 9 * L * B * T,
        "vcb": 5 * T / 8,
        "bmt": 3 * B * B / (35 * T),
        "waterplane_area": 2 / 3 * L * B,
    }
    print(
        f"\n{'figure':<16}{'batten':>18}"
        + "".join(f"{k:>18}{'rel. diff':>11}" for k in rows if k != "batten")
    )
    for k in keys:
        line = f"{k:<16}{h[k]:>18.10f}"
        for name, r in rows.items():
            if name == "batten":
                continue
            if k in r:
                line += f"{r[k]:>18.10f}{rel(h[k], r[k]):>11.1e}"
            else:
                line += f"{'':>18}{'':>11}"
        print(line)
    print("\nmesh against the analytic Wigley hull (the mesh's own error, 1,036 x 241 grid):")
    for k, v in analytic.items():
        print(f"  {k:<16}{h[k]:>16.8f}{v:>16.8f}  rel {rel(h[k], v):.1e}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
