"""Running a tree: the executor that ticks it, the session that starts the daemons (and the
simulator) around it, and what a run leaves behind for people: the report, terminal views and
tree snapshots (all from events)."""
