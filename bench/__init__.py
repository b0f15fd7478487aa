"""Benchmarks for stuart_bt, each measured beside an anchor in the same run.

A figure on its own says little on a shared 2-core machine; a ratio to something measured a
moment earlier on the same machine (raw py_trees, BehaviorTree.CPP, a bare pipe, rclpy) does.
Run ``python -m bench.run`` (see bench/README.md).
"""
