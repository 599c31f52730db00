"""``fricgen sweep``: the points of a sweep file as Dask tasks, each a ``fricgen run`` in its own folder.

Everything is checked before the output folder is touched: the sweep file
(:mod:`fricgen.app.sweep.config`), every point's configuration by the runner's
:func:`~fricgen.app.run.runner.check_run` (the file, the overrides, the law and the box, as a fresh
run is checked; no simulation is built), and that a finished point's folder holds a run of the same
configuration and ran this run's laws: the law hashes that its checkpoint records, for every
mode, are those of the laws and kernels of this run. A point that ran another version of its laws
(a law file edited and regenerated since) is stale: the sweep refuses on one line listing the stale
points, and ``--rerun-stale`` runs them afresh. A point's folder is a real folder inside the
output, never a symbolic link. A checkpoint that its configuration cannot resume is refused by the
point's own run (its run.log says why). The points that are not finished run on a ``distributed.LocalCluster``
(one single-threaded worker process per CPU this process may use, or ``--workers``) or on the
workers of a running scheduler (``--scheduler``); :mod:`fricgen.app.sweep.task` says what a point
does in its worker. A point with its summary.json and this run's laws is never run again, so the same command after a
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
from ..run.build import resolve_law
from ..run.checkpoints import recorded_laws
from ..run.config import RunConfig
from ..run.outputs import CHECKPOINT, CONFIG, check_folder, check_temporaries, dumps
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
    rerun_stale: bool = False


def run_sweep(request: SweepRequest, as_json: bool = False) -> int:
    """Check, run what is missing, gather; returns the exit status."""
    clock = time.perf_counter()
    sweep = load_sweep(request.source)
    out = Path(request.out or f"fricgen-sweep-{sweep.name}").absolute()
    check_folder(out, "--out")
    workers = _workers(request)
    _check_scheme(request.scheduler)
    points = sweep.points()
    specs = {point.name: _check_point(sweep, point, out / point.name, request.search) for point in points}
    stale = [name for name, spec in specs.items() if spec is not None and spec["stale"]]
    if stale and not request.rerun_stale:
        raise ConfigError(
            "law",
            f"{len(stale)} point(s) of {out} ran another version of their laws than this run's (the law hashes their checkpoints"
            f" record differ, or they record none): {', '.join(stale)}",
            "rerun them with --rerun-stale (a finished one keeps its old summary as summary-stale.json), or give another --out",
        )
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
    finished with this run's laws; ConfigError (named by the point) if its configuration or its
    finished run does not fit. A run in its folder (finished or not) that ran other laws than this
    run's (the law hashes its checkpoint records, :func:`~fricgen.app.run.checkpoints.recorded_laws`,
    for every mode) is stale: its spec says so, and its task starts it afresh."""
    try:
        _check_point_folder(folder)
        check_folder(folder, "--out")
        check_temporaries(folder, "--out")
        config = check_run(sweep.base, list(point.settings), search)
        laws = [[law.kernels.name, law.kernels.source_hash] for law in resolve_law(config.law, config.system.dimension, search).laws]
        state = folder_state(folder, config.run.steps)
        if state == "done":
            _check_finished(folder, config.as_dict())
        elif any((folder / name).exists() or (folder / name).is_symlink() for name in RUN_FILES):
            # its task resumes it (to more steps, maybe) or restarts it
            _check_finished(folder, config.as_dict(), "an unfinished run", ("run.steps",))
        stale = state != "fresh" and recorded_laws(folder / CHECKPOINT) != laws
        if state == "done" and not stale:
            return None
    except ConfigError as error:
        raise ConfigError(f"point {point.name}: {error.key}", error.problem, error.fix) from error
    return {
        "name": point.name,
        "folder": str(folder),
        "steps": config.run.steps,
        "law_hashes": laws,
        "stale": stale,
        "base": sweep.base,
        "settings": list(point.settings),
        "laws": [str(path) for path in search.folders],  # the search, as data: the task's edge rebuilds it
    }


def _check_point_folder(folder: Path) -> None:
    """A point's folder is a real folder inside the sweep's output, or absent, with a name the file
    system allows: never a symbolic link (to a sibling, whose run would count twice, or dangling)."""
    if folder.is_symlink():
        raise ConfigError(
            "--out",
            f"{folder} is a symbolic link (to {os.readlink(folder)}), not a point's own folder",
            "remove the link: each point runs in a real folder of its own inside the sweep's output",
        )
    existing = next(parent for parent in folder.parents if parent.is_dir())
    limit = os.pathconf(existing, "PC_NAME_MAX")
    if len(os.fsencode(folder.name)) > limit:
        raise ConfigError(
            "grid",
            f"the point's folder name is {len(os.fsencode(folder.name))} bytes long, more than the file system allows ({limit})",
            "use shorter values, or a named axis whose value names are short (docs/sweeps.md)",
        )


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
    except FileNotFoundError:
        stored = None
    except (OSError, ValueError) as error:  # cut short, garbled, not a file
        problem = error.strerror if isinstance(error, OSError) and error.strerror else "not a JSON table (cut short?)"
        raise ConfigError(
            "--out", f"{folder} holds {what} whose {CONFIG} cannot be read: {problem}", "give another --out, or delete that folder"
        ) from error
    if not isinstance(stored, dict):
        problem = f"without its {CONFIG}" if stored is None else f"whose {CONFIG} is not a JSON table"
        raise ConfigError(
            "--out", f"{folder} holds files of a run {problem} ({what} of another command?)", "give another --out, or move them away"
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


def _check_scheme(scheduler: str | None) -> None:
    """A --scheduler address in one of Dask's schemes (tcp://, tls://, ...) or without one; ConfigError otherwise."""
    from distributed.comm.registry import backends

    scheme, separator, _ = (scheduler or "").rpartition("://")
    if separator and scheme not in backends:
        raise ConfigError(
            "--scheduler",
            f"{scheme}:// is not a scheme of Dask's ({', '.join(f'{name}://' for name in sorted(backends))})",
            "give the scheduler's address as `dask scheduler` prints it, e.g. tcp://HOST:8786",
        )


def _connect(scheduler: str):
    """A client of the scheduler at ``scheduler`` within CONNECT_TIMEOUT seconds, or ConfigError.

    Dask's own timeout bounds the TCP connection, not the handshake: a server that accepts and never
    answers would hold ``Client()`` forever. So the client is made in a daemon thread that this one
    waits for with a deadline (in short steps, so Ctrl-C is seen at once), and is abandoned after it.
    """
    import threading

    from distributed import Client

    fix = "start `dask scheduler` and `dask worker ADDRESS`, or leave --scheduler away"
    made: dict = {}

    def connect() -> None:
        try:
            made["client"] = Client(scheduler, timeout=CONNECT_TIMEOUT)
        except Exception as error:  # reported below, in the waiting thread
            made["error"] = error

    thread = threading.Thread(target=connect, name="fricgen-sweep-connect", daemon=True)
    thread.start()
    deadline = time.monotonic() + CONNECT_TIMEOUT
    while thread.is_alive() and time.monotonic() < deadline:
        thread.join(0.1)
    if thread.is_alive():
        raise ConfigError("--scheduler", f"{scheduler} did not answer as a Dask scheduler within {CONNECT_TIMEOUT:g} s", fix)
    error = made.get("error")
    if error is not None:  # whatever the address answered (refused, an HTTP server to ws://, TLS not configured)
        problem = " ".join(str(error).split()) or type(error).__name__
        raise ConfigError("--scheduler", f"cannot connect to {scheduler} as a Dask scheduler: {problem}", fix) from error
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
