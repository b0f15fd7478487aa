"""The simulated world: a MuJoCo lab served to the framework and the skill daemons.

``python -m stuart_bt.sim.world`` runs the world server (:mod:`.server`); clients use
:class:`.client.WorldClient` over its Unix socket and read sim time through
:class:`.clock.SimClock`. See docs/sim.md.

This package's ``__init__`` imports nothing heavy, so a daemon that only needs the client or the
clock never loads MuJoCo.
"""
