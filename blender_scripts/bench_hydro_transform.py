"""Hydrostatic transformation (seed 002 §8) beside a plain Lackenby transform, on the PMB
barge of ``tests/test_form.py`` floating at 8 m, for three targets: Cb + 0.01 with the LCB held,
LCB + 0.25 % Lpp with ∇ held, and both (Cb + 0.01, LCB + 0.2 % Lpp).

- **batten**: ``batten_native.transform_hydrostatic`` (the PMB's ends moved through the form
  topology; the ends, deck and flats keep their shape).
- **plain Lackenby** (written here only, as FREE!ship's Lackenby dialog does it): every control
  point of every curve shifted along x, forward of midships by ``a_f·(x_F − x)`` and aft by
  ``−a_a·(x − x_A)`` (the shift falls linearly to zero at the hull's ends), ``a_f`` and
  ``a_a`` found by Newton's method (finite differences) on the same exact hydrostatics.

For each: whether the targets are met (|δ∇|/∇ ≤ 1e-5, |δLCB| ≤ 1e-5 Lpp), the hull
evaluations, the time (median of RUNS), and what happened to the curves a hull designer keeps:
the deck edge's shape (the largest distance of points along the new deck from the original
deck), and for the flat-of-side and flat-of-bottom curves how far their ends moved (where the
flats run out into the deck and the keel) and how far they left their planes.

    PYTHONPATH=build/native/release:addon:tests .venv/bin/python blender_scripts/bench_hydro_transform.py
"""

from __future__ import annotations

import statistics
import sys
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "tests"))

import batten_native as bn  # noqa: E402

T = 8.0
RUNS = 5
#: Points along the deck at which its change of shape is measured.
SAMPLES = 200
VOLUME_TOLERANCE, LCB_TOLERANCE = 1e-5, 1e-5


def _figures(curves, lpp, fp):
    _, _, model = bn.build_hull_model(curves)
    h = model.hydrostatics(T, lpp=lpp, fp=fp)
    return h["volume"], h["lcb"]


def _lackenby(curves, a_f, a_a, x_mid, x_aft, x_fwd):
    out = []
    for c in curves:
        p = np.array(c.control_points)
        x = p[:, 0]
        shift = np.where(x >= x_mid, a_f * (x_fwd - x), -a_a * (x - x_aft))
        p[:, 0] = x + shift
        out.append(bn.Curve(c.name, c.degree, c.knots, p, c.weights, c.role))
    return out


def plain_lackenby(curves, volume, lcb, lpp, fp, x_mid, x_aft, x_fwd):
    """Newton on (a_f, a_a) with a finite-difference Jacobian: the curves, the evaluations."""
    scale = np.array([volume, lpp])
    target = np.array([volume, lcb])
    a = np.zeros(2)
    evaluations = 0

    def misses(a):
        nonlocal evaluations
        evaluations += 1
        v, x = _figures(_lackenby(curves, a[0], a[1], x_mid, x_aft, x_fwd), lpp, fp)
        return (np.array([v, x]) - target) / scale

    f = misses(a)
    h = 1e-4
    while evaluations < 30:
        if abs(f[0]) <= VOLUME_TOLERANCE and abs(f[1]) <= LCB_TOLERANCE:
            break
        jac = np.column_stack([(misses(a + h * e) - f) / h for e in np.eye(2)])
        a = a - np.linalg.solve(jac, f)
        f = misses(a)
    return _lackenby(curves, a[0], a[1], x_mid, x_aft, x_fwd), evaluations, f


def kept_curves(before, after) -> str:
    """What moved of the curves a designer keeps: the deck's shape change, and the flats'
    end movement and distance from their planes (mm)."""
    old = {c.name: c for c in before}
    new = {c.name: c for c in after}
    deck = new["deck"]
    pts = np.asarray(deck.evaluate(np.linspace(*deck.domain, SAMPLES)))
    off_deck = max(old["deck"].nearest(p.tolist())[1] for p in pts)
    parts = [f"deck shape {off_deck * 1e3:.1f}"]
    for name in ("fos", "fob"):
        a, b = np.array(old[name].control_points), np.array(new[name].control_points)
        ends = max(np.linalg.norm(b[0] - a[0]), np.linalg.norm(b[-1] - a[-1]))
        # The plane of the original flat: through its control points (least squares).
        centre = a.mean(axis=0)
        normal = np.linalg.svd(a - centre)[2][-1]
        off_plane = float(np.abs((b - centre) @ normal).max())
        parts.append(f"{name} ends {ends * 1e3:.1f}, off plane {off_plane * 1e3:.1f}")
    return "; ".join(parts) + " (mm)"


def _median_s(f) -> float:
    times = []
    for _ in range(RUNS):
        t0 = time.perf_counter()
        f()
        times.append(time.perf_counter() - t0)
    return statistics.median(times)


def main() -> None:
    from test_form import _barge_curves  # noqa: PLC0415

    curves = _barge_curves()
    _, _, model = bn.build_hull_model(curves)
    h0 = model.hydrostatics(T)
    lpp, fp = h0["lpp"], h0["x_fp"]
    form = bn.form_topology(curves, draft=T)["parameters"]
    x_mid, (x_aft, x_fwd) = form["pmb_position"], (0.0, form["length"])
    cases = (
        ("Cb + 0.01, LCB held", {"cb": h0["cb"] + 0.01}),
        ("LCB + 0.25 % Lpp, ∇ held", {"lcb": h0["lcb"] + 0.0025 * lpp}),
        ("Cb + 0.01, LCB + 0.2 % Lpp", {"cb": h0["cb"] + 0.01, "lcb": h0["lcb"] + 0.002 * lpp}),
    )
    print(f"PMB barge at T = {T} m: ∇ {h0['volume']:.2f} m³, Cb {h0['cb']:.4f}, LCB {h0['lcb']:.3f} m")
    for label, targets in cases:
        ours, report = bn.transform_hydrostatic(curves, T, lpp=lpp, fp=fp, **targets)
        volume, lcb = report["target_volume"], report["target_lcb"]
        args = (curves, volume, lcb, lpp, fp, x_mid, x_aft, x_fwd)
        theirs, evaluations, f = plain_lackenby(*args)
        t_ours = _median_s(lambda kw=targets: bn.transform_hydrostatic(curves, T, lpp=lpp, fp=fp, **kw))
        t_theirs = _median_s(lambda args=args: plain_lackenby(*args))
        a = report["after"]
        ours_miss = (a["volume"] / volume - 1.0, (a["lcb"] - lcb) / lpp)
        print(f"\n{label}")
        print(
            f"  batten:   {report['stop']}, {report['evaluations']} evaluations, {t_ours:.3f} s, "
            f"misses ∇ {ours_miss[0]:.1e} LCB {ours_miss[1]:.1e} Lpp"
        )
        print(
            f"  Lackenby: {evaluations} evaluations, {t_theirs:.3f} s, misses ∇ {f[0]:.1e} LCB {f[1]:.1e} Lpp"
        )
        print(f"    kept curves, batten:   {kept_curves(curves, ours)}")
        print(f"    kept curves, Lackenby: {kept_curves(curves, theirs)}")


if __name__ == "__main__":
    main()
