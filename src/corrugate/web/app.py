"""The FastAPI application: JSON API, the single page, the offline OpenAPI page and downloads.

Endpoints (all JSON unless said otherwise):

* ``GET /``: the page (``static/index.html`` with ``static/app.js``);
* ``GET /docs``: Swagger UI served from the package (no CDN); ``GET /openapi.json``;
* ``GET /api/materials``: the library, as ``corrugate materials --json``;
* ``GET /api/models``: the moduli variants and the default;
* ``GET /api/formats``: every kind of file the app writes (the writers registry,
  :mod:`corrugate.export.writers`): name, file-name pattern, media type, extra, description and
  its place in the page's downloads;
* ``GET /api/load-cases``: every load case a requirement may name (the registry of behaviours,
  :mod:`corrugate.mechanics.behaviours`): name, label, kind, layouts, ...; the page's test menus;
* ``POST /api/analyze``: the options of ``corrugate analyze`` -> ``Analysis.to_dict()`` (the CLI's
  ``--json`` object);
* ``POST /api/mesh``: the same options -> the folded assembly as ``assembly.glb`` and
  ``assembly.stl`` in a new result (opaque id), with their download URLs;
* ``POST /api/pattern``: the same options plus the output options of ``corrugate pattern``
  (``cutter``, ``fold_style``, ``cut``, ``gap``, ``paper``) -> every file ``corrugate pattern
  --out`` writes (cut files, fold map, PDF, FOLD, GLB/STL, steps, design.json) in a new result;
* ``POST /api/design``: a spec (the keys of the TOML file) and the output options of
  ``corrugate design`` -> ``{"design": <corrugate design --json>, "result": {"id", "files"}}``:
  the certified design and every file ``corrugate design --out`` writes (cut files, FOLD, GLB,
  STL, steps, design.json, the report drawn from the very sheet plan of the cut files), or
  ``"result": null`` when the spec is infeasible;
* ``POST /api/jobs/design``: the body of ``/api/design`` as a background job (202 once the quick
  lane has read the spec; 422 naming the field before anything is queued; 503 with
  ``Retry-After`` when the queue is full), its
  solver under its own CPU budget (query ``budget``) and stopped at :data:`JOB_WALL_PER_CPU`
  wall seconds per budget second; ``POST /api/jobs/verify``: ``corrugate verify`` on a stored design (CalculiX;
  a series not shown asymptotic refined up to the server's ``fe_max_mesh``, as ``--max-mesh``);
  ``GET /api/jobs/{id}`` (state, last progress event, result), ``GET /api/jobs/{id}/events``
  (server-sent events), ``DELETE /api/jobs/{id}`` (cancel: the worker killed and replaced, no
  result folder left); ``GET /api/fea``: whether CalculiX is installed
  (:mod:`corrugate.web.jobs`);
* ``POST /api/spec/toml``: the body of ``/api/design`` -> the spec file ``corrugate design`` reads
  (``text/plain``, TOML: the request's ``cutter`` as ``[fabrication] machine``, the other output
  options as a comment naming the CLI's options), 422 naming a bad key;
  ``POST /api/spec/parse``: ``{"toml": <a spec file's text>}`` -> its keys as JSON, the form's
  ``cutter`` from ``[fabrication] machine`` (422 naming the key or the TOML error, as the CLI);
* ``GET /api/results/{id}/{name}``: a file the app made (looked up, never a path);
  ``GET /api/results/{id}/all.zip``: all of them in one zip archive.

Every computation of a request (its quantities parsed, analysed, meshed, its files written,
its spec solved) runs in a worker process of :class:`~corrugate.web.workers.Runner`: the quick
lane's for a request (a design within a :class:`~corrugate.web.workers.Share` of all its workers
but one, so an analysis never waits behind a design), the job pool's for a job (so a job never
delays a request); the
``*_job`` functions take and return plain picklable values (a job that writes files writes them
into a new result's folder, the server publishes them). A worker is killed at the time limit
(504) and replaced; its address space is capped (a job that needs more memory gets 422). The
event loop only reads requests, serves the page, the library and stored files, and waits.

Errors: a bad value -> 422 ``{"detail", "field", "errors": [...]}`` naming the field as the request
names it (a spec value by its TOML path, ``constraints.side.min``); malformed JSON -> 400; body over
the limit -> 413; body not complete within ``body_timeout_s`` -> 408; server busy, the job
queue full (with ``Retry-After``) or a worker lost -> 503; computation over the time limit -> 504 (its worker killed); more memory than a worker
may use -> 422 naming the body; unknown result or file -> 404; a Host header not allowed -> 400.
"""

from __future__ import annotations

import asyncio
import base64
import contextlib
import hashlib
import json
import logging
import math
import re
import threading
import time
from collections.abc import AsyncIterator, Callable
from contextlib import asynccontextmanager
from dataclasses import dataclass, replace
from pathlib import Path
from typing import Any

import numpy as np
from fastapi import Depends, FastAPI, Request
from fastapi.exceptions import RequestValidationError
from fastapi.openapi.docs import get_swagger_ui_html
from fastapi.responses import (
    FileResponse,
    HTMLResponse,
    JSONResponse,
    Response,
    StreamingResponse,
)
from fastapi.staticfiles import StaticFiles
from starlette.concurrency import run_in_threadpool
from starlette.exceptions import HTTPException as StarletteHTTPException

from corrugate import __version__
from corrugate.analysis.evaluate import Analysis
from corrugate.core.errors import InputError, OutputError
from corrugate.core.limits import LIMITS
from corrugate.core.memory import available_memory
from corrugate.core.units import ureg
from corrugate.export.machines import Machine
from corrugate.export.plan import OutputOptions
from corrugate.materials.library import library
from corrugate.mechanics.moduli import DEFAULT_MODEL, MODELS
from corrugate.names import DEFAULT_FOLD_STYLE, DEFAULT_PAPER
from corrugate.solver import Problem
from corrugate.spec.inputs import AnalysisRequest, analysis_request
from corrugate.spec.schema import Spec, SpecError, parse_spec
from corrugate.spec.toml_text import read_spec_toml, spec_toml
from corrugate.web.guards import BodySizeLimit, CatchAll, HostCheck, long_integers
from corrugate.web.jobs import Job, JobTable, solver_progress, sse
from corrugate.web.ondemand import FileMaker, FilesRecipe, recipe_of
from corrugate.web.schemas import (
    LOAD_CASE_KEYS,
    OUTPUT_OPTIONS,
    AnalyzeBody,
    DesignAnswer,
    DesignBody,
    ErrorBody,
    FeaInfo,
    FieldError,
    FormatInfo,
    JobBody,
    LoadCaseInfo,
    ModelInfo,
    ModelsBody,
    OutputBody,
    PatternBody,
    ResultBody,
    ResultFile,
    SpecFileBody,
    VerifyBody,
    format_list,
    load_case_list,
)
from corrugate.web.store import ZIP_NAME, ResultStore, StoredFile, file_response, zip_response
from corrugate.web.workers import (
    WORKER_MEMORY_BYTES,
    ComputeTimeoutError,
    Runner,
    ServerBusyError,
    Share,
    WorkerLostError,
    core_count,
    memory_cap,
    send_progress,
    wants_progress,
)
from corrugate.workflow import (
    DesignRequest,
    Events,
    MadeFor,
    Names,
    json_safe,
    made_for,
    output_errors,
    output_options,
    resolve_machine,
    run,
)

__all__ = [
    "FE_MEMORY_BYTES",
    "JOB_WALL_PER_CPU",
    "LOOPBACK_NAMES",
    "SOLVER_SHARE",
    "STATIC_DIR",
    "WebSettings",
    "analysis_payload",
    "check_design_job",
    "create_app",
    "design_answer",
    "design_job",
    "fea_info",
    "mesh_job",
    "pattern_job",
    "verify_job",
]

_log = logging.getLogger("corrugate.web")

#: Host names of this machine: what a browser sends to a server bound to a loopback address.
LOOPBACK_NAMES = ("127.0.0.1", "localhost", "[::1]")

#: The page, its script and the vendored front-end libraries.
STATIC_DIR = Path(__file__).resolve().parent / "static"

#: pint's registry keeps caches that are not documented as thread-safe: parse one request at a time
#: (parsing takes microseconds; each worker process runs one job at a time, so it rarely waits).
_PARSE_LOCK = threading.Lock()

_SWAGGER = "/static/vendor/swagger-ui"

_VALUE = "allowed a number or a string with units, e.g. '8' or '0.3 in'"
#: What each field takes, for type errors (pydantic's own words name the union's members).
_EXPECTED: dict[str, str] = {
    **{k: _VALUE for k in AnalyzeBody.model_fields},
    **{k: "allowed a string" for k in ("material", "material2", "layout", "model")},
    "eta": "allowed a list of angles, e.g. [0, 45, '1.2 rad']",
    "vertices": "allowed '0,0 1,0 0.5,1' or [[0, 0], [1, 0], [0.5, 1]]",
    "holes": "allowed a list of {shape, diameter | vertices, center}, e.g. "
    "[{'shape': 'circle', 'diameter': '6 mm', 'center': [0, 0]}]",
}


#: The share of a design request's time limit given to the solver as its CPU budget (the rest is
#: for writing the files and for a busy machine, where CPU seconds run slower than wall seconds).
SOLVER_SHARE = 0.6


#: The address space an FE verification job may map beyond its worker's start-up mapping
#: (``RLIMIT_AS``, inherited by its CalculiX runs): issue 23 asks the FE to fit in 8 GB.
FE_MEMORY_BYTES = 8 * 1024**3

#: Wall seconds a design job may take per CPU second of its solver budget: the budget is CPU
#: time, and on a shared machine a CPU second takes several wall seconds (the chassis plate of
#: issue 24: 66 s and 70 s of solver CPU, answered after 189 s and 204 s of wall on a 2-core
#: machine shared by other sessions, ``benchmarks/web_job.py``); the rest covers the files.
JOB_WALL_PER_CPU = 4.0


@dataclass(frozen=True, slots=True)
class WebSettings:
    """Limits of the web app.

    ``max_body_bytes``: longest request body (413 past it); ``body_timeout_s``: longest wait for
    a request's body after its head (408 past it); ``timeout_s``: longest computation (504 past
    it; its worker process is killed); ``solver_budget_s``: CPU seconds the solver of one design
    may spend, explanation included (None: :data:`SOLVER_SHARE` of ``timeout_s``, so that a
    design the solver cannot certify in time answers "not certified within the budget" with its
    best design, rather than 504; :mod:`corrugate.solver.budget`); ``worker_memory_bytes``: the address space
    each worker may map beyond its imported modules (``RLIMIT_AS``; None: no cap).

    Two pools of worker processes run the computations. The quick lane (``quick_processes``
    workers) runs the requests: analyses, meshes, patterns, spec files, a job's input check and
    the synchronous ``POST /api/design``; the designs (and the job checks) may hold at most
    ``quick_processes - 1`` of its workers at once (at least 1), so an analysis never waits
    behind a design; ``max_pending``: requests queued or running at once in it (503 past it).
    The job pool (``processes`` workers, None: one per core, at least 2) runs only the jobs, so a
    job never delays a request. ``max_creases``: largest n of a layer and ``max_extent_mm``: longest
    folded extent of a layer (422 past them; the pattern's glue tabs grow with the size, so these
    bound the memory and time of one request); ``max_results``/``result_ttl_s``: stored results kept; ``results_dir``: where the private
    result root is made (default: the system temporary folder); ``allowed_hosts``: the Host
    headers answered, others get 400 (None: any; ``corrugate serve`` on a loopback address sets
    :data:`LOOPBACK_NAMES` against DNS rebinding).

    Jobs (``/api/jobs``, :mod:`corrugate.web.jobs`): ``job_budget_s``: the solver's CPU seconds
    for a design job unless the client asks for another budget (a larger budget than
    ``max_job_budget_s`` is refused, 422 naming ``budget`` and the range); such a job is stopped
    at :meth:`job_time_limit_s` wall seconds; ``max_queued_jobs``: jobs waiting for a worker of
    the job pool (past it a new job gets 503 with ``Retry-After`` at submission, never a 202:
    :meth:`max_active_jobs` run or wait at once); ``max_jobs``: jobs kept (a finished one for
    ``result_ttl_s``); ``fe_workdir``: the parent of the CalculiX work folders (None: the system
    temporary folder), swept at start-up of the folders no running process owns, and of a
    worker's when it is killed or dies (:mod:`corrugate.fea.workdirs`); ``fe_timeout_s``: wall seconds of an FE verification job
    (and of each CalculiX run in it); ``fe_max_mesh``: its finest mesh (elements per facet): the
    finest a request may ask for, and the one a series not shown asymptotic is refined up to, as
    ``corrugate verify --max-mesh`` (docs/fea.md 6; an extending run whose memory estimate is
    above the job's cap or the memory available is not made: "not converged (memory)");
    ``fe_memory_bytes``: its address-space cap beyond the worker's start-up mapping (CalculiX
    runs as a child of the worker and inherits it; None: the worker's ``worker_memory_bytes``).
    """

    max_body_bytes: int = 64 * 1024
    body_timeout_s: float = 30.0
    timeout_s: float = 30.0
    solver_budget_s: float | None = None
    processes: int | None = None
    worker_memory_bytes: int | None = WORKER_MEMORY_BYTES
    max_pending: int = 32
    max_creases: int = 1000
    max_extent_mm: float = 5000.0
    max_results: int = 200
    result_ttl_s: float = 3600.0
    results_dir: Path | None = None
    allowed_hosts: tuple[str, ...] | None = None
    job_budget_s: float = 120.0
    max_job_budget_s: float = 600.0
    max_jobs: int = 64
    fe_timeout_s: float = 1800.0
    fe_max_mesh: int = 16
    fe_memory_bytes: int | None = FE_MEMORY_BYTES
    quick_processes: int = 2
    max_queued_jobs: int = 16
    fe_workdir: Path | None = None

    @property
    def job_processes(self) -> int:
        """Worker processes of the job pool (``processes``, else one per core, at least 2)."""
        return max(2, core_count()) if self.processes is None else self.processes

    @property
    def max_active_jobs(self) -> int:
        """Jobs running or queued at once: a worker of the job pool each, and
        ``max_queued_jobs`` waiting."""
        return self.job_processes + self.max_queued_jobs

    def job_time_limit_s(self, budget_s: float) -> float:
        """Wall seconds a design job with a solver budget of ``budget_s`` CPU seconds may run
        before it is stopped: :data:`JOB_WALL_PER_CPU` times the budget, so that the solver's
        budget, not the wall clock, ends a job on a busy machine."""
        return JOB_WALL_PER_CPU * budget_s

    @property
    def design_budget_s(self) -> float:
        """CPU seconds of the solver for one design request (``solver_budget_s``, else
        :data:`SOLVER_SHARE` of the time limit)."""
        if self.solver_budget_s is not None:
            return self.solver_budget_s
        return max(LIMITS["budget"].lo, SOLVER_SHARE * self.timeout_s)


def _check_size(req: AnalysisRequest, settings: WebSettings) -> None:
    """The web app's own bounds on the work one request may cause (the CLI has none)."""
    for suffix, layer in (("", req.assembly.layer1), ("2", req.assembly.layer2)):
        if layer.n > settings.max_creases:
            raise InputError(
                f"n{suffix}",
                layer.n,
                f"1 <= n <= {settings.max_creases} in the web app (use the CLI)",
            )
        if layer.chord_extent > settings.max_extent_mm:
            raise InputError(
                f"W{suffix}",
                f"{layer.W:g} mm",
                f"a folded extent (n + 1) W sin(alpha/2) <= {settings.max_extent_mm:g} mm in "
                "the web app (use the CLI)",
                reason=f"makes a part {layer.chord_extent:.4g} mm long",
            )


def _parse(body: AnalyzeBody, settings: WebSettings) -> AnalysisRequest:
    options = body.model_dump(
        exclude={"model", "eta", "support", *OUTPUT_OPTIONS, *LOAD_CASE_KEYS}, exclude_none=True
    )
    with _PARSE_LOCK:
        req = analysis_request(
            model=body.model, eta=body.eta, support=body.support, joint=body.joint, **options
        )
    _check_size(req, settings)
    return req


def _first_non_finite(obj: object, where: str = "") -> str | None:
    """The key path of the first NaN or infinity in a JSON-like object, or None."""
    if isinstance(obj, float):
        return None if math.isfinite(obj) else where or "value"
    items: list[tuple[str, object]] = []
    if isinstance(obj, dict):
        items = [(f"{where}.{k}" if where else str(k), v) for k, v in obj.items()]
    elif isinstance(obj, list | tuple):
        items = [(f"{where}[{i}]", v) for i, v in enumerate(obj)]
    for key, value in items:
        found = _first_non_finite(value, key)
        if found is not None:
            return found
    return None


def _require_finite(payload: dict[str, object]) -> None:
    bad = _first_non_finite(payload)
    if bad is not None:
        raise InputError(
            "body",
            "the request",
            "inputs of physically sensible magnitude",
            reason=f"gives a result that is not finite ({bad}): the inputs overflow the formulas",
        )


def _text(value: float | str | None) -> str | None:
    return None if value is None else str(value)


def analysis_payload(body: AnalyzeBody, settings: WebSettings) -> dict[str, object]:
    """``Analysis.to_dict()`` of the request (a job: runs in a worker process), with the ``load_case``
    of ``corrugate analyze --json`` when the body states one (``test``, ``load``, ``span``:
    :mod:`corrugate.analysis.load_case`, errors naming those fields)."""
    from corrugate.analysis.load_case import load_case_dict, load_case_of, load_case_rows

    def field(name: str) -> str:
        return name

    with _PARSE_LOCK:
        case = load_case_of(body.test, _text(body.load), _text(body.span), field)
    req = _parse(body, settings)
    with np.errstate(all="ignore"):  # overflow is reported as a 422 below, not as warnings
        result = req.run()
        payload = result.to_dict()
        if case is not None:
            payload["load_case"] = load_case_dict(case, load_case_rows(result, case, field))
    _require_finite(payload)
    return payload


def mesh_job(body: AnalyzeBody, settings: WebSettings, folder: Path) -> list[Path]:
    """Build the folded assembly of the request and write it as GLB and STL into ``folder`` (a
    job: runs in a worker process)."""
    from corrugate.export.files3d import write_mesh
    from corrugate.fabrication.build import build_pattern

    req = _parse(body, settings)
    a = req.assembly
    return list(write_mesh(a, build_pattern(a), folder))


def pattern_job(body: PatternBody, settings: WebSettings, folder: Path) -> list[Path]:
    """Every file ``corrugate pattern --out`` writes for the request's design, written into
    ``folder`` (a job: runs in a worker process): the CLI's own writer,
    :func:`corrugate.workflow.write_design_files`."""
    from corrugate.analysis.evaluate import analyze
    from corrugate.workflow import write_design_files

    req = _parse(body, settings)
    with _PARSE_LOCK:
        options = _output_options(body)
    analysis = analyze(req.assembly, req.model, (0.0, 90.0), options.fabrication, req.support)

    with output_errors(_NAMES, body.cutter):
        return list(write_design_files(analysis, folder, options))


async def files_answer(
    job: Callable[[Any, WebSettings, Path], list[Path]],
    body: Any,
    settings: WebSettings,
    store: ResultStore,
    runner: Runner,
) -> list[StoredFile]:
    """Run ``job(body, settings, folder)`` on the runner into a new result's folder of ``store``
    and publish the files it wrote (the result goes when the job fails or is stopped)."""
    with store.reserved() as (result_id, folder):
        paths = await runner.run(job, body, settings, folder)
        return store.publish(result_id, paths)


#: The request's fields the files step's errors name (a part too large for the machine, a
#: perforation the fold lines cannot take): :func:`corrugate.workflow.steps.output_errors`.
_NAMES = Names(machine="cutter", cut="cut", gap="gap")


def _output_options(
    body: OutputBody, made: MadeFor | None = None, machine: Machine | None = None
) -> OutputOptions:
    """The output options of a design or pattern request, as ``corrugate design --cutter ...
    --fold-style ... --cut ... --gap ... --paper ...`` reads them
    (:func:`corrugate.workflow.output_options`, default spacing, margin and tabs), for the
    machine and fold operations a design's spec is made for (:func:`corrugate.workflow.made_for`;
    None: the request's cutter, the machine's operations; ``machine``: its profile, when resolved);
    errors name the request's field."""
    return output_options(
        machine if machine is not None else body.cutter if made is None else made.cutter,
        body.fold_style,
        body.cut,
        body.gap,
        paper=body.paper,
        names={"fold-line style": "fold_style"},
        mountain=None if made is None else made.mountain,
        valley=None if made is None else made.valley,
        marks=None if made is None else made.marks,
    )


def _check_spec_size(spec: Spec, settings: WebSettings) -> None:
    """The web app's own bound on the crease count a spec may ask for (the CLI has none)."""
    if spec.variables.n.max > settings.max_creases:
        raise InputError(
            "variables.n.max",
            spec.variables.n.max,
            f"n <= {settings.max_creases} in the web app (use the CLI)",
        )


def _check_design_size(analysis: Analysis, settings: WebSettings) -> None:
    """Files are written only for a part the web app bounds (as for ``/api/mesh``)."""
    for layer in analysis.assembly.layers:
        if layer.chord_extent > settings.max_extent_mm:
            raise InputError(
                "variables.W.max",
                f"{layer.W:g} mm at the optimum",
                f"an optimum folding to at most {settings.max_extent_mm:g} mm in the web app "
                "(bound W, n or the size; or use the CLI)",
                reason=f"makes a part {layer.chord_extent:.4g} mm long",
            )


def _spec_data(body: DesignBody) -> dict[str, Any]:
    """The spec part of a design request: the keys the client sent, minus the output options."""
    return body.model_dump(exclude_unset=True, exclude=set(OUTPUT_OPTIONS))


def _result_body(files: list[StoredFile]) -> ResultBody:
    return ResultBody(
        id=files[0].result_id,
        files=[
            ResultFile(name=f.name, url=f.url, media_type=f.media_type, bytes=f.path.stat().st_size)
            for f in files
        ],
    )


def _prepare_design(body: DesignBody, settings: WebSettings) -> DesignRequest:
    """Read a design request as the CLI reads a spec and its options (:func:`_read_design`),
    raising its first bad value; the request (no output folder: answers first)."""
    return _read_design(body, settings)[0]


def _read_design(
    body: DesignBody, settings: WebSettings, budget_s: float | None = None
) -> tuple[DesignRequest, OutputOptions]:
    """Read a design request as the CLI reads a spec and its options, into the one request of a
    run (:class:`~corrugate.workflow.request.DesignRequest`, without an output folder: the
    answer comes first; its solver within ``budget_s`` CPU seconds, None:
    ``settings.design_budget_s``) and the output options of its files, made later
    (:mod:`corrugate.web.ondemand`); errors name the request's fields (the spec's by their TOML
    path)."""
    with _PARSE_LOCK:  # pint parses the spec's quantities, inline materials and the options
        try:
            spec = parse_spec(_spec_data(body))
        except SpecError as exc:
            if exc.reason == "is not a known key" and "." not in exc.field:
                allowed = f"{exc.allowed}, or an output option: {', '.join(OUTPUT_OPTIONS)}"
                raise SpecError(exc.field, exc.value, allowed, reason=exc.reason) from None
            raise
        # the request's cutter, when given, is the spec's machine (as design --machine is);
        # else the files are for the spec's [fabrication] machine
        given = body.cutter if "cutter" in body.model_fields_set else None
        # an unknown machine names the request's cutter; the machine is looked up once
        machine = None if given is None else resolve_machine(given)
        made = made_for(spec, given)
        spec = made.spec
        problem = Problem.from_spec(spec)
        if machine is None:
            machine = resolve_machine(made.cutter)  # the spec's (a checked name) or the default
        options = _output_options(body, made, machine)
    _check_spec_size(spec, settings)
    request = DesignRequest(
        spec,
        json.dumps(_spec_data(body), indent=2),
        problem,
        machine,
        settings.design_budget_s if budget_s is None else budget_s,
        None,
        strict_json=True,
        names=_NAMES,
    )
    return request, options


def spec_file_job(body: DesignBody, settings: WebSettings) -> str:
    """The spec file of a design request (``POST /api/spec/toml``): its spec keys as TOML
    (:func:`corrugate.spec.toml_text.spec_toml`), the request's ``cutter`` as ``[fabrication]
    machine`` (what ``corrugate design`` reads of a machine) and its other output options, which
    a spec does not hold, in a comment as the CLI's options. The request is read first as
    :func:`design_job` reads it: a bad value raises its error naming the field, nothing is made.
    A job: runs in a worker process."""
    _prepare_design(body, settings)
    data = _spec_data(body)
    if "cutter" in body.model_fields_set:
        fab = data.get("fabrication")
        data["fabrication"] = {**(fab if isinstance(fab, dict) else {}), "machine": body.cutter}
    options = []
    if body.fold_style != DEFAULT_FOLD_STYLE:
        options.append(f"--fold-style {body.fold_style}")
    for key in ("cut", "gap"):
        value = getattr(body, key)
        if value is not None and body.fold_style == "perforated":
            options.append(f"--{key} '{value}'")
    if body.paper != DEFAULT_PAPER:
        options.append(f"--paper {body.paper}")
    comments = ["a spec saved by the corrugate web page: corrugate design FILE.toml"]
    if options:
        comments.append(
            "the page's output options: corrugate design FILE.toml " + " ".join(options)
        )
    with _PARSE_LOCK:
        return spec_toml(data, comments)


def spec_parse_job(body: SpecFileBody) -> dict[str, Any]:
    """A spec file read into the page's form (``POST /api/spec/parse``): the file checked as
    ``corrugate design`` checks it (a bad value raises its error naming the key), then its keys as
    written, with ``[fabrication] machine`` as the form's ``cutter`` (the machine's checked
    name). A job: runs in a worker process."""
    with _PARSE_LOCK:
        spec, data = read_spec_toml(body.toml, body.name)
    machine = spec.fabrication.machine
    fab = data.get("fabrication")
    if machine not in (None, "none") and isinstance(fab, dict):
        fab.pop("machine", None)
        if not fab:
            del data["fabrication"]
        data["cutter"] = machine
    return data


def check_design_job(body: DesignBody, settings: WebSettings) -> None:
    """Read a design request and raise its first bad value (a job: runs in a worker process,
    before a design job is queued, so that bad input is 422 at once)."""
    _prepare_design(body, settings)


def design_job(
    body: DesignBody, settings: WebSettings, budget_s: float | None = None
) -> tuple[Any, bytes | None]:
    """Solve the spec of a design request within ``budget_s`` CPU seconds (None:
    ``settings.design_budget_s``), answers first: returns the ``corrugate design --json`` object
    and the recipe of its files (:class:`~corrugate.web.ondemand.FilesRecipe` as bytes; None for
    an infeasible spec, which has no files), which the server keeps so that the files are made
    when they are asked for (:mod:`corrugate.web.ondemand`). A job: runs in a worker process
    (which hands its freed memory back to the system after every job,
    :func:`~corrugate.web.workers.release_memory`); it takes and returns plain, picklable values.
    When its caller wants progress (a job of ``/api/jobs``) it sends the stage it is in and the
    branch and bound's iterations, gap and best value (:func:`corrugate.web.jobs.solver_progress`)."""
    if not wants_progress():
        return _design(body, settings, budget_s)
    send_progress({"stage": "reading"})
    with solver_progress() as events:
        return _design(body, settings, budget_s, solved=events.flush)


def _nothing() -> None:
    pass


def _design(
    body: DesignBody,
    settings: WebSettings,
    budget_s: float | None,
    solved: Callable[[], None] = _nothing,
) -> tuple[Any, bytes | None]:
    """The run of a design request without its files (:func:`corrugate.workflow.steps.run`, the
    steps of ``corrugate design``) and the recipe of its files: ``solved`` is called once the
    search is over (the search's last progress event). An optimum past the web app's size bound
    is refused here, as before its files were written."""
    request, options = _read_design(body, settings, budget_s)
    answer = run(request, Events(solved=solved))
    analysis = answer.solution.analysis
    if analysis is None:
        return answer.payload, None
    _check_design_size(analysis, settings)
    # the files need the solution and the answer's JSON, not the robust search's Monte Carlo
    # samples (some 1 MB for examples/blimp_gripper_robust.toml; 10-13 kB without, pickled)
    run_ = replace(answer.design, robust=None)
    recipe = FilesRecipe(run_, request.text, options, request.machine.name, request.names)
    return answer.payload, recipe_of(recipe)


def design_id_of(body: DesignBody, payload: dict[str, Any], store: ResultStore) -> str:
    """The design id of a request and its answer (:meth:`~corrugate.web.store.DesignCache.key`
    of the request's spec and output options, as canonical JSON, and of the answer's design)."""
    request = json.dumps(body.model_dump(mode="json"), sort_keys=True, separators=(",", ":"))
    design = json.dumps(payload.get("design"), sort_keys=True, separators=(",", ":"))
    return store.designs.key(request.encode(), design.encode())


def answer_of(
    body: DesignBody, payload: dict[str, Any], recipe: bytes | None, files: FileMaker
) -> DesignAnswer:
    """The answer of a design request: the design, and, for a design with files, its
    ``design_id`` and ``files_url`` (its recipe kept in the store) and its files when they are
    already made (``result``; null until they are asked for)."""
    if recipe is None:
        return DesignAnswer(design=payload, result=None, design_id=None, files_url=None)
    design_id = design_id_of(body, payload, files.store)
    files.store.designs.add(design_id, recipe)
    made = files.stored(design_id)
    return DesignAnswer(
        design=payload,
        result=None if made is None else _result_body(made),
        design_id=design_id,
        files_url=f"/api/designs/{design_id}/files",
    )


async def design_answer(
    body: DesignBody,
    settings: WebSettings,
    runner: Runner,
    files: FileMaker,
    share: Share | None = None,
) -> DesignAnswer:
    """Run :func:`design_job` on the runner (a worker process, within ``share`` of its workers
    if given): the answer first, its files made when asked for (:func:`answer_of`)."""
    async with share.turn() if share is not None else contextlib.nullcontext():
        payload, recipe = await runner.run(design_job, body, settings)
    return answer_of(body, payload, recipe, files)


def verify_job(
    folder: Path,
    meshes: tuple[int, ...],
    timeout_s: float,
    memory_bytes: int | None = None,
    workdir: Path | None = None,
    max_mesh: int | None = None,
) -> dict[str, Any]:
    """``corrugate verify --json`` of the design in ``folder`` (a stored result's folder), with
    its ``design`` label, on the mesh series ``meshes``, each CalculiX run stopped after
    ``timeout_s`` (:func:`corrugate.fea.verify.verify_design`), its work folders in ``workdir``
    (None: the system temporary folder), and its address space capped at
    ``memory_bytes`` beyond the worker's start-up mapping (None: the worker's own cap;
    :func:`corrugate.web.workers.memory_cap`). A job: runs in a worker process
    and sends one progress event per CalculiX run (``{"stage": "fe", "run": k, "line": ...}``,
    the line ``corrugate verify`` prints on stderr). Constraints without an FE twin come back as
    verify's own rows (``verdict`` "not checked", ``note`` saying why). A series not shown
    asymptotic is extended up to ``max_mesh`` elements per facet (None: the finest requested,
    no extension), as ``corrugate verify --max-mesh`` does, except that an extending run whose
    estimated memory (:data:`corrugate.fea.verify.BYTES_PER_NODE`) is above ``memory_bytes`` or
    the memory the machine has available is not made: its row is "not converged (memory)". The
    verdicts, ``exit_code`` and ``statement`` are the CLI's."""
    from corrugate.export.record import design_label, read_design
    from corrugate.fea.verify import verify_design

    assembly, constraints, joint = read_design(folder)
    count = 0

    def line(text: str) -> None:
        nonlocal count
        count += 1
        send_progress({"stage": "fe", "run": count, "line": f"[{count}] {text}"})

    send_progress({"stage": "reading"})
    limits = [m for m in (memory_bytes, available_memory()) if m is not None]
    with memory_cap(memory_bytes):
        result = verify_design(
            assembly,
            constraints,
            joint,
            meshes,
            progress=line,
            folder=workdir,
            timeout=timeout_s,
            max_mesh=max(meshes) if max_mesh is None else max(max_mesh, max(meshes)),
            memory_bytes=min(limits) if limits else None,
        )
    payload: dict[str, Any] = json_safe(
        {"design": design_label(assembly), "runs": count, **result.as_json()}
    )
    return payload


def fea_info(settings: WebSettings) -> FeaInfo:
    """Whether CalculiX is installed (:func:`corrugate.fea.ccx.find_ccx`) and what a web
    verification may run."""
    from corrugate.fea.ccx import SolverNotFoundError, find_ccx

    try:
        ccx: str | None = find_ccx()
        message = f"CalculiX found: {ccx}"
    except SolverNotFoundError as exc:
        ccx, message = None, f"FE verification needs CalculiX (ccx) on the server: {exc}"
    return FeaInfo(
        available=ccx is not None,
        ccx=ccx,
        message=message,
        max_mesh=settings.fe_max_mesh,
        time_limit_s=settings.fe_timeout_s,
    )


def _check_verify(
    body: VerifyBody, settings: WebSettings, store: ResultStore
) -> tuple[Path, tuple[int, ...]]:
    """The folder of the design to verify and the mesh series, or an InputError naming the
    request's field (``result``, ``mesh``, ``layout``: verify's own checks of the design)."""
    from corrugate.export.record import RECORD_NAME, read_design
    from corrugate.fea.verify import parse_meshes

    with _PARSE_LOCK:
        meshes = parse_meshes(body.mesh)
    if meshes[-1] > settings.fe_max_mesh:
        raise InputError(
            "mesh",
            body.mesh,
            f"at most {settings.fe_max_mesh} elements per facet in the web app (use corrugate verify)",
        )
    record = store.get(body.result, RECORD_NAME)
    if record is None:
        raise InputError(
            "result",
            body.result,
            "the id of a stored design result (results are kept for a while only)",
            reason="is not one",
        )
    folder = record.path.parent
    read_design(folder)  # the design's own record: a layout without FE fixtures is named here
    return folder, meshes


def _storage_detail(exc: OutputError) -> str:
    """What a client is told when the server cannot write a result's files (its disk is full,
    its results folder gone): a server-side failure, said without the server's paths or the
    command line's ``--out``, which the client never gave; the server's log has the path."""
    _log.error("could not write a result: %s", exc)
    reason = getattr(exc, "reason", "") or "an OS error"
    return f"the server could not write the files ({reason}): try again later"


def _failure(exc: BaseException) -> dict[str, Any]:
    """A failed job's ``error``: the HTTP status and body the same failure gets from a request."""
    from corrugate.core.errors import describe

    status, errors = 422, []
    if isinstance(exc, OutputError):
        body = ErrorBody(detail=_storage_detail(exc), field=None, errors=[])
        return {"status": 503, "body": body.model_dump()}
    if isinstance(exc, InputError):
        value = None if exc.value is None else str(exc.value)
        errors = [FieldError(field=exc.field, message=str(exc), value=value, allowed=exc.allowed)]
    elif isinstance(exc, ComputeTimeoutError):
        status = 504
    elif isinstance(exc, ServerBusyError | WorkerLostError | MemoryError | OSError):
        status = 503
    else:
        _log.error("job failed", exc_info=exc)
    body = ErrorBody(detail=describe(exc), field=errors[0].field if errors else None, errors=errors)
    return {"status": status, "body": body.model_dump()}


async def _run_job(
    job: Job, runner: Runner, fn: Callable[..., Any], *args: Any, timeout_s: float
) -> Any:
    """``fn(*args)`` on the runner with ``job`` collecting its progress events."""
    loop = asyncio.get_running_loop()

    def on_progress(event: dict[str, Any]) -> None:  # on a runner thread
        loop.call_soon_threadsafe(job.progress, event)

    return await runner.run(fn, *args, timeout_s=timeout_s, on_progress=on_progress)


async def design_job_task(
    job: Job, body: DesignBody, settings: WebSettings, files: FileMaker, runner: Runner
) -> None:
    """The task of a design job: :func:`design_job`, answers first (its files made when asked
    for, :func:`answer_of`); the job ends ``done`` with the answer of ``POST /api/design``, or
    ``failed`` or ``cancelled``."""
    try:
        payload, recipe = await _run_job(
            job,
            runner,
            design_job,
            body,
            settings,
            job.limits["budget_s"],
            timeout_s=job.limits["time_limit_s"],
        )
        answer = answer_of(body, payload, recipe, files)
        job.end("done", answer.model_dump())
    except asyncio.CancelledError:
        job.end("cancelled")
    except Exception as exc:
        job.end("failed", error=_failure(exc))


async def verify_job_task(
    job: Job, folder: Path, meshes: tuple[int, ...], settings: WebSettings, runner: Runner
) -> None:
    """The task of an FE verification job (:func:`verify_job`)."""
    try:
        result = await _run_job(
            job,
            runner,
            verify_job,
            folder,
            meshes,
            settings.fe_timeout_s,
            settings.fe_memory_bytes,
            settings.fe_workdir,
            settings.fe_max_mesh,
            timeout_s=settings.fe_timeout_s,
        )
        job.end("done", result)
    except asyncio.CancelledError:
        job.end("cancelled")
    except Exception as exc:
        job.end("failed", error=_failure(exc))


def _error(status: int, detail: str, errors: list[FieldError]) -> JSONResponse:
    body = ErrorBody(detail=detail, field=errors[0].field if errors else None, errors=errors)
    return JSONResponse(body.model_dump(), status_code=status)


def _input_error(exc: InputError) -> JSONResponse:
    value = None if exc.value is None else str(exc.value)
    err = FieldError(field=exc.field, message=str(exc), value=value, allowed=exc.allowed)
    return _error(422, str(exc), [err])


def _shown(value: object, limit: int = 60) -> str:
    text = repr(value)
    return text if len(text) <= limit else text[: limit - 3] + "..."


def _validation_error(exc: RequestValidationError) -> JSONResponse:
    """pydantic's errors as one :class:`FieldError` per field, the most specific one kept.

    A value that fails a union (number or string) gets one error per member; a member's own limit
    (a string too long, a list too long) says more than "not an integer", so it wins.
    """
    chosen: dict[str, tuple[bool, str]] = {}
    status = 422
    for e in exc.errors():
        loc = [str(p) for p in e.get("loc", ()) if p != "body"]
        kind = str(e.get("type", ""))
        if kind == "json_invalid":
            status = 400
            chosen.setdefault("body", (True, f"malformed JSON: {e.get('msg', '')}"))
            continue
        field = loc[0] if loc else "body"  # union members add their type to the location
        msg = str(e.get("msg", "is invalid"))
        generic = kind.endswith("_type")
        if kind == "missing":
            msg = f"{field} is required"
        elif kind == "extra_forbidden":
            msg = f"{field} is not a field of this request"
        elif field != "body" and generic:
            msg = f"{field} = {_shown(e.get('input'))} has the wrong type: {_EXPECTED.get(field, msg)}"
        else:
            msg = f"{field} = {_shown(e.get('input'))}: {msg}" if field != "body" else msg
        if field not in chosen or (chosen[field][0] and not generic):
            chosen[field] = (generic, msg)
    errors = [FieldError(field=f, message=m) for f, (_, m) in chosen.items()]
    detail = "; ".join(x.message for x in errors) or "invalid request"
    return _error(status, detail, errors)


def _importmap_hash(html: str) -> str:
    match = re.search(r'<script type="importmap">(.*?)</script>', html, re.S)
    if match is None:
        return ""
    digest = hashlib.sha256(match.group(1).encode("utf-8")).digest()
    return f"'sha256-{base64.b64encode(digest).decode()}'"


class _SecurityHeaders:
    """Pure ASGI middleware adding conservative headers to every answer; no caching of the API."""

    def __init__(self, app: Callable[..., Any]) -> None:
        self.app = app

    async def __call__(self, scope: Any, receive: Any, send: Any) -> None:
        if scope["type"] != "http":
            await self.app(scope, receive, send)
            return
        is_api = str(scope.get("path", "")).startswith("/api/")

        async def send_with_headers(message: Any) -> None:
            if message["type"] == "http.response.start":
                headers = list(message.get("headers", []))
                headers += [
                    (b"x-content-type-options", b"nosniff"),
                    (b"referrer-policy", b"no-referrer"),
                    (b"x-frame-options", b"DENY"),
                ]
                if is_api:
                    headers.append((b"cache-control", b"no-store"))
                message["headers"] = headers
            await send(message)

        await self.app(scope, receive, send_with_headers)


#: The error answers of the computing endpoints, for the OpenAPI document.
_ERROR_RESPONSES: dict[int | str, dict[str, Any]] = {
    400: {"model": ErrorBody, "description": "Malformed JSON"},
    413: {"model": ErrorBody, "description": "Request body too large"},
    422: {"model": ErrorBody, "description": "A value is invalid; `field` names it"},
    408: {"model": ErrorBody, "description": "The request body did not arrive in time"},
    503: {
        "model": ErrorBody,
        "description": "Too many computations in flight, or the worker "
        "process was lost (the server is stopping)",
    },
    504: {
        "model": ErrorBody,
        "description": "The computation took longer than the time limit (it was stopped)",
    },
}


def _add_error_handlers(app: FastAPI) -> None:
    """Every error as JSON ``{"detail", "field", "errors"}`` with its status (see the module
    docstring)."""

    @app.exception_handler(InputError)
    async def on_input_error(_: Request, exc: InputError) -> JSONResponse:
        return _input_error(exc)

    @app.exception_handler(RequestValidationError)
    async def on_validation_error(_: Request, exc: RequestValidationError) -> JSONResponse:
        return _validation_error(exc)

    @app.exception_handler(StarletteHTTPException)
    async def on_http_error(_: Request, exc: StarletteHTTPException) -> JSONResponse:
        errors = (
            [FieldError(field="body", message=str(exc.detail))] if exc.status_code == 400 else []
        )
        response = _error(exc.status_code, str(exc.detail), errors)
        response.headers.update(exc.headers or {})
        return response

    @app.exception_handler(OutputError)
    async def on_output_error(_: Request, exc: OutputError) -> JSONResponse:
        return _error(503, _storage_detail(exc), [])

    @app.exception_handler(ServerBusyError)
    async def on_busy(_: Request, exc: ServerBusyError) -> JSONResponse:
        response = _error(503, str(exc), [])
        response.headers["retry-after"] = str(exc.retry_after_s)
        return response

    @app.exception_handler(WorkerLostError)
    async def on_worker_lost(_: Request, exc: WorkerLostError) -> JSONResponse:
        response = _error(503, str(exc), [])
        response.headers["retry-after"] = "5"
        return response

    @app.exception_handler(ComputeTimeoutError)
    async def on_timeout(_: Request, exc: ComputeTimeoutError) -> JSONResponse:
        return _error(504, str(exc), [])


def _page_csp(index_html: str) -> str:
    """The page's Content-Security-Policy: its own scripts and the import map only."""
    return (
        "default-src 'self'; "
        f"script-src 'self' {_importmap_hash(index_html)}; "
        "style-src 'self'; img-src 'self' data: blob:; connect-src 'self' blob:; "
        "object-src 'none'; base-uri 'none'; form-action 'none'; frame-ancestors 'none'"
    )


def _add_pages(app: FastAPI, index_html: str) -> None:
    """The single page (``/``) and the offline Swagger UI (``/docs``)."""
    page_csp = _page_csp(index_html)

    @app.get("/", include_in_schema=False)
    async def index() -> HTMLResponse:
        return HTMLResponse(index_html, headers={"content-security-policy": page_csp})

    @app.get("/docs", include_in_schema=False)
    async def docs() -> HTMLResponse:
        return get_swagger_ui_html(
            openapi_url=app.openapi_url or "/openapi.json",
            title="corrugate API",
            swagger_js_url=f"{_SWAGGER}/swagger-ui-bundle.js",
            swagger_css_url=f"{_SWAGGER}/swagger-ui.css",
            swagger_favicon_url=f"{_SWAGGER}/favicon-32x32.png",
        )


def _add_api(
    app: FastAPI,
    cfg: WebSettings,
    runner: Runner,
    share: Share,
    store: ResultStore,
    files: FileMaker,
) -> None:
    """The JSON API: library, models, analyze, mesh, design, a design's files (made on demand by
    ``files``) and the result downloads, computed on ``runner`` (the quick lane), a design and
    its files within ``share`` of its workers."""
    error_responses = _ERROR_RESPONSES

    @app.get("/api/materials", summary="The material library")
    async def materials() -> list[dict[str, Any]]:
        """Every library sheet, as ``corrugate materials --json`` prints it."""
        return [m.as_dict() for m in library().values()]

    @app.get("/api/models", summary="The moduli variants")
    async def models() -> ModelsBody:
        """The names accepted by ``model`` and where each comes from."""
        return ModelsBody(
            default=DEFAULT_MODEL,
            models=[ModelInfo(name=m.name, source=m.source) for m in MODELS.values()],
        )

    @app.get("/api/formats", summary="The kinds of file the app writes")
    async def formats() -> list[FormatInfo]:
        """Every kind of file ``corrugate design --out`` writes (the writers registry), in the
        order they are written: its ``name``, file-name ``pattern`` (``cut-{sheet}.dxf``),
        ``media_type``, the ``extra`` it needs, a ``description`` and its place in the page's
        list of downloads (``order``, ascending)."""
        return format_list()

    @app.get("/api/load-cases", summary="The load cases a requirement may name")
    async def load_case_endpoint() -> list[LoadCaseInfo]:
        """Every load case of the registry of behaviours (docs/load_cases.md), in the order the
        spec lists them: its ``name`` (a spec's ``test``), ``label`` in the page's lists, its
        ``kind``, whether it is the support's ``own`` K, whether a ``deflection`` bound may name
        it, the ``layouts`` it applies to and its ``text``."""
        return load_case_list()

    @app.post(
        "/api/analyze",
        summary="Analyse one design",
        responses={200: {"description": "`corrugate analyze --json`"}, **error_responses},
    )
    async def analyze_endpoint(body: AnalyzeBody) -> JSONResponse:
        """Stiffness, size, mass and warnings of one design: the object ``corrugate analyze
        --json`` prints (keys carry their units)."""
        payload = await runner.run(analysis_payload, body, cfg)
        return JSONResponse(payload)

    @app.post("/api/mesh", summary="The folded assembly as GLB and STL", responses=error_responses)
    async def mesh_endpoint(body: AnalyzeBody) -> ResultBody:
        """Build the folded assembly (mm, z up) and keep it as a result; download its files from
        the URLs returned."""
        files = await files_answer(mesh_job, body, cfg, store, runner)
        return _result_body(files)

    @app.post(
        "/api/pattern",
        summary="Every file to cut and fold a given design",
        responses=error_responses,
    )
    async def pattern_endpoint(body: PatternBody) -> ResultBody:
        """The files ``corrugate pattern --out`` writes for one design (the analyse options plus
        ``cutter``, ``fold_style``, ``cut``, ``gap``, ``paper``): cut files, fold map, PDF, FOLD,
        GLB/STL, assembly steps and design.json, kept as a result (``all.zip`` holds them all)."""
        files = await files_answer(pattern_job, body, cfg, store, runner)
        return _result_body(files)

    @app.post(
        "/api/design",
        summary="The certified lightest design of a spec, with its files",
        responses=error_responses,
    )
    async def design_endpoint(body: DesignBody) -> DesignAnswer:
        """Solve a design spec (the keys of the TOML file, values with units; see
        ``examples/blimp_gripper.toml``) as ``corrugate design --json`` does, and keep every file
        ``corrugate design --out`` writes as a result (``result`` is null when the spec is
        infeasible: ``design.diagnosis`` says why). A bad spec value gets 422 naming its TOML path,
        e.g. ``constraints.side.min``."""
        return await design_answer(body, cfg, runner, files, share)

    @app.post(
        "/api/designs/{design_id}/files",
        summary="Make (once) and list the files of a design",
        responses={
            **error_responses,
            404: {"model": ErrorBody, "description": "No such design (or it expired)"},
        },
    )
    async def design_files_endpoint(design_id: str) -> ResultBody:
        """Every file ``corrugate design --out`` writes for a design answered by ``POST
        /api/design`` or a design job (``design_id``, the answer's ``files_url``), kept as a
        result: made on the first request for it, once (requests while it is made wait for it),
        the same stored result after."""
        made = await files.files(design_id)
        if made is None:
            return _error(  # type: ignore[return-value]
                404,
                f"no such design: {design_id[:40]!r} (its files are made for a design answered "
                "by POST /api/design or a design job; designs are kept for a while only)",
                [FieldError(field="design_id", message="is not the id of a design kept here")],
            )
        return _result_body(made)

    @app.post(
        "/api/spec/toml",
        summary="The spec file of a design request",
        response_class=Response,
        responses={200: {"content": {"text/plain": {}}}, **error_responses},
    )
    async def spec_file_endpoint(body: DesignBody) -> Response:
        """The TOML file ``corrugate design FILE.toml`` reads for the body of ``/api/design``
        (the same spec, the same answer): the request's ``cutter`` as ``[fabrication] machine``,
        its other output options in a comment. A bad value gets 422 naming its TOML path."""
        text = await runner.run(spec_file_job, body, cfg)
        return Response(
            text,
            media_type="text/plain; charset=utf-8",
            headers={"Content-Disposition": 'attachment; filename="spec.toml"'},
        )

    @app.post("/api/spec/parse", summary="A spec file's keys", responses=error_responses)
    async def spec_parse_endpoint(body: SpecFileBody) -> JSONResponse:
        """The keys of a spec file (TOML, as ``corrugate design`` reads it) as JSON, for the
        page's form; ``[fabrication] machine`` becomes the form's ``cutter``. A bad file gets 422
        naming the key, or the TOML error."""
        return JSONResponse(await runner.run(spec_parse_job, body))

    @app.get(
        "/api/results/{result_id}/" + ZIP_NAME,
        summary="Download every file of a result as one zip archive",
        response_class=Response,
        responses={404: {"model": ErrorBody, "description": "No such result"}},
    )
    async def result_zip(result_id: str) -> Response:
        """Every file of a stored result (the cut files, fold map, FOLD, 3D, report,
        design.json) in one zip archive."""
        # read and deflated on a thread: a large result would hold the event loop
        response = await run_in_threadpool(zip_response, store, result_id)
        if response is None:
            return _error(404, "no such result (results are kept for a while only)", [])
        return response

    @app.get(
        "/api/results/{result_id}/{name}",
        summary="Download a file the app made",
        response_class=FileResponse,
        responses={
            404: {"model": ErrorBody, "description": "No such result or file"},
            422: {"model": ErrorBody, "description": "Invalid request"},
        },
    )
    async def result_file(result_id: str, name: str) -> Response:
        """A file of a stored result, by the id and name the app returned (nothing else)."""
        response = await run_in_threadpool(file_response, store, result_id, name)
        if response is None:
            return _error(404, "no such result or file (results are kept for a while only)", [])
        return response


def _add_jobs(
    app: FastAPI,
    cfg: WebSettings,
    runner: Runner,
    checker: Runner,
    share: Share,
    files: FileMaker,
    jobs: JobTable,
) -> None:
    """The job API: designs and FE verifications that run in the background with progress on
    ``runner`` (the job pool); a design's spec is read first on ``checker`` (the quick lane,
    within ``share`` of its workers), and a job is refused (503) when the queue is full."""
    error_responses = _ERROR_RESPONSES
    not_found: dict[int | str, dict[str, Any]] = {
        404: {"model": ErrorBody, "description": "No such job (or it expired)"}
    }

    def missing() -> JSONResponse:
        return _error(404, "no such job (finished jobs are kept for a while only)", [])

    def start(job: Job, coro: Any) -> JSONResponse:
        job.task = asyncio.get_running_loop().create_task(coro)
        return JSONResponse(
            job.as_dict(), status_code=202, headers={"location": f"/api/jobs/{job.id}"}
        )

    @app.post(
        "/api/jobs/design",
        summary="Start a design job (progress, cancel)",
        status_code=202,
        response_model=JobBody,
        responses=error_responses,
    )
    async def design_job_endpoint(body: DesignBody, budget: float | None = None) -> JSONResponse:
        """The design of ``POST /api/design`` as a background job: answers 202 with the job
        (``id``, ``limits``: ``budget_s`` the solver's CPU seconds, ``budget`` in the query or
        the server's default, and ``time_limit_s`` the wall seconds after which it is stopped)
        once the spec is read (in the quick lane, so not behind the jobs running); a bad value
        is 422 at once, naming its field (a budget past the server's cap too); 503 with
        ``Retry-After`` when the job queue is full. Follow it with
        ``GET /api/jobs/{id}`` or ``/events``; ``DELETE`` cancels it."""
        budget_s = cfg.job_budget_s if budget is None else budget
        if not LIMITS["budget"].lo <= budget_s <= cfg.max_job_budget_s:
            raise InputError(
                "budget",
                budget_s,
                f"{LIMITS['budget'].lo:g} <= budget <= {cfg.max_job_budget_s:g} CPU seconds in "
                "the web app (use the CLI's --budget)",
            )
        jobs.check_room()  # a full queue is 503 before the spec is read
        async with share.turn():
            await checker.run(check_design_job, body, cfg)
        limits = {
            "budget_s": budget_s,
            "time_limit_s": cfg.job_time_limit_s(budget_s),
            "memory_bytes": cfg.worker_memory_bytes,
        }
        job = jobs.new("design", limits)
        return start(job, design_job_task(job, body, cfg, files, runner))

    @app.post(
        "/api/jobs/verify",
        summary="Start an FE verification of a stored design (corrugate verify)",
        status_code=202,
        response_model=JobBody,
        responses={
            **error_responses,
            503: {"model": ErrorBody, "description": "CalculiX is not installed, or busy"},
        },
    )
    async def verify_job_endpoint(body: VerifyBody) -> JSONResponse:
        """``corrugate verify`` on the folder of a design result (``result``: its id) as a
        background job, one progress event per CalculiX run; its result is ``corrugate verify
        --json``. 503 when CalculiX is not installed (``GET /api/fea`` says so beforehand)."""
        info = fea_info(cfg)
        if not info.available:
            return _error(503, info.message, [])
        jobs.check_room()
        folder, meshes = await run_in_threadpool(_check_verify, body, cfg, files.store)
        limits = {
            "time_limit_s": cfg.fe_timeout_s,
            "memory_bytes": cfg.fe_memory_bytes or cfg.worker_memory_bytes,
            "meshes": list(meshes),
            "max_mesh": cfg.fe_max_mesh,
        }
        job = jobs.new("verify", limits)
        return start(job, verify_job_task(job, folder, meshes, cfg, runner))

    @app.get("/api/fea", summary="Whether FE verification is available")
    async def fea_endpoint() -> FeaInfo:
        """Whether CalculiX is installed on the server, and the limits of a verification."""
        return fea_info(cfg)

    @app.get(
        "/api/jobs/{job_id}", summary="A job's state", response_model=JobBody, responses=not_found
    )
    async def job_status(job_id: str) -> JSONResponse:
        """The job: ``status``, the last ``progress`` event and, once done, its ``result``."""
        job = jobs.get(job_id)
        return missing() if job is None else JSONResponse(job.as_dict())

    @app.get(
        "/api/jobs/{job_id}/events",
        summary="A job's progress as server-sent events",
        response_class=StreamingResponse,
        responses={200: {"content": {"text/event-stream": {}}}, **not_found},
    )
    async def job_events(job_id: str, request: Request) -> Response:
        """``text/event-stream``: every ``progress`` event (``id`` its sequence number;
        ``Last-Event-ID`` resumes after it, an id it did not give replays from the start), then
        one event named ``done``, ``failed`` or ``cancelled`` carrying the job's state, and the
        stream ends."""
        job = jobs.get(job_id)
        if job is None:
            return missing()
        last = request.headers.get("last-event-id", "0")
        # an id this stream gave (ASCII digits): "²" is a digit to str.isdigit, not to int(), and
        # 5000 digits are beyond int(); any other id replays from the start
        after = int(last) if last.isascii() and last.isdigit() and len(last) <= 18 else 0
        return StreamingResponse(
            sse(job, after),
            media_type="text/event-stream",
            headers={"x-accel-buffering": "no"},
        )

    @app.delete(
        "/api/jobs/{job_id}", summary="Cancel a job", response_model=JobBody, responses=not_found
    )
    async def job_cancel(job_id: str) -> JSONResponse:
        """Cancel the job if it has not finished (its worker process is killed and replaced; the
        result it was writing is discarded); answers its state."""
        job = jobs.get(job_id)
        if job is None:
            return missing()
        jobs.cancel(job)
        if job.task is not None:
            with contextlib.suppress(asyncio.CancelledError):
                await asyncio.wait({job.task}, timeout=10)
        return JSONResponse(job.as_dict())


def create_app(settings: WebSettings | None = None) -> FastAPI:
    """A new, independent application (its own worker pool and result store)."""
    cfg = settings or WebSettings()
    from corrugate.fea.workdirs import sweep_owned, sweep_stale

    def reap(pid: int) -> None:  # a job's worker ended: its CalculiX work folders go
        sweep_owned(pid, cfg.fe_workdir)

    # The job pool: the jobs only, each admitted one a slot (never refused busy once accepted).
    runner = Runner(
        cfg.max_active_jobs,
        cfg.timeout_s,
        processes=cfg.job_processes,
        memory_bytes=cfg.worker_memory_bytes,
        ceiling_bytes=cfg.fe_memory_bytes,
        reap=reap,
    )
    # The quick lane: every request's computation, and a job's input check before it is queued,
    # so that neither waits behind the jobs; designs hold at most all but one of its workers.
    quick = Runner(
        cfg.max_pending,
        cfg.timeout_s,
        processes=cfg.quick_processes,
        memory_bytes=cfg.worker_memory_bytes,
    )
    share = Share(cfg.quick_processes - 1, cfg.max_pending)
    store = ResultStore(cfg.results_dir, max_results=cfg.max_results, ttl_s=cfg.result_ttl_s)
    jobs = JobTable(cfg.max_jobs, cfg.result_ttl_s, max_active=cfg.max_active_jobs)
    files = FileMaker(store, quick, share)
    started = time.time()
    # Load the unit registry and the material library before the first requests race for them.
    ureg()
    library()
    index_html = (STATIC_DIR / "index.html").read_text(encoding="utf-8")

    @asynccontextmanager
    async def lifespan(_: FastAPI) -> AsyncIterator[None]:
        # CalculiX work folders left by a server or worker that was killed (none runs now)
        swept = sweep_stale(cfg.fe_workdir, before=started)
        if swept:
            _log.info("removed %d CalculiX work folders left by ended processes", len(swept))
        quick.start_processes()  # the workers import their modules before the first request
        runner.start_processes()
        try:
            yield
        finally:
            jobs.close()
            quick.shutdown()
            runner.shutdown()
            store.close()

    app = FastAPI(
        title="corrugate",
        version=__version__,
        description=(
            "Analyse and design origami-inspired OADLC stiffening panels. `/api/analyze` and "
            "`/api/mesh` take the options of `corrugate analyze`; `/api/design` takes a spec with "
            "the keys of the TOML file and answers as `corrugate design --json`, with its files. "
            "Values are numbers in the field's default unit (mm, deg, MPa, g/cm^3) or strings "
            "with units ('0.3 in', '2.7 GPa'). A bad value gets HTTP 422 with the field named "
            "(a spec value by its TOML path, e.g. `constraints.side.min`)."
        ),
        docs_url=None,
        redoc_url=None,
        lifespan=lifespan,
        dependencies=[Depends(long_integers)],  # 10**400 named by its key, before pydantic
    )
    app.state.settings = cfg
    app.state.store = store
    app.state.runner = runner
    app.state.quick = quick
    app.state.jobs = jobs
    _add_error_handlers(app)
    _add_pages(app, index_html)
    app.state.files = files
    _add_api(app, cfg, quick, share, store, files)
    _add_jobs(app, cfg, runner, quick, share, files, jobs)
    app.mount("/static", StaticFiles(directory=STATIC_DIR), name="static")
    app.add_middleware(CatchAll)
    app.add_middleware(_SecurityHeaders)
    app.add_middleware(BodySizeLimit, max_bytes=cfg.max_body_bytes, timeout_s=cfg.body_timeout_s)
    if cfg.allowed_hosts is not None:
        app.add_middleware(HostCheck, allowed=cfg.allowed_hosts)
    return app
