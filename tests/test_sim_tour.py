"""The six-station lab tour on the simulator: every station reached in order and on the mark,
each station's script spoken while its gestures play, and the base never touching anything."""

from __future__ import annotations

import math

STATIONS = [f"station_{i}" for i in range(1, 7)]


def test_lab_tour_on_the_sim_visits_six_stations_on_the_mark_presenting_each(stuart_sim):
    result = stuart_sim("trees/lab_tour.yaml", seed=1)

    result.assert_success()
    result.assert_no_failures()
    result.assert_visited(*STATIONS, exactly=True)
    result.assert_arrivals_within(0.10, math.radians(5))
    result.assert_speech_overlaps_gestures(*(f"tour/{s}/present/" for s in STATIONS))
    result.assert_no_collisions()
    result.assert_final_pose(2.0, 2.5, math.pi)
    result.assert_said("Thank you for visiting")
