"""How long a report takes to open in headless Chromium (issue 26, docs/motion.md "In the report").

Two figures per run, each from a fresh browser profile, in Chromium without a GPU (``--disable-gpu``):

* ``load_s``: the page's load event (``PerformanceNavigationTiming.loadEventEnd``, from navigation start);
* ``view_s``: opened at its 3D view (the address ending in ``#frame=0``: the view put at the top), the time
  until the view has drawn its frame (its ``data-frame`` attribute set; in an earlier commit's report, plotly's
  plot holds its frames), polled every 20 ms through the DevTools protocol.

With ``psutil`` installed, also the CPU seconds Chromium's processes spent from the navigation to each of these
moments (``load_cpu_s``, ``view_cpu_s``): what the opening costs whatever else the machine is doing (its wall time
on an idle machine is about that CPU time spread over the cores Chromium can use).

Usage: ``python benchmarks/bench_report_open.py results/default/report.html [--repeat 3]``; prints JSON with the
file's size [MB], each run's times [s] and the load average. Needs Chromium and the ``websockets`` package.
"""

from __future__ import annotations

import argparse
import asyncio
import json
import os
import shutil
import subprocess
import tempfile
import time
import urllib.request
from pathlib import Path

FLAGS = [
    "--headless",
    "--no-sandbox",
    "--disable-gpu",
    "--enable-unsafe-swiftshader",
    "--no-first-run",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
    "--hide-scrollbars",
    "--window-size=1200,700",
]
#: The view drawn: its ``data-frame`` attribute set (or, in a report of an earlier commit, plotly's plot holding its
#: frames and a canvas).
DRAWN = (
    "(function(){var d=document.querySelector('.bs-view');if(d)return d.hasAttribute('data-frame');"
    "var p=document.querySelector('.js-plotly-plot');return !!(p && p._transitionData && p._transitionData._frames"
    " && p._transitionData._frames.length && p.querySelector('canvas'));})()"
)
LOADED = (
    "(function(){var n=performance.getEntriesByType('navigation')[0];return n && n.loadEventEnd>0?n.loadEventEnd:0;})()"
)


def _cpu_seconds(pid: int) -> float:
    """User + system CPU seconds of process ``pid`` and its living descendants (NaN without psutil)."""
    try:
        import psutil
    except ImportError:
        return float("nan")
    root = psutil.Process(pid)
    total = 0.0
    for p in [root, *root.children(recursive=True)]:
        try:
            t = p.cpu_times()
            total += t.user + t.system
        except psutil.Error:
            pass
    return total


async def _measure(ws_url: str, url: str, wait_view: bool, cpu, timeout: float = 60.0) -> tuple:
    import websockets

    async with websockets.connect(ws_url, max_size=None) as ws:
        ids = iter(range(1, 10**9))

        async def call(method, **params):
            i = next(ids)
            await ws.send(json.dumps({"id": i, "method": method, "params": params}))
            while True:
                msg = json.loads(await ws.recv())
                if msg.get("id") == i:
                    return msg.get("result", {})

        async def value(expr):
            r = await call("Runtime.evaluate", expression=expr, returnByValue=True)
            return r.get("result", {}).get("value")

        await call("Page.enable")
        cpu0 = cpu()
        await call("Page.navigate", url=url)
        t_end = time.monotonic() + timeout
        while time.monotonic() < t_end:
            if wait_view:
                if await value(DRAWN):
                    return float(await value("performance.now()")) / 1000.0, cpu() - cpu0
            else:
                ms = await value(LOADED)
                if ms:
                    return float(ms) / 1000.0, cpu() - cpu0
            await asyncio.sleep(0.02)
        raise TimeoutError(url)


def open_time(report: Path, wait_view: bool, port: int = 9333) -> tuple:
    """One measurement in a fresh Chromium: the load event [s], or with ``wait_view`` the view drawn [s], and
    Chromium's CPU seconds until then [s]."""
    chromium = next(shutil.which(n) for n in ("chromium", "chromium-browser", "google-chrome") if shutil.which(n))
    # ignore_cleanup_errors: Chromium's helper processes may still write the profile after the browser exits
    with tempfile.TemporaryDirectory(ignore_cleanup_errors=True) as profile:
        proc = subprocess.Popen(
            [chromium, *FLAGS, f"--user-data-dir={profile}", f"--remote-debugging-port={port}", "about:blank"],
            stdout=subprocess.DEVNULL,
            stderr=subprocess.DEVNULL,
            env={**os.environ, "HOME": profile},
        )
        try:
            for _ in range(200):
                try:
                    targets = json.loads(urllib.request.urlopen(f"http://127.0.0.1:{port}/json").read())
                    page = next(t for t in targets if t["type"] == "page")
                    break
                except (OSError, StopIteration, ValueError):
                    time.sleep(0.05)
            url = report.resolve().as_uri() + ("#frame=0" if wait_view else "")
            return asyncio.run(_measure(page["webSocketDebuggerUrl"], url, wait_view, lambda: _cpu_seconds(proc.pid)))
        finally:
            proc.terminate()
            proc.wait(timeout=30)


def main(argv=None) -> dict:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("report", type=Path)
    ap.add_argument("--repeat", type=int, default=3)
    a = ap.parse_args(argv)
    out = {"report": str(a.report), "size_MB": a.report.stat().st_size / 1e6, "load_average_before": os.getloadavg()[0]}
    for _ in range(a.repeat):
        for key, wait_view in (("load", False), ("view", True)):
            wall, cpu = open_time(a.report, wait_view)
            out.setdefault(f"{key}_s", []).append(round(wall, 3))
            out.setdefault(f"{key}_cpu_s", []).append(round(cpu, 3))
    out["load_average_after"] = os.getloadavg()[0]
    print(json.dumps(out, indent=1))
    return out


if __name__ == "__main__":
    main()
