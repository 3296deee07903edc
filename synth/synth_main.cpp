// clatter-synth: the serial synthesizer. Soundbanks plus a scene of rigid-body impulses in, WAV
// out (docs/synth.md). One loop over events feeds every sound source (synth/render_scene.cpp).
#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>

#include "io/linked_libraries.hpp"
#include "core/cleanup.hpp"
#include "core/errors.hpp"
#include "io/wav.hpp"
#include "synth/load_scene.hpp"
#include "synth/render_scene.hpp"

using namespace clatter;

namespace {

struct Options {
  std::string scene, impulses, bank, out = "out.wav", format = "float";
  int rate_hz = 44100;
  bool normalize = false, stems = false;
};

int run(const Options& o) {
  const auto t0 = std::chrono::steady_clock::now();
  if (o.rate_hz < 8000 || o.rate_hz > 384000) throw InputError(fmt::format("--rate {}: must be in [8000, 384000] Hz", o.rate_hz));
  const io::Scene scene = synth::load_scene(o.scene, o.impulses);
  const synth::PanSource pan(o.bank);
  synth::RenderOptions options;
  options.rate_hz = o.rate_hz;
  synth::RenderStats stats;
  auto stems = synth::render_scene(scene, {&pan}, options, &stats);
  const double render_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  // The mix: every source at every listener.
  std::vector<std::vector<double>> mix = stems.front();
  for (std::size_t s = 1; s < stems.size(); ++s)
    for (std::size_t l = 0; l < mix.size(); ++l)
      for (std::size_t n = 0; n < mix[l].size(); ++n) mix[l][n] += stems[s][l][n];
  double peak = 0;
  for (const auto& ch : mix)
    for (double v : ch) peak = std::max(peak, std::abs(v));
  double gain = 1.0;
  if (o.normalize && peak > 0) gain = 0.99 / peak;
  const auto format = o.format == "pcm24" ? io::SampleFormat::pcm24 : io::SampleFormat::float32;
  if (format == io::SampleFormat::pcm24 && peak * gain > 1.0)
    throw InputError(fmt::format("--format pcm24: the peak is {:.4g} Pa, beyond the 24-bit range of +-1; add --normalize "
                                 "or use --format float",
                                 peak));
  auto scaled = [&](std::vector<std::vector<double>> channels) {
    for (auto& ch : channels)
      for (double& v : ch) v *= gain;
    return channels;
  };
  io::write_wav(o.out, scaled(mix), o.rate_hz, format);
  if (o.stems)
    for (std::size_t s = 0; s < stems.size(); ++s) {
      const std::string base = o.out.size() > 4 && o.out.substr(o.out.size() - 4) == ".wav" ? o.out.substr(0, o.out.size() - 4) : o.out;
      io::write_wav(fmt::format("{}.{}.wav", base, s == 0 ? pan.name() : std::to_string(s)), scaled(stems[s]), o.rate_hz, format);
    }
  const double seconds = static_cast<double>(mix.front().size()) / o.rate_hz;
  std::printf("clatter-synth: wrote %s: %zu channel(s), %.3f s at %d Hz, %s; peak %.4g Pa%s\n", o.out.c_str(), mix.size(), seconds,
              o.rate_hz, o.format.c_str(), peak, o.normalize ? fmt::format(" (normalized by {:.4g})", gain).c_str() : "");
  std::printf("clatter-synth: %zu impacts from %zu events (%zu on objects not alive then, skipped) rendered in %.3f s\n",
              stats.impacts, scene.events.size(), stats.skipped_inactive, render_s);
  return kExitOk;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"clatter-synth: renders debris sound from Clatter soundbanks and a scene of rigid-body impulses "
               "(serial; no mpirun needed).\nExit codes: 0 done, 1 run-time failure, 2 bad input.",
               "clatter-synth"};
  app.set_version_flag("--version", io::version_text("clatter-synth"));
  Options o;
  app.add_option("-i,--scene", o.scene, "scene (JSON, docs/scene-format.md); with --impulses: the side file of "
                                        "objects, materials and listeners")->required();
  app.add_option("--impulses", o.impulses, "James-lab rigid-body impulse text file (C/P lines)");
  app.add_option("-b,--bank", o.bank, "PAN bank (clatter-bank pan)")->required();
  app.add_option("-o,--out", o.out, "output WAV")->capture_default_str();
  app.add_option("--rate", o.rate_hz, "output sample rate [Hz]")->capture_default_str();
  app.add_option("--format", o.format, "float (32-bit float, pascals) or pcm24")
      ->check(CLI::IsMember({"float", "pcm24"}))
      ->capture_default_str();
  app.add_flag("--normalize", o.normalize, "scale the peak to 0.99 instead of writing pascals");
  app.add_flag("--stems", o.stems, "also write one file per source type (OUT.pan.wav)");
  try {
    app.parse(argc, argv);
  } catch (const CLI::Success& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::fprintf(stderr, "clatter-synth: error: %s (see clatter-synth --help)\n", e.what());
    return kExitInputError;
  }
  try {
    return run(o);
  } catch (const InputError& e) {
    std::fprintf(stderr, "clatter-synth: error: %s\n", e.what());
    remove_registered_temporaries();
    return kExitInputError;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "clatter-synth: error: %s\n", e.what());
    remove_registered_temporaries();
    return kExitFailure;
  }
}
