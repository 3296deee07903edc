#include "banks/modal/modal_transfer.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <complex>
#include <cstdint>
#include <numbers>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/errors.hpp"
#include "core/interrupt.hpp"
#include "core/stage_log.hpp"
#include "kernels/transfer/surface_interpolation.hpp"
#include "mpi/collectives.hpp"
#include "mpi/interrupt.hpp"
#include "mpi/shared_counter.hpp"

namespace clatter::jobs {
namespace {

namespace kt = kernels::transfer;

// What the ranks need of the entry: axes, frequencies, surface and shapes.
void share_entry(MPI_Comm group, model::ModalEntry& entry) {
  entry.axes_m = mpi::broadcast(group, entry.axes_m);
  entry.frequencies_hz = mpi::broadcast(group, std::move(entry.frequencies_hz));
  entry.surface_nodes_m = mpi::broadcast(group, std::move(entry.surface_nodes_m));
  entry.surface_faces = mpi::broadcast(group, std::move(entry.surface_faces));
  entry.shapes = mpi::broadcast(group, std::move(entry.shapes));
}

// One mode's transfer but its coefficients, which travel in a flat vector of the rank's modes.
struct ModeRecord {
  std::uint64_t mode = 0, n_coefficients = 0;
  double k = 0, residual = 0, normal_fraction = 0, amplification = 0, depth = 0;
  std::int32_t order = 0, attempts = 0, sources = 0;
};

// The modes this rank computed, in its own order.
struct RankModes {
  std::vector<ModeRecord> records;
  std::vector<std::complex<double>> coefficients;

  void add(std::size_t mode, const kt::ModeTransfer& t) {
    const auto& c = t.expansion.coefficients;
    records.push_back({static_cast<std::uint64_t>(mode), static_cast<std::uint64_t>(c.size()), t.expansion.k_rad_m,
                       t.boundary_residual, t.normal_fraction, t.amplification, t.source_depth,
                       static_cast<std::int32_t>(t.expansion.order), static_cast<std::int32_t>(t.attempts),
                       static_cast<std::int32_t>(t.sources)});
    coefficients.insert(coefficients.end(), c.begin(), c.end());
  }
};

// A mode's record and where its coefficients are in its rank's flat vector.
struct Placed {
  const ModeRecord* record = nullptr;
  const std::complex<double>* coefficients = nullptr;
};

// On the group's rank 0: the ranks' modes in mode order.
model::ModalTransfer assemble(const std::vector<std::vector<ModeRecord>>& records,
                              const std::vector<std::vector<std::complex<double>>>& coefficients, std::size_t modes) {
  std::vector<Placed> by_mode(modes);
  for (std::size_t r = 0; r < records.size(); ++r) {
    std::size_t at = 0;
    for (const ModeRecord& m : records[r]) {
      if (at + m.n_coefficients > coefficients[r].size()) throw std::logic_error("transfer: coefficients missing");
      by_mode.at(static_cast<std::size_t>(m.mode)) = {&m, coefficients[r].data() + at};
      at += static_cast<std::size_t>(m.n_coefficients);
    }
  }
  model::ModalTransfer t;
  for (const Placed& p : by_mode) {
    if (p.record == nullptr) throw std::logic_error("transfer: a mode no rank computed");
    const ModeRecord& m = *p.record;
    t.wavenumber_rad_m.push_back(m.k);
    t.order.push_back(m.order);
    t.boundary_residual.push_back(m.residual);
    t.normal_fraction.push_back(m.normal_fraction);
    t.amplification.push_back(m.amplification);
    t.source_depth.push_back(m.depth);
    t.attempts.push_back(m.attempts);
    t.sources.push_back(m.sources);
    for (std::size_t i = 0; i < m.n_coefficients; ++i) {
      t.coefficients.push_back(p.coefficients[i].real());
      t.coefficients.push_back(p.coefficients[i].imag());
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

void compute_modal_transfer(MPI_Comm group, const ModeTransferSolver& solve, model::ModalEntry& entry) {
  Stage stage("transfer");
  const auto t0 = std::chrono::steady_clock::now();
  share_entry(group, entry);
  const int rank = mpi::rank(group);
  const auto n = static_cast<long long>(entry.frequencies_hz.size());
  RankModes mine;
  // The modes go out one at a time from a counter on the group's rank 0, the highest first: a
  // mode's cost grows with its frequency, so the cheap ones fill the gaps at the end. A rank that
  // is done takes the next mode at once. (In rounds of one mode per rank, every round lasted its
  // slowest mode: entry 0037 of the default bank took 0.80 s at 2 ranks, 0.48 s from the queue.)
  mpi::SharedCounter queue(group, 1);
  // A rank that is interrupted, or whose mode fails, empties the queue: the others finish the mode
  // they hold and take none, and all then agree below.
  const auto empty_queue = [&] { queue.add(0, n); };
  std::string failure;
  auto said = t0;
  for (;;) {
    if (interrupt_requested()) {
      empty_queue();
      break;
    }
    const long long taken = queue.add(0, 1);
    if (taken >= n) break;
    const auto i = static_cast<std::size_t>(n - 1 - taken);
    try {
      mine.add(i, solve(entry, i));
    } catch (const std::exception& e) {
      failure = fmt::format("the transfer of mode {} ({:.1f} Hz): {}", i, entry.frequencies_hz[i], e.what());
      empty_queue();
      break;
    }
    // A long entry (an object's hundred modes at tens of seconds each) says how far it is, at most
    // every 30 s, from the group's rank 0.
    const auto now = std::chrono::steady_clock::now();
    if (rank == 0 && now - said > std::chrono::seconds(30)) {
      const long long handed_out = std::min(n, taken + 1);
      const double spent_s = std::chrono::duration<double>(now - t0).count();
      spdlog::info("transfer: {} of {} modes handed out in {:.0f} s, ETA {:.0f} s", handed_out, n, spent_s,
                   spent_s / static_cast<double>(handed_out) * static_cast<double>(n - handed_out));
      said = now;
    }
  }
  // The rank's own time, before it waits for the others' last modes (cost.transfer_core_s).
  const double own_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  try {
    mpi::agree(group, [&] {
      if (!failure.empty()) throw std::runtime_error(failure);
    });
  } catch (const mpi::CollectiveError& e) {
    throw TaskFailure(e.what());
  }
  mpi::poll_interrupt(group, "the rest of the transfer");
  const auto core_s = mpi::gather(group, own_s);
  const auto records = mpi::gather(group, mine.records);
  const auto coefficients = mpi::gather(group, mine.coefficients);
  if (rank != 0) return;
  entry.cost.transfer_core_s = 0;
  for (const double s : core_s) entry.cost.transfer_core_s += s;
  entry.transfer = assemble(records, coefficients, static_cast<std::size_t>(n));
  entry.cost.transfer_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace clatter::jobs
