"""Rerun recordings of searches and plans (needs the ``[record]`` extra)."""
