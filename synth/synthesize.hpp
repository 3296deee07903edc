#pragma once
// One render as a library call: the banks a user names become sound sources, and a scene becomes
// one output per source and listener. clatter-synth (synth_main.cpp) and the Python module
// (python/) both call this, so the same options give the same samples, bit for bit.
#include <memory>
#include <string>
#include <vector>

#include "io/scene.hpp"
#include "io/wav.hpp"
#include "synth/ground_source.hpp"
#include "synth/modal_source.hpp"
#include "synth/render_scene.hpp"
#include "synth/sources.hpp"

namespace clatter::synth {

// Everything clatter-synth's command line sets except where its output goes.
struct SynthOptions {
  std::string pan_bank;                  // -b: PAN bank of proxies (and mesh entries)
  std::vector<std::string> object_pans;  // -P: PAN banks of mesh entries
  std::vector<std::string> modal_banks;  // -m: one per nu class
  std::vector<std::string> object_banks; // -O: objects' own modal models
  std::string ground_bank;               // -g
  ModalOptions modal;
  RenderOptions render;                  // rate_hz, max_sustained_s
  bool modal_sound() const { return !modal_banks.empty() || !object_banks.empty(); }
};

// InputError naming the option (clatter-synth's flag name) for a rate outside [8000, 384000] Hz, a
// negative or NaN limit, or no bank at all.
void check_options(const SynthOptions& options);

// A finished render: the sources (for their counts and voices) and their outputs.
struct Synthesis {
  std::vector<std::unique_ptr<SoundSource>> sources;  // PAN, modal, ground: those with a bank
  PanSource* pan = nullptr;
  ModalSource* modal = nullptr;
  GroundSource* ground = nullptr;
  std::vector<std::vector<std::vector<double>>> stems;  // [source][listener][sample], pascals
  RenderStats stats;
  // Every source summed, per listener (what the WAV holds, before --normalize's gain).
  std::vector<std::vector<double>> mix() const;
};

// Opens the banks (InputError naming a file of the wrong kind) and renders the scene, which
// load_scene read with base_frequencies = options.modal_sound().
Synthesis synthesize(const io::Scene& scene, const SynthOptions& options);

// The largest |sample| of every channel.
double peak_of(const std::vector<std::vector<double>>& channels);

// Peak and RMS over every channel of one source (clatter-synth's summary lines).
struct Level {
  double peak_pa = 0, rms_pa = 0;
};
Level level_of(const std::vector<std::vector<double>>& channels);

// Writes `mix` to `out` and, with stems, each source to OUT.NAME.wav (OUT without its .wav), every
// sample times `gain`; returns the paths written. InputError for pcm24 with a scaled peak beyond
// +-1, before anything is written.
std::vector<std::string> write_outputs(const Synthesis& synthesis, const std::vector<std::vector<double>>& mix,
                                       const std::string& out, int rate_hz, io::SampleFormat format, double gain, bool stems);

}  // namespace clatter::synth
