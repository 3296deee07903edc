#include "synth/synthesize.hpp"

#include <fmt/format.h>

#include <cmath>

#include "core/errors.hpp"
#include "core/stage_log.hpp"

namespace clatter::synth {

void check_options(const SynthOptions& o) {
  const int rate = o.render.rate_hz;
  if (rate < 8000 || rate > 384000) throw InputError(fmt::format("--rate {}: must be in [8000, 384000] Hz", rate));
  if (o.pan_bank.empty() && o.object_pans.empty() && !o.modal_sound() && o.ground_bank.empty())
    throw InputError("give a PAN bank (-b or -P), a modal bank (-m), an object bank (-O) or a ground bank (-g), or several");
  // The command line's validators check these too; a library caller gets the same words.
  auto non_negative = [](const char* flag, double v) {
    if (!(v >= 0)) throw InputError(fmt::format("{} {}: must be a number >= 0", flag, v));
  };
  non_negative("--max-sustained-s", o.render.max_sustained_s);
  non_negative("--proxy-above-hz", o.modal.proxy_above_hz);
  non_negative("--nu-tolerance", o.modal.poisson_tolerance);
  if (!(o.modal.max_frequency_hz > 0))
    throw InputError(fmt::format("--max-mode-hz {}: must be a number > 0", o.modal.max_frequency_hz));
}

std::vector<std::vector<double>> Synthesis::mix() const {
  std::vector<std::vector<double>> out = stems.front();
  for (std::size_t s = 1; s < stems.size(); ++s)
    for (std::size_t l = 0; l < out.size(); ++l)
      for (std::size_t n = 0; n < out[l].size(); ++n) out[l][n] += stems[s][l][n];
  return out;
}

Synthesis synthesize(const io::Scene& scene, const SynthOptions& o) {
  check_options(o);
  Synthesis r;
  {
    Stage banks("banks");  // read and checked, then each source's own set-up
    if (!o.pan_bank.empty() || !o.object_pans.empty()) {
      auto p = std::make_unique<PanSource>(o.pan_bank, o.object_pans);
      r.pan = p.get();
      r.sources.push_back(std::move(p));
    }
    if (o.modal_sound()) {
      auto m = std::make_unique<ModalSource>(o.modal_banks, o.modal, o.object_banks);
      r.modal = m.get();
      r.sources.push_back(std::move(m));
    }
    if (!o.ground_bank.empty()) {
      auto g = std::make_unique<GroundSource>(o.ground_bank);
      r.ground = g.get();
      r.sources.push_back(std::move(g));
    }
  }
  std::vector<SoundSource*> sources;
  for (auto& s : r.sources) sources.push_back(s.get());
  r.stems = render_scene(scene, sources, o.render, &r.stats);
  return r;
}

double peak_of(const std::vector<std::vector<double>>& channels) {
  double peak = 0;
  for (const auto& ch : channels)
    for (double v : ch) peak = std::max(peak, std::abs(v));
  return peak;
}

Level level_of(const std::vector<std::vector<double>>& channels) {
  double peak = 0, energy = 0;
  std::size_t count = 0;
  for (const auto& ch : channels)
    for (double v : ch) peak = std::max(peak, std::abs(v)), energy += v * v, ++count;
  return {peak, std::sqrt(energy / static_cast<double>(std::max<std::size_t>(count, 1)))};
}

std::vector<std::string> write_outputs(const Synthesis& r, const std::vector<std::vector<double>>& mix, const std::string& out,
                                       int rate_hz, io::SampleFormat format, double gain, bool stems) {
  const double peak = peak_of(mix);
  if (format == io::SampleFormat::pcm24 && peak * gain > 1.0)
    throw InputError(fmt::format("--format pcm24: the peak is {:.4g} Pa, beyond the 24-bit range of +-1; add --normalize "
                                 "or use --format float",
                                 peak));
  auto scaled = [&](std::vector<std::vector<double>> channels) {
    for (auto& ch : channels)
      for (double& v : ch) v *= gain;
    return channels;
  };
  std::vector<std::string> written{out};
  io::write_wav(out, scaled(mix), rate_hz, format);
  if (!stems) return written;
  const std::string base = out.size() > 4 && out.substr(out.size() - 4) == ".wav" ? out.substr(0, out.size() - 4) : out;
  for (std::size_t s = 0; s < r.stems.size(); ++s) {
    written.push_back(fmt::format("{}.{}.wav", base, r.sources[s]->name()));
    io::write_wav(written.back(), scaled(r.stems[s]), rate_hz, format);
  }
  return written;
}

}  // namespace clatter::synth
