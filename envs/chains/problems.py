"""The problem records of the synthetic chains (:mod:`voot.problems`).

The authors' settings on a chain depend on its dimension (the ``dim`` keyword): the
thresholds, ``w = 100`` re-evaluations, no decay, root commitment 5 / 5 / 3,
:math:`\\gamma = 0.9` (:func:`voot.tree.chains.chain_planner_options`, from the record's
``chain``); VOO samples its best cell in ``centered_uniform`` mode. A chain has no episode limit
(its episode ends at the first infeasible action; the env's ``horizon`` keyword adds
one) and no ``reward_threshold`` (the return grows with every feasible action). Read at
``import voot``: imports no env code.
"""

from __future__ import annotations

from voot.problems import CHAIN_PLANNERS, PaperSetup, ProblemRecord

#: The paper's chain experiments (the authors' code): 10,000 simulations, 20 seeds.
CHAIN_SETUP = PaperSetup(10_000, 20, CHAIN_PLANNERS)


def _chain(name: str) -> ProblemRecord:
    return ProblemRecord(
        id=f"voot/{name}Chain-v0",
        family="chain",
        entry_point=f"voot.envs.chains.env:{name}ChainEnv",
        paper_setup=CHAIN_SETUP,
        voo_options={"sampler": "centered_uniform"},
        chain=name.lower(),
    )


#: The chains' gymnasium ids (keyword ``dim``: 3, 10 and 20 have reference thresholds).
RECORDS: tuple[ProblemRecord, ...] = (_chain("Shekel"), _chain("Griewank"), _chain("Rastrigin"))
