"""The ROS 2 bridge (``stuart-bt ros``): the original system's topics in front of the mission pipeline.

This package is the only place in stuart_bt that imports rclpy, and it only runs inside the bridge
process (docs/ros.md). :mod:`.topics` turns events into outgoing messages and knows nothing of ROS,
:mod:`.node` is the rclpy node, :mod:`.cli` the command, :mod:`.guard` keeps the vendor SDK out of
the process. Importing this package itself loads neither rclpy nor the mission pipeline.
"""
