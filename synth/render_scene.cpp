#include "synth/render_scene.hpp"

#include <fmt/format.h>

#include <array>
#include <cmath>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>

#include "core/errors.hpp"
#include "core/stage_log.hpp"
#include "kernels/contact.hpp"

namespace clatter::synth {
namespace {

// Radius of curvature of the proxy ellipsoid where the ray along `arm` (proxy frame) leaves it:
// 1 / sqrt(Gaussian curvature), K = 1 / (a b c)^2 / (x^2/a^4 + y^2/b^4 + z^2/c^4)^2.
double proxy_contact_radius(const kernels::ProxyFit& fit, const Vec3& arm_body) {
  const Vec3 d = kernels::to_proxy_frame(fit, arm_body);
  const double a = fit.a_m, b = fit.b_m, c = fit.c_m;
  const double s = std::sqrt(d[0] * d[0] / (a * a) + d[1] * d[1] / (b * b) + d[2] * d[2] / (c * c));
  if (!(s > 0)) return std::cbrt(a * b * c);  // contact at the centre: no direction, use the mean radius
  const Vec3 x{d[0] / s, d[1] / s, d[2] / s};
  const double q = x[0] * x[0] / (a * a * a * a) + x[1] * x[1] / (b * b * b * b) + x[2] * x[2] / (c * c * c * c);
  return a * b * c * q;  // = 1 / sqrt(K)
}

// The object's radius of curvature at the contact (arm: body frame, from the centre of mass): its
// mesh's where it has one (kernels/mesh_contact.hpp; the body frame is the mesh frame moved to the
// centre of mass), else its proxy's. `feature` gets the mesh's feature there, -1 for the proxy.
double contact_radius(const ObjectModel& m, const Vec3& arm_body, const std::string& where, int& feature) {
  feature = -1;
  if (!m.contact) return proxy_contact_radius(m.proxy, arm_body);
  try {
    const kernels::MeshContactPoint p = m.contact->at(add(arm_body, m.object->rest_centre_m));
    feature = static_cast<int>(p.feature);
    return p.radius_m;
  } catch (const std::invalid_argument& e) {
    throw InputError(fmt::format("{}: object {} ({}): {}", where, m.object->id, m.object->mesh_path, e.what()));
  }
}

}  // namespace

std::vector<ObjectModel> object_models(const io::Scene& scene, const std::string& scene_path) {
  std::vector<ObjectModel> models;
  std::map<const io::TriangleMesh*, std::shared_ptr<const kernels::MeshContact>> contacts;  // one per mesh file
  for (const auto& o : scene.objects) {
    ObjectModel m;
    m.object = &o;
    m.index = models.size();
    try {
      m.proxy = kernels::fit_proxy(o.inertia_kg_m2, o.mass_kg, o.volume_m3);
    } catch (const std::invalid_argument& e) {
      throw InputError(fmt::format("{}: object {}: inertia_kg_m2: {}", scene_path, o.id, e.what()));
    }
    if (o.mesh) {
      auto& contact = contacts[o.mesh.get()];
      if (!contact) {
        try {
          contact = std::make_shared<const kernels::MeshContact>(
              o.mesh->vertices_m, o.mesh->triangles,
              kernels::mesh_contact_rule(m.proxy, o.volume_m3, o.mesh->vertices_m, o.rest_centre_m));
        } catch (const std::invalid_argument& e) {
          throw InputError(fmt::format("{}: object {}: mesh {}: {}", scene_path, o.id, o.mesh_path, e.what()));
        }
      }
      m.contact = contact;
    }
    models.push_back(m);
  }
  return models;
}

namespace {

// Contact duration and half-sine peak of one event. Hertz: effective mass and radius of the pair
// (the ground: infinite mass, flat), each object's radius from its own surface (contact_radius);
// a fracture impulse or a sustained contact brings its own duration.
struct Contact {
  double tau_s = 0, peak_force_n = 0;
  Vec3 arm_a{}, arm_b{};
  std::array<int, 2> feature{-1, -1};  // kernels::ContactFeature on a's and b's mesh; -1: none
};

Contact event_contact(const io::Scene& scene, const io::SceneEvent& e, const ObjectModel* a, const ObjectModel* b, double j) {
  Contact c;
  c.arm_a = rotate_inverse(e.pose_a.orientation_wxyz, sub(e.point_m, e.pose_a.position_m));
  if (b) c.arm_b = rotate_inverse(e.pose_b.orientation_wxyz, sub(e.point_m, e.pose_b.position_m));
  if (e.fracture || e.sustained) {
    c.tau_s = e.contact_time_s;
  } else {
    double inv_r = 1 / contact_radius(*a, c.arm_a, e.where, c.feature[0]), inv_m = 1 / a->object->mass_kg;
    if (b) {
      inv_r += 1 / contact_radius(*b, c.arm_b, e.where, c.feature[1]);
      inv_m += 1 / b->object->mass_kg;
    }
    const auto& mat_a = scene.materials.at(a->object->material);
    const auto& mat_b = b ? scene.materials.at(b->object->material) : scene.materials.at(scene.ground_material);
    c.tau_s = kernels::hertz_contact_time_s(1 / inv_m, 1 / inv_r, mat_a, mat_b, e.normal_speed_m_s);
  }
  c.peak_force_n = kernels::half_sine_peak(j, c.tau_s);
  return c;
}

}  // namespace

std::vector<std::vector<std::vector<double>>> render_scene(const io::Scene& scene, const std::vector<SoundSource*>& sources,
                                                           const RenderOptions& options, RenderStats* stats) {
  const std::vector<ObjectModel> models = object_models(scene, scene.path);
  std::map<int, const ObjectModel*> by_id;
  for (const auto& m : models) by_id[m.object->id] = &m;
  const double last = scene.events.empty() ? 0.0 : scene.events.back().t_s;
  const double duration = scene.duration_s > 0 ? scene.duration_s : last + options.tail_s;
  const auto n = static_cast<std::size_t>(std::ceil(duration * options.rate_hz));
  std::vector<std::vector<std::vector<double>>> out(
      sources.size(), std::vector<std::vector<double>>(scene.listeners_m.size(), std::vector<double>(n, 0.0)));
  for (SoundSource* s : sources) s->begin(scene, models, options.rate_hz);
  RenderStats local;
  for (SoundSource* s : sources) local.coverage.push_back(s->coverage(models));
  Stage render_stage("render");
  for (const auto& e : scene.events) {
    Stage event_stage("event");  // one stage per event: per-impact stages would cost ~5 % here
    const ObjectModel* a = by_id.at(e.a);
    const ObjectModel* b = e.b ? by_id.at(e.b) : nullptr;
    const double j = std::sqrt(e.impulse_n_s[0] * e.impulse_n_s[0] + e.impulse_n_s[1] * e.impulse_n_s[1] +
                               e.impulse_n_s[2] * e.impulse_n_s[2]);
    if (!(j > 0)) continue;  // a resting contact: no sound
    if (e.sustained && e.contact_time_s > options.max_sustained_s) {
      ++local.skipped_sustained;
      continue;
    }
    const Contact contact = event_contact(scene, e, a, b, j);
    for (const int f : contact.feature)
      if (f >= 0) ++local.mesh_contacts[static_cast<std::size_t>(f)];
    const Vec3 dir_world{e.impulse_n_s[0] / j, e.impulse_n_s[1] / j, e.impulse_n_s[2] / j};
    for (int side = 0; side < (b ? 2 : 1); ++side) {
      const ObjectModel* m = side == 0 ? a : b;
      const io::Pose& pose = side == 0 ? e.pose_a : e.pose_b;
      const double sign = side == 0 ? 1.0 : -1.0;  // B receives the opposite impulse
      if (e.t_s < m->object->created_s || e.t_s >= m->object->destroyed_s) {
        ++local.skipped_inactive;
        continue;
      }
      Impact im;
      im.model = m;
      im.t_s = e.t_s;
      im.tau_s = contact.tau_s;
      im.peak_force_n = contact.peak_force_n;
      im.direction_body = rotate_inverse(pose.orientation_wxyz, {sign * dir_world[0], sign * dir_world[1], sign * dir_world[2]});
      im.contact_body_m = side == 0 ? contact.arm_a : contact.arm_b;
      im.pose = pose;
      im.on_ground = !b && !e.fracture;
      im.sustained = e.sustained;
      im.point_world_m = e.point_m;
      im.impulse_world_n_s = {sign * e.impulse_n_s[0], sign * e.impulse_n_s[1], sign * e.impulse_n_s[2]};
      for (std::size_t s = 0; s < sources.size(); ++s) {
        try {
          sources[s]->add(im, scene.listeners_m, options.rate_hz, out[s]);
        } catch (const InputError& err) {
          throw InputError(fmt::format("{}: {}", e.where, err.what()));
        }
      }
      ++local.impacts;
      if (e.fracture) ++local.fracture_impacts;
      if (e.sustained) ++local.sustained_impacts;
    }
  }
  for (std::size_t s = 0; s < sources.size(); ++s) sources[s]->finish(out[s]);
  if (stats) *stats = local;
  return out;
}

}  // namespace clatter::synth
