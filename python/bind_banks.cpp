// The four bank files as Python objects (docs/python.md "Banks"): each read and checked by its
// io/ reader, as clatter-synth reads it; headers as dicts, entries as objects whose arrays are
// read-only numpy views of the bank's memory; `probe` as clatter-bank's, on many points at once.
#include <fmt/format.h>
#include <pybind11/stl.h>

#include <cmath>
#include <complex>
#include <memory>

#include "core/errors.hpp"
#include "io/ground_bank.hpp"
#include "io/h5.hpp"
#include "io/modal_bank.hpp"
#include "io/object_bank.hpp"
#include "io/pan_bank.hpp"
#include "kernels/pan/field.hpp"
#include "kernels/transfer/multipole.hpp"
#include "python/arrays.hpp"
#include "python/bindings.hpp"

namespace clatter::python {
namespace {

py::dict material_dict(const model::Material& m) {
  py::dict d;
  d["name"] = m.name;
  d["rho_kg_m3"] = m.rho_kg_m3;
  d["youngs_pa"] = m.youngs_pa;
  d["poisson"] = m.poisson;
  if (m.damping) d["rayleigh_alpha_1_s"] = m.damping->alpha_1_s, d["rayleigh_beta_s"] = m.damping->beta_s;
  if (m.fracture_energy_j_m2) d["fracture_energy_j_m2"] = *m.fracture_energy_j_m2;
  if (m.tensile_strength_pa) d["tensile_strength_pa"] = *m.tensile_strength_pa;
  d["source"] = m.source;
  return d;
}

py::dict sweep_dict(const model::SweepStatus& s) {
  py::dict d;
  d["sweep_id"] = s.sweep_id;
  d["tasks_total"] = s.tasks_total;
  d["failed"] = s.failed;
  d["missing"] = s.missing;
  d["complete"] = s.complete();
  return d;
}

py::dict transfer_settings_dict(const model::TransferSettings& t) {
  py::dict d;
  d["method"] = t.method;
  d["sound_speed_m_s"] = t.sound_speed_m_s;
  d["air_density_kg_m3"] = t.air_density_kg_m3;
  d["points_per_source"] = t.points_per_source;
  d["sources_per_wavelength"] = t.sources_per_wavelength;
  d["residual_target"] = t.residual_target;
  d["tail_tolerance"] = t.tail_tolerance;
  return d;
}

py::dict solve_settings_dict(const model::ModalSolveSettings& s) {
  py::dict d;
  d["f_max_multiple"] = s.f_max_multiple;
  d["cluster_gap"] = s.cluster_gap;
  d["degenerate_gap"] = s.degenerate_gap;
  d["tolerance"] = s.tolerance;
  d["residual_limit"] = s.residual_limit;
  return d;
}

// |p| of every mode of `entry` (scaled by `scale`, 003 eq. 9) at each point: (points, modes).
py::array modal_probe(const model::ModalEntry& e, const py::handle& points, double scale, double valid_from_m) {
  const auto x = points_arg(points, "points");
  for (std::size_t p = 0; p < x.size(); ++p) {
    const double r = std::hypot(x[p][0], x[p][1], x[p][2]);
    if (!(r >= valid_from_m))
      throw InputError(fmt::format("points[{}]: ({}, {}, {}) is {:.4g} m from the centre; the transfer holds from {:.4g} m", p,
                                   x[p][0], x[p][1], x[p][2], r, valid_from_m));
  }
  py::array_t<double> out({static_cast<py::ssize_t>(x.size()), static_cast<py::ssize_t>(e.modes())});
  auto o = out.mutable_unchecked<2>();
  for (std::size_t i = 0; i < e.modes(); ++i) {
    const auto m = kernels::transfer::scaled(kernels::transfer::stored_multipole(e.transfer, i), scale);
    for (std::size_t p = 0; p < x.size(); ++p)
      o(static_cast<py::ssize_t>(p), static_cast<py::ssize_t>(i)) = std::abs(m.pressure(Eigen::Vector3d(x[p][0], x[p][1], x[p][2])));
  }
  return out;
}

void bind_modal_entry(py::module_& m) {
  py::class_<model::ModalTransfer>(m, "ModalTransfer", "every mode's multipole expansion (docs/transfer.md)")
      .def_property_readonly("wavenumber_rad_m", [](py::object s) { return view(s.cast<const model::ModalTransfer&>().wavenumber_rad_m, s); })
      .def_property_readonly("order", [](py::object s) { return view(s.cast<const model::ModalTransfer&>().order, s); })
      .def("coefficients", [](py::object s, std::size_t mode) {
             const auto& t = s.cast<const model::ModalTransfer&>();
             if (mode >= t.order.size()) throw InputError(fmt::format("mode: {} is not in 0-{}", mode, t.order.size() - 1));
             const auto n = static_cast<py::ssize_t>((t.order[mode] + 1) * (t.order[mode] + 1));
             // (re, im) pairs are laid out as numpy's complex128
             return view(reinterpret_cast<const std::complex<double>*>(t.coefficients.data() + 2 * t.offset(mode)), {n}, s);
           }, py::arg("mode"), "M_n^m [Pa] of one mode at index n^2 + n + m, complex (a view)")
      .def_property_readonly("boundary_residual", [](py::object s) { return view(s.cast<const model::ModalTransfer&>().boundary_residual, s); })
      .def_property_readonly("normal_fraction", [](py::object s) { return view(s.cast<const model::ModalTransfer&>().normal_fraction, s); });
  py::class_<model::ModalEntry>(m, "ModalEntry", "one ellipsoid (or object) of a modal bank: its modes on its surface")
      .def_readonly("sample", &model::ModalEntry::sample)
      .def_property_readonly("axes_m", [](const model::ModalEntry& e) { return e.axes_m; })
      .def_property_readonly("modes", &model::ModalEntry::modes)
      .def_property_readonly("frequencies_hz", [](py::object s) { return view(s.cast<const model::ModalEntry&>().frequencies_hz, s); })
      .def_property_readonly("damping_ratios", [](py::object s) { return view(s.cast<const model::ModalEntry&>().damping_ratios, s); })
      .def_property_readonly("cluster", [](py::object s) { return view(s.cast<const model::ModalEntry&>().cluster, s); })
      .def_property_readonly("multiplet", [](py::object s) { return view(s.cast<const model::ModalEntry&>().multiplet, s); })
      .def_property_readonly("symmetry_order", [](py::object s) { return view(s.cast<const model::ModalEntry&>().symmetry_order, s); })
      .def_property_readonly("relative_residuals", [](py::object s) { return view(s.cast<const model::ModalEntry&>().relative_residuals, s); })
      .def_property_readonly("surface_nodes_m", [](py::object s) { return view(s.cast<const model::ModalEntry&>().surface_nodes_m, s); })
      .def_property_readonly("surface_faces", [](py::object s) { return view(s.cast<const model::ModalEntry&>().surface_faces, s); })
      .def_property_readonly("shapes", [](py::object s) {
        const auto& e = s.cast<const model::ModalEntry&>();
        return view(e.shapes.data(), {static_cast<py::ssize_t>(e.modes()), static_cast<py::ssize_t>(e.surface_nodes_m.size()), 3}, s);
      }, "(modes, surface nodes, 3): mass-normalized displacement [kg^-1/2]")
      .def_readonly("transfer", &model::ModalEntry::transfer, py::return_value_policy::reference_internal)
      .def_property_readonly("band", [](const model::ModalEntry& e) {
        return py::dict(py::arg("f_max_hz") = e.band.f_max_hz, py::arg("mesh_error") = e.band.mesh_error,
                        py::arg("keep_to_hz") = e.band.keep_to_hz);
      })
      .def_property_readonly("symmetry", [](const model::ModalEntry& e) { return e.symmetry.kind; });
}

template <class Bank>
struct BankFile {
  std::string path;
  Bank bank;
};
using PanFile = BankFile<model::PanBank>;
using ModalFile = BankFile<model::ModalBank>;
using ObjectFile = BankFile<model::ObjectBank>;
using GroundFile = BankFile<model::GroundBank>;

template <class File>
const auto& entry_at(const File& f, const auto& entries, long index) {
  const auto n = static_cast<long>(entries.size());
  if (index < -n || index >= n) throw py::index_error(fmt::format("entry {}: {} holds {} entries", index, f.path, n));
  return entries[static_cast<std::size_t>(index < 0 ? index + n : index)];
}

py::dict pan_header(const model::PanBankHeader& h, py::handle owner) {
  py::dict d;
  d["c_m_s"] = h.c_m_s, d["rho_kg_m3"] = h.rho_kg_m3, d["h_s"] = h.h_s, d["dt_s"] = h.dt_s;
  d["t_first_s"] = h.t_first_s, d["epsilon"] = h.epsilon, d["a_m"] = h.a_m, d["length"] = h.length;
  d["radii_m"] = view(h.radii_m, owner);
  d["divisions"] = h.divisions, d["max_levels"] = h.max_levels, d["lattice"] = h.lattice();
  return d;
}

// (n, 3) unit vectors of a field's direction set: lattice point (a, b) is (a, b, L - a - b) / |.|.
py::array directions_xyz(const model::PanDirections& d, std::int32_t lattice) {
  py::array_t<double> out({static_cast<py::ssize_t>(d.vertices.size()), py::ssize_t{3}});
  auto o = out.mutable_unchecked<2>();
  for (std::size_t i = 0; i < d.vertices.size(); ++i) {
    const double x = d.vertices[i].a, y = d.vertices[i].b, z = lattice - x - y, r = std::sqrt(x * x + y * y + z * z);
    const auto k = static_cast<py::ssize_t>(i);
    o(k, 0) = x / r, o(k, 1) = y / r, o(k, 2) = z / r;
  }
  return out;
}

// p_i^(scale h)(x, t) of one field of one entry at each point, as `clatter-bank probe` gives one.
py::dict pan_probe(const PanFile& f, long entry, int field, const py::handle& points, double scale, double rate_hz,
                   const std::string& interpolation) {
  const auto& p = entry_at(f, f.bank.proxies, entry);
  if (field < 1 || field > 6) throw InputError(fmt::format("field: {} is not in 1-6", field));
  if (!p.solved(field)) throw InputError(fmt::format("field: {} was not solved for entry {} of {}", field, entry, f.path));
  if (!(finite_arg(scale, "scale") > 0)) throw InputError(fmt::format("scale: {}: must be > 0", scale));
  if (!(finite_arg(rate_hz, "rate_hz") >= 0)) throw InputError(fmt::format("rate_hz: {}: must be >= 0 (0: the bank's own rate)", rate_hz));
  if (interpolation != "quadratic" && interpolation != "linear")
    throw InputError(fmt::format("interpolation: '{}': expected 'quadratic' or 'linear'", interpolation));
  const auto x = points_arg(points, "points");
  const double a = f.bank.header.a_m * scale;
  std::vector<kernels::pan::Series> series;
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double r = std::hypot(x[i][0], x[i][1], x[i][2]);
    if (!(r > a))
      throw InputError(fmt::format("points[{}]: |x| = {} m is inside the entry's bounding sphere (radius A scale = {} m)", i, r, a));
    series.push_back(kernels::pan::evaluate({&f.bank.header, &p, field}, x[i], scale, rate_hz,
                                            interpolation == "linear" ? kernels::pan::Interpolation::linear
                                                                      : kernels::pan::Interpolation::quadratic));
  }
  const auto n = series.empty() ? py::ssize_t{0} : static_cast<py::ssize_t>(series.front().p.size());
  py::array_t<double> p_out({static_cast<py::ssize_t>(series.size()), n}), t0({static_cast<py::ssize_t>(series.size())});
  for (std::size_t i = 0; i < series.size(); ++i) {
    std::copy(series[i].p.begin(), series[i].p.end(), p_out.mutable_data(static_cast<py::ssize_t>(i), 0));
    t0.mutable_at(static_cast<py::ssize_t>(i)) = series[i].t0_s;
  }
  return py::dict(py::arg("t0_s") = t0, py::arg("dt_s") = series.empty() ? 0.0 : series.front().dt_s, py::arg("p") = p_out);
}

void bind_pan(py::module_& m) {
  py::class_<model::PanField>(m, "PanField", "one field of one entry: its direction set and sparse wavelet terms")
      .def_property_readonly("solved", &model::PanField::solved)
      .def_property_readonly("lattice_points", [](py::object s) {
        const auto& v = s.cast<const model::PanField&>().directions.vertices;
        static_assert(sizeof(model::LatticePoint) == 2 * sizeof(std::int32_t));
        return view(reinterpret_cast<const std::int32_t*>(v.data()), {static_cast<py::ssize_t>(v.size()), 2}, s);
      }, "(directions, 2) int32: lattice point (a, b) of each direction")
      .def_property_readonly("elements", [](py::object s) { return view(s.cast<const model::PanField&>().directions.elements, s); })
      .def_property_readonly("first_child", [](py::object s) { return view(s.cast<const model::PanField&>().directions.first_child, s); })
      .def("terms", [](py::object s, std::size_t vertex) {
             const auto& f = s.cast<const model::PanField&>();
             if (vertex >= f.terms.size()) throw py::index_error(fmt::format("vertex {}: the field has {} directions", vertex, f.terms.size()));
             const auto& t = f.terms[vertex];
             const auto cols = t.index.empty() ? py::ssize_t{0} : static_cast<py::ssize_t>(t.value.size() / t.index.size());
             return py::make_tuple(view(t.index, s), view_rows(t.value, cols, s));
           }, py::arg("vertex"), "(index, values): kept wavelet coefficients j and per j the far field F^j and residuals D_i^j");
  py::class_<model::PanProxy>(m, "PanEntry", "one entry of a PAN bank: a proxy ellipsoid (A, B, C) or a normalized mesh")
      .def_readonly("b_m", &model::PanProxy::b_m)
      .def_readonly("c_m", &model::PanProxy::c_m)
      .def_property_readonly("is_mesh", &model::PanProxy::is_mesh)
      .def_property_readonly("mesh_key", [](const model::PanProxy& p) { return p.mesh.key; })
      .def_property_readonly("mesh_scale", [](const model::PanProxy& p) { return p.mesh.scale; })
      .def_property_readonly("octants", &model::PanProxy::octants)
      .def("solved", [](const model::PanProxy& p, int field) {
        if (field < 1 || field > 6) throw InputError(fmt::format("field: {} is not in 1-6", field));
        return p.solved(field);
      }, py::arg("field"))
      .def("field", [](const model::PanProxy& p, int field, int octant) -> const model::PanField& {
             if (field < 1 || field > 6) throw InputError(fmt::format("field: {} is not in 1-6", field));
             if (octant < 0 || octant >= p.octants()) throw InputError(fmt::format("octant: {} is not in 0-{}", octant, p.octants() - 1));
             return p.field(field, octant);
           }, py::arg("field"), py::arg("octant") = 0, py::return_value_policy::reference_internal)
      .def("held_out", [](py::object s, int field) {
        const auto& p = s.cast<const model::PanProxy&>();
        if (field < 1 || field > 6) throw InputError(fmt::format("field: {} is not in 1-6", field));
        const auto& h = p.held_out[static_cast<std::size_t>(field - 1)];
        return py::dict(py::arg("points_m") = view(h.points_m, s), py::arg("error") = view(h.error, s), py::arg("raw_l2") = view(h.raw_l2, s));
      }, py::arg("field"), "the merge's held-out check of one field: points, relative L2 error, raw L2");
  py::class_<PanFile, std::shared_ptr<PanFile>>(m, "PanBank", "a PAN bank (clatter-bank pan or pan-object)")
      .def_readonly("path", &PanFile::path)
      .def_property_readonly("kind", [](const PanFile&) { return "pan"; })
      .def_property_readonly("header", [](py::object s) { return pan_header(s.cast<const PanFile&>().bank.header, s); })
      .def_property_readonly("sweep", [](const PanFile& f) { return sweep_dict(f.bank.sweep); })
      .def("__len__", [](const PanFile& f) { return f.bank.proxies.size(); })
      .def("__getitem__", [](const PanFile& f, long i) -> const model::PanProxy& { return entry_at(f, f.bank.proxies, i); },
           py::return_value_policy::reference_internal)
      .def("directions", [](const PanFile& f, long entry, int field, int octant) {
             const auto& p = entry_at(f, f.bank.proxies, entry);
             if (field < 1 || field > 6) throw InputError(fmt::format("field: {} is not in 1-6", field));
             if (octant < 0 || octant >= p.octants()) throw InputError(fmt::format("octant: {} is not in 0-{}", octant, p.octants() - 1));
             return directions_xyz(p.field(field, octant).directions, f.bank.header.lattice());
           }, py::arg("entry"), py::arg("field"), py::arg("octant") = 0, "(n, 3) unit vectors of a field's directions")
      .def("probe", &pan_probe, py::arg("entry"), py::arg("field"), py::arg("points"), py::arg("scale") = 1.0, py::arg("rate_hz") = 0.0,
           py::arg("interpolation") = "quadratic",
           "p_i^(scale h)(x, t) per unit (angular) acceleration at each point: {'t0_s': (n,), 'dt_s', 'p': (n, samples)}, "
           "as `clatter-bank probe` gives one point");
}

void bind_modal(py::module_& m) {
  bind_modal_entry(m);
  py::class_<ModalFile, std::shared_ptr<ModalFile>>(m, "ModalBank", "a modal bank (clatter-bank modal): one material's ellipsoids")
      .def_readonly("path", &ModalFile::path)
      .def_property_readonly("kind", [](const ModalFile&) { return "modal"; })
      .def_property_readonly("header", [](const ModalFile& f) {
        const auto& h = f.bank.header;
        py::dict d;
        d["material"] = material_dict(h.material);
        d["solve"] = solve_settings_dict(h.solve);
        d["band"] = py::dict(py::arg("top_hz") = h.band.top_hz, py::arg("largest_piece_m") = h.band.largest_piece_m,
                             py::arg("proxy_above_hz") = h.band.proxy_above_hz, py::arg("max_multiple") = h.band.max_multiple);
        d["elements_per_wavelength"] = h.elements_per_wavelength;
        d["min_ratio"] = h.min_ratio, d["cigar_ratio"] = h.cigar_ratio;
        d["ranks_per_task"] = h.ranks_per_task, d["solver_libraries"] = h.solver_libraries;
        d["transfer"] = transfer_settings_dict(h.transfer);
        return d;
      })
      .def_property_readonly("sweep", [](const ModalFile& f) { return sweep_dict(f.bank.sweep); })
      .def("__len__", [](const ModalFile& f) { return f.bank.entries.size(); })
      .def("__getitem__", [](const ModalFile& f, long i) -> const model::ModalEntry& { return entry_at(f, f.bank.entries, i); },
           py::return_value_policy::reference_internal)
      .def("probe", [](const ModalFile& f, long entry, const py::handle& points, double scale) {
             const auto& e = entry_at(f, f.bank.entries, entry);
             if (!(finite_arg(scale, "scale") > 0)) throw InputError(fmt::format("scale: {}: must be > 0", scale));
             return modal_probe(e, points, scale, 2 * scale * e.axes_m[2]);  // the bank promises r >= 2c
           }, py::arg("entry"), py::arg("points"), py::arg("scale") = 1.0,
           "|p| [Pa per unit modal amplitude] of every mode at each point, (points, modes), in the entry's frame scaled by "
           "`scale` (frequencies / scale), as `clatter-bank probe`");
}

void bind_object(py::module_& m) {
  py::class_<model::ObjectEntry>(m, "ObjectEntry", "one object of an object bank: its own modal model")
      .def_readonly("key", &model::ObjectEntry::key)
      .def_readonly("mesh_hash", &model::ObjectEntry::mesh_hash)
      .def_readonly("source", &model::ObjectEntry::source)
      .def_property_readonly("material", [](const model::ObjectEntry& e) { return material_dict(e.material); })
      .def_readonly("mass_kg", &model::ObjectEntry::mass_kg)
      .def_readonly("volume_m3", &model::ObjectEntry::volume_m3)
      .def_property_readonly("centre_m", [](const model::ObjectEntry& e) { return e.centre_m; })
      .def_readonly("radius_m", &model::ObjectEntry::radius_m)
      .def_readonly("surface_area_m2", &model::ObjectEntry::surface_area_m2)
      .def_readonly("modal", &model::ObjectEntry::modal, py::return_value_policy::reference_internal);
  py::class_<ObjectFile, std::shared_ptr<ObjectFile>>(m, "ObjectBank", "an object bank (clatter-bank object)")
      .def_readonly("path", &ObjectFile::path)
      .def_property_readonly("kind", [](const ObjectFile&) { return "object"; })
      .def_property_readonly("header", [](const ObjectFile& f) {
        const auto& h = f.bank.header;
        return py::dict(py::arg("solve") = solve_settings_dict(h.solve), py::arg("f_max_hz") = h.f_max_hz,
                        py::arg("elements_per_wavelength") = h.elements_per_wavelength,
                        py::arg("elements_through_thickness") = h.elements_through_thickness,
                        py::arg("proxy_above_hz") = h.proxy_above_hz, py::arg("ranks_per_task") = h.ranks_per_task,
                        py::arg("solver_libraries") = h.solver_libraries, py::arg("transfer") = transfer_settings_dict(h.transfer));
      })
      .def_property_readonly("sweep", [](const ObjectFile& f) { return sweep_dict(f.bank.sweep); })
      .def("__len__", [](const ObjectFile& f) { return f.bank.entries.size(); })
      .def("__getitem__", [](const ObjectFile& f, long i) -> const model::ObjectEntry& { return entry_at(f, f.bank.entries, i); },
           py::return_value_policy::reference_internal)
      .def("probe", [](const ObjectFile& f, long entry, const py::handle& points) {
             const auto& e = entry_at(f, f.bank.entries, entry);
             return modal_probe(e.modal, points, 1.0, e.radius_m);
           }, py::arg("entry"), py::arg("points"),
           "|p| [Pa per unit modal amplitude] of every mode at each point (body frame, from the centre of mass), (points, modes)");
}

void bind_ground(py::module_& m) {
  py::class_<model::GroundMaterial>(m, "GroundMaterial", "one ground of a ground bank: its (elevation, eta) grid of Pi series")
      .def_property_readonly("name", [](const model::GroundMaterial& g) { return g.name; })
      .def_property_readonly("material", [](const model::GroundMaterial& g) { return material_dict(g); })
      .def_property_readonly("elevation_rad", [](py::object s) { return view(s.cast<const model::GroundMaterial&>().elevation_rad, s); })
      .def_property_readonly("eta", [](py::object s) { return view(s.cast<const model::GroundMaterial&>().eta, s); })
      .def("series", [](py::object s, std::size_t i_elevation, std::size_t i_eta) {
             const auto& g = s.cast<const model::GroundMaterial&>();
             if (i_elevation >= g.elevation_rad.size()) throw py::index_error(fmt::format("i_elevation {}: the grid has {}", i_elevation, g.elevation_rad.size()));
             if (i_eta >= g.eta.size()) throw py::index_error(fmt::format("i_eta {}: the grid has {}", i_eta, g.eta.size()));
             const auto& r = g.at(i_elevation, i_eta);
             return py::dict(py::arg("t_hat_start") = r.t_hat_start, py::arg("dt_hat") = r.dt_hat, py::arg("pi") = view(r.pi, s),
                             py::arg("tail") = view(r.tail, s));
           }, py::arg("i_elevation"), py::arg("i_eta"), "Pi(t_hat) of one grid point (docs/ground.md)");
  py::class_<GroundFile, std::shared_ptr<GroundFile>>(m, "GroundBank", "a ground bank (clatter-bank ground)")
      .def_readonly("path", &GroundFile::path)
      .def_property_readonly("kind", [](const GroundFile&) { return "ground"; })
      .def_property_readonly("header", [](const GroundFile& f) {
        return py::dict(py::arg("c0_m_s") = f.bank.c0_m_s, py::arg("rho0_kg_m3") = f.bank.rho0_kg_m3);
      })
      .def_property_readonly("sweep", [](const GroundFile& f) { return sweep_dict(f.bank.sweep); })
      .def("__len__", [](const GroundFile& f) { return f.bank.materials.size(); })
      .def("__getitem__", [](const GroundFile& f, long i) -> const model::GroundMaterial& { return entry_at(f, f.bank.materials, i); },
           py::return_value_policy::reference_internal);
}

// The bank at `path` as the object of its kind, by its `format` attribute.
py::object open_bank(const std::string& path, const std::string& expected) {
  std::shared_ptr<PanFile> pan;
  std::shared_ptr<ModalFile> modal;
  std::shared_ptr<ObjectFile> object;
  std::shared_ptr<GroundFile> ground;
  exclusive([&] {
    const std::string kind = bank_kind(path);
    if (kind.empty())
      throw InputError(fmt::format("{}: not a Clatter bank (its 'format' attribute names none: a PAN, modal, object or ground bank)", path));
    if (!expected.empty() && kind != expected)
      throw InputError(fmt::format("{}: a {} bank ('clatter-{}-bank'), expected a {} bank", path, kind, kind, expected));
    if (kind == "pan") pan = std::make_shared<PanFile>(PanFile{path, io::read_pan_bank(path)});
    if (kind == "modal") modal = std::make_shared<ModalFile>(ModalFile{path, io::read_modal_bank(path)});
    if (kind == "object") object = std::make_shared<ObjectFile>(ObjectFile{path, io::read_object_bank(path)});
    if (kind == "ground") ground = std::make_shared<GroundFile>(GroundFile{path, io::read_ground_bank(path)});
    return 0;
  });
  if (pan) return py::cast(pan);
  if (modal) return py::cast(modal);
  if (object) return py::cast(object);
  return py::cast(ground);
}

}  // namespace

std::mutex& library_mutex() {
  static std::mutex mutex;
  return mutex;
}

std::string bank_kind(const std::string& path) {
  auto file = io::File::open(path);
  if (!io::has_attribute(file, "/", "format")) return "";
  const std::string format = io::read_string_attribute(file, "/", "format");
  for (const char* kind : {io::kPanBankFormat, io::kModalBankFormat, io::kObjectBankFormat, io::kGroundBankFormat})
    if (format == kind) return std::string(kind).substr(8, std::string(kind).size() - 13);  // clatter-KIND-bank
  return "";
}

void bind_banks(py::module_& m) {
  bind_pan(m);
  bind_modal(m);
  bind_object(m);
  bind_ground(m);
  m.def("open_bank", &open_bank, py::arg("path"), py::arg("kind") = "",
        "open a bank file, read and checked as clatter-synth reads it: a PanBank, ModalBank, ObjectBank or GroundBank by "
        "its format; with kind ('pan', 'modal', 'object', 'ground') an InputError unless it is one");
  m.def("_bank_kind", [](const std::string& path) { return exclusive([&] { return bank_kind(path); }); }, py::arg("path"));
}

}  // namespace clatter::python
