"""``POST /api/pattern``: the cut files of a given design from the analyse tab, the same files
``corrugate pattern --out`` writes (the CLI's own writer), and its errors in the request's words."""

from __future__ import annotations

import io
import json
import zipfile
from pathlib import Path

import ezdxf
import pytest
from fastapi.testclient import TestClient

from corrugate.cli import main

from .conftest import CASE1


def test_pattern_returns_the_files_corrugate_pattern_writes(
    client: TestClient, tmp_path: Path
) -> None:
    r = client.post("/api/pattern", json={**CASE1, "cutter": "cameo4-12x12"})
    assert r.status_code == 200, r.text
    result = r.json()
    names = {f["name"] for f in result["files"]}
    args = ["pattern", "--W", "8", "--n", "8", "--alpha", "84", "--material", "dura-lar"]
    with pytest.raises(SystemExit) as info:
        main([*args, "--model", "paper", "--out", str(tmp_path / "cli"), "--quiet"])
    assert info.value.code in (0, None)
    # the same files (the CLI's folder also holds its hidden manifest of the set written)
    assert names == {p.name for p in (tmp_path / "cli").iterdir() if not p.name.startswith(".")}
    assert {"cut-1.dxf", "assembly.glb", "assembly.stl", "design.json"} <= names
    files = {f["name"]: f for f in result["files"]}
    dxf = client.get(files["cut-1.dxf"]["url"])
    assert dxf.status_code == 200
    doc = ezdxf.read(io.StringIO(dxf.content.decode("utf-8")))  # a DXF the cutter software reads
    assert len(doc.modelspace()) > 0
    record = json.loads(client.get(files["design.json"]["url"]).content)
    assert record["layers"][0]["n"] == 8 and record["layers"][0]["W_mm"] == 8
    archive = zipfile.ZipFile(
        io.BytesIO(client.get(f"/api/results/{result['id']}/all.zip").content)
    )
    assert sorted(archive.namelist()) == sorted(names)


def test_pattern_svg_cutter_and_bad_options_name_their_field(client: TestClient) -> None:
    r = client.post("/api/pattern", json={**CASE1, "cutter": "maker-12x12"})
    assert r.status_code == 200
    assert "cut-1.svg" in {f["name"] for f in r.json()["files"]}
    for body, field in (
        ({**CASE1, "cutter": "plotter"}, "cutter"),
        ({**CASE1, "fold_style": "wavy"}, "fold_style"),
        ({**CASE1, "W": -1}, "W"),
        ({**CASE1, "paper": "a3"}, "paper"),
    ):
        bad = client.post("/api/pattern", json=body)
        assert bad.status_code == 422, (body, bad.text)
        assert bad.json()["field"] == field
