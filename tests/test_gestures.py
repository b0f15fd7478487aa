"""The gesture library: names, aliases, spellings and vendor action ids."""

from __future__ import annotations

import pytest

from stuart_bt.core import gestures


@pytest.mark.parametrize(("spoken", "canonical", "action_id"), [
    ("high wave", "high wave", 26), ("wave", "high wave", 26), ("High_Wave", "high wave", 26),
    ("face wave", "face wave", 25), ("high five", "high five", 18), ("clap", "clap", 17),
    ("hug", "hug", 19), ("heart", "heart", 20), ("shake hand", "shake hand", 27),
    ("handshake", "shake hand", 27), ("hands up", "hands up", 15), ("reject", "reject", 22),
    ("release arm", "release arm", 99), ("x-ray", "x-ray", 24), ("x ray", "x-ray", 24),
    ("26", "high wave", 26), ("99", "release arm", 99),
])
def test_lookup_accepts_names_aliases_spellings_and_vendor_ids(spoken, canonical, action_id):
    gesture = gestures.lookup(spoken)
    assert gesture is not None and (gesture.name, gesture.action_id) == (canonical, action_id)


@pytest.mark.parametrize("unknown", ["wavve", "dance", "42", ""])
def test_unknown_gestures_are_none(unknown):
    assert gestures.lookup(unknown) is None


def test_every_vendor_id_is_unique_and_every_alias_points_into_the_library():
    ids = [g.action_id for g in gestures.LIBRARY.values()]
    assert len(ids) == len(set(ids))
    assert set(gestures.ALIASES.values()) <= set(gestures.LIBRARY)
