"""Tests of the web app (``corrugate.web``): API, limits, result store, live server and browser."""
