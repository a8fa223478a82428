"""The problem records of the kitchen family (:mod:`voot.problems`), one per gymnasium id.

* ``voot/KitchenClearing-v0`` (alias ``kitchen``): the paper's kitchen, every check
  inside the planners' retries; the authors plan it with :math:`\\gamma = 0.9` and VOO in
  ``uniform`` mode;
* ``voot/KitchenClearing-v1`` (``kitchen_v1``): the same entry point at its ``v1`` preset,
  the authors' two-stage protocol (docs/environments.md) with their tree rules, root
  commitment 10 and VOO's per-operator distance;
* ``voot/GeneratedKitchen-v0`` (``generated_kitchen``): kitchens generated from
  ``layout_seed`` at a ``difficulty`` on the v1 rules, with the v1 kitchen's settings and
  the protocol's training / held-out layouts;
* ``voot/KitchenClearing-v2`` (``kitchen_v2``): the generated kitchens' first name, kept as
  an alias that warns once (the committed results name it).

Every version truncates at :data:`HORIZON` steps (``KitchenConfig.horizon``'s default,
registered as ``max_episode_steps``). The paper's budget (Figure 4): 2,000 simulations,
20 seeds. Read at ``import voot``: imports no env code.
"""

from __future__ import annotations

from voot.problems import ROBOT_PLANNERS, PaperSetup, ProblemRecord, robot_versions

#: The family's name (:attr:`voot.envs.core.env.ManipulationEnv.family` of its envs).
FAMILY = "kitchen"
#: The paper's Figure 4 budget on the kitchen.
KITCHEN_SETUP = PaperSetup(2_000, 20, ROBOT_PLANNERS)
#: The discount the authors plan the kitchen with.
KITCHEN_DISCOUNT = 0.9
#: The kitchen's episode limit (steps): ``KitchenConfig.horizon``'s default.
HORIZON = 50

#: The kitchen's gymnasium ids: v0, then v1 and the generated kitchens on the authors'
#: rules (commitment 10), and the generated kitchens' first name.
RECORDS: tuple[ProblemRecord, ...] = robot_versions(
    ProblemRecord(
        id="voot/KitchenClearing-v0",
        family=FAMILY,
        entry_point="voot.envs.kitchen.env:KitchenClearingEnv",
        aliases=("kitchen",),
        paper_setup=KITCHEN_SETUP,
        discount=KITCHEN_DISCOUNT,
        voo_options={"sampler": "uniform"},
    ),
    root_commitment=10,
    generated_entry_point="voot.envs.kitchen.generated.env:GeneratedKitchenEnv",
    generated=("GeneratedKitchen", "generated_kitchen"),
    max_episode_steps=HORIZON,
)
