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
#include "core/stage_log.hpp"
#include "io/text_file.hpp"
#include "io/wav.hpp"
#include "synth/ground_source.hpp"
#include "synth/load_scene.hpp"
#include "synth/modal_source.hpp"
#include "synth/render_scene.hpp"
#include "synth/synthesize.hpp"

using namespace clatter;

namespace {

struct Options {
  std::string scene, impulses, out = "out.wav", format = "float", voices;
  synth::SynthOptions synth;  // the banks and every option of the render
  bool normalize = false, stems = false, log_view = false;
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
    const synth::Level level = synth::level_of(stems[s]);
    std::printf("clatter-synth: %-6s peak %.4g Pa, RMS %.4g Pa\n", sources[s]->name().c_str(), level.peak_pa, level.rms_pa);
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
  Stage total("total");
  const auto t0 = std::chrono::steady_clock::now();
  synth::check_options(o.synth);
  if (!o.voices.empty() && !o.synth.modal_sound()) throw InputError("--voices: needs modal sound (-m or -O)");
  const io::Scene scene = synth::load_scene(o.scene, o.impulses, o.synth.modal_sound());
  const synth::Synthesis r = synth::synthesize(scene, o.synth);
  const double render_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const auto& stems = r.stems;
  const auto& stats = r.stats;
  std::vector<synth::SoundSource*> sources;
  for (const auto& s : r.sources) sources.push_back(s.get());
  const auto mix = r.mix();  // every source at every listener
  const double peak = synth::peak_of(mix);
  double gain = 1.0;
  if (o.normalize && peak > 0) gain = 0.99 / peak;
  const auto format = o.format == "pcm24" ? io::SampleFormat::pcm24 : io::SampleFormat::float32;
  synth::write_outputs(r, mix, o.out, o.synth.render.rate_hz, format, gain, o.stems);
  const double seconds = static_cast<double>(mix.front().size()) / o.synth.render.rate_hz;
  std::printf("clatter-synth: wrote %s: %zu channel(s), %.3f s at %d Hz, %s; peak %.4g Pa%s\n", o.out.c_str(), mix.size(), seconds,
              o.synth.render.rate_hz, o.format.c_str(), peak, o.normalize ? fmt::format(" (normalized by {:.4g})", gain).c_str() : "");
  std::printf("clatter-synth: %zu impacts (%zu of them fracture impulses, %zu sustained contacts) from %zu events (%zu on "
              "objects not alive then, %zu sustained contacts longer than %g s, skipped) rendered in %.3f s\n",
              stats.impacts, stats.fracture_impacts, stats.sustained_impacts, scene.events.size(), stats.skipped_inactive,
              stats.skipped_sustained, o.synth.render.max_sustained_s, render_s);
  if (r.pan && !o.synth.object_pans.empty())
    std::printf("clatter-synth: pan: %zu of %zu objects sound with their own PAN (-P, their mesh's entry), the others with "
                "proxies\n", r.pan->own_entries(), scene.objects.size());
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
  print_summary(sources, stems, r.modal, o.synth.modal);
  if (!o.voices.empty()) {
    write_voices(o.voices, *r.modal, scene);
    std::printf("clatter-synth: wrote %s: each object's modal voice\n", o.voices.c_str());
  }
  if (r.ground) print_ground_summary(*r.ground, scene.listeners_m.size());
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
  app.add_option("-b,--bank", o.synth.pan_bank, "PAN bank (clatter-bank pan): acceleration noise");
  app.add_option("-P,--object-pan", o.synth.object_pans, "PAN bank of meshes (clatter-bank pan-object), repeatable: objects "
                                                  "whose mesh one holds sound with their own acceleration noise, the others "
                                                  "with -b's proxies");
  app.add_option("-m,--modal-bank", o.synth.modal_banks, "modal bank (clatter-bank modal), repeatable: one per nu class; each "
                                                   "object rings with the bank nearest its material's nu");
  app.add_option("-O,--object-bank", o.synth.object_banks, "object bank (clatter-bank object), repeatable: objects whose base "
                                                    "frequency is below --proxy-above-hz ring with their own model when one "
                                                    "holds their mesh in their material");
  app.add_option("--proxy-above-hz", o.synth.modal.proxy_above_hz, "omega_proxy / 2 pi of 003 section 5.4: objects with a lower base "
                                                             "frequency should have their own model (-O)")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  app.add_option("-g,--ground-bank", o.synth.ground_bank, "ground bank (clatter-bank ground): the sound of the ground itself at "
                                                    "object-ground impacts; its material named by the scene's ground_material");
  app.add_option("--max-mode-hz", o.synth.modal.max_frequency_hz, "modes above this after scaling are skipped (and above 0.45 of "
                                                            "the rate)")->capture_default_str()->check(CLI::PositiveNumber);
  app.add_option("--nu-tolerance", o.synth.modal.poisson_tolerance, "a modal bank serves materials whose nu is within this of its "
                                                              "own")->capture_default_str()->check(CLI::NonNegativeNumber);
  app.add_option("-o,--out", o.out, "output WAV")->capture_default_str();
  app.add_option("--rate", o.synth.render.rate_hz, "output sample rate [Hz]")->capture_default_str();
  app.add_option("--max-sustained-s", o.synth.render.max_sustained_s, "sustained contacts (resting, sliding) longer than this are not "
                                                          "rendered (docs/synth.md)")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  app.add_option("--format", o.format, "float (32-bit float, pascals) or pcm24")
      ->check(CLI::IsMember({"float", "pcm24"}))
      ->capture_default_str();
  app.add_flag("--normalize", o.normalize, "scale the peak to 0.99 instead of writing pascals");
  app.add_flag("--no-energy-rule", [&o](std::int64_t) { o.synth.modal.energy_rule = false; },
               "render modal sound without the energy rule (docs/synth.md \"Energy account\"), to measure what it changes");
  app.add_option("--voices", o.voices, "write each object's modal voice as CSV: own model or proxy, scale, its first "
                                        "rendered frequencies, impacts, energy into its modes and radiated");
  app.add_flag("--log-view", o.log_view, "print the stage-timing table at the end (scene, banks, render)");
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
    const int status = run(o);
    if (o.log_view) std::fputs(format_stage_table(merge_stage_entries({stage_log().entries()}), 1).c_str(), stdout);
    return status;
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
