"""Every batten file reader reads text the same way: UTF-8 with a byte-order mark dropped, and a
file that is missing or not UTF-8 is a NetworkFileError naming the file (never a
UnicodeDecodeError)."""

import pytest
from batten.file_text import read_text
from batten_native import BattenError, NetworkFileError


def test_utf8_with_a_byte_order_mark_reads_without_it(tmp_path):
    f = tmp_path / "hull.json"
    f.write_bytes('\ufeff{"name": "Ægir"}'.encode())
    assert read_text(f, "network file") == '{"name": "Ægir"}'


def test_latin1_bytes_are_a_network_file_error_naming_the_file_and_the_byte(tmp_path):
    f = tmp_path / "offsets.csv"
    f.write_bytes(b"st10,1.0,2.0,3.0\nst\xe911,1,2,3\n")
    with pytest.raises(NetworkFileError) as e:
        read_text(f, "section file")
    msg = str(e.value)
    assert msg.startswith(f"section file '{f}': not UTF-8 text"), msg
    assert "0xe9" in msg and "offset 19" in msg, msg
    assert isinstance(e.value, BattenError) and isinstance(e.value, ValueError)


def test_a_missing_file_names_it(tmp_path):
    f = tmp_path / "nowhere.json"
    with pytest.raises(NetworkFileError, match="network file '.*nowhere.json': No such file"):
        read_text(f, "network file")
