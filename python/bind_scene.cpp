// Scenes and proxies from Python (docs/python.md "Scenes"): a scene is read by io/'s one scene
// reader, from a file or from the text clatter.Scene builds from numpy arrays, so both meet the same
// checks and messages; proxies are fitted by kernels/rigid_body (eq. 11) and kernels/modal (eq. 12).
#include <fmt/format.h>
#include <pybind11/stl.h>

#include <cmath>
#include <stdexcept>

#include "core/errors.hpp"
#include "kernels/mass_properties.hpp"
#include "kernels/modal/modal_proxy.hpp"
#include "kernels/rigid_body.hpp"
#include "io/mesh.hpp"
#include "python/arrays.hpp"
#include "python/bindings.hpp"
#include "synth/load_scene.hpp"

namespace clatter::python {

const io::Scene& PyScene::for_render(bool modal_sound) {
  if (modal_sound && !frequencies_added) {
    synth::add_base_frequencies(scene);
    frequencies_added = true;
  }
  return scene;
}

namespace {

py::dict proxy_dict(const kernels::ProxyFit& fit) {
  const auto frame = kernels::modal::modal_proxy_frame(fit);
  py::dict d;
  d["semi_axes_m"] = std::array<double, 3>{fit.a_m, fit.b_m, fit.c_m};
  d["axes"] = fit.axes;  // columns: the proxy's axes in the body frame
  d["moments_kg_m2"] = fit.moments_kg_m2;
  d["modal_unit_axes"] = frame.unit_axes;  // eq. 12, a <= b <= c, a^2 + b^2 + c^2 = 1
  d["modal_rotation"] = frame.rotation;
  return d;
}

kernels::Mat3 matrix_arg(const py::handle& h, const char* argument) {
  const auto a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(h);
  if (!a || a.ndim() != 2 || a.shape(0) != 3 || a.shape(1) != 3) throw InputError(fmt::format("{}: expected a 3x3 matrix", argument));
  kernels::Mat3 m{};
  for (std::size_t r = 0; r < 3; ++r)
    for (std::size_t c = 0; c < 3; ++c) {
      m[r][c] = a.at(static_cast<py::ssize_t>(r), static_cast<py::ssize_t>(c));
      if (!std::isfinite(m[r][c])) throw InputError(fmt::format("{}[{}][{}]: {} is not finite", argument, r, c, m[r][c]));
    }
  return m;
}

py::dict fit_proxy(const py::handle& inertia, double mass_kg, double volume_m3) {
  const auto m = matrix_arg(inertia, "inertia_kg_m2");
  if (!(finite_arg(mass_kg, "mass_kg") > 0)) throw InputError(fmt::format("mass_kg: {}: must be > 0", mass_kg));
  if (!(finite_arg(volume_m3, "volume_m3") > 0)) throw InputError(fmt::format("volume_m3: {}: must be > 0", volume_m3));
  try {
    return proxy_dict(kernels::fit_proxy(m, mass_kg, volume_m3));
  } catch (const std::invalid_argument& e) {
    throw InputError(fmt::format("inertia_kg_m2: {}", e.what()));
  }
}

// The uniform solid a closed triangle mesh bounds: its mass properties and its proxy.
py::dict mesh_proxy(const py::handle& vertices, const py::handle& triangles, double density_kg_m3) {
  const auto v = points_arg(vertices, "vertices_m");
  const auto t = py::array_t<std::int64_t, py::array::c_style | py::array::forcecast>::ensure(triangles);
  if (!t || t.ndim() != 2 || t.shape(1) != 3 || t.shape(0) < 4)
    throw InputError("triangles: expected an (m, 3) array of vertex indices, m >= 4");
  std::vector<std::array<int, 3>> tri(static_cast<std::size_t>(t.shape(0)));
  for (py::ssize_t i = 0; i < t.shape(0); ++i)
    for (py::ssize_t k = 0; k < 3; ++k) {
      const auto index = t.at(i, k);
      if (index < 0 || index >= static_cast<std::int64_t>(v.size()))
        throw InputError(fmt::format("triangles[{}][{}]: {} is not a vertex index (0-{})", i, k, index, v.size() - 1));
      tri[static_cast<std::size_t>(i)][static_cast<std::size_t>(k)] = static_cast<int>(index);
    }
  if (!(finite_arg(density_kg_m3, "density_kg_m3") > 0)) throw InputError(fmt::format("density_kg_m3: {}: must be > 0", density_kg_m3));
  const auto props = kernels::mesh_mass_properties(v, tri);
  if (!(props.volume_m3 > 0))
    throw InputError(fmt::format("triangles: the mesh encloses a signed volume of {} m^3: faces must wind counter-clockwise "
                                 "seen from outside", props.volume_m3));
  kernels::Mat3 inertia{};
  for (std::size_t r = 0; r < 3; ++r)
    for (std::size_t c = 0; c < 3; ++c) inertia[r][c] = density_kg_m3 * props.inertia_per_density_m5[r][c];
  const double mass = density_kg_m3 * props.volume_m3;
  py::dict d;
  try {
    d = proxy_dict(kernels::fit_proxy(inertia, mass, props.volume_m3));
  } catch (const std::invalid_argument& e) {
    throw InputError(fmt::format("vertices_m: the mesh's inertia: {}", e.what()));
  }
  d["mass_kg"] = mass;
  d["volume_m3"] = props.volume_m3;
  d["centre_of_mass_m"] = props.centroid_m;
  d["inertia_kg_m2"] = inertia;
  d["surface_area_m2"] = props.surface_area_m2;
  return d;
}

std::shared_ptr<PyScene> resolved(io::Scene scene) {
  synth::resolve_meshes(scene);
  return std::make_shared<PyScene>(PyScene{std::move(scene), false});
}

py::list objects_of(const std::vector<io::SceneObject>& objects) {
  py::list out;
  for (const auto& o : objects) {
    py::dict d;
    d["id"] = o.id, d["material"] = o.material, d["mass_kg"] = o.mass_kg, d["volume_m3"] = o.volume_m3;
    d["inertia_kg_m2"] = o.inertia_kg_m2;
    d["mesh"] = o.mesh_path;
    d["base_frequency_hz"] = o.base_frequency_hz;  // 0: not given (a mesh object's: from the first modal render)
    d["created_s"] = o.created_s, d["destroyed_s"] = o.destroyed_s;
    out.append(d);
  }
  return out;
}

// The events as columns (copies: an event is a struct of many kinds of field).
py::dict events_of(const io::Scene& s) {
  const auto n = static_cast<py::ssize_t>(s.events.size());
  py::array_t<double> t(n), speed(n), contact(n), point({n, py::ssize_t{3}}), impulse({n, py::ssize_t{3}});
  py::array_t<std::int32_t> a(n), b(n);
  py::list kind;
  for (py::ssize_t i = 0; i < n; ++i) {
    const auto& e = s.events[static_cast<std::size_t>(i)];
    t.mutable_at(i) = e.t_s, a.mutable_at(i) = e.a, b.mutable_at(i) = e.b;
    speed.mutable_at(i) = e.normal_speed_m_s, contact.mutable_at(i) = e.contact_time_s;
    for (py::ssize_t k = 0; k < 3; ++k) {
      point.mutable_at(i, k) = e.point_m[static_cast<std::size_t>(k)];
      impulse.mutable_at(i, k) = e.impulse_n_s[static_cast<std::size_t>(k)];
    }
    kind.append(e.fracture ? "fracture" : e.sustained ? "sustained" : "contact");
  }
  return py::dict(py::arg("t_s") = t, py::arg("a") = a, py::arg("b") = b, py::arg("kind") = kind, py::arg("point_m") = point,
                  py::arg("impulse_n_s") = impulse, py::arg("normal_speed_m_s") = speed, py::arg("contact_time_s") = contact);
}

}  // namespace

void bind_scene(py::module_& m) {
  py::class_<PyScene, std::shared_ptr<PyScene>>(m, "SceneData", "a scene read and checked by Clatter's scene reader")
      .def_property_readonly("path", [](const PyScene& s) { return s.scene.path; })
      .def_property_readonly("duration_s", [](const PyScene& s) { return s.scene.duration_s; })
      .def_property_readonly("ground_material", [](const PyScene& s) { return s.scene.ground_material; })
      .def_property_readonly("materials", [](const PyScene& s) {
        py::dict d;
        for (const auto& [name, mat] : s.scene.materials) {
          py::dict md;
          md["youngs_modulus_pa"] = mat.youngs_pa, md["poisson_ratio"] = mat.poisson;
          if (mat.rho_kg_m3 > 0) md["density_kg_m3"] = mat.rho_kg_m3;
          if (mat.damping) md["rayleigh_alpha"] = mat.damping->alpha_1_s, md["rayleigh_beta"] = mat.damping->beta_s;
          d[py::str(name)] = md;
        }
        return d;
      })
      .def_property_readonly("objects", [](const PyScene& s) {
        // A render in another thread may be adding base frequencies: read them under its lock.
        return objects_of(exclusive([&] { return s.scene.objects; }));
      })
      .def_property_readonly("listeners_m", [](py::object self) { return view(self.cast<const PyScene&>().scene.listeners_m, self); })
      .def_property_readonly("events", [](const PyScene& s) { return events_of(s.scene); })
      .def("__len__", [](const PyScene& s) { return s.scene.events.size(); })
      .def("write", [](const PyScene& s, const std::string& path) {
             exclusive([&] {
               io::write_scene(s.scene, path, R"json({"program": "clatter (Python)"})json");
               return 0;
             });
           }, py::arg("path"), "the scene as a scene file clatter-synth reads (meshes into PATH's .meshes folder), atomically");
  m.def("_parse_scene", [](const std::string& text, const std::string& name) {
          return exclusive([&] { return resolved(io::parse_scene(text, name)); });
        },
        py::arg("text"), py::arg("name"));
  m.def("_load_scene", [](const std::string& path, const std::string& impulses) {
          return exclusive([&] { return std::make_shared<PyScene>(PyScene{synth::load_scene(path, impulses, false), false}); });
        }, py::arg("path"), py::arg("impulses") = "");
  m.def("read_mesh", [](const std::string& path) {
          const io::TriangleMesh mesh = exclusive([&] { return io::read_obj(path); });
          py::array_t<double> v({static_cast<py::ssize_t>(mesh.vertices_m.size()), py::ssize_t{3}});
          py::array_t<std::int32_t> t({static_cast<py::ssize_t>(mesh.triangles.size()), py::ssize_t{3}});
          std::copy_n(&mesh.vertices_m.front()[0], 3 * mesh.vertices_m.size(), v.mutable_data());
          std::copy_n(&mesh.triangles.front()[0], 3 * mesh.triangles.size(), t.mutable_data());
          return py::make_tuple(v, t);
        }, py::arg("path"), "an OBJ file as clatter-synth reads a mesh object's: (vertices_m (n, 3), triangles (m, 3))");
  m.def("fit_proxy", &fit_proxy, py::arg("inertia_kg_m2"), py::arg("mass_kg"), py::arg("volume_m3"),
        "the proxy ellipsoid of a rigid body (000 eq. 11: principal moments and volume): semi_axes_m (a >= b >= c), axes "
        "(columns, body frame), moments_kg_m2, and the modal bank's normalized axes (003 eq. 12)");
  m.def("fit_proxy_to_mesh", &mesh_proxy, py::arg("vertices_m"), py::arg("triangles"), py::arg("density_kg_m3"),
        "the uniform solid a closed, outward-wound triangle mesh bounds: mass, volume, centre of mass, inertia about it, "
        "area, and its proxy as fit_proxy gives it");
}

}  // namespace clatter::python
