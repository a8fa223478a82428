"""The synthetic planning chains as gymnasium environments (``voot/ShekelChain-v0`` ...).

* :mod:`.env`: :class:`~voot.envs.chains.env.SyntheticChainEnv` and one class per function;
* :mod:`.problems`: their problem records (imported at ``import voot``, so this package
  imports nothing itself).
"""
