"""The server cannot write a result's files (its disk full, its results folder gone): a
server-side failure, 503 without the server's paths, for a request and for a job alike.

Seen by hand with ``results_dir`` on a 600 kB tmpfs (``mount -t tmpfs -o size=600k``): ``POST
/api/pattern`` answered 422 ``--out = /tmp/full2/corrugate-web-.../... cannot be written (No
space left on device)``, naming a command-line option the client never gave and the server's
folder. The same error is raised here by a route of the test's own, so that the answer can be
checked without filling a disk."""

from __future__ import annotations

from collections.abc import Iterator

import pytest
from fastapi.testclient import TestClient

from corrugate.core.errors import OutputError
from corrugate.web import WebSettings, create_app
from corrugate.web.app import _failure

pytestmark = pytest.mark.slow  # the app starts its worker processes

SECRET = "/srv/corrugate-results/corrugate-web-x1/0123abcd"


def _full() -> OutputError:
    return OutputError("--out", SECRET, "No space left on device")


@pytest.fixture(scope="module")
def api() -> Iterator[TestClient]:
    app = create_app(WebSettings())

    @app.post("/test-only/full-disk")
    async def full_disk() -> None:
        raise _full()

    with TestClient(app, raise_server_exceptions=False) as c:
        yield c


def test_a_result_the_server_cannot_write_is_503_without_its_path(api: TestClient) -> None:
    r = api.post("/test-only/full-disk")
    assert r.status_code == 503, r.text
    answer = r.json()
    assert answer == {
        "detail": "the server could not write the files (No space left on device): try again later",
        "field": None,
        "errors": [],
    }
    assert SECRET not in r.text and "--out" not in r.text


def test_a_job_that_cannot_write_its_result_fails_with_the_same_answer() -> None:
    failure = _failure(_full())
    assert failure["status"] == 503
    assert failure["body"]["detail"].startswith("the server could not write the files")
    assert SECRET not in str(failure)
