"""MJCF models of the robot and scenes, authored in this repository (package data)."""
