"""The demo's report.html in a real browser: headless Chromium (the system's, e.g. Debian `chromium`)
driven by Playwright. Every image must decode with a non-zero size and every number of the summary
table must be the one in summary.json. Skips, with the reason, where Playwright or Chromium is absent."""

from __future__ import annotations

import math
import os
import shutil

import pytest


def _chromium() -> str | None:
    env = os.environ.get("NETSHAPE_CHROMIUM")
    if env:
        return env
    for name in ("chromium", "chromium-browser", "google-chrome", "google-chrome-stable"):
        path = shutil.which(name)
        if path:
            return path
    return None


def _lookup(summary: dict, key: str):
    node = summary
    for part in key.split("."):
        node = node[part]
    return node


@pytest.mark.slow
def test_report_in_headless_chromium(demo_run):
    sync_api = pytest.importorskip("playwright.sync_api", reason="playwright is not installed (test extra)")
    exe = _chromium()
    if exe is None:
        pytest.skip("no Chromium on PATH (Debian: apt-get install chromium; or set NETSHAPE_CHROMIUM)")
    out, summary, _ = demo_run
    with sync_api.sync_playwright() as p:
        browser = p.chromium.launch(executable_path=exe, headless=True,
                                    args=["--no-sandbox", "--disable-gpu", "--disable-dev-shm-usage"])
        try:
            page = browser.new_page()
            requests = []
            page.on("request", lambda r: requests.append(r.url))
            page.goto((out / "report.html").as_uri(), wait_until="load")
            images = page.eval_on_selector_all(
                "img", "els => els.map(e => [e.getAttribute('src'), e.complete, e.naturalWidth, e.naturalHeight])")
            cells = page.eval_on_selector_all(
                "td[data-key]", "els => els.map(e => [e.dataset.key, e.textContent.trim()])")
        finally:
            browser.close()
    assert len(images) == 5
    for src, complete, w, h in images:
        assert complete and w > 0 and h > 0, src
    assert all(u.startswith("file://") for u in requests), requests
    keys = [k for k, _ in cells]
    for src in ("deflection", "volumetric", "total"):
        for k in ("max_before_mm", "max_after_mm", "rms_before_mm", "rms_after_mm"):
            assert f"errors.{src}.{k}" in keys
    assert "cycle_time_s.original" in keys and "cycle_time_s.compensated" in keys
    for key, text in cells:
        value = _lookup(summary, key)
        if value is None:
            assert text == "—", key
        else:
            assert math.isclose(float(text), value, rel_tol=1e-5, abs_tol=1e-15), (key, text, value)
