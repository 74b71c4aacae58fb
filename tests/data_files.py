"""Paths of the test data under tests/data that several test folders read (tests/ is on the
path, as for plan_readers)."""

from __future__ import annotations

from pathlib import Path

#: The paper's case study under the paper's printed model: its answer is the paper's case 1
#: (W 8, n 8, alpha 84); examples/blimp_gripper.toml is the same spec under the default model.
PAPER_CASE_STUDY = Path(__file__).resolve().parent / "data" / "paper_case_study.toml"

#: A 20 mm square of Dura-Lar with an EI bound and a three-point deflection, a few seconds of
#: CalculiX per mesh: the design tests/fea/test_verify.py and test_verify_dask.py verify.
VERIFY_SMALL = Path(__file__).resolve().parent / "data" / "verify_small.toml"
