#include "io/wav.hpp"

#include <fmt/format.h>
#include <sndfile.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <stdexcept>

#include "core/cleanup.hpp"

namespace clatter::io {

void write_wav(const std::string& path, const std::vector<std::vector<double>>& channels, int rate_hz,
               SampleFormat format) {
  if (channels.empty()) throw std::invalid_argument("write_wav: no channels");
  const std::filesystem::path final_path(path);
  if (final_path.has_parent_path()) std::filesystem::create_directories(final_path.parent_path());
  const std::string temp = (final_path.parent_path() / fmt::format(".{}.tmp-{}", final_path.filename().string(), ::getpid())).string();
  SF_INFO info{};
  info.samplerate = rate_hz;
  info.channels = static_cast<int>(channels.size());
  info.format = SF_FORMAT_WAV | (format == SampleFormat::float32 ? SF_FORMAT_FLOAT : SF_FORMAT_PCM_24);
  register_temporary(temp);
  SNDFILE* file = sf_open(temp.c_str(), SFM_WRITE, &info);
  if (!file) throw std::runtime_error(fmt::format("{}: cannot create: {}", path, sf_strerror(nullptr)));
  const std::size_t frames = channels[0].size();
  std::vector<double> interleaved(frames * channels.size());
  for (std::size_t n = 0; n < frames; ++n)
    for (std::size_t c = 0; c < channels.size(); ++c) interleaved[n * channels.size() + c] = channels[c][n];
  const sf_count_t written = sf_writef_double(file, interleaved.data(), static_cast<sf_count_t>(frames));
  const int closed = sf_close(file);
  if (written != static_cast<sf_count_t>(frames) || closed != 0) {
    std::remove(temp.c_str());
    unregister_temporary(temp);
    throw std::runtime_error(fmt::format("{}: write failed", path));
  }
  std::filesystem::rename(temp, final_path);
  unregister_temporary(temp);
}

}  // namespace clatter::io
