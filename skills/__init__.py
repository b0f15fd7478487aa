"""Daemon programs, one per skill family, and their backends (dry, sim, unitree)."""
