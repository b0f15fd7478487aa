"""Hearing: sound in, what was said out, in front of the wake filter.

One module per job, bottom first: :mod:`.audio` (16 kHz mono samples, reading and resampling
any file), :mod:`.sources` (where sound comes from, chosen by name: ``file``, ``-`` for raw PCM
on stdin, ``mic``), :mod:`.vad` (voice activity: a stream cut into utterances),
:mod:`.vocabulary` (the words the robot expects, to bias recognition), :mod:`.recognisers`
(offline speech recognition behind one interface: faster-whisper), :mod:`.command_grammar`,
:mod:`.pronounce` and :mod:`.sphinx` (a command-only engine: pocketsphinx held to a grammar
made from the vocabulary), :mod:`.second_opinion` (whisper with that engine as a second
opinion, the default) and :mod:`.pipeline` (source -> segments -> transcripts). See docs/hearing.md.

Nothing here imports a heavy package at import time: numpy, the recogniser and PortAudio load
only when a source or a recogniser is made.
"""
