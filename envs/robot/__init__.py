"""The mobile manipulator: its model, arm inverse kinematics, grasps, collisions.

* :mod:`.model`: the robot of ``voot.models/robot.xml``, named access, its footprint;
* :mod:`.arm_ik`: arm IK relative to the base (closed-form seeds refined by mink);
* :mod:`.grasp`: the original's side grasp of a box; :mod:`.mesh_grasp`: grasps on the
  real shape of a mesh object (ray-cast grasp tables);
* :mod:`.collision`: collision checks of the robot and what it holds, with MuJoCo;
* :mod:`.rotations`: elementary rotations and XYX Euler angles.
"""
