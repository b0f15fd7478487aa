"""pocketsphinx held to the command grammar: hears only commands, and hears them right.

pocketsphinx 5.1.1 ships its en-US acoustic model and the CMU dictionary inside its wheel, so
nothing is downloaded. Each vocabulary gets its own grammar search (:func:`.command_grammar.jsgf`),
made the first time that vocabulary is heard; words the dictionary lacks ("3d", "1") are added
with a pronunciation built by :mod:`.pronounce`.

Why these settings: espeak-ng audio and the silence the segmenter pads utterances with hold
runs of digital zeros, whose log energy the front end cannot take (an alignment of the right
words then fails outright); ``dither`` adds noise below one bit, seeded. The front end is made
anew for each utterance (``reinit_feat``, ~0.1 ms), so the same sound is always heard the same
way: kept, the dither's random stream and the live cepstral mean carry over from one utterance
to the next, and the same "Stuart, stop" at 10 dB SNR was heard as "stuart halt", then as
"stuart stop". ``bestpath`` off: the lattice pass took longer than the search and
gave nothing we use.
"""

from __future__ import annotations

import time
from typing import TYPE_CHECKING, Any

from .audio import AudioError
from .command_grammar import jsgf, matcher, normalise, spoken, words
from .pronounce import pronounce
from .vocabulary import Vocabulary

if TYPE_CHECKING:
    import re

    import numpy as np


MOST_VARIANTS = 4  # the CMU dictionary's words have up to four pronunciations ("word(2)" ...)


class GrammarRecogniser:
    """The grammar engine: :meth:`hear` gives the grammar tokens of the command it heard, or
    ``[]`` when its search reached no end of a sentence. Never an engine on its own: it hears
    every sound as a command (:mod:`.second_opinion` decides whether to believe it)."""

    def __init__(self) -> None:
        try:
            from pocketsphinx import Decoder, get_model_path
        except ImportError:
            raise AudioError("the grammar engine needs pocketsphinx: install the 'hearing' extra") from None
        self._decoder: Any = Decoder(hmm=get_model_path("en-us/en-us"), dict=get_model_path("en-us/cmudict-en-us.dict"),
                                     loglevel="FATAL", dither=True, seed=1, bestpath=False)
        self._searches: dict[Vocabulary, tuple[str, re.Pattern[str]] | None] = {}
        self.seconds = 0.0  # how long the last :meth:`hear` took

    def hear(self, samples: np.ndarray, vocabulary: Vocabulary) -> list[str]:
        import numpy as np

        started = time.perf_counter()
        search = self._search(vocabulary)
        if search is None:
            self.seconds = 0.0
            return []
        name, sentence = search
        if self._decoder.current_search() != name:
            self._decoder.activate_search(name)
        self._decoder.reinit_feat()  # nothing carried over from the last utterance (module docstring)
        self._decoder.start_utt()
        self._decoder.process_raw(np.asarray(samples, dtype="<i2").tobytes(), full_utt=True)
        self._decoder.end_utt()
        hypothesis = self._decoder.hyp()
        text = hypothesis.hypstr if hypothesis is not None else ""
        self.seconds = time.perf_counter() - started
        return text.split() if sentence.fullmatch(normalise(text)) else []  # a partial path is no sentence

    def pronunciation(self, word: str) -> str | None:
        """The phones the engine hears ``word`` as (the dictionary's or :mod:`.pronounce`'s)."""
        return pronounce(word, self._decoder.lookup_word)

    def pronunciations(self, word: str) -> list[str]:
        """Every way the dictionary says ``word`` ("stuart": S T UW ER T, S T Y UW ER T, S T AO R
        T), or the one :mod:`.pronounce` builds; none for a word with no letters it knows."""
        known = self._decoder.lookup_word(word.lower())
        if not known:
            built = self.pronunciation(word)
            return [built] if built else []
        ways = [known]
        while len(ways) < MOST_VARIANTS and (more := self._decoder.lookup_word(f"{word.lower()}({len(ways) + 1})")):
            ways.append(more)
        return ways

    def _search(self, vocabulary: Vocabulary) -> tuple[str, re.Pattern[str]] | None:
        """The search for ``vocabulary`` (made the first time), over the phrases it can say; None
        when it cannot say the robot's name."""
        if vocabulary in self._searches:
            return self._searches[vocabulary]
        sayable = self._sayable(vocabulary)
        if sayable is None:
            self._searches[vocabulary] = None
            return None
        grammar = jsgf(sayable)
        missing = {w: p for w in words(grammar) if not self._decoder.lookup_word(w) and (p := self.pronunciation(w))}
        for n, (word, phones) in enumerate(missing.items(), 1):
            self._decoder.add_word(word, phones, n == len(missing))  # the search is rebuilt once, after the last
        name = f"commands{len(self._searches)}"
        self._decoder.add_jsgf_string(name, grammar)
        known = self._searches[vocabulary] = (name, matcher(sayable))
        return known

    def _sayable(self, vocabulary: Vocabulary) -> Vocabulary | None:
        """``vocabulary`` without the phrases that hold a word with no pronunciation at all (no
        letter the rules know: a name in another script); None if that is the robot's name."""
        def sayable(phrase: str) -> bool:
            return all(self.pronunciation(w) for w in spoken(phrase))

        if not sayable(vocabulary.name):
            return None
        return Vocabulary(vocabulary.name, *(tuple(p for p in phrases if sayable(p)) for phrases in (
            vocabulary.places, vocabulary.objects, vocabulary.gestures, vocabulary.extra)))
