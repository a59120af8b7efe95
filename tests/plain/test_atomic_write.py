"""Files are written whole or not at all."""

import pytest
from batten.atomic_write import write_atomically


def test_writes_and_replaces_making_folders(tmp_path):
    path = tmp_path / "a" / "b" / "hull.json"
    assert write_atomically(path, "one") == path
    write_atomically(path, "two ✓")
    assert path.read_text(encoding="utf-8") == "two ✓"
    assert sorted(p.name for p in path.parent.iterdir()) == ["hull.json"], "no temporary file is left"


def test_a_failed_write_keeps_the_old_file_and_leaves_no_temporary(tmp_path):
    path = tmp_path / "hull.json"
    write_atomically(path, "old")
    with pytest.raises(UnicodeEncodeError):
        write_atomically(path, "new \ud800")  # a lone surrogate cannot be written as UTF-8
    assert path.read_text(encoding="utf-8") == "old"
    assert [p.name for p in tmp_path.iterdir()] == ["hull.json"]
