"""Long work shows its progress: headless (these tests), a ``batten:`` line on stderr."""

import re

import batten.api as api
from batten import progress


def test_importing_sections_prints_its_progress_headless(examples_dir, capsys, monkeypatch):
    # Every step prints when lines may come at any interval; the count is the file's curves.
    monkeypatch.setattr(progress, "LINE_INTERVAL_S", 0.0)
    coll, reports = api.import_sections(examples_dir / "sections" / "multi_chine.json")
    fitted = sum(1 for r in reports if r.get("kind") != "chine")
    lines = re.findall(r"batten: fitting sections (\d+)/(\d+)", capsys.readouterr().err)
    assert [int(d) for d, _ in lines] == list(range(1, fitted + 1)), lines
    assert {int(t) for _, t in lines} == {fitted}


def test_headless_lines_are_few_when_steps_are_quick(capsys):
    # The default interval: 1000 quick steps print the first and the last line only.
    with progress.Progress("probing", 1000) as p:
        for _ in range(1000):
            p.step()
    assert capsys.readouterr().err.splitlines() == ["batten: probing 1/1000", "batten: probing 1000/1000"]
