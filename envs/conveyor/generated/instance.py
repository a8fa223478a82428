"""A solvable storage instance from ``(layout_seed, difficulty)``, generated once and cached.

:func:`storage_instance` is what ``voot/GeneratedStorage-v0`` loads. Cold, it draws the
layout (:func:`~voot.envs.conveyor.generated.layout.generate_storage_layout`, attempt 0), compiles
its scene (:mod:`voot.envs.conveyor.generated.scene`), builds the env on it and proves it solvable
(:func:`~voot.envs.conveyor.generated.witness.find_witness`); a layout that fails (no witness
packing, or a box whose fixed grasp is infeasible) is **rejected** and the next attempt
of the same seed drawn, deterministically, up to :data:`MAX_ATTEMPTS`
(:func:`voot.envs.core.generation.first_accepted`). The rejections are counted and their
reasons kept (:attr:`StorageInstance.rejections`).

Caching. The accepted instance is kept in the process (:data:`INSTANCES`: a second env of
the same layout costs a model copy) and on disk, keyed by ``(layout_seed, difficulty)`` in a
folder named after the generator's version and MuJoCo's (``storage-g1-mj3.x.y``: the
compiled model is stored in MuJoCo's binary format, which is version specific): a JSON
record (the attempt, the rejections, the witness, a hash of the scene's MJCF) and the
model (``.mjb.z``: MuJoCo's binary model, zlib-compressed: its procedural textures make
2.8 MB of an uncompressed file, about 45 kB compressed). A cached instance loads without
generating, compiling or searching, and only if it is the one made for the key asked
(:func:`_load`): the record names its key and carries a hash of its own contents and of
the model file, and its scene hash must match the scene the generator writes for that
attempt; a foreign, swapped or edited file is regenerated and replaced, with one
:class:`~voot.envs.core.caches.CacheWarning` naming it. The folder is under voot's cache
(:func:`voot.envs.core.caches.cache_dir`: ``$VOOT_CACHE``, else ``~/.cache/voot``), beside
the meshes' cache; if it cannot be written (``$VOOT_CACHE`` a file, a path under a file, a
read-only folder) the instance is still made and kept in the process, with one warning
naming ``VOOT_CACHE``. Files are written atomically (a temporary file renamed), so
concurrent processes can share the cache. The process keeps the last
:data:`STORAGE_CACHE_SIZE` instances (:data:`INSTANCES`).
"""

from __future__ import annotations

import copy
import json
import zlib
from collections.abc import Mapping
from dataclasses import dataclass, replace
from pathlib import Path
from typing import Any, Unpack

import mujoco
import numpy as np

from voot.envs.assets.mjcf import mjcf_sha256
from voot.envs.conveyor.config import ConveyorConfig, conveyor_config
from voot.envs.conveyor.env import ConveyorPackingEnv
from voot.envs.conveyor.generated.layout import (
    DIFFICULTIES,
    GENERATOR_VERSION,
    StorageLayout,
    generate_storage_layout,
)
from voot.envs.conveyor.generated.scene import compile_storage_scene, storage_xml
from voot.envs.conveyor.generated.witness import Witness, find_witness
from voot.envs.core.caches import cache_dir as voot_cache_dir
from voot.envs.core.caches import sha256, warn_rebuilt, write_atomic
from voot.envs.core.generation import (
    GeneratedInstance,
    InstanceCache,
    Rejection,
    check_layout_seed,
    first_accepted,
    parse_difficulty,
    reject_layout_fields,
)
from voot.envs.core.names import Difficulty
from voot.envs.core.rendering import RenderOptions

#: Attempts of one seed before giving up (none has needed more than a few).
MAX_ATTEMPTS = 50
#: The config fields a layout sets (an env keyword may not override them).
LAYOUT_FIELDS = frozenset({"loading_region", "workspace", "n_objects"})


@dataclass(frozen=True, eq=False)
class StorageInstance(GeneratedInstance[StorageLayout, Witness]):
    """An accepted storage layout with its compiled scene and the proof that it is
    solvable (the packing: :class:`~voot.envs.conveyor.generated.witness.Witness`); the
    fields are :class:`~voot.envs.core.generation.GeneratedInstance`'s."""


def layout_config(layout: StorageLayout, **options: Any) -> ConveyorConfig:
    """The v1 :class:`ConveyorConfig` on ``layout``: its loading region, workspace and box
    count, with ``options`` (other config fields) applied.

    Raises:
        ValueError: An option is one of :data:`LAYOUT_FIELDS` or no config field.
    """
    reject_layout_fields(options, LAYOUT_FIELDS)
    return conveyor_config(
        "v1",
        loading_region=layout.loading_region,
        workspace=layout.workspace,
        n_objects=layout.n_boxes,
        **options,
    )


class SceneConveyorEnv(ConveyorPackingEnv):
    """The conveyor on a given compiled scene with a given config: what the solvability
    search steps (:func:`generate_instance`), the base of ``voot/GeneratedStorage-v0``'s
    env, and a way to run a layout's scene without the cache. ``model`` is taken over
    (pass a copy to keep yours unchanged).

    Args:
        model: The compiled scene.
        config: Settings (:func:`layout_config`).
        **render: The render arguments (:class:`~voot.envs.core.rendering.RenderOptions`).
    """

    def __init__(
        self, model: mujoco.MjModel, config: ConveyorConfig, **render: Unpack[RenderOptions]
    ) -> None:
        self._pending_model: mujoco.MjModel | None = model
        super().__init__(config=config, **render)

    def _scene_model(self) -> mujoco.MjModel:
        """The given scene (handed over once: the env keeps no second reference)."""
        model, self._pending_model = self._pending_model, None
        if model is None:  # pragma: no cover - called once, by __init__
            raise RuntimeError("the generated scene was already loaded")
        return model


def cache_dir() -> Path:
    """The on-disk cache's folder for this generator and MuJoCo version (module docstring)."""
    return voot_cache_dir() / f"storage-g{GENERATOR_VERSION}-mj{mujoco.__version__}"


#: Storage instances kept per process (the least recently used one is forgotten past
#: this: an instance holds its compiled model, about 3.5 MB with its textures; 48 keep
#: the protocol's 40 split layouts). Measured: docs/environments.md.
STORAGE_CACHE_SIZE = 48

#: The instances made or loaded in this process, by ``(layout_seed, difficulty)``.
INSTANCES: InstanceCache[tuple[int, Difficulty], StorageInstance] = InstanceCache(
    STORAGE_CACHE_SIZE
)


def clear_memo() -> None:
    """Forget the instances kept in this process (the disk cache stays)."""
    INSTANCES.clear()


def storage_instance(layout_seed: int, difficulty: str, *, disk: bool = True) -> StorageInstance:
    """The solvable instance of ``(layout_seed, difficulty)``: from this process's memo,
    else from the disk cache (``disk=True``), else generated (and cached)."""
    seed = check_layout_seed(layout_seed)
    level = parse_difficulty(difficulty, DIFFICULTIES)
    return INSTANCES.get_or_make((seed, level), lambda: _load_or_generate(seed, level, disk))


def _load_or_generate(layout_seed: int, difficulty: Difficulty, disk: bool) -> StorageInstance:
    hit = _load(layout_seed, difficulty) if disk else None
    if hit is None:
        hit = generate_instance(layout_seed, difficulty)
        if disk:
            _store(hit)
    return hit


def generate_instance(layout_seed: int, difficulty: str) -> StorageInstance:
    """Generate, compile and prove ``(layout_seed, difficulty)`` (no cache; see module).

    Raises:
        RuntimeError: No attempt of :data:`MAX_ATTEMPTS` was solvable.
    """

    def attempt(k: int) -> StorageInstance | str:
        layout = generate_storage_layout(layout_seed, difficulty, k)
        xml = storage_xml(layout)
        model = compile_storage_scene(layout, xml)
        try:
            env = SceneConveyorEnv(copy.copy(model), layout_config(layout))
        except RuntimeError as exc:  # a fixed grasp that fails: the layout is rejected
            return str(exc)
        witness = find_witness(env, layout)
        env.close()
        if not witness.solved:
            return witness.reason
        return StorageInstance(layout, model, witness, (), mjcf_sha256(xml))

    what = f"layout for layout_seed={layout_seed}, difficulty='{difficulty}'"
    instance, rejections = first_accepted(attempt, MAX_ATTEMPTS, what)
    return replace(instance, rejections=rejections)


def _paths(layout_seed: int, difficulty: str) -> tuple[Path, Path]:
    stem = cache_dir() / f"{difficulty}-{layout_seed}"
    return stem.with_suffix(".json"), stem.with_suffix(".mjb.z")


#: The format of the cache's records: a record of another format is regenerated silently.
RECORD_FORMAT = 2


def _key(layout_seed: int, difficulty: str) -> dict[str, Any]:
    """What a cached instance was made for (written in its record, checked on loading)."""
    return {
        "layout_seed": int(layout_seed),
        "difficulty": str(difficulty),
        "generator_version": GENERATOR_VERSION,
        "mujoco": mujoco.__version__,
    }


def _record_sha256(record: Mapping[str, Any]) -> str:
    """SHA-256 of a record's canonical JSON, without its own ``record_sha256``."""
    body = {k: v for k, v in record.items() if k != "record_sha256"}
    return sha256(json.dumps(body, sort_keys=True).encode())


def _load(layout_seed: int, difficulty: str) -> StorageInstance | None:
    """The cached instance of ``(layout_seed, difficulty)``, or None (then regenerated).

    Missing files, or a record of an older format, are None silently. Otherwise the
    record must be the one written for this key (its key, the hash of its own contents:
    an edited witness is refused), its scene hash the scene the generator writes for that
    key and attempt, and the model file the one written with it (its SHA-256 in the
    record: another layout's model copied over it is refused); a file that fails a check
    or cannot be read is None with one :class:`~voot.envs.core.caches.CacheWarning`
    naming it.
    """
    record_path, model_path = _paths(layout_seed, difficulty)
    if not record_path.is_file():
        return None
    try:
        record = json.loads(record_path.read_text())
        if not isinstance(record, dict) or record.get("format") != RECORD_FORMAT:
            return None  # an older record: regenerated and replaced
        if record.get("record_sha256") != _record_sha256(record):
            warn_rebuilt(record_path, "does not match its digest (edited)")
            return None
        if record.get("key") != _key(layout_seed, difficulty):
            warn_rebuilt(
                record_path,
                f"was made for {record.get('key')}, not {_key(layout_seed, difficulty)}",
            )
            return None
        layout = generate_storage_layout(layout_seed, difficulty, int(record["attempt"]))
        sha = mjcf_sha256(storage_xml(layout))
        if record["xml_sha256"] != sha:
            warn_rebuilt(record_path, "records another scene than this layout's")
            return None
        blob = zlib.decompress(model_path.read_bytes())
        if sha256(blob) != record["model_sha256"]:
            warn_rebuilt(model_path, "is not the model its record was written with")
            return None
        model = mujoco.MjModel.from_binary_path("model.mjb", {"model.mjb": blob})
        witness = Witness.from_json(record["witness"])
        rejections = tuple(Rejection(int(k), str(why)) for k, why in record["rejections"])
    except (OSError, ValueError, KeyError, TypeError, zlib.error) as exc:
        warn_rebuilt(record_path, f"or its model cannot be read ({type(exc).__name__})")
        return None
    return StorageInstance(layout, model, witness, rejections, sha)


def _store(instance: StorageInstance) -> None:
    """Write ``instance`` to the disk cache (atomically, the model first); skipped (one
    warning naming ``VOOT_CACHE``) if the folder is unusable."""
    layout = instance.layout
    record_path, model_path = _paths(layout.layout_seed, layout.difficulty)
    buffer = np.zeros(mujoco.mj_sizeModel(instance.model), dtype=np.uint8)
    mujoco.mj_saveModel(instance.model, None, buffer)
    blob = buffer.tobytes()
    record: dict[str, Any] = {
        "format": RECORD_FORMAT,
        "key": _key(layout.layout_seed, layout.difficulty),
        "attempt": layout.attempt,
        "rejections": [list(r) for r in instance.rejections],
        "witness": instance.witness.to_json(),
        "xml_sha256": instance.xml_sha256,
        "model_sha256": sha256(blob),
    }
    record["record_sha256"] = _record_sha256(record)
    if write_atomic(model_path, zlib.compress(blob, 6)):
        write_atomic(record_path, json.dumps(record, sort_keys=True).encode())
