"""A design's files, made on demand and once (docs/web.md, "Answers first").

``POST /api/design`` and a design job answer with the design alone; the worker that solved it
also returns a :class:`FilesRecipe` (pickled: the solved run, the spec's text, the output options
and the machine's name), which the server keeps by design id in the store
(:class:`corrugate.web.store.DesignCache`). When the page asks for the files (``POST
/api/designs/{id}/files``), :class:`FileMaker` has a worker of the quick lane write them from the
recipe (:func:`design_files_job`: :func:`corrugate.workflow.write_design`, the files
``corrugate design --out`` writes) into a new stored result, once: requests for the same design
while it is being made wait for that one run, and later ones get the stored result.
"""

from __future__ import annotations

import asyncio
import pickle
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

from corrugate.web.store import ResultStore, StoredFile
from corrugate.web.workers import Runner, Share
from corrugate.workflow import Names, output_errors, write_design

if TYPE_CHECKING:
    from corrugate.export.plan import OutputOptions
    from corrugate.workflow import DesignRun

__all__ = ["FileMaker", "FilesRecipe", "design_files_job", "recipe_of"]


@dataclass(frozen=True)
class FilesRecipe:
    """What writing a solved design's files needs: the ``run`` (solution and the answer's JSON
    object, merged into ``design.json``), the spec's ``text`` (shown in the report), the output
    ``options`` (lengths in mm), the ``machine``'s name and the boundary's ``names`` of the
    options the files step's errors name."""

    run: DesignRun
    text: str
    options: OutputOptions
    machine: str
    names: Names


def recipe_of(recipe: FilesRecipe) -> bytes:
    """The recipe as the bytes the server keeps (made in the worker that solved the design)."""
    return pickle.dumps(recipe, protocol=pickle.HIGHEST_PROTOCOL)


def design_files_job(recipe: bytes, folder: Path) -> list[Path]:
    """Write every file of the design of ``recipe`` (bytes of :func:`recipe_of`, which only the
    server holds) into ``folder``, a new result's folder; the paths written. A job: runs in a
    worker process."""
    # bytes made by our own worker and kept by the server: never from a client
    made: FilesRecipe = pickle.loads(recipe)
    with output_errors(made.names, made.machine):
        return write_design(made.run, folder, made.options, made.text)


class FileMaker:
    """The files of the designs of ``store.designs``, made on ``runner`` (within ``share`` of
    its workers) once per design. Lives on the event loop."""

    def __init__(self, store: ResultStore, runner: Runner, share: Share) -> None:
        self.store = store
        self.runner = runner
        self.share = share
        self._making: dict[str, asyncio.Task[list[StoredFile]]] = {}

    def stored(self, design_id: str) -> list[StoredFile] | None:
        """The design's files if they are made and still stored, else None."""
        result_id = self.store.designs.result_id(design_id)
        if result_id is None:
            return None
        return self.store.files(result_id) or None

    async def files(self, design_id: str) -> list[StoredFile] | None:
        """The design's stored files, made now if they are not (or no longer) stored; None when
        the design is not kept (unknown, or expired)."""
        found = self.stored(design_id)
        if found is not None:
            return found
        task = self._making.get(design_id)
        if task is None:
            recipe = self.store.designs.recipe(design_id)
            if recipe is None:
                return None
            task = asyncio.get_running_loop().create_task(self._make(design_id, recipe))
            self._making[design_id] = task
            task.add_done_callback(lambda t: self._done(design_id, t))
        # a client that stops waiting leaves the files to be made for the next one
        return await asyncio.shield(task)

    def _done(self, design_id: str, task: asyncio.Task[list[StoredFile]]) -> None:
        self._making.pop(design_id, None)
        if not task.cancelled():
            task.exception()  # retrieved: every waiter has it raised, or none waits any more

    async def _make(self, design_id: str, recipe: bytes) -> list[StoredFile]:
        async with self.share.turn():
            with self.store.reserved() as (result_id, folder):
                paths = await self.runner.run(design_files_job, recipe, folder)
                files = self.store.publish(result_id, paths)
        self.store.designs.made(design_id, result_id)
        return files
