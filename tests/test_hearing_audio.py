"""Sound in: any file becomes 16 kHz mono int16, raw PCM streams in blocks, and what cannot be
read says which file and why."""

from __future__ import annotations

import io
import subprocess

import numpy as np
import pytest

from speech_support import NEEDS_ESPEAK, NEEDS_SOX, SOX
from stuart_bt.hearing.audio import RATE, AudioError, read_audio, resample, write_wav
from stuart_bt.hearing.sources import BLOCK_S, FileSource, PcmSource, open_source
from stuart_bt.testing import speak

pytest.importorskip("av", reason="the 'hearing' extra is not installed (make test installs it)")


def _peak_hz(samples: np.ndarray) -> float:
    spectrum = np.abs(np.fft.rfft(samples.astype(np.float64)))
    return float(np.argmax(spectrum) * RATE / len(samples))


def test_a_48_khz_stereo_tone_becomes_16_khz_mono_at_the_same_pitch():
    t = np.arange(48_000) / 48_000
    tone = (8000 * np.sin(2 * np.pi * 440 * t)).astype(np.int16)
    out = resample(np.repeat(tone, 2), 48_000, channels=2)
    assert abs(len(out) - RATE) <= 64 and out.dtype == np.int16
    assert _peak_hz(out) == pytest.approx(440, abs=2)


@NEEDS_ESPEAK
@NEEDS_SOX
def test_wav_and_flac_at_any_rate_and_channel_count_read_the_same(tmp_path):
    wav = speak("Hey Stuart, go to the kitchen", tmp_path / "a.wav")  # 22.05 kHz mono
    flac = tmp_path / "a.flac"
    subprocess.run([SOX, str(wav), "-r", "44100", "-c", "2", str(flac)], check=True, timeout=30)
    a, b = read_audio(wav), read_audio(flac)
    assert a.dtype == b.dtype == np.int16
    assert abs(len(a) - len(b)) <= RATE // 100  # the same duration within 10 ms
    assert np.corrcoef(a[: min(len(a), len(b))], b[: min(len(a), len(b))])[0, 1] > 0.9


def test_a_file_that_is_not_audio_is_one_clear_error_naming_it(tmp_path):
    junk = tmp_path / "notes.wav"
    junk.write_bytes(b"this is not a RIFF file at all\n" * 20)
    with pytest.raises(AudioError) as e:
        read_audio(junk)
    assert str(junk) in e.value.reason and "cannot read it as audio" in e.value.reason
    with pytest.raises(AudioError, match="no such file"):
        read_audio(tmp_path / "missing.wav")


def test_raw_pcm_on_a_stream_comes_out_in_whole_blocks_and_nothing_is_lost():
    samples = (np.arange(16_000 + 123) % 1000).astype("<i2")
    blocks = list(PcmSource(io.BytesIO(samples.tobytes())).blocks())
    assert all(len(b) == int(RATE * BLOCK_S) for b in blocks)
    joined = np.concatenate(blocks)
    assert np.array_equal(joined, samples[: len(joined)]) and len(samples) - len(joined) < int(RATE * BLOCK_S)


def test_a_folder_is_read_in_name_order_with_silence_between_files(tmp_path):
    write_wav(tmp_path / "2.wav", np.full(1600, 2000, np.int16))
    write_wav(tmp_path / "1.wav", np.full(1600, 1000, np.int16))
    (tmp_path / "readme.txt").write_text("not audio")
    out = np.concatenate(list(FileSource([tmp_path]).blocks()))
    assert out[0] == 1000 and out[-1] == 2000 and (out == 0).sum() >= RATE  # a second of silence between


def test_an_unknown_source_name_suggests_the_closest():
    with pytest.raises(AudioError, match=r"no sound source 'mik:0' \(did you mean 'mic'\?\)"):
        open_source("mik:0")


def test_an_unknown_source_suggests_and_lists_the_names_its_caller_opens_elsewhere():
    with pytest.raises(AudioError) as caught:
        open_source("robto", elsewhere=["robot", "robot:mic", "robot:asr"])
    message = str(caught.value)
    assert "(did you mean 'robot'?)" in message and "robot:asr" in message.split("sources are")[1]
