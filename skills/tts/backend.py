"""What every speech backend offers: say a text (a newer utterance preempts the current one)."""

from __future__ import annotations

from abc import abstractmethod
from typing import Any

from stuart_bt.daemon import args as a
from stuart_bt.daemon.backend import Activity, Backend, Handler


class TtsBackend(Backend):
    family = "tts"

    @abstractmethod
    def say(self, text: str) -> Activity:
        """Speak ``text`` exactly as given; accepted data carries ``duration``, the result
        ``{"text", "duration"}``."""

    def commands(self) -> dict[str, Handler]:
        return {"say": self._say_command}

    def _say_command(self, args: dict[str, Any]) -> Activity:
        a.only_known(args, ("text",), "say")
        return self.say(a.string(args, "text", "say"))
