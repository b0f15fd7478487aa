"""The simulated world: a MuJoCo lab served to the framework and the skill daemons.

``python -m stuart_bt.sim.world`` runs the world server: :mod:`.process` (options, READY, an
orderly end), :mod:`.server` (the one-thread loop of physics steps and requests) and
:mod:`.world` (the MuJoCo world and its commands). Clients use :class:`.client.WorldClient`
over its Unix socket and read sim time through :class:`.clock.SimClock`. See docs/sim.md.

This package's ``__init__`` imports nothing heavy, so a daemon that only needs the client or the
clock never loads MuJoCo.
"""
