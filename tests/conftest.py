"""The stuart_bt pytest plugin for this checkout (an installed stuart_bt also registers it
through its ``pytest11`` entry point; registering twice is avoided), pytester for the plugin's
own tests, the session guard (tests/session_guard.py): no process a test started outlives
the session, and temporary files stay in a folder of the session's own; and the fixtures the
browser tests (``page``, tests/web_support.py) and the fake-robot tests (``robot``,
``unitree_daemon``, tests/unitree_fake.py) share."""

from __future__ import annotations

import pytest

# the last four: shared fixtures
pytest_plugins = ["pytester", "session_guard", "web_support", "unitree_fake", "speech_support", "ears_fakes"]


def pytest_configure(config: pytest.Config) -> None:
    from stuart_bt import pytest_plugin

    if not config.pluginmanager.is_registered(pytest_plugin):
        config.pluginmanager.register(pytest_plugin, "stuart_bt")
