"""Perception: camera -> detector -> depth projection -> spatial memory.

Small modules with one job each (docs/perception.md): ``frames`` (the frame and camera source
interface), ``sim_camera`` / ``recorded`` / ``realsense`` (sources), ``detect`` (the detector
interface), ``sim_detector`` / ``yolo`` (detectors), ``projection`` (pixels -> torso -> world),
``memory`` (the decaying spatial memory), ``pipeline`` (one frame through all of it) and
``annotate`` (the picture a person looks at).
"""
