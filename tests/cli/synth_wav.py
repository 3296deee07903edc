"""What the clatter-synth checks share: reading the float32 WAVs clatter-synth writes (libsndfile)."""
import numpy as np


def wav(path):
    """The samples of a float32 WAV's data chunk, one column per channel, as float64."""
    raw = open(path, "rb").read()
    channels = int.from_bytes(raw[22:24], "little")
    i = raw.index(b"data")
    n = int.from_bytes(raw[i + 4:i + 8], "little")
    return np.frombuffer(raw[i + 8:i + 8 + n], dtype="<f4").reshape(-1, channels).astype(np.float64)
