"""Maps: the occupancy grid, inflation by the robot's radius, path planning, map and marker files.

One package for what the simulator's world server and the loco daemon both need, so the map the
world is built from and the map the robot plans on cannot drift apart. It depends on
``stuart_bt.core`` and numpy only (never on MuJoCo): ``stuart_bt.sim.world.occupancy`` builds a
grid from the scene's geoms, the loco backends read the saved map and plan on it.

Nothing is imported here on purpose: :mod:`stuart_bt.maps.markers` is needed by the tree loader
and the web view, which run without numpy (the ``sim`` extra), so import the modules directly.
"""
