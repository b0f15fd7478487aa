"""Simulator: MuJoCo models, scenes, maps and the world server (filled by the simulator work)."""
