"""The problem records of the conveyor family (:mod:`voot.problems`), one per gymnasium id.

* ``voot/ConveyorPacking-v0`` (alias ``conveyor``): the paper's conveyor, every check
  inside the planners' retries; the authors plan it with :math:`\\gamma = 0.99`, VOO in
  ``uniform`` mode with :math:`\\omega = 0.3`, and 200 feasibility retries for the
  progressive-widening planners;
* ``voot/ConveyorPacking-v1`` (``conveyor_v1``): the same entry point at its ``v1`` preset,
  the authors' two-stage protocol with their tree rules, root commitment 1 and VOO's
  per-operator distance;
* ``voot/GeneratedStorage-v0`` (``generated_storage``): the conveyor on storage rooms
  generated from ``layout_seed`` at a ``difficulty`` on the v1 rules, with the v1
  conveyor's settings and the protocol's training / held-out layouts;
* ``voot/ConveyorPacking-v2`` (``conveyor_v2``): the generated storage rooms' first name,
  kept as an alias that warns once (the committed results name it).
* ``voot/ConveyorPacking-v3`` (``conveyor_v3``): v1 on the authors' domain (preset
  ``v3``): the exact footprint where the disc finds no path (geodesic heuristic), the
  walls of their ``convbelt_env_diffcult_shapes_two_rooms.xml`` and their big-box ban;
  the same tree rules as v1. v1 stays the published protocol's conveyor.

Every version truncates at :data:`HORIZON` steps (``ConveyorConfig.horizon``'s default,
registered as ``max_episode_steps``). The paper's budget (Figure 4): 3,000 simulations,
50 seeds. Read at ``import voot``: imports no env code.
"""

from __future__ import annotations

from dataclasses import replace

from voot.problems import ROBOT_PLANNERS, PaperSetup, ProblemRecord, robot_versions

#: The family's name (:attr:`voot.envs.core.env.ManipulationEnv.family` of its envs).
FAMILY = "conveyor"
#: The paper's Figure 4 budget on the conveyor.
CONVEYOR_SETUP = PaperSetup(3_000, 50, ROBOT_PLANNERS)
#: The discount the authors plan the conveyor with.
CONVEYOR_DISCOUNT = 0.99
#: The conveyor's episode limit (steps): ``ConveyorConfig.horizon``'s default.
HORIZON = 20

#: The conveyor's gymnasium ids: v0 (with the progressive-widening planners' 200
#: retries), then v1 and the generated storage rooms on the authors' rules (commitment
#: 1), the storage rooms' first name, and v3 (the authors' domain).
_VERSIONS: tuple[ProblemRecord, ...] = robot_versions(
    ProblemRecord(
        id="voot/ConveyorPacking-v0",
        family=FAMILY,
        entry_point="voot.envs.conveyor.env:ConveyorPackingEnv",
        aliases=("conveyor",),
        paper_setup=CONVEYOR_SETUP,
        discount=CONVEYOR_DISCOUNT,
        voo_options={"sampler": "uniform", "omega": 0.3},
        pw_retries=200,
    ),
    root_commitment=1,
    generated_entry_point="voot.envs.conveyor.generated.env:ConveyorFamilyEnv",
    generated=("GeneratedStorage", "generated_storage"),
    max_episode_steps=HORIZON,
)
#: The authors' domain: v1's record at the ``v3`` preset.
AUTHORS_DOMAIN = replace(
    _VERSIONS[1],
    id="voot/ConveyorPacking-v3",
    kwargs={"preset": "v3"},
    aliases=("conveyor_v3",),
    authors_domain=True,
)
RECORDS: tuple[ProblemRecord, ...] = (*_VERSIONS, AUTHORS_DOMAIN)
