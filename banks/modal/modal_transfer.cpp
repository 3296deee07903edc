#include "banks/modal/modal_transfer.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <cstring>
#include <numbers>
#include <span>
#include <string>

#include "core/stage_log.hpp"
#include "banks/modal/modal_solve.hpp"
#include "kernels/transfer/surface_interpolation.hpp"
#include "mpi/comm.hpp"

namespace clatter::jobs {
namespace {

namespace kt = kernels::transfer;

// Plain bytes of vectors of trivially copyable values, for mpi::broadcast / mpi::gather.
class Packer {
 public:
  template <class T>
  void put(const std::vector<T>& v) {
    put_value(static_cast<std::uint64_t>(v.size()));
    bytes_.append(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(T));
  }
  template <class T>
  void put_value(const T& x) { bytes_.append(reinterpret_cast<const char*>(&x), sizeof(T)); }
  std::string& bytes() { return bytes_; }

 private:
  std::string bytes_;
};

class Unpacker {
 public:
  explicit Unpacker(const std::string& bytes) : bytes_(bytes) {}
  template <class T>
  std::vector<T> get() {
    const auto n = get_value<std::uint64_t>();
    std::vector<T> v(n);
    std::memcpy(v.data(), bytes_.data() + at_, n * sizeof(T));
    at_ += n * sizeof(T);
    return v;
  }
  template <class T>
  T get_value() {
    T x;
    std::memcpy(&x, bytes_.data() + at_, sizeof(T));
    at_ += sizeof(T);
    return x;
  }
  bool done() const { return at_ >= bytes_.size(); }

 private:
  const std::string& bytes_;
  std::size_t at_ = 0;
};

// What the ranks need of the entry: axes, frequencies, surface and shapes.
void share_entry(MPI_Comm group, model::ModalEntry& entry) {
  Packer p;
  if (mpi::rank(group) == 0) {
    p.put(std::vector<double>(entry.axes_m.begin(), entry.axes_m.end()));
    p.put(entry.frequencies_hz);
    p.put(entry.surface_nodes_m);
    p.put(entry.surface_faces);
    p.put(entry.shapes);
  }
  const std::string bytes = mpi::broadcast(group, std::move(p.bytes()));
  if (mpi::rank(group) == 0) return;
  Unpacker u(bytes);
  const auto axes = u.get<double>();
  std::copy(axes.begin(), axes.end(), entry.axes_m.begin());
  entry.frequencies_hz = u.get<double>();
  entry.surface_nodes_m = u.get<std::array<double, 3>>();
  entry.surface_faces = u.get<std::array<std::int32_t, 6>>();
  entry.shapes = u.get<double>();
}

void pack_mode(Packer& p, std::size_t mode, const kt::ModeTransfer& t) {
  p.put_value(static_cast<std::uint64_t>(mode));
  p.put_value(t.expansion.k_rad_m);
  p.put_value(static_cast<std::int32_t>(t.expansion.order));
  p.put_value(t.boundary_residual);
  p.put_value(t.normal_fraction);
  p.put_value(t.amplification);
  p.put_value(t.source_depth);
  p.put_value(static_cast<std::int32_t>(t.attempts));
  p.put_value(static_cast<std::int32_t>(t.sources));
  p.put(t.expansion.coefficients);
}

struct PackedMode {
  double k = 0, residual = 0, normal_fraction = 0, amplification = 0, depth = 0;
  std::int32_t order = 0, attempts = 0, sources = 0;
  std::vector<std::complex<double>> coefficients;
};

model::ModalTransfer assemble(const std::vector<std::string>& parts, std::size_t modes, double& core_s) {
  std::vector<PackedMode> by_mode(modes);
  core_s = 0;
  for (const auto& bytes : parts) {
    Unpacker u(bytes);
    core_s += u.get_value<double>();
    while (!u.done()) {
      const auto mode = u.get_value<std::uint64_t>();
      PackedMode& m = by_mode.at(mode);
      m.k = u.get_value<double>();
      m.order = u.get_value<std::int32_t>();
      m.residual = u.get_value<double>();
      m.normal_fraction = u.get_value<double>();
      m.amplification = u.get_value<double>();
      m.depth = u.get_value<double>();
      m.attempts = u.get_value<std::int32_t>();
      m.sources = u.get_value<std::int32_t>();
      m.coefficients = u.get<std::complex<double>>();
    }
  }
  model::ModalTransfer t;
  for (const auto& m : by_mode) {
    t.wavenumber_rad_m.push_back(m.k);
    t.order.push_back(m.order);
    t.boundary_residual.push_back(m.residual);
    t.normal_fraction.push_back(m.normal_fraction);
    t.amplification.push_back(m.amplification);
    t.source_depth.push_back(m.depth);
    t.attempts.push_back(m.attempts);
    t.sources.push_back(m.sources);
    for (const auto& c : m.coefficients) {
      t.coefficients.push_back(c.real());
      t.coefficients.push_back(c.imag());
    }
  }
  return t;
}

}  // namespace

kt::ModeTransfer mode_transfer(const model::ModalEntry& entry, std::size_t mode, const kt::TransferSettings& settings) {
  const std::size_t per_mode = 3 * entry.surface_nodes_m.size();
  const std::span<const double> shape(entry.shapes.data() + mode * per_mode, per_mode);
  const auto u = kt::mesh_displacement(entry.axes_m, entry.surface_nodes_m, entry.surface_faces, shape);
  const double omega = 2 * std::numbers::pi * entry.frequencies_hz[mode];
  return kt::solve_mode_transfer(entry.axes_m, omega, kt::surface_node_spacing_m(entry.surface_nodes_m, entry.surface_faces),
                                 u, settings);
}

void compute_modal_transfer(MPI_Comm group, const model::TransferSettings& settings, model::ModalEntry& entry) {
  Stage stage("transfer");
  const auto t0 = std::chrono::steady_clock::now();
  share_entry(group, entry);
  const int rank = mpi::rank(group), size = mpi::size(group);
  Packer p;
  std::string results;
  // In rounds of one mode per rank, polled between rounds: SIGTERM stops the task within a mode.
  const std::size_t n = entry.frequencies_hz.size(), ranks = static_cast<std::size_t>(size);
  for (std::size_t round = 0; round * ranks < n; ++round) {
    poll_interrupt(group, "the next transfer round");
    const std::size_t i = round * ranks + static_cast<std::size_t>(rank);
    if (i < n) pack_mode(p, i, mode_transfer(entry, i, settings));
  }
  const double own_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  Packer out;
  out.put_value(own_s);
  out.bytes() += p.bytes();
  const auto parts = mpi::gather(group, out.bytes());
  if (rank != 0) return;
  entry.transfer = assemble(parts, entry.frequencies_hz.size(), entry.cost.transfer_core_s);
  entry.cost.transfer_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace clatter::jobs
