"""``POST /api/spec/toml`` and ``POST /api/spec/parse`` in process: the page's spec as the file the
CLI reads, and a spec file into the page's keys, with the CLI's errors (issue 36).

The independent sources: the shipped example files read by ``tomllib``, and the CLI itself
(``corrugate design FILE --json``, in-process) on the file the API wrote, against ``POST
/api/design`` on the same body.
"""

from __future__ import annotations

import json
import tomllib
from collections.abc import Iterator
from pathlib import Path
from typing import TYPE_CHECKING, Any

import pytest
from fastapi.testclient import TestClient

from corrugate.web import create_app

from .test_design_api import EXAMPLES, spec_of, without_timings

if TYPE_CHECKING:
    from conftest import CliRun


@pytest.fixture(scope="module")
def client() -> Iterator[TestClient]:
    with TestClient(create_app()) as c:
        yield c


def test_the_saved_file_is_the_spec_and_the_cli_gives_the_web_answer(
    client: TestClient, tmp_path: Path, cli: CliRun
) -> None:
    body = {**spec_of("blimp_gripper.toml"), "cutter": "maker-12x12"}
    r = client.post("/api/spec/toml", json=body)
    assert r.status_code == 200, r.text
    assert r.headers["content-type"].startswith("text/plain")
    assert "attachment" in r.headers["content-disposition"]
    saved = tmp_path / "spec.toml"
    saved.write_text(r.text)
    expected = spec_of("blimp_gripper.toml")
    expected["fabrication"] = {"machine": "maker-12x12"}
    assert tomllib.loads(r.text) == expected
    assert "--fold-style" not in r.text  # the output options are the CLI's defaults
    web = client.post("/api/design", json=body)
    assert web.status_code == 200, web.text
    code, out, err = cli(["design", str(saved), "--json"])
    assert code == 0, err
    assert without_timings(json.loads(out)) == without_timings(web.json()["design"])


def test_output_options_become_a_comment_naming_the_cli_options(client: TestClient) -> None:
    body = {**spec_of("blimp_gripper.toml"), "fold_style": "perforated", "cut": "1 mm"}
    body |= {"gap": "0.5 mm", "paper": "a4"}
    r = client.post("/api/spec/toml", json=body)
    assert r.status_code == 200, r.text
    (line,) = [ln for ln in r.text.splitlines() if "output options" in ln]
    assert line.endswith("--fold-style perforated --cut '1 mm' --gap '0.5 mm' --paper a4")
    assert tomllib.loads(r.text) == spec_of("blimp_gripper.toml")


@pytest.mark.parametrize(
    ("change", "field"),
    [
        ({"constraints": {"side": {"min": "50 kg"}}}, "constraints.side.min"),
        ({"cutter": "cameo3"}, "cutter"),
        ({"colour": "red"}, "colour"),
    ],
)
def test_a_bad_form_is_422_naming_the_field(
    client: TestClient, change: dict[str, Any], field: str
) -> None:
    r = client.post("/api/spec/toml", json={**spec_of("blimp_gripper.toml"), **change})
    assert r.status_code == 422, r.text
    assert r.json()["field"] == field


@pytest.mark.parametrize("path", sorted(EXAMPLES.glob("*.toml")), ids=lambda p: p.stem)
def test_every_example_file_reads_into_its_keys(client: TestClient, path: Path) -> None:
    r = client.post("/api/spec/parse", json={"toml": path.read_text(), "name": path.name})
    assert r.status_code == 200, r.text
    expected = tomllib.loads(path.read_text())
    machine = expected.get("fabrication", {}).pop("machine", None)
    if machine is not None:
        expected["cutter"] = machine
        if not expected["fabrication"]:
            del expected["fabrication"]
    assert r.json() == expected


def test_a_file_with_a_byte_order_mark_reads_as_without(client: TestClient) -> None:
    """A file saved with a UTF-8 byte-order mark (tomllib: "Invalid statement (at line 1, column
    1)") is read as the same text without it."""
    text = (EXAMPLES / "blimp_gripper.toml").read_text(encoding="utf-8")
    plain = client.post("/api/spec/parse", json={"toml": text, "name": "mine.toml"})
    marked = client.post("/api/spec/parse", json={"toml": "\ufeff" + text, "name": "mine.toml"})
    assert plain.status_code == marked.status_code == 200, marked.text
    assert marked.json() == plain.json()


@pytest.mark.parametrize(
    ("text", "field", "words"),
    [
        ("name = ", "spec", "is not valid TOML"),
        ('[constraints]\nside = { min = "50 kg" }\n', "constraints.side.min", "50 kg"),
        ("[fabrication]\nmachine = 'cameo3'\n", "fabrication.machine", "cameo3"),
    ],
)
def test_a_bad_file_is_422_naming_the_key(
    client: TestClient, text: str, field: str, words: str
) -> None:
    r = client.post("/api/spec/parse", json={"toml": text, "name": "mine.toml"})
    assert r.status_code == 422, r.text
    assert r.json()["field"] == field and words in r.json()["detail"]
    assert "\n" not in r.json()["detail"]  # one line, never a traceback
