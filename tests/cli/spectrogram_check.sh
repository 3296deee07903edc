#!/usr/bin/env bash
# analysis/spectrogram.py on synthetic clatter-synth-like output (float32 WAV, format tag 3, two
# channels): a mix and two stems, "modal" (a decaying 1 kHz sinusoid) and "pan" (a short noise
# burst) scaled so that E_pan : E_modal = 3 : 1 exactly. The plot must be written and the printed
# shares must be 75 % / 25 % within 0.5 %; a missing file, a stem of another length and a stem at
# another rate must each be refused with exit 2 and a message naming the file.
# Usage: spectrogram_check.sh SPECTROGRAM_PY [PYTHON (default /usr/bin/python3)] [SCRATCH]
set -euo pipefail
script=$1
python=${2:-/usr/bin/python3}
if [[ -n ${3:-} ]]; then
  scratch=$3
  rm -rf "$scratch" && mkdir -p "$scratch"
else
  scratch=$(mktemp -d)
  trap 'rm -rf "$scratch"' EXIT
fi
fail() { echo "FAIL: $*"; exit 1; }

"$python" - "$scratch" <<'EOF'
import struct, sys
import numpy as np

def write_float_wav(path, x, rate):  # x: [frames, channels]; tag 3, as libsndfile writes it
    x = np.ascontiguousarray(x, dtype="<f4")
    ch = x.shape[1]
    fmt = struct.pack("<HHIIHH", 3, ch, rate, rate * 4 * ch, 4 * ch, 32)
    fact = struct.pack("<I", x.shape[0])
    data = x.tobytes()
    body = (b"WAVE" + b"fmt " + struct.pack("<I", len(fmt)) + fmt + b"fact" + struct.pack("<I", 4)
            + fact + b"data" + struct.pack("<I", len(data)) + data)
    with open(path, "wb") as f:
        f.write(b"RIFF" + struct.pack("<I", len(body)) + body)

d, rate = sys.argv[1], 48000
t = np.arange(int(0.5 * rate)) / rate
modal = np.zeros((len(t), 2))
modal[:, 0] = 0.5 * np.exp(-t / 0.08) * np.sin(2 * np.pi * 1000 * t)
modal[:, 1] = 0.5 * modal[:, 0]
pan = np.zeros_like(modal)
burst = slice(int(0.1 * rate), int(0.11 * rate))
pan[burst, 0] = np.random.default_rng(1).standard_normal(burst.stop - burst.start)
pan[:, 1] = 2 * pan[:, 0]
modal, pan = modal.astype(np.float32).astype(float), pan.astype(np.float32).astype(float)
pan *= np.sqrt(3 * np.sum(modal[:, 0] ** 2) / np.sum(pan[:, 0] ** 2))  # channel 0: 3:1
write_float_wav(f"{d}/out.wav", modal + pan, rate)
write_float_wav(f"{d}/out.modal.wav", modal, rate)
write_float_wav(f"{d}/out.pan.wav", pan, rate)
write_float_wav(f"{d}/short.wav", modal[:-10], rate)
write_float_wav(f"{d}/short.modal.wav", modal[:-20], rate)
write_float_wav(f"{d}/rate.wav", modal, rate)
write_float_wav(f"{d}/rate.modal.wav", modal, 44100)
EOF

summary=$("$python" "$script" "$scratch/out.wav") || fail "spectrogram.py exited $?"
echo "$summary"
[[ -s $scratch/out.spectrogram.png ]] || fail "no $scratch/out.spectrogram.png"
share() { awk -v n="$1" '$1 == n && NF == 4 { print $4 }' <<<"$summary"; }
check_share() {  # NAME EXPECTED_PERCENT
  local got
  got=$(share "$1")
  [[ -n $got ]] || fail "no share printed for $1"
  awk -v g="$got" -v w="$2" 'BEGIN { exit !(g - w <= 0.5 && w - g <= 0.5) }' || fail "$1: share $got %, expected $2 %"
}
check_share pan 75
check_share modal 25
# Channel 1 has the same 3:1 ratio times 4:0.25 = 48:1 (pan doubled, modal halved): 97.96 / 2.04 %.
summary=$("$python" "$script" "$scratch/out.wav" --channel 1 -o "$scratch/ch1.png" --freq-scale linear) ||
  fail "spectrogram.py --channel 1 exited $?"
[[ -s $scratch/ch1.png ]] || fail "no $scratch/ch1.png"
check_share pan 97.96
check_share modal 2.04

refused() {  # FILE_IN_MESSAGE ARGS...: exit 2 with one stderr line naming the file
  local want=$1 rc=0 err
  shift
  err=$("$python" "$script" "$@" 2>&1 >/dev/null) || rc=$?
  [[ $rc == 2 ]] || fail "$*: exit $rc, expected 2"
  [[ $err == *"$want"* && $(wc -l <<<"$err") == 1 ]] || fail "$*: message '$err' does not name $want in one line"
}
refused "$scratch/missing.wav" "$scratch/missing.wav"
refused "$scratch/short.modal.wav" "$scratch/short.wav"
refused "$scratch/rate.modal.wav" "$scratch/rate.wav"
refused "$scratch/out.wav" "$scratch/out.wav" --channel 2
echo "spectrogram checks: all passed"
