// Rendering from Python (docs/python.md "Rendering"): synth::synthesize, the call clatter-synth
// makes, on a scene read by io/; the outputs as numpy arrays and the summary clatter-synth prints
// as dicts. The GIL is released while the scene renders.
#include <fmt/format.h>
#include <pybind11/stl.h>

#include <map>
#include <memory>

#include "core/errors.hpp"
#include "core/stage_log.hpp"
#include "python/arrays.hpp"
#include "python/bindings.hpp"
#include "synth/synthesize.hpp"

namespace clatter::python {
namespace {

struct PyRender {
  synth::Synthesis synthesis;
  std::vector<std::vector<double>> mix;  // every source summed, before the gain
  double gain = 1, peak_pa = 0;
  int rate_hz = 0;
  double max_sustained_s = 0;
  std::size_t events = 0, objects = 0, listeners = 0;
  std::vector<std::string> object_pans;
  std::map<std::string, double> stages_s;  // this render's share of the stage log (synthesize's stages)
};

std::map<std::string, std::pair<long long, double>> stage_seconds() {
  std::map<std::string, std::pair<long long, double>> out;
  for (const auto& e : stage_log().entries()) out[e.path] = {e.count, e.seconds};
  return out;
}

// Channels [listener][sample] times gain as one (listeners, samples) array.
py::array channels_array(const std::vector<std::vector<double>>& channels, double gain) {
  const auto n = channels.empty() ? py::ssize_t{0} : static_cast<py::ssize_t>(channels.front().size());
  py::array_t<double> out({static_cast<py::ssize_t>(channels.size()), n});
  for (std::size_t l = 0; l < channels.size(); ++l) {
    double* row = out.mutable_data(static_cast<py::ssize_t>(l), 0);
    for (std::size_t k = 0; k < channels[l].size(); ++k) row[k] = channels[l][k] * gain;
  }
  return out;
}

py::dict modal_summary(const synth::ModalSource& modal) {
  const synth::ModalStats& m = modal.stats();
  py::dict d;
  d["objects"] = m.objects, d["modes"] = m.modes, d["skipped_high"] = m.skipped_high, d["skipped_low"] = m.skipped_low;
  d["skipped_overdamped"] = m.skipped_overdamped;
  d["base_frequency_from"] = py::dict(py::arg("scene") = m.from_scene, py::arg("mesh") = m.from_mesh, py::arg("proxy") = m.from_proxy);
  d["own_models"] = m.own_models, d["own_model_missing"] = m.own_model_missing;
  d["band_short"] = m.band_short, d["min_band_share"] = m.min_band_share, d["transfer_short"] = m.transfer_short;
  d["transfer_short_objects"] = modal.transfer_short_objects();
  d["excitations"] = m.excitations, d["silent_modes"] = m.silent_modes;
  d["mode_samples"] = m.resonators.mode_samples;
  d["injected_j"] = m.injected_j, d["radiated_j"] = m.radiated_j, d["worst_object"] = m.worst_object;
  d["worst_ratio"] = m.worst_ratio, d["bounded"] = m.bounded, d["radiation_damped"] = m.radiation_damped;
  return d;
}

py::dict ground_summary(const synth::GroundSource& ground) {
  const synth::GroundStats& g = ground.stats();
  py::dict d;
  d["material"] = ground.medium().material->name;
  d["impacts"] = g.impacts, d["skipped_upward"] = g.skipped_upward, d["eta_below_sample"] = g.eta_below_sample;
  d["eta_below_grid"] = g.eta_below_grid, d["eta_above_grid"] = g.eta_above_grid;
  d["elevation_outside"] = g.elevation_outside, d["sustained_too_slow"] = g.sustained_too_slow;
  d["outside_output"] = g.outside_output, d["no_series"] = g.no_series;
  return d;
}

// What clatter-synth prints after a render, as one dict (its keys: docs/python.md).
py::dict summary(const PyRender& r) {
  const synth::Synthesis& s = r.synthesis;
  py::dict d;
  d["rate_hz"] = r.rate_hz, d["listeners"] = r.listeners, d["objects"] = r.objects, d["events"] = r.events;
  d["peak_pa"] = r.peak_pa, d["gain"] = r.gain;
  d["impacts"] = s.stats.impacts, d["fracture_impacts"] = s.stats.fracture_impacts;
  d["sustained_impacts"] = s.stats.sustained_impacts, d["skipped_inactive"] = s.stats.skipped_inactive;
  d["skipped_sustained"] = s.stats.skipped_sustained, d["max_sustained_s"] = r.max_sustained_s;
  const auto& mc = s.stats.mesh_contacts;
  d["mesh_contacts"] = py::dict(py::arg("smooth") = mc[0], py::arg("edge") = mc[1], py::arg("corner") = mc[2]);
  py::dict levels;
  for (std::size_t k = 0; k < s.sources.size(); ++k) {
    const synth::Level level = synth::level_of(s.stems[k]);
    levels[py::str(s.sources[k]->name())] = py::dict(py::arg("peak_pa") = level.peak_pa, py::arg("rms_pa") = level.rms_pa);
  }
  d["levels"] = levels;
  if (s.pan) d["pan"] = py::dict(py::arg("own_entries") = r.object_pans.empty() ? 0 : s.pan->own_entries());
  if (s.modal) d["modal"] = modal_summary(*s.modal);
  if (s.ground) d["ground"] = ground_summary(*s.ground);
  return d;
}

// One dict per object: how the modal source voiced it (clatter-synth --voices' columns).
py::list voices(const PyRender& r, const io::Scene& scene) {
  py::list out;
  const synth::ModalSource* modal = r.synthesis.modal;
  if (!modal) return out;
  for (std::size_t i = 0; i < scene.objects.size(); ++i) {
    const synth::ModalVoice& v = modal->voice(i);
    const synth::ObjectEnergy& e = modal->energy().at(i);
    py::array_t<double> f(static_cast<py::ssize_t>(v.omega_rad_s.size()));
    for (std::size_t k = 0; k < v.omega_rad_s.size(); ++k) f.mutable_at(static_cast<py::ssize_t>(k)) = v.omega_rad_s[k] / (2 * 3.14159265358979323846);
    py::dict d;
    d["object"] = scene.objects[i].id, d["voiced_by"] = v.own_model ? "own" : "proxy", d["bank"] = v.bank;
    d["entry"] = v.own_model ? py::object(py::str(v.object_entry->key)) : py::object(py::int_(v.entry));
    d["base_frequency_hz"] = v.base_frequency_hz, d["base_frequency_from"] = v.base_frequency_from, d["gamma"] = v.gamma;
    d["frequencies_hz"] = f, d["impacts"] = e.impacts, d["injected_j"] = e.injected_j, d["radiated_j"] = e.radiated_j;
    d["band_reach_hz"] = v.band_reach_hz, d["band_share"] = v.band_share;
    out.append(d);
  }
  return out;
}

std::shared_ptr<PyRender> render(PyScene& scene, const synth::SynthOptions& options, bool normalize) {
  synth::check_options(options);
  auto r = std::make_shared<PyRender>();
  exclusive([&] {
    const io::Scene& ready = scene.for_render(options.modal_sound());
    const auto before = stage_seconds();
    r->synthesis = synth::synthesize(ready, options);
    r->mix = r->synthesis.mix();
    for (const auto& [path, now] : stage_seconds()) {
      const auto it = before.find(path);
      const auto was = it == before.end() ? std::pair<long long, double>{0, 0.0} : it->second;
      if (now.first > was.first) r->stages_s[path] = now.second - was.second;  // the stages this render entered
    }
    r->events = ready.events.size(), r->objects = ready.objects.size(), r->listeners = ready.listeners_m.size();
    return 0;
  });
  r->peak_pa = synth::peak_of(r->mix);
  if (normalize && r->peak_pa > 0) r->gain = 0.99 / r->peak_pa;
  r->rate_hz = options.render.rate_hz;
  r->max_sustained_s = options.render.max_sustained_s;
  r->object_pans = options.object_pans;
  return r;
}

}  // namespace

void bind_synth(py::module_& m) {
  py::class_<synth::SynthOptions>(m, "SynthOptions", "every option of clatter-synth's render (see clatter.render)")
      .def(py::init<>())
      .def_readwrite("pan_bank", &synth::SynthOptions::pan_bank)
      .def_readwrite("object_pans", &synth::SynthOptions::object_pans)
      .def_readwrite("modal_banks", &synth::SynthOptions::modal_banks)
      .def_readwrite("object_banks", &synth::SynthOptions::object_banks)
      .def_readwrite("ground_bank", &synth::SynthOptions::ground_bank)
      .def_property("rate_hz", [](const synth::SynthOptions& o) { return o.render.rate_hz; },
                    [](synth::SynthOptions& o, int v) { o.render.rate_hz = v; })
      .def_property("max_sustained_s", [](const synth::SynthOptions& o) { return o.render.max_sustained_s; },
                    [](synth::SynthOptions& o, double v) { o.render.max_sustained_s = v; })
      .def_property("proxy_above_hz", [](const synth::SynthOptions& o) { return o.modal.proxy_above_hz; },
                    [](synth::SynthOptions& o, double v) { o.modal.proxy_above_hz = v; })
      .def_property("max_mode_hz", [](const synth::SynthOptions& o) { return o.modal.max_frequency_hz; },
                    [](synth::SynthOptions& o, double v) { o.modal.max_frequency_hz = v; })
      .def_property("nu_tolerance", [](const synth::SynthOptions& o) { return o.modal.poisson_tolerance; },
                    [](synth::SynthOptions& o, double v) { o.modal.poisson_tolerance = v; })
      .def_property("energy_rule", [](const synth::SynthOptions& o) { return o.modal.energy_rule; },
                    [](synth::SynthOptions& o, bool v) { o.modal.energy_rule = v; });
  py::class_<PyRender, std::shared_ptr<PyRender>>(m, "RenderData", "a finished render")
      .def_readonly("rate_hz", &PyRender::rate_hz)
      .def_readonly("gain", &PyRender::gain)
      .def_readonly("peak_pa", &PyRender::peak_pa)
      .def_readonly("stages_s", &PyRender::stages_s)
      .def_property_readonly("sources", [](const PyRender& r) {
        std::vector<std::string> names;
        for (const auto& s : r.synthesis.sources) names.push_back(s->name());
        return names;
      })
      .def("mix", [](const PyRender& r) { return channels_array(r.mix, r.gain); })
      .def("stem", [](const PyRender& r, std::size_t source) {
             if (source >= r.synthesis.stems.size()) throw py::index_error(fmt::format("source {}: the render has {}", source, r.synthesis.stems.size()));
             return channels_array(r.synthesis.stems[source], r.gain);
           }, py::arg("source"))
      .def_property_readonly("coverage", [](const PyRender& r) {
        py::dict d;
        for (std::size_t k = 0; k < r.synthesis.sources.size(); ++k) d[py::str(r.synthesis.sources[k]->name())] = r.synthesis.stats.coverage[k];
        return d;
      })
      .def("summary", &summary)
      .def("voices", [](const PyRender& r, const PyScene& scene) { return voices(r, scene.scene); }, py::arg("scene"))
      .def("write_wav", [](const PyRender& r, const std::string& path, const std::string& format, bool stems) {
             if (format != "float" && format != "pcm24") throw InputError(fmt::format("format: '{}': expected 'float' or 'pcm24'", format));
             return exclusive([&] {
               return synth::write_outputs(r.synthesis, r.mix, path, r.rate_hz,
                                           format == "pcm24" ? io::SampleFormat::pcm24 : io::SampleFormat::float32, r.gain, stems);
             });
           }, py::arg("path"), py::arg("format") = "float", py::arg("stems") = false);
  m.def("stage_table", [] { return exclusive([] { return format_stage_table(merge_stage_entries({stage_log().entries()}), 1); }); },
        "the stage-timing table of every load_scene and render of this process so far (clatter-synth --log-view's)");
  m.def("_render", &render, py::arg("scene"), py::arg("options"), py::arg("normalize"));
}

}  // namespace clatter::python
