"""The local web app (``corrugate serve``): a JSON API and a single page, FastAPI + uvicorn.

Needs the ``web`` extra (``pip install 'corrugate[web]'``). The core package never imports this
subpackage; ``corrugate serve`` imports it when run.
"""

from corrugate.web.app import WebSettings, create_app

__all__ = ["WebSettings", "create_app"]
