"""``fricgen sweep``: the points of a sweep file as Dask tasks, each a ``fricgen run`` in its own folder.

Everything is checked before the output folder is touched: the sweep file
(:mod:`fricgen.app.sweep.config`), every point's configuration by the runner's
:func:`~fricgen.app.run.runner.check_run` (the file, the overrides, the law and the box, as a fresh
run is checked; no simulation is built), and that a finished point's folder holds a run of the same
configuration. A checkpoint that its configuration cannot resume is refused by the point's own run
(its run.log says why). The points that are not finished run on a ``distributed.LocalCluster``
(one single-threaded worker process per CPU this process may use, or ``--workers``) or on the
workers of a running scheduler (``--scheduler``); :mod:`fricgen.app.sweep.task` says what a point
does in its worker. A point with its summary.json is never run again, so the same command after a
Ctrl-C or a lost worker completes only what is missing. Outputs: ``OUT/<point>/`` (the run and its
``run.log``), ``OUT/sweep.json`` (the points and their overrides), ``OUT/results.csv`` and
``OUT/phase_diagram.png`` (:mod:`fricgen.app.sweep.results`). Exit status: 0 every point done, 1 a
point failed (blew up), 2 a bad sweep file, 130 interrupted.
"""


from __future__ import annotations

import contextlib
import dataclasses
import json
import logging
import os
import sys
import time
import uuid
from dataclasses import dataclass
from pathlib import Path

from tqdm import tqdm

from fricgen.derive.law.catalogues import BUILT_IN, LawSearch

from ...errors import ConfigError
from ..run.config import RunConfig
from ..run.outputs import CONFIG, check_folder, dumps
from ..run.runner import RUN_FILES, check_run
from .config import Point, Sweep, flatten, load_sweep
from .results import phase_diagram, result_row, write_table
from .task import finished, folder_state, run_point

#: Seconds to reach a scheduler given by --scheduler.
CONNECT_TIMEOUT = 20
#: What a point's exit status means when it left no summary.
EXITS = {1: "blew up", 2: "bad configuration", 130: "interrupted", -2: "interrupted"}


@dataclass(frozen=True)
class SweepRequest:
    """The command line of ``fricgen sweep``: the file, --out, --scheduler, --workers and --laws."""

    source: str
    out: str | None = None
    scheduler: str | None = None
    workers: int | None = None
    search: LawSearch = BUILT_IN


def run_sweep(request: SweepRequest, as_json: bool = False) -> int:
    """Check, run what is missing, gather; returns the exit status."""
    clock = time.perf_counter()
    sweep = load_sweep(request.source)
    out = Path(request.out or f"fricgen-sweep-{sweep.name}").absolute()
    check_folder(out, "--out")
    workers = _workers(request)
    points = sweep.points()
    specs = {point.name: _check_point(sweep, point, out / point.name, request.search) for point in points}
    todo = [spec for spec in specs.values() if spec is not None]
    try:
        with _client(request.scheduler, min(workers, len(todo))) if todo else contextlib.nullcontext() as client:
            out.mkdir(parents=True, exist_ok=True)
            (out / "sweep.json").write_text(dumps(_record(sweep, points, request)))
            outcomes = _run(client, todo, len(points)) if todo else {}
    except KeyboardInterrupt:
        print(
            f"fricgen sweep: interrupted; {out} keeps the finished points, and running ones stop at a checkpoint "
            "(on a scheduler's workers they run to their end). Run the same command again to complete the rest",
            file=sys.stderr,
        )
        return 130
    rows = [result_row(point, out / point.name, _status(out / point.name, outcomes.get(point.name))) for point in points]
    files = [write_table(rows, out / "results.csv")]
    if sweep.plot is not None:
        panels = next((axis.values for axis in sweep.axes if axis.name == sweep.plot.panels), (None,))
        files.append(phase_diagram(rows, sweep.plot, panels, out / "phase_diagram.png"))
    summary = {"out": str(out), "points": len(points), "ran": len(todo), "seconds": time.perf_counter() - clock, "results": rows}
    print(dumps(summary) if as_json else _describe(summary, files))
    statuses = {row["status"] for row in rows}
    return 0 if statuses == {"done"} else 130 if statuses <= {"done", "interrupted"} else 1


def _workers(request: SweepRequest) -> int:
    """Worker processes of the local cluster: --workers, else one per CPU this process may use."""
    if request.workers is None:
        return len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else os.cpu_count() or 1
    if request.scheduler is not None:
        raise ConfigError("--workers", "sizes the local cluster; with --scheduler the scheduler's workers run the points", "leave one away")
    if request.workers < 1:
        raise ConfigError("--workers", f"must be >= 1, got {request.workers}", "give the number of worker processes")
    return request.workers


def _check_point(sweep: Sweep, point: Point, folder: Path, search: LawSearch) -> dict | None:
    """The task's spec of a point (:func:`~fricgen.app.sweep.task.run_point`), None if it is
    finished; ConfigError (named by the point) if its configuration or its finished run does not fit."""
    try:
        check_folder(folder, "--out")
        config = check_run(sweep.base, list(point.settings), search)
        if folder_state(folder, config.run.steps) == "done":
            _check_finished(folder, config.as_dict())
            return None
        if any((folder / name).exists() or (folder / name).is_symlink() for name in RUN_FILES):
            # its task resumes it (to more steps, maybe) or restarts it
            _check_finished(folder, config.as_dict(), "an unfinished run", ("run.steps",))
    except ConfigError as error:
        raise ConfigError(f"point {point.name}: {error.key}", error.problem, error.fix) from error
    return {
        "name": point.name,
        "folder": str(folder),
        "steps": config.run.steps,
        "base": sweep.base,
        "settings": list(point.settings),
        "laws": [str(path) for path in search.folders],  # the search, as data: the task's edge rebuilds it
    }


def _newer_default(key: str, value) -> bool:
    """Whether ``value`` is the default of the setting ``key`` (a dotted key of RunConfig): a run recorded
    before that setting existed ran as its default says (new settings default to the old behaviour)."""
    section, *path = RunConfig, *key.split(".")
    for part in path:
        found = {f.name: f for f in dataclasses.fields(section)}.get(part)
        if found is None or (found.default is dataclasses.MISSING and found.default_factory is dataclasses.MISSING):
            return False
        section = found.default if found.default_factory is dataclasses.MISSING else found.default_factory()
        if part != path[-1] and not dataclasses.is_dataclass(section):
            return False
    return json.loads(dumps(section)) == value


def _check_finished(folder: Path, wanted: dict, what: str = "a finished run", free: tuple[str, ...] = ()) -> None:
    """A point's folder that holds a run (finished, or files of one that is not) holds a run of this
    configuration (its config.json): the files of any other run (another sweep's, a run of the
    user's) are never resumed over, restarted over or deleted. Keys in ``free`` may differ (an
    unfinished run continues to another ``run.steps``), and a setting the stored run predates may be
    at its default."""
    try:
        stored = json.loads((folder / CONFIG).read_text())
    except (OSError, ValueError):
        stored = None
    if not isinstance(stored, dict):
        raise ConfigError(
            "--out",
            f"{folder} holds files of a run without its {CONFIG} ({what} of another command?)",
            "give another --out, or move them away",
        )
    stored.pop("command", None)
    there, here = flatten(stored), flatten(json.loads(dumps(wanted)))
    differing = [
        key
        for key in dict.fromkeys([*here, *there])
        if here.get(key) != there.get(key) and key not in free and not (key not in there and _newer_default(key, here[key]))
    ]
    if differing:
        key = differing[0]
        raise ConfigError(
            key,
            f"{folder} holds {what} with {there.get(key)!r}, not {here.get(key)!r}",
            "give another --out, or delete that folder",
        )


@contextlib.contextmanager
def _client(scheduler: str | None, workers: int):
    """A Dask client: of the scheduler at ``scheduler``, else of a local cluster of ``workers``
    single-threaded processes (closed, with its workers, when the block ends)."""
    from distributed import Client, LocalCluster

    if scheduler is None:
        cluster = LocalCluster(n_workers=workers, threads_per_worker=1, processes=True, dashboard_address=None, silence_logs=logging.ERROR)
        with cluster, Client(cluster) as client:
            yield client
        return
    with _connect(scheduler) as client:
        yield client


def _connect(scheduler: str):
    """A client of the scheduler at ``scheduler`` within CONNECT_TIMEOUT seconds, or ConfigError.

    Dask's own timeout bounds the TCP connection, not the handshake: a server that accepts and never
    answers would hold ``Client()`` forever. So the client is made in a daemon thread that this one
    waits for with a deadline (in short steps, so Ctrl-C is seen at once), and is abandoned after it.
    """
    import threading

    from distributed import Client

    made: dict = {}

    def connect() -> None:
        try:
            made["client"] = Client(scheduler, timeout=CONNECT_TIMEOUT)
        except Exception as error:  # reported below, in the waiting thread
            made["error"] = error

    fix = "start `dask scheduler` and `dask worker ADDRESS`, or leave --scheduler away"
    thread = threading.Thread(target=connect, name="fricgen-sweep-connect", daemon=True)
    thread.start()
    deadline = time.monotonic() + CONNECT_TIMEOUT
    while thread.is_alive() and time.monotonic() < deadline:
        thread.join(0.1)
    if thread.is_alive():
        raise ConfigError("--scheduler", f"{scheduler} did not answer as a Dask scheduler within {CONNECT_TIMEOUT:g} s", fix)
    error = made.get("error")
    if isinstance(error, OSError | TimeoutError | ValueError):
        raise ConfigError("--scheduler", f"cannot reach {scheduler}: {error}", fix) from error
    if error is not None:
        raise error
    return made["client"]


def _run(client, specs: list[dict], total: int) -> dict[str, dict]:
    """Each spec as a task, with a progress bar over all points; the outcome of each by point."""
    from distributed import as_completed

    futures = {client.submit(run_point, spec, key=f"fricgen-sweep-{spec['name']}-{uuid.uuid4().hex[:8]}"): spec["name"] for spec in specs}
    outcomes = {}
    with tqdm(total=total, initial=total - len(specs), desc="fricgen sweep", unit="point", file=sys.stderr, dynamic_ncols=True) as bar:
        for future in as_completed(futures):
            name = futures[future]
            outcomes[name] = future.result() if future.status == "finished" else {"point": name, "error": str(future.exception())}
            bar.update()
    return outcomes


def _status(folder: Path, outcome: dict | None) -> str:
    """``done`` (summary.json), else what became of the point's task."""
    if finished(folder):
        return "done"
    if outcome is None:
        return "missing"
    if "error" in outcome:
        return f"task failed: {outcome['error']}"
    return EXITS.get(outcome["returncode"], f"exit status {outcome['returncode']}")


def _record(sweep: Sweep, points: list[Point], request: SweepRequest) -> dict:
    """OUT/sweep.json: the sweep as it ran, point by point."""
    return {
        "sweep": request.source,
        "base": sweep.base,
        "set": list(sweep.settings),
        "axes": {axis.name: list(axis.values) for axis in sweep.axes},
        "points": [{"name": p.name, "coordinates": p.coordinates, "set": list(p.settings)} for p in points],
    }


def _describe(summary: dict, files: list[Path]) -> str:
    rows = summary["results"]
    lines = [f"fricgen sweep: {summary['points']} points ({summary['ran']} run now) in {summary['seconds']:.1f} s"]
    lines += [f"  {row['point']}: {row['status']} (see its run.log)" for row in rows if row["status"] != "done"]
    lines.append(f"  results in {', '.join(str(f) for f in files)}")
    return "\n".join(lines)
