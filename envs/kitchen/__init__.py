"""The kitchen-clearing family: clear the obstacles from the robot's path to the sink.

The paper's kitchen (``voot/KitchenClearing-v0`` and ``-v1``):

* :mod:`.env`: :class:`KitchenClearingEnv`;
* :mod:`.config`: the task rules and the v0/v1 presets (:class:`KitchenConfig`);
* :mod:`.task`: the task record, the records an episode reaches, the rewards;
* :mod:`.path`: the fixed path, the handling order, the obstacles on the path;
* :mod:`.poses`: pick and place actions decoded into poses;
* :mod:`.checks`: the checks of a pick or a place (the step's and the v1 pre-check);
* :mod:`.screen`: the exact pre-screen and the carry-disc test.

Kitchens generated from a seed (``voot/GeneratedKitchen-v0``) are in :mod:`.generated`.
"""
