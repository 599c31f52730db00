"""One point of a sweep as a Dask task: a run in a child process that owns the point's folder.

The task, :func:`run_point`, runs on a worker and starts ``python -m fricgen.app.sweep.task SPEC``
with ``NUMBA_NUM_THREADS=1`` (one core per point) in a session of its own (a Ctrl-C at the terminal
reaches the sweep, which stops the workers, not each run twice), its output appended to the folder's
``run.log``. The child

- keeps the sweep's priority (:func:`keep_niceness`): a ``nice -n 19 fricgen sweep`` yields the cores
  to the user's other work, its tests or a benchmark, in the new session too;
- holds an exclusive lock (``flock``) on the folder's ``.lock`` while it works, so a copy of the point
  that Dask reschedules after a lost worker waits until the old child has exited, never writing
  beside it (the kernel drops the lock when a process dies, however it dies);
- stops as on Ctrl-C once its worker is gone (a watchdog thread sees its parent change): it writes a
  checkpoint at the end of the current chunk and exits, so no orphan keeps writing;
- decides under the lock what the folder needs (:func:`folder_state`): nothing, a resume from the
  checkpoint (bit for bit, as ``fricgen run --resume``), or a fresh start (the files of a start that
  died before its first checkpoint are deleted first);
- runs the point as ``fricgen run`` does, by the runner's :func:`~fricgen.app.run.runner.plan` and
  :func:`~fricgen.app.run.runner.execute`, with its exit status and its errors on one line.
"""

from __future__ import annotations

import contextlib
import fcntl
import json
import os
import signal
import socket
import subprocess
import sys
import threading
import time
import zipfile
from pathlib import Path

import numpy as np

from fricgen.derive.errors import DeriveError
from fricgen.derive.law.catalogues import LawSearch

from ...errors import FricgenError
from ..run.checkpoints import recorded_laws
from ..run.outputs import CHECKPOINT, SUMMARY, fail
from ..run.runner import RUN_FILES, _free_name, execute, plan

LOG, LOCK = "run.log", ".lock"
#: Seconds between the watchdog's looks at its parent.
WATCH_PERIOD = 0.2


def finished(folder: Path) -> bool:
    """The folder holds a summary.json (complete: one cut short by a kill does not count)."""
    try:
        json.loads((folder / SUMMARY).read_text())
    except (OSError, ValueError):
        return False
    return True


def folder_state(folder: Path, steps: int) -> str:
    """``done`` (summary.json), ``resume`` (a checkpoint short of ``steps``, or one that ``fricgen run``
    will refuse with its reason) or ``fresh`` (nothing, or a run that ended without its summary)."""
    if finished(folder):
        return "done"
    checkpoint = folder / CHECKPOINT
    if not checkpoint.is_file():
        return "fresh"
    try:
        with np.load(checkpoint) as data:
            return "fresh" if int(data["step"]) == steps else "resume"
    except (OSError, ValueError, KeyError, zipfile.BadZipFile):
        return "resume"  # the runner's --resume check names the problem


def run_point(spec: dict) -> dict:
    """The Dask task of a point: its child process to the end; ``spec`` has the point's ``name``,
    ``folder``, ``steps``, and the ``base`` configuration, its ``settings`` (``SECTION.KEY=VALUE``) and
    the user's law folders ``laws`` of its run."""
    folder = Path(spec["folder"])
    folder.mkdir(parents=True, exist_ok=True)
    clock = time.perf_counter()
    with open(folder / LOG, "a") as log:
        child = subprocess.run(
            [sys.executable, "-m", __name__, json.dumps({**spec, "parent": os.getpid()})],
            stdout=log,
            stderr=subprocess.STDOUT,
            env={**os.environ, "NUMBA_NUM_THREADS": "1", "TQDM_MININTERVAL": "10"},
            start_new_session=True,
            check=False,
        )
    return {"point": spec["name"], "returncode": child.returncode, "seconds": time.perf_counter() - clock}


def keep_niceness() -> None:
    """Give this process's scheduling group the process's own nice value.

    On Linux with autogroups (``/proc/sys/kernel/sched_autogroup_enabled``) a new session starts a
    group of its own at nice 0, and the scheduler shares the CPU between groups before it looks at
    the processes' nice values: a run of a ``nice -n 19`` sweep would take a core from the user's
    test suite as if it were not niced. Without autogroups, nothing changes."""
    niceness = os.nice(0)
    if niceness > 0:
        with contextlib.suppress(OSError):
            Path("/proc/self/autogroup").write_text(str(niceness))


def _watch(parent: int) -> None:
    """SIGINT to this process once ``parent`` (the worker) is gone: the run stops as on Ctrl-C."""

    def watch():
        while os.getppid() == parent:
            time.sleep(WATCH_PERIOD)
        os.kill(os.getpid(), signal.SIGINT)

    threading.Thread(target=watch, daemon=True).start()


@contextlib.contextmanager
def _lock(folder: Path):
    """The folder's lock, held until the block ends (or the process does); its file names the holder."""
    with open(folder / LOCK, "a+") as handle:
        fcntl.flock(handle, fcntl.LOCK_EX)
        handle.truncate(0)
        handle.write(f"{socket.gethostname()} {os.getpid()}\n")
        handle.flush()
        yield


def _begin_attempt(folder: Path, worker: int) -> None:
    """The attempt's first line in run.log, ``# date on host, worker pid``, written under the lock (an
    earlier attempt has exited) and on a line of its own (a stopped progress bar ends mid-line)."""
    with open(folder / LOG, "rb+") as log:
        fresh_line = log.seek(0, os.SEEK_END) == 0 or (log.seek(-1, os.SEEK_END) >= 0 and log.read(1) == b"\n")
        log.write(b"" if fresh_line else b"\n")
        log.write(f"# {time.strftime('%Y-%m-%d %H:%M:%S')} on {socket.gethostname()}, worker pid {worker}\n".encode())


def _run(spec: dict, out: str | None = None, resume: str | None = None) -> int:
    """The point's run (``fricgen run BASE --set ... --laws ...`` with ``--out`` or ``--resume``) in this
    process; its exit status, and an error (a configuration or checkpoint that does not fit) as the
    command line reports it."""
    try:
        search = LawSearch.of(*spec["laws"], named_by="the sweep's law folders")
        return execute(plan(spec["base"], spec["settings"], None, out, resume, search))
    except (FricgenError, DeriveError) as error:
        return fail("fricgen run", error, getattr(error, "exit_status", 2))
    except KeyboardInterrupt:
        return fail("fricgen run", "interrupted", 130)


def _child(spec: dict) -> int:
    keep_niceness()
    _watch(spec["parent"])
    folder = Path(spec["folder"])
    with _lock(folder):
        _begin_attempt(folder, spec["parent"])
        state = folder_state(folder, spec["steps"])
        if state != "fresh" and recorded_laws(folder / CHECKPOINT) != spec["law_hashes"]:  # another version of its laws ran here
            if finished(folder):
                (folder / SUMMARY).replace(_free_name(folder, "summary-stale", ".json"))
            state = "fresh"
        print(f"fricgen sweep: point {spec['name']}: {state}", flush=True)
        if state == "done":
            return 0
        if state == "resume":
            return _run(spec, resume=str(folder / CHECKPOINT))
        for name in (*RUN_FILES, f"{CHECKPOINT}.tmp"):
            (folder / name).unlink(missing_ok=True)
        return _run(spec, out=str(folder))


if __name__ == "__main__":
    try:
        sys.exit(_child(json.loads(sys.argv[1])))
    except KeyboardInterrupt:  # stopped before or after the run (the run itself exits 130 on its own)
        sys.exit(130)
