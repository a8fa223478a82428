"""The generic resumable sweep: specs fanned out to a backend, each finished run a row.

A sweep is a list of specs (frozen dataclasses with a ``kind``, a ``seed``, a
``config()`` and the ``run_id`` hashed from it; :class:`Spec`). :func:`run_sweep` runs
every spec not yet finished in a :class:`~voot.bench.store.result_store.ResultStore` on a
backend (:mod:`voot.bench.sweep.backends`: in-process, a local process pool, or Ray) and
writes each row as soon as its run finishes; calling it again with the same specs
resumes. The modules that define a kind of spec register its run function here
(:func:`register_runner`): :mod:`voot.bench.sweep.bbfo` the black-box runs (``"bbfo"``),
:mod:`voot.bench.sweep.plan` the planning runs (``"plan"``), so one :func:`run_any` runs
both, in any process (unpickling a spec imports its module, which registers its kind).

Also here, because every kind of run shares them: :func:`timed_row` (a run's row, or its
failed row on an exception), :func:`one_blas_thread`, :func:`name_key` (the
process-independent key the seeding rules hash names with), :func:`params_key` (the label
of a hyperparameter setting) and the grid names :data:`GRIDS`.
"""

from __future__ import annotations

import functools
import hashlib
import sys
import time
from collections.abc import Callable, Iterable, Mapping, Sequence
from dataclasses import dataclass, field, fields
from typing import Any, ClassVar, Protocol, TypeVar

import numpy as np
from threadpoolctl import threadpool_limits

from voot import validation as V
from voot.bench.store.format import Row, StoreError, exception_row, make_row, make_run_id
from voot.bench.store.lock import describe_holder
from voot.bench.store.result_store import ResultStore
from voot.bench.sweep.backends import Backend, SerialBackend

#: Hyperparameter grids of a sweep: each method's or planner's paper grid, or its
#: defaults only.
GRIDS: tuple[str, ...] = ("paper", "default")


def check_grid(grid: str) -> None:
    """Raise ValueError unless ``grid`` is one of :data:`GRIDS` (the message lists them)."""
    if grid not in GRIDS:
        raise ValueError(f"unknown grid {grid!r}; valid grids are: {', '.join(GRIDS)}")


def name_key(name: str) -> int:
    """A process-independent 32-bit integer for a name (SHA-256 based)."""
    return int.from_bytes(hashlib.sha256(name.encode()).digest()[:4], "little")


def int_list(values: Iterable[Any], what: str, minimum: int) -> list[int]:
    """``values`` as integers >= ``minimum``, duplicates removed (order kept); a
    ValueError naming ``what`` if one is not, or if there is none."""
    out = V.integers(values, what, minimum)
    if not out:
        raise ValueError(f"no {what} given")
    return list(dict.fromkeys(out))


def params_key(params: Mapping[str, Any]) -> str:
    """A short stable label of a hyperparameter setting (``"omega=0.001"``; ``"default"``)."""
    if not params:
        return "default"
    return ", ".join(f"{k}={params[k]}" for k in sorted(params))


def jsonable(value: Any) -> Any:
    """``value`` as JSON: numbers, strings, None, lists and string-keyed dicts as they
    are (recursively), anything else by its ``repr``."""
    if isinstance(value, str | int | float | bool) or value is None:
        return value
    if isinstance(value, Mapping):
        return {str(k): jsonable(v) for k, v in value.items()}
    if isinstance(value, list | tuple):
        return [jsonable(v) for v in value]
    return repr(value)


class Spec(Protocol):
    """What the sweep needs of a run's spec (a black-box or a plan spec)."""

    @property
    def kind(self) -> str: ...

    @property
    def seed(self) -> int: ...

    @property
    def run_id(self) -> str: ...

    def config(self) -> dict[str, Any]: ...


class SpecBase:
    """A run's identity from its fields, for the frozen dataclasses of run specs.

    :meth:`config` is the row's ``config``: the spec's fields in their order (those in
    :attr:`mapping_fields`, ``(name, value)`` pairs, as dicts) but those declared with
    ``compare=False`` (not part of the run, e.g. a recording's path) and those of
    :attr:`optional_fields`, then ``"protocol"``, then each field of
    :attr:`optional_fields` only when it is set (a field added later that way leaves the
    run ids of the runs without it unchanged). :attr:`run_id` hashes it with the spec's
    ``kind``.
    """

    kind: ClassVar[str]
    protocol: ClassVar[int]
    mapping_fields: ClassVar[tuple[str, ...]] = ("params",)
    optional_fields: ClassVar[tuple[str, ...]] = ()
    #: The hyperparameters set by the grid, sorted ``(name, value)`` pairs (a field of
    #: every spec).
    params: tuple[tuple[str, Any], ...]

    @property
    def params_dict(self) -> dict[str, Any]:
        return dict(self.params)

    def config(self) -> dict[str, Any]:
        """The row's ``config`` (JSON-serialisable; hashed into the run id)."""
        out: dict[str, Any] = {}
        for name in _config_fields(type(self)):
            value = getattr(self, name)
            out[name] = dict(value) if name in self.mapping_fields else value
        out["protocol"] = self.protocol
        for name in self.optional_fields:
            if getattr(self, name):
                out[name] = getattr(self, name)
        return out

    @property
    def run_id(self) -> str:
        return make_run_id(self.kind, self.config())


def _config_fields(spec_type: type[Any]) -> tuple[str, ...]:
    """The fields of the spec dataclass ``spec_type`` that every row's ``config`` holds,
    in their order (:meth:`SpecBase.config`)."""
    return tuple(
        f.name for f in fields(spec_type) if f.compare and f.name not in spec_type.optional_fields
    )


S = TypeVar("S", bound=Spec)
_Spec = TypeVar("_Spec")
_Out = TypeVar("_Out")


def one_blas_thread(run: Callable[[_Spec], _Out]) -> Callable[[_Spec], _Out]:
    """Run ``run(spec)`` with one BLAS/OpenMP thread, in whatever process executes it.

    Results of the GP-based optimisers differ in their last bits between BLAS thread
    counts, so a run is bit-identical across processes and machines only at a fixed
    count; one thread also keeps parallel runs from oversubscribing the cores.
    """

    @functools.wraps(run)
    def wrapper(spec: _Spec) -> _Out:
        with threadpool_limits(limits=1):
            return run(spec)

    return wrapper


def timed_row(spec: Any, run: Callable[[], dict[str, Any]], **on_failure: Any) -> Row:
    """The row of ``spec``: ``run()`` gives its fields (``best_so_far`` and any others, in
    row order), timed from now; an exception gives a row with status ``"failed"``, the
    error and ``on_failure``'s fields instead."""
    start = time.perf_counter()
    try:
        fields = run()
        best = fields.pop("best_so_far")
        return make_row(
            spec.kind,
            spec.config(),
            status="ok",
            wall_time=time.perf_counter() - start,
            best_so_far=best,
            **fields,
        )
    except Exception as exc:
        return exception_row(spec, exc, start, [], **on_failure)


#: The run function of each spec kind (``kind`` -> run); the modules defining a kind add
#: theirs with :func:`register_runner` when imported. Unpickling a spec in a worker
#: imports its module, so the worker knows its run function too.
RUNNERS: dict[str, Callable[[Any], Row]] = {}
#: How a run of each kind is described in messages: ``kind`` -> describe(row config).
DESCRIBERS: dict[str, Callable[[Mapping[str, Any]], str]] = {}


def register_runner(
    kind: str, run: Callable[[Any], Row], describe: Callable[[Mapping[str, Any]], str]
) -> None:
    """Make :func:`run_any` run specs of ``kind`` with ``run``, and :func:`describe_row`
    describe their rows with ``describe``."""
    RUNNERS[kind] = run
    DESCRIBERS[kind] = describe


def run_any(spec: Any) -> Row:
    """Run a spec of any registered kind (:data:`RUNNERS`)."""
    run = RUNNERS.get(getattr(spec, "kind", None))  # type: ignore[arg-type]
    if run is None:
        raise TypeError(
            f"cannot run a {type(spec).__name__}; expected a spec of a registered kind"
            f" ({', '.join(sorted(RUNNERS))}), e.g. a RunSpec or a PlanSpec"
        )
    return run(spec)


def describe_row(row: Row) -> str:
    """A one-line description of the run of ``row`` (by its kind's describer)."""
    describe = DESCRIBERS.get(row.get("kind"))  # type: ignore[arg-type]
    config = row.get("config") or {}
    return describe(config) if describe is not None else f"{row.get('kind')} run {config}"


@dataclass
class SweepSummary:
    """What :func:`run_sweep` did."""

    total: int = 0
    skipped: int = 0
    ran: int = 0
    failed: int = 0
    failed_errors: list[str] = field(default_factory=list)

    def __str__(self) -> str:
        text = (
            f"{self.total} runs: {self.skipped} already in the store, {self.ran} ran"
            f" ({self.failed} failed)"
        )
        if self.failed_errors:
            text += "\nfirst failures:\n  " + "\n  ".join(self.failed_errors[:5])
        return text


def execution_order(specs: Sequence[S]) -> list[S]:
    """Seed-major order, shuffled (deterministically) within each seed.

    Every block of one seed holds the same mix of cheap and costly runs, so the progress
    bar's time estimate is fair from the start, and an interrupted sweep leaves complete
    seeds rather than complete methods.
    """
    rng = np.random.default_rng(0)
    by_seed: dict[int, list[S]] = {}
    for s in specs:
        by_seed.setdefault(s.seed, []).append(s)
    out: list[S] = []
    for seed in sorted(by_seed):
        block = by_seed[seed]
        out.extend(block[i] for i in rng.permutation(len(block)))
    return out


def pending_specs(specs: Sequence[S], store: ResultStore, *, retry_failed: bool = True) -> list[S]:
    """The specs whose run is not finished in ``store`` (duplicates removed).

    A run with an ``"ok"`` row is finished. With ``retry_failed=False`` a run with a
    ``"failed"`` row counts as finished too.
    """
    rows = store.load(status=None, arrays=True, expand=False)
    done = {r["run_id"] for r in rows if r["status"] == "ok" or not retry_failed}
    unique: dict[str, S] = {}
    for s in specs:
        unique.setdefault(s.run_id, s)
    return [s for rid, s in unique.items() if rid not in done]


def _progress_bar(total: int, enabled: bool, desc: str) -> Any:
    if not enabled or total == 0:  # nothing to run: no bar (tqdm would draw it twice)
        return None
    try:
        from tqdm import tqdm
    except ImportError:  # pragma: no cover - tqdm is in the [bench] extra
        return None
    return tqdm(
        total=total, desc=desc, unit="run", file=sys.stderr, smoothing=0.05, dynamic_ncols=True
    )


def run_sweep(
    specs: Sequence[S],
    store: ResultStore,
    backend: Backend | None = None,
    *,
    progress: bool = True,
    retry_failed: bool = True,
    run: Callable[[Any], Row] = run_any,
) -> SweepSummary:
    """Run every spec not finished in ``store``, writing each row as its run finishes.

    Interrupting (Ctrl-C, an exception, a kill) loses only the runs in flight; calling
    again with the same specs resumes. The sweep holds the store's writer lock
    (:meth:`~voot.bench.store.result_store.ResultStore.writing`) from before it reads what is finished
    until its last row is written: a second sweep on the same store raises
    :class:`~voot.bench.store.lock.StoreBusyError` naming this one, before running anything.
    """
    with store.writing() as lock:
        if lock.stale:
            print(
                f"{store.path}: took over the writer lock of a sweep that did not release it"
                f" ({describe_holder(lock.stale)}; no longer running)",
                file=sys.stderr,
            )
        return _run_pending(specs, store, backend, progress, retry_failed, run)


def _run_pending(
    specs: Sequence[S],
    store: ResultStore,
    backend: Backend | None,
    progress: bool,
    retry_failed: bool,
    run: Callable[[Any], Row],
) -> SweepSummary:
    """The body of :func:`run_sweep`, under the store's writer lock."""
    backend = backend if backend is not None else SerialBackend()
    unique = {s.run_id for s in specs}
    todo = execution_order(pending_specs(specs, store, retry_failed=retry_failed))
    summary = SweepSummary(total=len(unique), skipped=len(unique) - len(todo))
    bar = _progress_bar(
        len(todo), progress, f"{specs[0].kind if specs else 'sweep'} ({backend.name})"
    )
    rows = backend.map_unordered(run, todo)
    try:
        for row in rows:
            write_row(store, row)
            summary.ran += 1
            if row["status"] != "ok":
                summary.failed += 1
                summary.failed_errors.append(f"{describe_row(row)}: {row.get('error')}")
            if bar is not None:
                bar.update(1)
                if summary.failed:
                    bar.set_postfix(failed=summary.failed, refresh=False)
    finally:
        close = getattr(rows, "close", None)
        if close is not None:  # a generator backend: cancel what has not started
            close()
        if bar is not None:
            bar.close()
    return summary


def write_row(store: ResultStore, row: Row) -> None:
    """Write ``row`` into ``store``; a write the file system refuses stops the sweep.

    A full disk (``ENOSPC``), a quota or an I/O error while writing a row is a
    :class:`~voot.bench.store.format.StoreError` naming the store, the run and the cause
    (not a traceback, and not a failed row: the run itself did not fail). The store's
    atomic write leaves no part of that row behind (its temporary file is removed), so
    the store stays loadable with every row written before; the same command, run again
    once there is room, redoes that run and those not yet finished, and no other.
    """
    try:
        store.write(row)
    except OSError as exc:
        cause = exc.strerror or type(exc).__name__
        raise StoreError(
            f"{store.path}: could not write the row of run {row.get('run_id')!r}"
            f" ({cause}); the sweep stopped. The rows written before are kept; free the"
            " space (or fix the cause) and run the same command again to resume"
        ) from exc
