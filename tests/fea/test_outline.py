"""The FE of any outline (issue 23, item 4; docs/fea.md 2.8): the wheel and corner fixtures
against plane-elasticity and beam solutions of a flat plate, a 4-vertex polygon against the
square, and ``verify``'s rows of a circle against ``validate --fixture`` of the same fixture."""

from __future__ import annotations

import json
import math
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np
import pytest

from corrugate.fea.assembly import AssemblyMesh, assembly_deck, solve_assembly
from corrugate.fea.outline import (
    OutlineFixture,
    cut_outline,
    plate_shell,
    solve_outline,
    solve_shells,
)
from corrugate.geometry.layer import Assembly, Layer
from corrugate.geometry.layouts import Polygon, Square
from corrugate.materials.library import get_material
from corrugate.mechanics.wheel import WHEEL_FACTOR

if TYPE_CHECKING:
    from conftest import CliRun


def _annulus_K(E: float, nu: float, t: float, a: float, b: float) -> float:
    """Force per displacement (N/mm) of a flat annulus (plane stress, thickness t) whose inner
    edge r = b is held and whose outer edge r = a is translated rigidly, by hand: with
    u_r = U(r) cos th, u_th = V(r) sin th the Navier equations give for the dilatation
    e = E(r) cos th and the rotation w = O(r) sin th the system c E' = O / r, O' = c E / r
    (c = 2 / (1 - nu)), so E = a1 r + a2 / r; with S = U + V and D = U - V,
    (r^2 S)' = r^2 (E + O) and D' = E - O, four constants fixed by U = V = 0 at b and
    U = 1, V = -1 at a (u = x-hat). The resultant on the outer edge is
    pi a t (S_rr - S_rth) with sigma_rr = S_rr cos th, sigma_rth = S_rth sin th."""
    G = E / (2 * (1 + nu))
    c = 2 / (1 - nu)
    lam = 2 * G * nu / (1 - nu)

    def rows(r: float) -> tuple[np.ndarray, ...]:
        S = np.array([(1 + c) * r * r / 4, (1 - c) / 2, 1 / r**2, 0.0])
        D = np.array([(1 - c) * r * r / 2, (1 + c) * math.log(r), 0.0, 1.0])
        Sp = np.array([(1 + c) * r / 2, 0.0, -2 / r**3, 0.0])
        Dp = np.array([(1 - c) * r, (1 + c) / r, 0.0, 0.0])
        U, V, Up, Vp = (S + D) / 2, (S - D) / 2, (Sp + Dp) / 2, (Sp - Dp) / 2
        return U, V, (lam + 2 * G) * Up + lam * S / r, G * (Vp - S / r)

    Ub, Vb, _, _ = rows(b)
    Ua, Va, Srr, Srt = rows(a)
    coef = np.linalg.solve(np.array([Ub, Vb, Ua, Va]), np.array([0.0, 0.0, 1.0, -1.0]))
    return float(math.pi * a * t * ((Srr - Srt) @ coef))


def _disc(cx: float, cy: float, r: float, k: int = 720) -> np.ndarray:
    th = np.arange(k) * 2 * np.pi / k
    return np.column_stack([cx + r * np.cos(th), cy + r * np.sin(th)])


@pytest.mark.fea
def test_wheel_fixture_on_a_flat_annulus_matches_plane_elasticity(ccx: str) -> None:
    """A flat isotropic annulus (a = 20, b = 5 mm), the ground patch the whole rim: the
    fixture's K is the closed form's within the staircase rim's error (5 %; 2.8 % at this
    mesh, 1.7 % at 0.5 mm elements, docs/fea.md 2.8), and the same along every eta."""
    E, nu, t, a, b = 1000.0, 0.3, 0.2, 20.0, 5.0
    outline, hole = _disc(a, a, a), _disc(a, a, b)
    sh = cut_outline(plate_shell(2 * a, 2 * a, 2.0, E, nu, t), outline)
    keep = cut_outline(sh, hole)  # the elements inside the hole
    inner = {tuple(e) for e in keep.elements}
    ring_elements = [e for e in sh.elements if tuple(e) not in inner]
    used = np.isin(sh.ids, np.array([n for e in ring_elements for n in e]))
    from dataclasses import replace

    annulus = replace(sh, ids=sh.ids[used], xyz=sh.xyz[used], elements=ring_elements)
    whole_rim = OutlineFixture(patch_deg=180.0)
    k0 = solve_shells([annulus], "wheel", outline, [hole], 0.0, whole_rim)[0]
    k30 = solve_shells([annulus], "wheel", outline, [hole], 30.0, whole_rim)[0]
    exact = _annulus_K(E, nu, t, a, b)
    assert k0 == pytest.approx(exact, rel=0.05)
    assert k30 == pytest.approx(k0, rel=1e-6)  # isotropic: no direction


@pytest.mark.fea
def test_wheel_fixture_on_a_flat_disc_mesh_matches_plane_elasticity(ccx: str) -> None:
    """A flat isotropic annulus (a = 20, b = 5 mm) meshed by disc_mesh (a zig-zag of height 0,
    2 mm elements), the ground patch the whole rim: K is the plane-stress closed form's 605.91
    N/mm (tests/fea/test_outline.py derives it) within 1 %, where the staircase annulus at the
    same size is 2.8 % off (docs/fea.md 2.8), and the same at eta 0 and 30 deg (isotropic)."""
    E, nu, t, a, b = 1000.0, 0.3, 0.2, 20.0, 5.0
    from corrugate.fea.discmesh import Disc, disc_mesh
    from corrugate.fea.planmesh import Corrugation
    from corrugate.fea.shells import Shell

    pm = disc_mesh(Corrugation((1.0, 0.0), 0.0, 10.0, 0.0), Disc((a, a), a, b), 5)
    ids = np.arange(1, len(pm.xyz) + 1, dtype=np.int64)
    quads = [[int(ids[i]) for i in r] for r in pm.elements["S8R"]]
    tris = [[int(ids[i]) for i in r] for r in pm.elements["S6"]]
    sh = Shell(ids, pm.xyz, quads, t, E, nu, tris)
    outline, hole = _disc(a, a, a), _disc(a, a, b)
    whole_rim = OutlineFixture(patch_deg=180.0)
    k0 = solve_shells([sh], "wheel", outline, [hole], 0.0, whole_rim)[0]
    k30 = solve_shells([sh], "wheel", outline, [hole], 30.0, whole_rim)[0]
    exact = _annulus_K(E, nu, t, a, b)
    assert exact == pytest.approx(605.91, abs=0.01)
    assert k0 == pytest.approx(exact, rel=0.01)
    assert k30 == pytest.approx(k0, rel=0.01)


@pytest.mark.fea
def test_corner_fixture_on_a_narrow_plate_is_a_simply_supported_beam(ccx: str) -> None:
    """A flat 100 x 10 mm plate (nu = 0: no anticlastic curvature) pinned at its four corner
    nodes, a point load at its centre: P / delta = 48 E I / L^3 of a simply supported beam,
    I = b t^3 / 12, within 1 % (0.09 % here: the local terms are of order (b / L)^2)."""
    E, t, L, b = 1000.0, 1.0, 100.0, 10.0
    ring = np.array([[0.0, 0.0], [L, 0.0], [L, b], [0.0, b]])
    sh = plate_shell(L, b, 2.0, E, 0.0, t)
    tiny = OutlineFixture(bolt_radius=1e-3, load_radius=1e-3)
    k = solve_shells([sh], "corners", ring, [], 0.0, tiny)[0]
    assert k == pytest.approx(48 * E * (b * t**3 / 12) / L**3, rel=0.01)


def _layer() -> Layer:
    return Layer(W=5.0, n=5, alpha_deg=100.0, material=get_material("dura-lar"), t=0.125)


def test_a_square_polygon_writes_the_square_deck() -> None:
    """A polygon of 4 vertices on its box is the square: the same decks, line for line."""
    sq = Assembly.identical(_layer(), Square())
    poly = Assembly.identical(_layer(), Polygon(((0, 0), (2, 0), (2, 2), (0, 2))))
    for test in ("platens", "three-point", "four-point", "cantilever"):
        for eta in (0.0, 90.0):
            d_sq = assembly_deck(sq, test, AssemblyMesh(4), eta)[0]  # type: ignore[arg-type]
            d_po = assembly_deck(poly, test, AssemblyMesh(4), eta)[0]  # type: ignore[arg-type]
            assert d_po == d_sq, (test, eta)


@pytest.mark.fea
def test_a_square_polygon_reproduces_the_square_and_a_hexagon_is_cut(ccx: str) -> None:
    """K and D of the 4-vertex polygon equal the square's to 1e-6; a hexagon (flat edges at
    y = 0 and Ly, half the width) is cut from its box: fewer elements, and between platens
    on its flat edges less than the box's K (the strips outside the edges carry nothing)."""
    sq = Assembly.identical(_layer(), Square())
    poly = Assembly.identical(_layer(), Polygon(((0, 0), (1, 0), (1, 1), (0, 1))))
    for test in ("platens", "three-point"):
        a = solve_assembly(sq, test, AssemblyMesh(2))  # type: ignore[arg-type]
        b = solve_assembly(poly, test, AssemblyMesh(2))  # type: ignore[arg-type]
        assert b.value() == pytest.approx(a.value(), rel=1e-6)
    hexagon = Polygon(((0.25, 0), (0.75, 0), (1, 0.5), (0.75, 1), (0.25, 1), (0, 0.5)))
    h = solve_assembly(Assembly.identical(_layer(), hexagon), "platens", AssemblyMesh(2))
    box = solve_assembly(sq, "platens", AssemblyMesh(2))
    assert h.elements < box.elements
    assert 0 < h.value() < box.value()


def _wheel_folder(tmp_path: Path) -> Path:
    """A small disc (W 5, n 6, alpha 120, Dura-Lar 0.125 mm: 30.3 mm across, a 4 mm axle
    hole) as design.json, with a K bound along 0 and 45 deg and a D bound."""
    layer = {"W_mm": 5.0, "n": 6, "alpha_deg": 120.0, "material": "dura-lar", "t_mm": 0.125}
    record = {
        "layout": {
            "shape": "circle",
            "holes": [{"shape": "circle", "center_mm": [0.0, 0.0], "diameter_mm": 4.0}],
        },
        "layers": [layer, layer],
        "constraints": [
            {
                "name": "K0",
                "quantity": "K@0",
                "sense": "min",
                "bound": 1.0,
                "value": 2.0,
                "unit": "N/mm",
            },
            {
                "name": "K45",
                "quantity": "K@45",
                "sense": "min",
                "bound": 1e6,
                "value": 2.0,
                "unit": "N/mm",
            },
            {
                "name": "D0",
                "quantity": "D@0",
                "sense": "min",
                "bound": 1.0,
                "value": 2.0,
                "unit": "N*mm",
            },
        ],
    }
    folder = tmp_path / "wheel"
    folder.mkdir()
    (folder / "design.json").write_text(json.dumps(record))
    return folder


@pytest.mark.fea
def test_verify_on_a_wheel_is_validate_fixture_wheel(ccx: str, cli: CliRun, tmp_path: Path) -> None:
    """verify's K rows of a circle are `validate --fixture wheel` at the same mesh, number for
    number; the D row has no FE twin and says why (not checked); one mesh shows no asymptote,
    so neither K row holds or fails: not converged, exit 5 (docs/fea.md 6)."""
    folder = _wheel_folder(tmp_path)
    args = ["verify", str(folder), "--mesh", "2", "--max-mesh", "2", "--json", "-q"]
    code, out, err = cli([*args, "--no-first-failure"])
    assert code == 5, err
    rows = {r["name"]: r for r in json.loads(out)["constraints"]}
    code, out, err = cli(
        [
            "validate",
            "--design",
            str(folder / "design.json"),
            "--fixture",
            "wheel",
            "--mesh",
            "2",
            "--eta",
            "0",
            "--eta",
            "45",
            "--json",
            "-q",
        ]
    )
    assert code == 0, err
    fixture = {r["eta_deg"]: r for r in json.loads(out)["rows"]}
    for name, eta in (("K0", 0.0), ("K45", 45.0)):
        assert rows[name]["fe_series"]["2"] == fixture[eta]["fe_series"]["2"]
        assert "wheel's radial K" in rows[name]["note"]
        # beside the model's K, the wheel test's bound c(eta) K (docs/load_cases.md 9)
        c = WHEEL_FACTOR[eta]
        assert fixture[eta]["wheel_test_K"] == pytest.approx(c * fixture[eta]["model_K"])
    assert rows["K0"]["verdict"] == rows["K45"]["verdict"] == "not converged"
    assert rows["K0"]["fe"] > 1.0 > rows["K45"]["fe"] / 1e6  # 1 N/mm met, 1e6 N/mm missed
    assert rows["D0"]["fe"] is None and rows["D0"]["verdict"] == "not checked"
    assert "no FE twin" in rows["D0"]["note"]
    # the same run by the function, on the record's assembly
    from corrugate.export.record import read_record

    a = read_record(folder / "design.json").assembly(any_layout=True)
    r = solve_outline(a, "wheel", AssemblyMesh(2), 45.0)
    assert r.value == pytest.approx(fixture[45.0]["fe_series"]["2"], rel=1e-12)
    assert all(f > 0 for f in r.layer_forces)


def test_corner_fixtures_refuse_a_circle(cli: CliRun, tmp_path: Path) -> None:
    folder = _wheel_folder(tmp_path)
    code, _, err = cli(
        ["validate", "--design", str(folder / "design.json"), "--fixture", "corners"]
    )
    assert code == 2
    assert "fixture" in err and "corners" in err and len(err.strip().splitlines()) == 1
    code, _, err = cli(["validate", "--design", str(folder), "--fixture", "spokes"])
    assert code == 2 and "fixture" in err
    for series in ("3", "4,2", "2,x"):
        code, _, err = cli(
            ["validate", "--design", str(folder), "--fixture", "wheel", "--series", series]
        )
        assert code == 2 and "mesh" in err and len(err.strip().splitlines()) == 1, series
    code, _, err = cli(["validate", "--design", str(folder), "--series", "2,4"])
    assert code == 2 and "series" in err


@pytest.mark.fea
def test_verify_on_a_polygon_runs_the_cut_fixture(ccx: str, cli: CliRun, tmp_path: Path) -> None:
    """A hexagon's K along its creases is the compression fixture on the hexagon cut from its
    box, number for number, with the note saying what differs; off the creases it has no twin
    (not checked); one mesh is not converged, the worst verdict: exit 5."""
    hexagon = [[0.25, 0], [0.75, 0], [1, 0.5], [0.75, 1], [0.25, 1], [0, 0.5]]
    layer = {"W_mm": 5.0, "n": 5, "alpha_deg": 100.0, "material": "dura-lar", "t_mm": 0.125}
    record = {
        "layout": {"shape": "polygon", "vertices": hexagon},
        "layers": [layer, layer],
        "constraints": [
            {"name": n, "quantity": q, "sense": "min", "bound": 1.0, "value": 2.0, "unit": "N/mm"}
            for n, q in (("K0", "K@0"), ("K30", "K@30"))
        ],
    }
    folder = tmp_path / "hexagon"
    folder.mkdir()
    (folder / "design.json").write_text(json.dumps(record))
    code, out, err = cli(["verify", str(folder), "--mesh", "2", "--max-mesh", "2", "--json", "-q"])
    assert code == 5, err  # K0 on one mesh: not converged; K30 has no twin: not checked
    rows = {r["name"]: r for r in json.loads(out)["constraints"]}
    a = Assembly.identical(_layer(), Polygon(tuple((x, y) for x, y in hexagon)))
    direct = solve_assembly(a, "platens", AssemblyMesh(2)).value()
    assert rows["K0"]["fe_series"]["2"] == pytest.approx(direct, rel=1e-12)
    assert "polygon cut from its box" in rows["K0"]["note"]
    assert rows["K30"]["fe"] is None and "off the crease directions" in rows["K30"]["note"]
    assert rows["K30"]["verdict"] == "not checked" and rows["K0"]["verdict"] == "not converged"


@pytest.mark.fea
def test_a_wheel_test_bound_is_verified_as_the_models_test(
    ccx: str, cli: CliRun, tmp_path: Path
) -> None:
    """A K bound in the wheel test (quantity Kwhl@0, docs/load_cases.md 9) runs the wheel fixture
    and its row says it is the model's test; a K bound without a test on the same disc runs the
    same fixture, number for number, and says it is not (one mesh: not converged, exit 5)."""
    folder = _wheel_folder(tmp_path)
    record = json.loads((folder / "design.json").read_text())
    record["constraints"] = [
        {"name": n, "quantity": q, "sense": "min", "bound": 1.0, "value": 2.0, "unit": "N/mm"}
        for n, q in (("Kwheel", "Kwhl@0"), ("Kplain", "K@0"))
    ]
    (folder / "design.json").write_text(json.dumps(record))
    code, out, err = cli(["verify", str(folder), "--mesh", "2", "--max-mesh", "2", "--json", "-q"])
    assert code == 5, err
    rows = {r["name"]: r for r in json.loads(out)["constraints"]}
    wheel, plain = rows["Kwheel"], rows["Kplain"]
    assert wheel["note"].startswith("the model's test") and "wheel's radial K" in wheel["note"]
    assert plain["note"].startswith("not the model's test")
    assert "wheel" in wheel["test"] and wheel["test"] == plain["test"]
    assert wheel["fe_series"]["2"] == plain["fe_series"]["2"] > 1.0
    assert wheel["verdict"] == "not converged"
