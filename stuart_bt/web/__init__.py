"""The live web view (``stuart-bt serve``): the tree while it ticks, the mission console, the map
and the gesture recorder, in one page served from this package (no CDN, no build step).

It learns what happens only from the event stream and draws the shared tree snapshot
(:mod:`stuart_bt.run.snapshot`); it commands only through the public run and mission APIs
(:mod:`.control`). See docs/web.md.
"""
