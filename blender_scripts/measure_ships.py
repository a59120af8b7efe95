"""Measure the real ships as a new user gets them (real-ships issue acceptance figures):
import ``shared/hulls/<ship>/network.json`` and build with every setting at its default, then
compare with ``reference.json``: displaced volume, LCB and wetted surface below the design
draught T (from the mesh, and from ``api.hydrostatics`` on the patches with the references'
Lpp, AP at x = 0), the surface's holes, folds and
normal jumps, how far the input points are from the surface, and the time taken.

    PYTHONPATH=build/native/release:addon .venv/bin/python blender_scripts/measure_ships.py

The input points' distance from the surface is measured on a finer mesh
(``DISTANCE_RESOLUTION`` intervals per patch side), so the figure is the surface's and not the
display mesh's chords (at 16 the chords alone put 43 of KCS's points past 5 mm).

Mesh figures: the triangles of the welded mesh (built at ``--resolution``, default 16) are
clipped at z = T; with the field (0, y, 0) and (0, x·y, 0) the divergence theorem gives the
half hull's volume and x-moment from the surface alone (the centreplane has y = 0, the
waterplane n_y = 0), exact for the triangles; both are doubled for the two halves.
"""

from __future__ import annotations

import argparse
import json
import sys
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent


def clipped_triangles(positions: np.ndarray, corners: np.ndarray, sizes: np.ndarray, z_max: float):
    """The mesh's polygons fanned into triangles and clipped to z ≤ ``z_max`` (each clipped
    piece fanned again): an (m, 3, 3) array."""
    tris = []
    start = 0
    for k in sizes:
        face = corners[start : start + k]
        start += k
        for i in range(1, k - 1):
            tris.append(positions[[face[0], face[i], face[i + 1]]])
    out = []
    for tri in tris:
        poly = []
        for a, b in zip(tri, np.roll(tri, -1, axis=0), strict=True):
            if a[2] <= z_max:
                poly.append(a)
            if (a[2] - z_max) * (b[2] - z_max) < 0:
                w = (z_max - a[2]) / (b[2] - a[2])
                poly.append(a + w * (b - a))
        for i in range(1, len(poly) - 1):
            out.append([poly[0], poly[i], poly[i + 1]])
    return np.array(out).reshape(-1, 3, 3)


def mesh_figures(tris: np.ndarray) -> dict:
    """Volume, LCB (x of the centre of buoyancy) and wetted area of the clipped half-hull
    triangles, both halves."""
    a, b, c = tris[:, 0], tris[:, 1], tris[:, 2]
    area_vec = 0.5 * np.cross(b - a, c - a)
    ay = area_vec[:, 1]
    ybar = (a[:, 1] + b[:, 1] + c[:, 1]) / 3.0
    volume = abs(np.sum(ybar * ay))
    # ∫ x·y dA over a triangle of linear x, y: A/12 (Σ x_i y_i + Σx Σy).
    xs, ys = tris[:, :, 0], tris[:, :, 1]
    xy = (np.sum(xs * ys, axis=1) + xs.sum(axis=1) * ys.sum(axis=1)) / 12.0
    moment = abs(np.sum(xy * ay))
    wetted = np.sum(np.linalg.norm(area_vec, axis=1))
    return {"volume": 2 * volume, "lcb": moment / volume, "wetted_surface": 2 * wetted}


def closest_on_triangles(p: np.ndarray, a: np.ndarray, b: np.ndarray, c: np.ndarray) -> np.ndarray:
    """The closest points to ``p`` on the triangles ``a b c`` (all (n, 3), row by row):
    Ericson, *Real-Time Collision Detection* §5.1.5, by Voronoi region."""
    ab, ac, ap = b - a, c - a, p - a
    d1, d2 = np.einsum("ij,ij->i", ab, ap), np.einsum("ij,ij->i", ac, ap)
    bp = p - b
    d3, d4 = np.einsum("ij,ij->i", ab, bp), np.einsum("ij,ij->i", ac, bp)
    cp = p - c
    d5, d6 = np.einsum("ij,ij->i", ab, cp), np.einsum("ij,ij->i", ac, cp)
    va, vb, vc = d3 * d6 - d5 * d4, d5 * d2 - d1 * d6, d1 * d4 - d3 * d2
    with np.errstate(divide="ignore", invalid="ignore"):
        denom = 1.0 / (va + vb + vc)
        v, w = vb * denom, vc * denom
        out = a + ab * v[:, None] + ac * w[:, None]  # inside the face
        # Edges and vertices, from the least to the most specific region.
        t_bc = (d4 - d3) / ((d4 - d3) + (d5 - d6))
        edge_bc = (va <= 0) & (d4 - d3 >= 0) & (d5 - d6 >= 0)
        out[edge_bc] = (b + (c - b) * t_bc[:, None])[edge_bc]
        t_ac = d2 / (d2 - d6)
        edge_ac = (vb <= 0) & (d2 >= 0) & (d6 <= 0)
        out[edge_ac] = (a + ac * t_ac[:, None])[edge_ac]
        t_ab = d1 / (d1 - d3)
        edge_ab = (vc <= 0) & (d1 >= 0) & (d3 <= 0)
        out[edge_ab] = (a + ab * t_ab[:, None])[edge_ab]
    out[(d6 >= 0) & (d5 <= d6)] = c[(d6 >= 0) & (d5 <= d6)]
    out[(d3 >= 0) & (d4 <= d3)] = b[(d3 >= 0) & (d4 <= d3)]
    out[(d1 <= 0) & (d2 <= 0)] = a[(d1 <= 0) & (d2 <= 0)]
    return out


#: Intervals per patch side of the mesh the input points' distance is measured on: its chords
#: stay well under a millimetre on the real ships' patches.
DISTANCE_RESOLUTION = 48

#: Triangles (nearest by centroid) that give each point a first bound on its distance.
CANDIDATES = 24


def surface_distance(points: np.ndarray, tris: np.ndarray) -> np.ndarray:
    """Distance of each point from the triangle mesh ``tris`` ((m, 3, 3)), exactly: the
    ``CANDIDATES`` triangles with the nearest centroids give a bound ``d``; every triangle
    nearer than ``d`` has its centroid within ``d`` plus the largest centroid-to-corner
    distance of the mesh, so those triangles are all searched. (The nearest centroids alone
    missed the nearest triangle among long thin ones — a flat side's patches are 100 m long —
    and put 5 of KCS's and 8 of KVLCC2's points past 5 mm that were not.)"""
    from scipy.spatial import cKDTree

    centroids = tris.mean(axis=1)
    reach = float(np.linalg.norm(tris - centroids[:, None, :], axis=2).max())
    tree = cKDTree(centroids)
    _, idx = tree.query(points, k=min(CANDIDATES, len(tris)))
    best = np.full(len(points), np.inf)
    for j in range(idx.shape[1]):
        t = tris[idx[:, j]]
        q = closest_on_triangles(points, t[:, 0], t[:, 1], t[:, 2])
        best = np.minimum(best, np.linalg.norm(points - q, axis=1))
    for i, near in enumerate(tree.query_ball_point(points, best + reach)):
        t = tris[near]
        p = np.broadcast_to(points[i], (len(near), 3))
        q = closest_on_triangles(p, t[:, 0], t[:, 1], t[:, 2])
        best[i] = min(best[i], float(np.linalg.norm(p - q, axis=1).min()))
    return best


#: A data point lies on the flat of side (bottom) when it is within this (m) of the data's own
#: side (base) plane, the one the import finds (``flat_of_bottom.side_plane``/``base_plane``:
#: KCS's side is at |y| = 16.1003 m, not the reference's B/2 = 16.1 m).
FLAT = 1e-3
#: The data near the plane (m) that the flat region is drawn between.
FLAT_NEAR = 1.0
#: A mesh vertex farther than this (m) from the plane is not on the flat, whatever the data say.
FLAT_VERTEX_NEAR = 0.05
FLAT_NEIGHBOURS = 6


def flatness(points: np.ndarray, positions: np.ndarray, axis: int, value: float) -> float:
    """Largest distance (m) from the plane ``x[axis] = value`` of the mesh vertices where the
    data are flat, 0 when they are nowhere: the data near the plane are triangulated in it
    (Delaunay), and a vertex is on the flat when the triangle it falls in has all three corners
    flat (module constants) — the region the data outline as flat, where they stay on the plane
    between their points as well as at them."""
    from scipy.spatial import Delaunay, QhullError

    other = [a for a in range(3) if a != axis]
    near = np.abs(points[:, axis] - value) <= FLAT_NEAR
    flat = np.abs(points[near, axis] - value) <= FLAT
    if flat.sum() < 3:
        return 0.0
    try:
        tri = Delaunay(points[near][:, other])
    except QhullError:
        return 0.0
    simplex = tri.find_simplex(positions[:, other])
    inside = (np.abs(positions[:, axis] - value) <= FLAT_VERTEX_NEAR) & (simplex >= 0)
    inside[inside] = flat[tri.simplices[simplex[inside]]].all(axis=1)
    return float(np.abs(positions[inside, axis] - value).max()) if inside.any() else 0.0


def flatness_nearest(points: np.ndarray, positions: np.ndarray, axis: int, value: float) -> float:
    """:func:`flatness` as the earlier measure had it: a mesh vertex is on the flat when its
    :data:`FLAT_NEIGHBOURS` nearest data points all are. Where the data leave the flat along a
    curve whose next point is farther than those six (KVLCC2's wl_z23.50 at x = 82 m, between a
    point 0.5 mm and one 2.5 mm off the side), it counts the surface leaving with them."""
    from scipy.spatial import cKDTree

    flat = np.abs(points[:, axis] - value) <= FLAT
    if flat.sum() < FLAT_NEIGHBOURS:
        return 0.0
    _, idx = cKDTree(points).query(positions, k=FLAT_NEIGHBOURS)
    inside = flat[idx].all(axis=1)
    return float(np.abs(positions[inside, axis] - value).max()) if inside.any() else 0.0


def measure(api, ship: Path, resolution: int) -> dict:
    import bpy

    bpy.ops.wm.read_homefile(use_empty=True, use_factory_startup=True)
    ref = json.loads((ship / "reference.json").read_text())
    data = json.loads((ship / "network.json").read_text())
    t0 = time.perf_counter()
    coll, fits = api.import_sections(ship / "network.json", collection=ship.name)
    t1 = time.perf_counter()
    result = api.build(coll)
    t2 = time.perf_counter()
    r = result.report
    from batten_native import build_surface

    curves, planes = api.read_curves(coll), api.tangent_planes(coll)
    (positions, corners, sizes, _), _ = build_surface(curves, resolution=resolution, tangent_planes=planes)
    T, lpp = ref["T"], ref["Lpp"]
    fig = mesh_figures(clipped_triangles(positions, corners, sizes, T))
    c = ref["computed"]
    points = np.array([p for curve in data["curves"] for p in curve["points"]])
    fine, _ = build_surface(curves, resolution=DISTANCE_RESOLUTION, tangent_planes=planes)
    dist = surface_distance(points, clipped_triangles(*fine[:3], np.inf))
    from batten import flat_of_bottom
    from batten_native import DEFAULT_SECTION_MODEL_TOLERANCE

    side = flat_of_bottom.side_plane(points, DEFAULT_SECTION_MODEL_TOLERANCE)
    base = flat_of_bottom.base_plane(points, DEFAULT_SECTION_MODEL_TOLERANCE)
    warnings = {}
    for w in r["warnings"]:
        warnings[w["kind"]] = warnings.get(w["kind"], 0) + 1
    try:
        h = api.hydrostatics(coll, T, lpp=lpp, fp=lpp)
        hydro = {
            "volume_diff_pct": 100 * (h["volume"] / c["displaced_volume"] - 1),
            "lcb_diff_pct_lpp": 100 * (h["lcb"] - c["LCB_from_AP"]) / lpp,
            "vcb_diff_pct": 100 * (h["vcb"] / c["VCB_above_baseline_brep"] - 1),
            "waterplane_area_diff_pct": 100 * (h["waterplane_area"] / c["waterplane_area"] - 1),
            "lcf_diff_pct_lpp": 100 * (h["lcf"] - c["LCF_from_AP"]) / lpp,
            "wetted_area_diff_pct": 100 * (h["wetted_area"] / c["wetted_surface_below_T"] - 1),
            "cb": h["cb"],
            "cb_reference": c["Cb"],
            "cm": h["cm"],
            "cm_reference": c["Cm"],
            "lwl": h["lwl"],
            "lwl_reference": c["Lwl_at_T"],
        }
    except api.BattenError as e:
        hydro = {"error": str(e)}
    return {
        "ship": ship.name,
        "hydrostatics": hydro,
        "import_s": round(t1 - t0, 3),
        "build_s": round(t2 - t1, 3),
        "faces": r["faces"],
        "holes": r["holes"],
        "folds": r["folds"],
        "side_blended": warnings.get("side_blended", 0),
        "near_misses": warnings.get("near_miss", 0),
        "warnings": warnings,
        "max_normal_angle_deg": r["max_normal_angle_deg"],
        "max_normal_angle_at": r["max_normal_angle_at"],
        "max_point_deviation_from_curve_mm": 1e3 * max(f["max_deviation"] for f in fits),
        "max_point_distance_from_surface_mm": 1e3 * float(dist.max()),
        "points_beyond_5_mm": int((dist > 0.005).sum()),
        "points": len(points),
        "flat_of_side_plane_m": side,
        "flat_of_side_max_mm": 1e3 * flatness(points, positions, 1, side) if side is not None else None,
        "flat_of_side_max_mm_nearest6": 1e3 * flatness_nearest(points, positions, 1, side)
        if side is not None
        else None,
        "flat_of_bottom_plane_m": base,
        "flat_of_bottom_max_mm": 1e3 * flatness(points, positions, 2, base) if base is not None else None,
        "crease_angles_deg": r["crease_angles_deg"],
        "volume": fig["volume"],
        "volume_diff_pct": 100 * (fig["volume"] / c["displaced_volume"] - 1),
        "lcb_diff_pct_lpp": 100 * (fig["lcb"] - c["LCB_from_AP"]) / lpp,
        "wetted_surface_diff_pct": 100 * (fig["wetted_surface"] / c["wetted_surface_below_T"] - 1),
    }


def main() -> None:
    argv = sys.argv[sys.argv.index("--") + 1 :] if "--" in sys.argv else sys.argv[1:]
    ap = argparse.ArgumentParser(prog="measure_ships.py")
    ap.add_argument("--ships", type=Path, default=ROOT.parent / "shared" / "hulls")
    ap.add_argument("--resolution", type=int, default=16)
    args = ap.parse_args(argv)
    sys.path.insert(0, str(ROOT / "addon"))
    import batten

    batten.register()
    from batten import api

    for ship in sorted(p.parent for p in args.ships.glob("*/network.json")):
        print(json.dumps(measure(api, ship, args.resolution), indent=1))


if __name__ == "__main__":
    main()
