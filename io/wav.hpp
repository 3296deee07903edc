#pragma once
// WAV output through libsndfile, atomic like every Clatter output: written under a hidden
// temporary name and renamed into place when complete.
#include <string>
#include <vector>

namespace clatter::io {

enum class SampleFormat { float32, pcm24 };

// channels[c][n]: sample n of channel c, in the unit the caller chose (pascals by default). pcm24
// clips at +-1: normalize first (clatter-synth --normalize) or stay with float32.
void write_wav(const std::string& path, const std::vector<std::vector<double>>& channels, int rate_hz,
               SampleFormat format);

}  // namespace clatter::io
