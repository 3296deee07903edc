// clatter-synth: the serial synthesizer. Soundbanks plus a scene of rigid-body impulses in, WAV
// out (docs/synth.md). One loop over events feeds every sound source (synth/render_scene.cpp).
#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "io/linked_libraries.hpp"
#include "core/cleanup.hpp"
#include "core/errors.hpp"
#include "io/text_file.hpp"
#include "io/wav.hpp"
#include "synth/ground_source.hpp"
#include "synth/load_scene.hpp"
#include "synth/modal_source.hpp"
#include "synth/render_scene.hpp"

using namespace clatter;

namespace {

struct Options {
  std::string scene, impulses, bank, ground_bank, out = "out.wav", format = "float", voices;
  std::vector<std::string> modal_banks, object_banks;
  std::vector<std::string> object_pans;  // -P: PAN banks of mesh entries (clatter-bank pan-object)
  synth::ModalOptions modal;
  int rate_hz = 44100;
  double max_sustained_s = synth::RenderOptions{}.max_sustained_s;
  bool normalize = false, stems = false;
};

// The ground source's counts: impacts rendered, the clamps of eta and elevation, and every skip (docs/synth.md).
void print_ground_summary(const synth::GroundSource& ground, std::size_t listeners) {
  const synth::GroundStats& g = ground.stats();
  const model::GroundMaterial& m = *ground.medium().material;
  std::printf("clatter-synth: ground: %zu impacts on '%s' rendered at %zu listener(s) (%zu pulling away from the ground, "
              "skipped); eta raised to one sample %zu, clamped to the bank's [%.3g, %.3g] %zu below and %zu above; "
              "elevation clamped to [%.3g, %.3g] rad %zu; sustained contacts slower than eta_max, skipped %zu; sound "
              "outside the output, skipped %zu; no series at the grid point, skipped %zu (counts per impact and listener)\n",
              g.impacts, m.name.c_str(), listeners, g.skipped_upward, g.eta_below_sample, m.eta.front(), m.eta.back(),
              g.eta_below_grid, g.eta_above_grid, m.elevation_rad.front(), m.elevation_rad.back(), g.elevation_outside,
              g.sustained_too_slow, g.outside_output, g.no_series);
}

// Peak and RMS of each source over all listeners, and the modal source's counts.
void print_summary(const std::vector<synth::SoundSource*>& sources, const std::vector<std::vector<std::vector<double>>>& stems,
                   const synth::ModalSource* modal, const synth::ModalOptions& options) {
  for (std::size_t s = 0; s < sources.size(); ++s) {
    double peak = 0, energy = 0;
    std::size_t count = 0;
    for (const auto& ch : stems[s])
      for (double v : ch) peak = std::max(peak, std::abs(v)), energy += v * v, ++count;
    std::printf("clatter-synth: %-6s peak %.4g Pa, RMS %.4g Pa\n", sources[s]->name().c_str(), peak,
                std::sqrt(energy / static_cast<double>(std::max<std::size_t>(count, 1))));
  }
  if (!modal) return;
  const synth::ModalStats& m = modal->stats();
  std::printf("clatter-synth: modal: %zu objects, %zu modes rendered (skipped: %zu above the top frequency, %zu below %g Hz, "
              "%zu overdamped); base frequency from the scene %zu, the mesh %zu, the proxy %zu; %zu excitations into %zu "
              "resonators, %.3g mode-samples\n",
              m.objects, m.modes, m.skipped_high, m.skipped_low, options.min_frequency_hz, m.skipped_overdamped, m.from_scene, m.from_mesh, m.from_proxy,
              m.excitations, m.resonators.resonators, static_cast<double>(m.resonators.mode_samples));
  std::printf("clatter-synth: modal: own models (objects below %g Hz, 003 section 5.4): %zu objects ring with their own "
              "model from an object bank, %zu below it ring with their proxy (listed above)\n",
              options.proxy_above_hz, m.own_models, m.own_model_missing);
  std::printf("clatter-synth: modal: energy: %.3g J into the rendered modes, %.3g J radiated (%.3g); worst object %d radiates "
              "%.3g of its modes' energy; the energy rule %s: %zu objects' transfer bounded by their surface, %zu with radiation "
              "damping > 1 %% of their material's (docs/synth.md \"Energy account\")\n",
              m.injected_j, m.radiated_j, m.injected_j > 0 ? m.radiated_j / m.injected_j : 0.0, m.worst_object, m.worst_ratio,
              options.energy_rule ? "on" : "OFF", m.bounded, m.radiation_damped);
  for (const auto& [id, radius_m] : modal->transfer_short_objects())
    std::printf("clatter-synth: modal: note: object %d is silent at a listener closer than %.3g m: its proxy, scaled to its base "
                "frequency, is larger than the object, and its multipoles hold only beyond that (docs/synth.md \"Coverage\")\n",
                id, radius_m);
  if (m.transfer_short)
    std::printf("clatter-synth: modal: %zu impact-listener pairs skipped for a listener inside a scaled proxy's transfer region\n",
                m.transfer_short);
  if (m.objects > 0)
    std::printf("clatter-synth: modal: band: %zu of %zu objects get every mode of their audible band; the smallest share any "
                "object gets is %.0f %% (in octaves from its base frequency; per object in --voices, the short ones in the "
                "coverage list)\n", m.objects - m.band_short, m.objects, 100 * m.min_band_share);
  if (m.band_short)
    std::printf("clatter-synth: modal: warning: for %zu objects the bank's last mode, scaled, lies below the top frequency: "
                "their modes above it are missing (a bank to a higher f_max multiple has them; docs/modal.md)\n",
                m.band_short);
}

// One row per object: how the modal source voiced it and what its modes received and radiated
// (docs/synth.md "Objects with their own models"; analysis/proxy_table.py compares two renders).
void write_voices(const std::string& path, const synth::ModalSource& modal, const io::Scene& scene) {
  std::string text = "object,voiced_by,bank,entry,base_frequency_hz,gamma,modes_rendered,f1_hz,f2_hz,f3_hz,f4_hz,f5_hz,"
                     "impacts,injected_j,radiated_j,band_reach_hz,band_share\n";
  for (std::size_t i = 0; i < scene.objects.size(); ++i) {
    const synth::ModalVoice& v = modal.voice(i);
    const synth::ObjectEnergy& e = modal.energy().at(i);
    std::string f;
    for (std::size_t k = 0; k < 5; ++k)
      f += k < v.omega_rad_s.size() ? fmt::format("{:.6g},", v.omega_rad_s[k] / (2 * 3.14159265358979323846)) : ",";
    text += fmt::format("{},{},{},{},{:.6g},{:.6g},{},{}{},{:.6g},{:.6g},{:.6g},{:.4f}\n", scene.objects[i].id, v.own_model ? "own" : "proxy",
                        v.bank, v.own_model ? v.object_entry->key : std::to_string(v.entry), v.base_frequency_hz, v.gamma,
                        v.modes.size(), f, e.impacts, e.injected_j, e.radiated_j, v.band_reach_hz, v.band_share);
  }
  io::write_text_file(path, text, "voices");
}

int run(const Options& o) {
  const auto t0 = std::chrono::steady_clock::now();
  if (o.rate_hz < 8000 || o.rate_hz > 384000) throw InputError(fmt::format("--rate {}: must be in [8000, 384000] Hz", o.rate_hz));
  if (o.bank.empty() && o.object_pans.empty() && o.modal_banks.empty() && o.object_banks.empty() && o.ground_bank.empty())
    throw InputError("give a PAN bank (-b or -P), a modal bank (-m), an object bank (-O) or a ground bank (-g), or several");
  const bool modal_sound = !o.modal_banks.empty() || !o.object_banks.empty();
  const io::Scene scene = synth::load_scene(o.scene, o.impulses, modal_sound);
  std::vector<std::unique_ptr<synth::SoundSource>> owned;
  synth::ModalSource* modal = nullptr;
  synth::PanSource* pan = nullptr;
  if (!o.bank.empty() || !o.object_pans.empty()) {
    auto p = std::make_unique<synth::PanSource>(o.bank, o.object_pans);
    pan = p.get();
    owned.push_back(std::move(p));
  }
  if (modal_sound) {
    auto m = std::make_unique<synth::ModalSource>(o.modal_banks, o.modal, o.object_banks);
    modal = m.get();
    owned.push_back(std::move(m));
  }
  synth::GroundSource* ground = nullptr;
  if (!o.ground_bank.empty()) {
    auto g = std::make_unique<synth::GroundSource>(o.ground_bank);
    ground = g.get();
    owned.push_back(std::move(g));
  }
  std::vector<synth::SoundSource*> sources;
  for (auto& s : owned) sources.push_back(s.get());
  synth::RenderOptions options;
  options.rate_hz = o.rate_hz;
  options.max_sustained_s = o.max_sustained_s;
  synth::RenderStats stats;
  auto stems = synth::render_scene(scene, sources, options, &stats);
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
      io::write_wav(fmt::format("{}.{}.wav", base, sources[s]->name()), scaled(stems[s]), o.rate_hz, format);
    }
  const double seconds = static_cast<double>(mix.front().size()) / o.rate_hz;
  std::printf("clatter-synth: wrote %s: %zu channel(s), %.3f s at %d Hz, %s; peak %.4g Pa%s\n", o.out.c_str(), mix.size(), seconds,
              o.rate_hz, o.format.c_str(), peak, o.normalize ? fmt::format(" (normalized by {:.4g})", gain).c_str() : "");
  std::printf("clatter-synth: %zu impacts (%zu of them fracture impulses, %zu sustained contacts) from %zu events (%zu on "
              "objects not alive then, %zu sustained contacts longer than %g s, skipped) rendered in %.3f s\n",
              stats.impacts, stats.fracture_impacts, stats.sustained_impacts, scene.events.size(), stats.skipped_inactive,
              stats.skipped_sustained, o.max_sustained_s, render_s);
  if (pan && !o.object_pans.empty())
    std::printf("clatter-synth: pan: %zu of %zu objects sound with their own PAN (-P, their mesh's entry), the others with "
                "proxies\n", pan->own_entries(), scene.objects.size());
  const auto& mc = stats.mesh_contacts;
  if (mc[0] + mc[1] + mc[2] > 0)
    std::printf("clatter-synth: Hertz contacts on objects' own meshes: %zu on smooth or flat surface, %zu on sharp edges, "
                "%zu on corners (docs/synth.md \"Contact from the object's surface\")\n",
                mc[0], mc[1], mc[2]);
  for (std::size_t s = 0; s < sources.size(); ++s) {
    const auto& lines = stats.coverage[s];
    if (lines.empty()) {
      std::printf("clatter-synth: %s: every object within the bank's coverage\n", sources[s]->name().c_str());
      continue;
    }
    std::printf("clatter-synth: %s: note: %zu of %zu objects outside the bank's coverage (docs/synth.md \"Coverage\"):\n",
                sources[s]->name().c_str(), lines.size(), scene.objects.size());
    for (const auto& line : lines) std::printf("clatter-synth: %s:   %s\n", sources[s]->name().c_str(), line.c_str());
  }
  print_summary(sources, stems, modal, o.modal);
  if (!o.voices.empty()) {
    if (!modal) throw InputError("--voices: needs modal sound (-m or -O)");
    write_voices(o.voices, *modal, scene);
    std::printf("clatter-synth: wrote %s: each object's modal voice\n", o.voices.c_str());
  }
  if (ground) print_ground_summary(*ground, scene.listeners_m.size());
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
  app.add_option("-b,--bank", o.bank, "PAN bank (clatter-bank pan): acceleration noise");
  app.add_option("-P,--object-pan", o.object_pans, "PAN bank of meshes (clatter-bank pan-object), repeatable: objects "
                                                  "whose mesh one holds sound with their own acceleration noise, the others "
                                                  "with -b's proxies");
  app.add_option("-m,--modal-bank", o.modal_banks, "modal bank (clatter-bank modal), repeatable: one per nu class; each "
                                                   "object rings with the bank nearest its material's nu");
  app.add_option("-O,--object-bank", o.object_banks, "object bank (clatter-bank object), repeatable: objects whose base "
                                                    "frequency is below --proxy-above-hz ring with their own model when one "
                                                    "holds their mesh in their material");
  app.add_option("--proxy-above-hz", o.modal.proxy_above_hz, "omega_proxy / 2 pi of 003 section 5.4: objects with a lower base "
                                                             "frequency should have their own model (-O)")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  app.add_option("-g,--ground-bank", o.ground_bank, "ground bank (clatter-bank ground): the sound of the ground itself at "
                                                    "object-ground impacts; its material named by the scene's ground_material");
  app.add_option("--max-mode-hz", o.modal.max_frequency_hz, "modes above this after scaling are skipped (and above 0.45 of "
                                                            "the rate)")->capture_default_str()->check(CLI::PositiveNumber);
  app.add_option("--nu-tolerance", o.modal.poisson_tolerance, "a modal bank serves materials whose nu is within this of its "
                                                              "own")->capture_default_str()->check(CLI::NonNegativeNumber);
  app.add_option("-o,--out", o.out, "output WAV")->capture_default_str();
  app.add_option("--rate", o.rate_hz, "output sample rate [Hz]")->capture_default_str();
  app.add_option("--max-sustained-s", o.max_sustained_s, "sustained contacts (resting, sliding) longer than this are not "
                                                          "rendered (docs/synth.md)")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  app.add_option("--format", o.format, "float (32-bit float, pascals) or pcm24")
      ->check(CLI::IsMember({"float", "pcm24"}))
      ->capture_default_str();
  app.add_flag("--normalize", o.normalize, "scale the peak to 0.99 instead of writing pascals");
  app.add_flag("--no-energy-rule", [&o](std::int64_t) { o.modal.energy_rule = false; },
               "render modal sound without the energy rule (docs/synth.md \"Energy account\"), to measure what it changes");
  app.add_option("--voices", o.voices, "write each object's modal voice as CSV: own model or proxy, scale, its first "
                                        "rendered frequencies, impacts, energy into its modes and radiated");
  app.add_flag("--stems", o.stems, "also write one file per source type (OUT.pan.wav, OUT.modal.wav, OUT.ground.wav)");
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
