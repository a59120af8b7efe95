"""Long work shows its progress and can be cancelled: headless (these tests), a ``batten:`` line
on stderr per step; a ``progress=`` callback that returns False stops the work with
``Cancelled`` and nothing changed (no curve, no file, no object); the modal operators step the
same jobs on timer events and cancel on Esc."""

import re
from pathlib import Path

import batten.api as api
import batten_native
import bpy
import numpy as np
import pytest
from batten import cad_operators, operators, progress
from helpers import new_curve, noisy_arc
from operator_runs import execute, run_modal, stand_in

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"


@pytest.fixture
def every_line(monkeypatch):
    """Every step prints a line (lines may come at any interval)."""
    monkeypatch.setattr(progress, "LINE_INTERVAL_S", 0.0)


def _lines(err: str, label: str) -> list[tuple[int, int]]:
    return [(int(d), int(t)) for d, t in re.findall(rf"batten: {re.escape(label)} (\d+)/(\d+)", err)]


class StopAfter:
    """A progress callback that asks to stop at its ``k``-th call, and records its calls."""

    def __init__(self, k: int) -> None:
        self.k, self.calls = k, []

    def __call__(self, label, done, total):
        self.calls.append((label, done, total))
        return len(self.calls) < self.k


def _splines(objects) -> list:
    """Every control point of the objects' splines, exactly as Blender holds them."""
    out = []
    for obj in objects:
        for s in obj.data.splines:
            if s.type == "BEZIER":
                co = np.empty(3 * len(s.bezier_points), dtype=np.float32)
                s.bezier_points.foreach_get("co", co)
            else:
                co = np.empty(4 * len(s.points), dtype=np.float32)
                s.points.foreach_get("co", co)
            out.append((obj.name, s.type, co.tolist()))
    return out


@pytest.fixture
def arcs():
    """Three noisy polylines, selected, and the fair tolerance their noise allows."""
    objs = [new_curve(f"arc {k}", "POLY", noisy_arc(40, r=8.0 + k, seed=k)) for k in range(3)]
    for obj in objs:
        obj.select_set(True)
    bpy.context.view_layer.objects.active = objs[0]
    bpy.context.scene.batten.fair_tolerance = 0.05
    return objs


def _noisy_wigley():
    coll = api.load_example("wigley_lines.json")
    curves = api.read_curves(coll)
    noisy = batten_native.section_noise(curves, 0.003, 3)
    objects = {o.name: o for o in api.curve_objects(coll)}
    from batten.bridge import curves_out

    curves_out.replace_splines_of([(objects[c.name], [c]) for c in noisy])
    return coll


# --- headless lines ---------------------------------------------------------------------------


def test_importing_sections_prints_its_progress_headless(examples_dir, capsys, every_line):
    # The count is the file's curves.
    coll, reports = api.import_sections(examples_dir / "sections" / "multi_chine.json")
    fitted = sum(1 for r in reports if r.get("kind") != "chine")
    lines = _lines(capsys.readouterr().err, "fitting sections")
    assert [d for d, _ in lines] == list(range(1, fitted + 1)), lines
    assert {t for _, t in lines} == {fitted}


def test_headless_lines_are_few_when_steps_are_quick(capsys):
    # The default interval: 1000 quick steps print the first and the last line only.
    with progress.Progress("probing", 1000) as p:
        for _ in range(1000):
            p.step()
    assert capsys.readouterr().err.splitlines() == ["batten: probing 1/1000", "batten: probing 1000/1000"]


def test_fairing_a_selection_prints_a_line_per_object(arcs, capsys, every_line):
    reports = api.fair_curves(arcs, tolerance=0.05)
    assert len(reports) == 3
    assert _lines(capsys.readouterr().err, "fairing curves") == [(1, 3), (2, 3), (3, 3)]


def test_surface_fairing_prints_a_line_per_round_of_the_core(capsys, every_line):
    coll = _noisy_wigley()
    seen = []
    report = api.fair_surface(coll, tolerance=0.01, progress=lambda *a: seen.append(a))
    rounds = report["rounds"]
    assert rounds >= 2, rounds
    # Every round the core made, in order, out of max_rounds (12), each once.
    assert [d for _, d, _ in seen] == list(range(1, rounds + 1)), seen
    assert _lines(capsys.readouterr().err, "fairing the surface") == [(k, 12) for k in range(1, rounds + 1)]


@pytest.mark.parametrize("fmt", ["iges", "step", "3dm"])
def test_exports_print_their_steps(fmt, tmp_path, capsys, every_line):
    coll = api.load_network(EXAMPLES / "wigley_lines.json")
    path = getattr(api, f"export_{fmt}")(coll, tmp_path / f"hull.{fmt}")
    assert path.stat().st_size > 0
    err = capsys.readouterr().err
    what = "3dm file" if fmt == "3dm" else f"{fmt.upper()} file"
    if fmt == "3dm":
        faces = _lines(err, f"{what}: faces")
        n = faces[-1][1] - 1
        assert n >= 4 and faces == [(k, n + 1) for k in range(1, n + 1)], faces
        assert _lines(err, f"{what}: written") == [(n + 1, n + 1)]
        fitting = _lines(err, f"{what}: fitting")
        assert fitting[-1] == (n, n) and all(t == n for _, t in fitting[1:]), fitting
    else:
        # A line per face fitted (the count never going back, though two workers may report
        # out of order), up to every face, then the file.
        faces = _lines(err, f"{what}: faces")
        n = faces[-1][1]
        done = [d for d, _ in faces]
        assert n >= 4 and done == sorted(done) and done[-1] == n and len(set(done)) > n // 2, faces
        assert _lines(err, f"{what}: written") == [(n + 1, n + 1)]


def test_lines_plan_and_offsets_table_print_their_steps(tmp_path, capsys, every_line):
    coll = api.load_example("wigley_lines.json")
    api.lines_plan(coll, tmp_path / "plan.svg", draft=6.25, progress=None)
    api.offsets_table(coll, tmp_path / "offsets.csv", stations=5)
    api.export_sections(coll, tmp_path / "sections.json", stations=5, waterlines=3)
    err = capsys.readouterr().err
    assert _lines(err, "lines plan") == [(1, 2), (2, 2)]
    assert _lines(err, "offsets table") == [(1, 3), (2, 3), (3, 3)]
    assert _lines(err, "section file") == [(1, 3), (2, 3), (3, 3)]


# --- cancelling through the callback ----------------------------------------------------------


def test_a_cancelled_selection_fairing_changes_no_curve(arcs):
    before = _splines(arcs)
    stop = StopAfter(2)
    with pytest.raises(api.Cancelled, match=r"fairing curves cancelled after 2/3 steps"):
        api.fair_curves(arcs, tolerance=0.05, progress=stop)
    assert [d for _, d, _ in stop.calls] == [1, 2], "no step after the cancel"
    assert _splines(arcs) == before
    assert isinstance(api.Cancelled("x"), api.BattenError)


def test_a_callback_returning_none_goes_on(arcs):
    reports = api.fair_curves(arcs, tolerance=0.05, progress=lambda *_: None)
    assert len(reports) == 3 and all(o.data.splines[0].type == "NURBS" for o in arcs)


def test_a_cancelled_surface_fairing_stops_the_core_and_changes_no_curve():
    coll = _noisy_wigley()
    objects = api.curve_objects(coll)
    before = _splines(objects)
    stop = StopAfter(2)
    with pytest.raises(api.Cancelled, match="fairing the surface cancelled after 2/12"):
        api.fair_surface(coll, tolerance=0.01, progress=stop)
    assert [d for _, d, _ in stop.calls] == [1, 2]
    assert _splines(objects) == before
    # The same request uncancelled makes more rounds than that, and moves curves.
    report = api.fair_surface(coll, tolerance=0.01)
    assert report["rounds"] > 2 and _splines(objects) != before


def test_the_binding_stops_on_false_and_passes_a_callback_error_on():
    coll = _noisy_wigley()
    curves = api.read_curves(coll)
    calls = []

    def stop_at_three(done, total):
        calls.append((done, total))
        return done < 3

    with pytest.raises(batten_native.Cancelled, match="cancelled"):
        batten_native.fair_sections(curves, tolerance=0.01, progress=stop_at_three)
    assert calls == [(1, 12), (2, 12), (3, 12)], "the core stopped at the round that said so"

    def broken(done, total):
        raise ZeroDivisionError("the callback's own error")

    with pytest.raises(ZeroDivisionError, match="own error"):
        batten_native.fair_sections(curves, tolerance=0.01, progress=broken)
    faired, report = batten_native.fair_sections(curves, tolerance=0.01, progress=lambda d, t: True)
    assert report["rounds"] > 3 and len(faired) == len(curves)


@pytest.mark.parametrize("fmt", ["iges", "3dm"])
def test_a_cancelled_export_leaves_the_target_file_as_it_was(fmt, tmp_path):
    coll = api.load_network(EXAMPLES / "wigley_lines.json")
    target = tmp_path / f"hull.{fmt}"
    target.write_bytes(b"the designer's old file")
    stop = StopAfter(1 if fmt == "iges" else 3)
    with pytest.raises(api.Cancelled):
        getattr(api, f"export_{fmt}")(coll, target, progress=stop)
    assert len(stop.calls) == stop.k
    assert target.read_bytes() == b"the designer's old file"
    assert sorted(p.name for p in tmp_path.iterdir()) == [target.name], "no temporary file left"


def test_the_written_step_cannot_cancel(tmp_path):
    # A callback saying stop once the file is written: the file is there, no Cancelled.
    coll = api.load_network(EXAMPLES / "wigley_lines.json")
    path = api.export_step(coll, tmp_path / "hull.stp", progress=lambda label, _d, _t: "written" not in label)
    assert path.read_text().startswith("ISO-10303-21;")


@pytest.mark.parametrize("call", ["cad_text", "cad_faces"])
def test_the_core_stops_fitting_faces_when_told(call):
    # The export's fitting reports each face from the core's workers and stops starting faces
    # once the callback says so: far fewer faces fitted than the surface has.
    coll = api.load_network(EXAMPLES / "wigley_lines.json")
    model = batten_native.build_hull_model(api.read_curves(coll), tangent_planes=api.tangent_planes(coll))[2]
    args = {
        "cad_text": (model, "iges", 1e-4, False, "hull", "hull.igs", "", (2026, 1, 1, 0, 0, 0)),
        "cad_faces": (model, 1e-4, False),
    }[call]
    _, stats = getattr(batten_native, call)(*args)
    calls = []

    def stop_at_two(done, total):
        calls.append((done, total))
        return len(calls) < 2

    with pytest.raises(batten_native.Cancelled, match="exporting the surface cancelled"):
        getattr(batten_native, call)(*args, progress=stop_at_two)
    assert {t for _, t in calls} == {stats["faces"]}, "each call says how many faces there are"
    # The workers finish the faces they had started (one per core), and start no more.
    assert 2 <= len(calls) <= 2 + 4 < stats["faces"], (len(calls), stats["faces"])

    def broken(done, total):
        raise ZeroDivisionError("the callback's own error")

    with pytest.raises(ZeroDivisionError, match="own error"):
        getattr(batten_native, call)(*args, progress=broken)


def test_cancelled_lines_plan_offsets_and_section_file_write_nothing(tmp_path):
    coll = api.load_example("wigley_lines.json")
    calls = [
        lambda stop: api.lines_plan(coll, tmp_path / "plan.svg", draft=6.25, progress=stop),
        lambda stop: api.offsets_table(coll, tmp_path / "offsets.csv", stations=5, progress=stop),
        lambda stop: api.export_sections(coll, tmp_path / "s.json", stations=5, waterlines=3, progress=stop),
    ]
    for call in calls:
        for k in (1, 2):
            if call is calls[0] and k == 2:
                continue  # the lines plan's second step is the written file
            with pytest.raises(api.Cancelled):
                call(StopAfter(k))
    assert not any(tmp_path.iterdir())


def test_a_cancelled_import_creates_nothing(examples_dir):
    objects, collections, curves = len(bpy.data.objects), len(bpy.data.collections), len(bpy.data.curves)
    stop = StopAfter(3)
    with pytest.raises(api.Cancelled, match="fitting sections cancelled after 3/"):
        api.import_sections(examples_dir / "sections" / "multi_chine.json", progress=stop)
    assert (len(bpy.data.objects), len(bpy.data.collections), len(bpy.data.curves)) == (
        objects,
        collections,
        curves,
    )


def test_start_runs_only_the_long_calls():
    with pytest.raises(api.InvalidArgumentError, match="no long call"):
        api.start(api.build, "nothing")


def test_a_started_job_runs_step_by_step_and_gives_the_call_s_result(arcs):
    before = _splines(arcs)
    job = api.start(api.fair_curves, arcs, tolerance=0.05)
    assert job.step() is False and job.progress.done == 1
    assert _splines(arcs) == before, "nothing written before the last step"
    while not job.step():
        pass
    assert [r["object"] for r in job.result] == [o.name for o in arcs]
    assert _splines(arcs) != before


# --- the modal operators ----------------------------------------------------------------------


def test_the_modal_fair_operator_steps_on_timers_and_cancels_on_esc(arcs):
    before = _splines(arcs)
    events = ["TIMER", "MOUSEMOVE", "ESC"]
    results, reports, _ = run_modal(operators.BATTEN_OT_fair_curves, bpy.context, events)
    assert results == [{"RUNNING_MODAL"}, {"RUNNING_MODAL"}, {"CANCELLED"}]
    assert reports == [({"WARNING"}, "fairing curves: cancelled, nothing changed")]
    assert _splines(arcs) == before
    assert progress.cancel_hint == "", "the status bar's hint is gone"


def test_the_modal_fair_operator_shows_its_step_and_finishes_as_the_api(arcs):
    op, _ = stand_in(operators.BATTEN_OT_fair_curves)
    op.begin(bpy.context)
    assert op.modal(bpy.context, _event("TIMER")) == {"RUNNING_MODAL"}
    assert op._job.progress.status_text() == "batten: fairing curves 1/3 — Esc to cancel"
    results, reports, _ = run_modal(operators.BATTEN_OT_fair_curves, bpy.context, ["TIMER"] * 5)
    op._job.cancel()
    assert results[-1] == {"FINISHED"} and len(results) == 4, results
    assert reports[0][1].startswith("Faired 3 curve(s)")
    faired = _splines(arcs)
    # The same as the API's: fair fresh copies the same way.
    copies = [new_curve(f"copy {k}", "POLY", noisy_arc(40, r=8.0 + k, seed=k)) for k in range(3)]
    api.fair_curves(copies, tolerance=0.05)
    assert [c for _, _, c in _splines(copies)] == [c for _, _, c in faired]


def _event(kind):
    from operator_runs import FakeEvent

    return FakeEvent(kind, "PRESS")


def test_the_modal_export_cancels_with_no_file_and_runs_at_once_headless(tmp_path):
    coll = api.load_network(EXAMPLES / "wigley_lines.json")
    bpy.context.scene.batten.source = coll
    path = tmp_path / "hull.igs"
    props = {"filepath": str(path), "tolerance": api.DEFAULT_EXPORT_TOLERANCE, "allow_holes": False}
    events = ["TIMER", "ESC"]
    results, reports, _ = run_modal(cad_operators.BATTEN_OT_export_iges, bpy.context, events, **props)
    assert results == [{"RUNNING_MODAL"}, {"CANCELLED"}]
    assert "cancelled" in reports[0][1] and not path.exists()
    # Headless, execute runs the job to its end.
    result, reports = execute(cad_operators.BATTEN_OT_export_iges, bpy.context, **props)
    assert result == {"FINISHED"} and path.exists(), reports


def test_a_modal_error_is_reported_and_changes_nothing(tmp_path):
    bad = tmp_path / "bad.json"
    bad.write_text("{not json")
    objects = len(bpy.data.objects)
    props = {"filepath": str(bad), "tolerance": api.DEFAULT_SECTION_TOLERANCE}
    results, reports, _ = run_modal(operators.BATTEN_OT_import_sections, bpy.context, ["TIMER"], **props)
    assert results == [{"CANCELLED"}]
    assert reports[0][0] == {"ERROR"} and "bad.json" in reports[0][1]
    assert len(bpy.data.objects) == objects


def test_invoked_headless_the_operator_still_runs_at_once(arcs):
    # Invoked (as a click would), without a window: the job runs to its end, as from a script.
    before = _splines(arcs)
    assert bpy.ops.batten.fair_curves("INVOKE_DEFAULT") == {"FINISHED"}
    assert _splines(arcs) != before


def test_the_fair_surface_operator_fairs_as_the_api_and_cancels_on_esc():
    coll = _noisy_wigley()
    scene = bpy.context.scene
    scene.batten.source = coll
    scene.batten.surface_fair_tolerance = 0.01
    assert operators.BATTEN_OT_fair_surface.poll(bpy.context)
    objects = api.curve_objects(coll)
    before = _splines(objects)
    # Modal: a round or so, then Esc: nothing changed.
    results, reports, _ = run_modal(operators.BATTEN_OT_fair_surface, bpy.context, ["TIMER", "ESC"])
    assert results == [{"RUNNING_MODAL"}, {"CANCELLED"}]
    assert reports == [({"WARNING"}, "fairing the surface: cancelled, nothing changed")]
    assert _splines(objects) == before and progress.cancel_hint == ""
    # Run to its end: the sections move, and the report is the API's figures.
    result, reports = execute(operators.BATTEN_OT_fair_surface, bpy.context)
    assert result == {"FINISHED"}, reports
    faired = _splines(objects)
    assert faired != before
    message = reports[0][1]
    assert message.startswith("Faired ") and "curvature variation" in message, message
    # The same as the API's on the same noisy hull with the same settings (drawn again under
    # the same names, which order the curves).
    for obj in objects:
        bpy.data.objects.remove(obj)
    again = _noisy_wigley()
    tolerance = scene.batten.surface_fair_tolerance  # 0.01 as Blender's float32 holds it
    report = api.fair_surface(again, tolerance=tolerance, families=["stations", "waterlines"])
    assert [c for _, _, c in _splines(api.curve_objects(again))] == [c for _, _, c in faired]
    assert f"in {report['rounds']} round(s)" in message
    # With no family chosen there is nothing to fair.
    scene.batten.surface_fair_families = set()
    assert not operators.BATTEN_OT_fair_surface.poll(bpy.context)
