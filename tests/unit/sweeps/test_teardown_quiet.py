"""A sweep's Dask cluster torn down after an interrupt says nothing (issue #40 item 5: a loaded machine made a
worker log "Failed to communicate with scheduler during heartbeat" into the one line of a Ctrl-C): while the
cluster stops after an interrupt, distributed's loggers say only what is critical; after a normal end, errors
still show. Dask itself is replaced by a stand-in that logs as its teardown does."""

from __future__ import annotations

import logging
from types import SimpleNamespace

import pytest

from blastscale.sweeps import runner


class _Client:
    """A client whose chunks raise ``stop`` and whose close logs what distributed logs when its peers are gone."""

    def __init__(self, stop):
        self.stop = stop

    def scheduler_info(self):
        return {"workers": {"a": 1}}

    def submit(self, *args, **kwargs):
        raise self.stop

    def close(self):
        logging.getLogger("distributed.worker").error("Failed to communicate with scheduler during heartbeat.")
        logging.getLogger("distributed.client").warning("Client lost its scheduler")


@pytest.fixture
def fake_dask(monkeypatch):
    def fake(stop):
        ns = SimpleNamespace(Client=lambda *a, **k: _Client(stop), LocalCluster=None, as_completed=iter)
        monkeypatch.setattr(runner, "require", lambda *a, **k: ns)

    return fake


def _logged(caplog) -> list[str]:
    return [r.getMessage() for r in caplog.records if r.name.startswith("distributed")]


def test_teardown_after_an_interrupt_logs_nothing(fake_dask, caplog):
    caplog.set_level(logging.DEBUG)
    fake_dask(KeyboardInterrupt())
    logging.getLogger("distributed.client").setLevel(logging.WARNING)  # as dask's own configuration sets it
    with pytest.raises(KeyboardInterrupt):
        runner._run_dask({}, [(0, 0, 1)], None, "tcp://127.0.0.1:1", 2, None)
    assert _logged(caplog) == []
    assert logging.getLogger("distributed.client").level == logging.WARNING  # restored


def test_teardown_after_an_error_still_logs_errors(fake_dask, caplog):
    caplog.set_level(logging.ERROR)
    fake_dask(RuntimeError("boom"))
    with pytest.raises(RuntimeError, match="boom"):
        runner._run_dask({}, [(0, 0, 1)], None, "tcp://127.0.0.1:1", 2, None)
    assert _logged(caplog) == ["Failed to communicate with scheduler during heartbeat."]
