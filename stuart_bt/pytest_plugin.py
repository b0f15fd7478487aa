"""pytest fixtures for simulated and dry tree tests; installed with stuart_bt (entry point
``pytest11: stuart_bt``), so a user's test suite gets them without a conftest::

    def test_fetch_brings_the_bottle(stuart_sim):
        result = stuart_sim("trees/fetch_bottle.yaml")
        result.assert_success()
        result.assert_object_raised("bottle", by=0.05)

``stuart_sim`` and ``stuart_dry`` are callables: each call runs one tree on its own world and
daemons and shuts them down before returning (or raising), so nothing outlives a failing test.
Tests using ``stuart_sim`` get the ``sim`` marker (``pytest -m "not sim"`` skips them). When a
test fails, its runs are summarised in the failure report and their reports saved as JSON.
"""

from __future__ import annotations

import os
from collections.abc import Iterator
from pathlib import Path
from typing import TYPE_CHECKING, Any

import pytest

from .core.jsonfile import to_json

if TYPE_CHECKING:  # imported when a fixture runs: pytest starts no slower for having stuart_bt installed
    from .run.session import RunOptions
    from .testing import Hook, RunResult

RUNS = pytest.StashKey["list[RunResult]"]()
RUN_DIR = pytest.StashKey[Path]()


class TreeRunner:
    """The object behind ``stuart_sim`` / ``stuart_dry``: call it to run a tree on its backend."""

    def __init__(self, backend: str, search: list[Path], results: list[RunResult], tmp_path: Path) -> None:
        self.backend = backend
        self.search = search  # where relative tree paths are looked up, in order
        self.results = results
        # speech audio goes to the test's temporary folder instead of a new /tmp folder per run
        self.defaults: dict[str, dict[str, Any]] = {"tts": {"audio_dir": str(tmp_path / "audio")}} \
            if backend == "sim" else {}

    def __call__(self, tree: str | Path | None = None, *, text: str | None = None, seed: int | None = None,
                 start: str | None = None, on_tick: Hook | list[Hook] | None = None,
                 max_duration: float | None = 600.0, daemon_options: dict[str, dict[str, Any]] | None = None,
                 speed: float | None = None, rate: float = 20.0, watch: bool | int = True, settle: float = 0.0,
                 markers: str | Path | None = None, options: RunOptions | None = None) -> RunResult:
        """Run ``tree`` (a path: tried from the current directory, the test's folder, then the
        rootdir) or YAML ``text``; see :func:`stuart_bt.testing.run_tree` for the options."""
        from .testing import run_tree

        families = {f: {**self.defaults.get(f, {}), **(daemon_options or {}).get(f, {})}
                    for f in {*self.defaults, *(daemon_options or {})}}
        result = run_tree(self.resolve(tree) if tree is not None else None, text=text, backend=self.backend,
                          speed=speed, rate=rate, markers=markers, start=start, seed=seed,
                          max_duration=max_duration, on_tick=on_tick, daemon_options=families,
                          watch=watch, settle=settle, options=options)
        self.results.append(result)
        return result

    def resolve(self, tree: str | Path) -> Path:
        path = Path(tree)
        if path.is_absolute() or path.exists():
            return path
        for base in self.search:
            if (base / path).exists():
                return base / path
        return path  # the loader says what is missing


def _runner(backend: str, request: pytest.FixtureRequest, tmp_path: Path) -> TreeRunner:
    results = request.node.stash.setdefault(RUNS, [])  # shared when a test uses both fixtures
    request.node.stash[RUN_DIR] = tmp_path
    return TreeRunner(backend, [Path(request.path).parent, Path(request.config.rootpath)], results, tmp_path)


@pytest.fixture
def stuart_sim(request: pytest.FixtureRequest, tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Iterator[TreeRunner]:
    """Run trees on the MuJoCo simulator: ``result = stuart_sim("trees/x.yaml")``."""
    pytest.importorskip("mujoco", reason="the sim backend needs the 'sim' extra: pip install 'stuart-bt[sim]'")
    if "MUJOCO_GL" not in os.environ:
        monkeypatch.setenv("MUJOCO_GL", "egl")  # headless rendering unless the user chose otherwise
    yield _runner("sim", request, tmp_path)


@pytest.fixture
def stuart_dry(request: pytest.FixtureRequest, tmp_path: Path) -> Iterator[TreeRunner]:
    """Run trees on the dry backend (symbolic, 50x by default): fast tests of tree logic."""
    yield _runner("dry", request, tmp_path)


def pytest_configure(config: pytest.Config) -> None:
    config.addinivalue_line("markers", "sim: runs trees on the MuJoCo simulator (stuart_sim); "
                                       "deselect with -m 'not sim'")


def pytest_collection_modifyitems(items: list[pytest.Item]) -> None:
    for item in items:
        if "stuart_sim" in getattr(item, "fixturenames", ()):
            item.add_marker(pytest.mark.sim)


@pytest.hookimpl(wrapper=True)
def pytest_runtest_makereport(item: pytest.Item, call: pytest.CallInfo[None]) -> Any:
    report = yield
    if report.when == "call" and report.failed:
        results = item.stash.get(RUNS, [])
        if results:
            report.sections.append(("stuart_bt runs", describe_runs(results, item.stash.get(RUN_DIR, None))))
    return report


def describe_runs(results: list[RunResult], save_to: Path | None) -> str:
    """One paragraph per run of the failed test; the full reports go to ``save_to``."""
    lines = []
    for n, r in enumerate(results, 1):
        rep = r.report
        lines.append(f"run {n}: {r.status} ({rep.get('backend')}, {rep.get('tree')}, {rep.get('duration')} s, "
                     f"{rep.get('ticks')} ticks){': ' + str(rep.get('reason')) if rep.get('reason') else ''}")
        lines.append(f"  visited {rep['visited']}; final pose {rep['final_pose']}; held {rep.get('held')!r}")
        for f in rep["failures"]:
            lines.append(f"  failed t={f['t']:.2f} {f['path']}: {f['reason']}")
        if r.final_world is not None:
            w = r.final_world
            lines.append(f"  world at t={w['t']:.2f}: base {w['base']} {w['base_status']}, held {w['held']}, "
                         f"person {w['person']}")
        if save_to is not None:
            path = save_to / f"stuart_run_{n}.json"
            doc = {**rep, "world": {"initial": r.initial_world, "final": r.final_world}}
            path.write_text(to_json(doc, indent=1, default=str), encoding="utf-8")
            lines.append(f"  report: {path}")
    return "\n".join(lines)
