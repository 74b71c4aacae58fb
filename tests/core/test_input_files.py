"""Input files read as untrusted (:func:`corrugate.core.fileio.read_input`): regular files only,
checked before a byte is read (a FIFO never blocks, /dev/zero is never read), size-capped,
strictly UTF-8; :func:`printable` strips control characters (files in tmp_path)."""

from __future__ import annotations

import os
import signal
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path

import pytest

from corrugate.core.errors import InputError
from corrugate.core.fileio import MAX_INPUT_BYTES, read_input, read_input_text
from corrugate.core.text import printable


@contextmanager
def _within(seconds: int) -> Iterator[None]:
    """Fail (instead of hanging for ever) when the block takes longer than ``seconds``."""

    def expired(signum: int, frame: object) -> None:
        raise TimeoutError(f"took more than {seconds} s")

    old = signal.signal(signal.SIGALRM, expired)
    signal.alarm(seconds)
    try:
        yield
    finally:
        signal.alarm(0)
        signal.signal(signal.SIGALRM, old)


def test_a_fifo_without_a_writer_is_refused_at_once(tmp_path: Path) -> None:
    fifo = tmp_path / "design.json"
    os.mkfifo(fifo)
    with _within(5), pytest.raises(InputError, match=r"^design = .*design.json is a FIFO"):
        read_input(fifo, "design")


def test_a_device_a_folder_and_a_missing_file_are_one_line(tmp_path: Path) -> None:
    (tmp_path / "zero").symlink_to("/dev/zero")
    with _within(5), pytest.raises(InputError, match="is a device, not a regular file"):
        read_input(tmp_path / "zero", "design")
    with pytest.raises(InputError, match="is a folder"):
        read_input(tmp_path, "design")
    with pytest.raises(InputError, match=r"cannot be read \(No such file or directory\)"):
        read_input(tmp_path / "none.json", "design")


def test_the_size_cap_is_exact(tmp_path: Path) -> None:
    f = tmp_path / "a.json"
    f.write_bytes(b"x" * 10)
    assert read_input(f, "design", limit=10) == b"x" * 10
    f.write_bytes(b"x" * 11)
    with pytest.raises(
        InputError, match=r"too large \(11 bytes\): allowed a regular file of at most 10"
    ):
        read_input(f, "design", limit=10)
    assert MAX_INPUT_BYTES == 8 * 1024 * 1024


def test_text_is_strict_utf8_and_utf16_is_named(tmp_path: Path) -> None:
    f = tmp_path / "a.json"
    f.write_text('{"name": "Düse"}', encoding="utf-8")
    assert read_input_text(f, "design") == '{"name": "Düse"}'
    f.write_text('{"name": "x"}', encoding="utf-16")  # with its byte-order mark
    with pytest.raises(InputError, match="is UTF-16 text: save it as UTF-8"):
        read_input_text(f, "design")
    f.write_bytes(b'{"name": "D\xfcse"}')  # Latin-1
    with pytest.raises(InputError, match=r"is not UTF-8 text \(byte 11\)"):
        read_input_text(f, "design")


def test_printable_strips_control_characters_and_cuts() -> None:
    assert printable("\x1b[31mred\x1b[0m\r\x07ok\x9b") == "[31mred[0mok"
    # a newline or a tab from a file would break the one-line error: removed too
    assert printable("tab\tand\nnewline") == "tabandnewline"
    assert printable("x" * 300, 10) == "xxxxxxx..."
