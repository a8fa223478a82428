"""Result cards, and the re-run check of a leaderboard store.

A **card** (``STORE/cards/<entry>.json``, one per entry) says what a third party
submits with a store: the planner's name and version, the setting selected per family
and how (:class:`voot.bench.leaderboard.plan.Choice`), the suite's version and digest,
the budgets, the coverage (evaluation runs finished of those the suite lists), the
measured cost (CPU seconds of search and simulator calls, summed over the entry's
finished runs) and the **store checksum** (:func:`voot.bench.store.shipped.store_digest`:
SHA-256 over every row file's name and row checksum). The card carries its own SHA-256
(``card_sha256``, over its other fields), so an edited card is an error naming the file
(:func:`read_card`), and a card whose store checksum is not the store's is too
(:func:`check_cards`).

**Verify** (:func:`verify_store`): re-run a deterministic sample of the store's finished
runs from their configs (:func:`voot.bench.sweep.plan.run_plan_spec`) and compare every
deterministic field bit for bit (curves of returns, objects left and simulator calls,
the best plan and its rewards, counts): the timings (``elapsed``, ``cpu_elapsed``,
``search_time``, ``wall_time``, ``finished_at``) and the software versions are excluded.
A compact store's re-run row is compacted the same way before the comparison.
"""

from __future__ import annotations

import hashlib
import json
import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from voot.bench.leaderboard.suite import Entry, Suite
from voot.bench.store.compact import COMPACT_KEY
from voot.bench.store.format import Row, StoreError
from voot.bench.store.result_store import ResultStore

#: The folder of the cards inside a store.
CARDS_DIR = "cards"
#: The card's own checksum key.
CARD_CHECKSUM = "card_sha256"
#: Row keys a re-run may change (timings, and the software that ran it).
NONDETERMINISTIC_KEYS = frozenset(
    {"elapsed", "cpu_elapsed", "search_time", "wall_time", "finished_at", "versions"}
)


def _sha(payload: Mapping[str, Any]) -> str:
    return hashlib.sha256(json.dumps(payload, sort_keys=True).encode()).hexdigest()


def entries_in(rows: Sequence[Row], suite: Suite) -> list[Entry]:
    """The entries a store's rows hold (the suite's, then others by name), in suite order."""
    from voot.bench.protocol.select import planner_label

    names = list(
        dict.fromkeys(
            planner_label(r["config"]["planner"], r["config"].get("variant")) for r in rows
        )
    )
    known = [e for e in suite.entries if e.name in names]
    others = [suite.entry(n) for n in names if n not in {e.name for e in known}]
    for e in others:  # a variant outside the suite: rebuild it from its rows
        if "[" in e.name and not e.variant:
            planner, _, variant = e.name.partition("[")
            others[others.index(e)] = Entry(planner, variant.rstrip("]"))
    return [*known, *others]


def make_card(
    store_path: str | Path, suite: Suite, entry: Entry, rows: Sequence[Row]
) -> dict[str, Any]:
    """The card of ``entry`` from the store's finished plan ``rows`` (see the module)."""
    from voot.bench.leaderboard.plan import (
        canonical_problem,
        choose_settings,
        evaluation_specs,
        run_cpu_seconds,
    )
    from voot.bench.protocol.select import planner_label
    from voot.bench.store.shipped import store_digest
    from voot.bench.sweep.planners import planner_entry

    choices = choose_settings(suite, [entry], rows)
    mine = [
        r
        for r in rows
        if planner_label(r["config"]["planner"], r["config"].get("variant")) == entry.name
    ]
    ids = {r["run_id"] for r in mine}
    families = []
    for family in suite.families:
        choice = choices[(family.problem, entry.name)]
        expected = (
            evaluation_specs(suite, family, entry, choice.params)
            if choice.params is not None
            else []
        )
        per_level = {
            level: sum(
                1 for s in expected if s.env_kwargs_dict["difficulty"] == level and s.run_id in ids
            )
            for level in suite.levels
        }
        fam_rows = [
            r for r in mine if canonical_problem(str(r["config"]["problem"])) == family.problem
        ]
        families.append(
            {
                "problem": family.problem,
                "simulations": family.simulations,
                "settings": None if choice.params is None else dict(choice.params),
                "settings_source": choice.source,
                "settings_note": choice.note,
                "evaluation_runs_finished": per_level,
                "evaluation_runs_listed": len(expected) // max(1, len(suite.levels)),
                "runs_in_store": len(fam_rows),
                "cpu_seconds_search": math.fsum(run_cpu_seconds(r) or 0.0 for r in fam_rows),
                "simulator_calls": int(sum(int(r.get("simulator_calls") or 0) for r in fam_rows)),
            }
        )
    try:
        version = planner_entry(entry.planner).version or ""
    except ValueError:
        version = ""
    import voot

    card: dict[str, Any] = {
        "entry": entry.name,
        "planner": entry.planner,
        "variant": entry.variant,
        "fixed_options": dict(entry.set),
        "planner_version": version or f"voot {voot.__version__}",
        "suite": suite.name,
        "suite_digest": suite.digest,
        "families": families,
        "store": Path(store_path).name,
        "store_checksum": store_digest(store_path)["sha256"],
    }
    card[CARD_CHECKSUM] = _sha(card)
    return card


def write_cards(store_path: str | Path, suite: Suite) -> list[Path]:
    """Write the card of every entry the store holds; their paths."""
    from voot.bench.store.index import write_atomic

    store = ResultStore(store_path, create=False)
    rows = store.load(kind="plan", status="ok")
    folder = Path(store_path) / CARDS_DIR
    folder.mkdir(exist_ok=True)
    out = []
    for entry in entries_in(rows, suite):
        card = make_card(store_path, suite, entry, rows)
        path = folder / f"{_file_name(entry.name)}.json"
        write_atomic(path, (json.dumps(card, indent=1, sort_keys=True) + "\n").encode())
        out.append(path)
    return out


def _file_name(name: str) -> str:
    return "".join(c if c.isalnum() or c in "-_." else "_" for c in name)


def read_card(path: str | Path) -> dict[str, Any]:
    """A card, its own checksum verified; a StoreError naming the file otherwise."""
    p = Path(path)
    try:
        card = json.loads(p.read_bytes())
    except (OSError, ValueError) as exc:
        raise StoreError(f"{p}: not a readable result card ({exc})") from None
    if not isinstance(card, dict) or CARD_CHECKSUM not in card:
        raise StoreError(f"{p}: not a result card (no {CARD_CHECKSUM})")
    body = {k: v for k, v in card.items() if k != CARD_CHECKSUM}
    if _sha(body) != card[CARD_CHECKSUM]:
        raise StoreError(f"{p}: the card was changed after it was written (its checksum differs)")
    return card


def check_cards(store_path: str | Path, suite: Suite | None = None) -> list[dict[str, Any]]:
    """Every card of the store, checked against the store's checksum (and the suite's
    digest, if given); StoreError naming the first bad one."""
    from voot.bench.store.shipped import store_digest

    folder = Path(store_path) / CARDS_DIR
    paths = sorted(folder.glob("*.json")) if folder.is_dir() else []
    if not paths:
        raise StoreError(f"{store_path}: no result cards (write them: voot-bench leaderboard card)")
    checksum = store_digest(store_path)["sha256"]
    cards = []
    for p in paths:
        card = read_card(p)
        if card.get("store_checksum") != checksum:
            raise StoreError(
                f"{p}: store checksum {card.get('store_checksum')!r}, the store's is"
                f" {checksum!r} (rows lost, added or changed since the card was written)"
            )
        if suite is not None and card.get("suite_digest") != suite.digest:
            raise StoreError(
                f"{p}: suite digest {card.get('suite_digest')!r} is not suite {suite.name}'s"
                f" ({suite.digest!r})"
            )
        cards.append(card)
    return cards


# ----- verify ----------------------------------------------------------------------------
@dataclass(frozen=True)
class Mismatch:
    """A re-run that did not reproduce its row: the run, and the fields that differ."""

    run_id: str
    description: str
    fields: tuple[str, ...]


def sample_rows(rows: Sequence[Row], k: int, seed: int = 0) -> list[Row]:
    """``k`` of ``rows`` (all if fewer), drawn deterministically by run id."""
    ordered = sorted(rows, key=lambda r: str(r["run_id"]))
    if k >= len(ordered):
        return ordered
    rng = np.random.default_rng(seed)
    picks = sorted(rng.choice(len(ordered), size=k, replace=False).tolist())
    return [ordered[i] for i in picks]


def _same(a: Any, b: Any) -> bool:
    """Bit-for-bit equality of JSON-like values (floats by their bits, NaN equal to NaN)."""
    if isinstance(a, float) and isinstance(b, float):
        return a == b or (math.isnan(a) and math.isnan(b))
    if isinstance(a, Mapping) and isinstance(b, Mapping):
        return a.keys() == b.keys() and all(_same(a[k], b[k]) for k in a)
    if isinstance(a, list | tuple) and isinstance(b, list | tuple):
        return len(a) == len(b) and all(_same(x, y) for x, y in zip(a, b, strict=True))
    return bool(type(a) is type(b) and a == b)


def differing_fields(stored: Row, rerun: Row) -> list[str]:
    """The deterministic fields of two rows of one run that differ (see the module)."""
    keys = (set(stored) | set(rerun)) - NONDETERMINISTIC_KEYS
    out = []
    for key in sorted(keys):
        a, b = stored.get(key), rerun.get(key)
        if key == COMPACT_KEY and isinstance(a, Mapping) and isinstance(b, Mapping):
            ca, cb = a.get("curves") or {}, b.get("curves") or {}
            if a.get("version") != b.get("version"):
                out.append(f"{key}.version")
            out += [
                f"{key}.{c}"
                for c in sorted(set(ca) | set(cb))
                if c not in NONDETERMINISTIC_KEYS and not _same(ca.get(c), cb.get(c))
            ]
        elif not _same(a, b):
            out.append(key)
    return out


def spec_of(config: Mapping[str, Any]) -> Any:
    """The plan spec of a row's ``config`` (its run id is the row's for a genuine row)."""
    from voot.bench.sweep.plan import PlanSpec

    try:
        return PlanSpec(
            str(config["problem"]),
            None if config.get("dim") is None else int(config["dim"]),
            tuple(sorted(dict(config.get("env_kwargs") or {}).items())),
            str(config["planner"]),
            tuple(sorted(dict(config.get("params") or {}).items())),
            int(config["simulations"]),
            int(config["seed"]),
            variant=str(config.get("variant") or ""),
        )
    except (KeyError, TypeError, ValueError) as exc:
        raise StoreError(f"a row's config is not a plan run's ({exc}): {dict(config)}") from None


def verify_store(
    store_path: str | Path, k: int, *, seed: int = 0, run: Any = None
) -> tuple[int, list[Mismatch]]:
    """Re-run ``k`` sampled finished runs of the store and compare them (see the module).

    Returns ``(runs re-run, mismatches)``. Raises StoreError if the store is corrupt (a
    row whose checksum fails, names its file) or holds no finished plan run.
    """
    from voot.bench.store.compact import compact_row
    from voot.bench.store.format import row_bytes
    from voot.bench.sweep.engine import describe_row
    from voot.bench.sweep.plan import run_plan_spec

    store = ResultStore(store_path, create=False)
    raw = [r for r in store.load(kind="plan", status="ok", expand=False)]
    if not raw:
        raise StoreError(f"{store_path}: no finished plan runs to verify")
    runner = run if run is not None else run_plan_spec
    mismatches = []
    chosen = sample_rows(raw, k, seed)
    for stored in chosen:
        spec = spec_of(stored["config"])
        if spec.run_id != stored["run_id"]:
            mismatches.append(Mismatch(str(stored["run_id"]), describe_row(stored), ("run_id",)))
            continue
        rerun = runner(spec)
        if store.compact is not None and "compact" in stored:
            rerun = compact_row(rerun, store.compact)
        rerun = json.loads(row_bytes(rerun))  # as it would be stored (JSON floats)
        stored_body = {k: v for k, v in stored.items() if k != "checksum"}
        rerun = {k: v for k, v in rerun.items() if k != "checksum"}
        bad = differing_fields(stored_body, rerun)
        if bad:
            mismatches.append(Mismatch(str(stored["run_id"]), describe_row(stored), tuple(bad)))
    return len(chosen), mismatches
