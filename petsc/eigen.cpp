#include "petsc/eigen.hpp"

#include <slepceps.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <numeric>
#include <stdexcept>
#include <type_traits>

#include "core/stage_log.hpp"
#include "mpi/collectives.hpp"
#include "petsc/error.hpp"

namespace clatter::petsc {
namespace {

struct EpsDeleter {
  void operator()(EPS eps) const { EPSDestroy(&eps); }
};
using EpsPtr = std::unique_ptr<std::remove_pointer_t<EPS>, EpsDeleter>;

void validate(const Matrix& K, const Matrix& M, const SliceSettings& s, std::span<const Vector> deflation) {
  if (!(K.layout() == M.layout())) throw std::invalid_argument("solve_interval: K and M have different row layouts");
  if (!K.assembled() || !M.assembled()) throw std::invalid_argument("solve_interval: assemble K and M first");
  if (!(std::isfinite(s.lambda_lo) && std::isfinite(s.lambda_hi) && s.lambda_lo < s.lambda_hi))
    throw std::invalid_argument("solve_interval: need finite lambda_lo < lambda_hi");
  if (!(s.tolerance > 0 && s.tolerance < 1)) throw std::invalid_argument("solve_interval: tolerance must be in (0, 1)");
  if (s.max_iterations < 0 || s.nev_per_shift < 0)
    throw std::invalid_argument("solve_interval: max_iterations and nev_per_shift must be >= 0");
  for (const Vector& v : deflation)
    if (!(v.layout() == K.layout())) throw std::invalid_argument("solve_interval: a deflation vector is not on K's layout");
}

// PETSc's running total of one of its logged events on this rank (the default log is on: Session).
struct EventTotal {
  double seconds = 0;
  long long count = 0;
};

EventTotal event_total(const char* name) {
  PetscLogEvent event = 0;
  check(PetscLogEventGetId(name, &event), "PetscLogEventGetId");
  PetscEventPerfInfo info{};
  check(PetscLogEventGetPerfInfo(0, event, &info), "PetscLogEventGetPerfInfo");
  return {info.time, info.count};
}

// The factorisations PETSc ran since `before`, as children of the open stage.
void record_factorisations(const EventTotal before[2], SolveStats& stats) {
  const char* events[2] = {"MatCholFctrSym", "MatCholFctrNum"};
  const char* stages[2] = {"factor symbolic", "factor numeric"};
  for (int i = 0; i < 2; ++i) {
    const EventTotal now = event_total(events[i]);
    const long long count = now.count - before[i].count;
    const double seconds = now.seconds - before[i].seconds;
    if (count > 0) stage_log().add(stages[i], count, seconds);
    (i == 0 ? stats.symbolic_factorisations : stats.numeric_factorisations) += count;
    (i == 0 ? stats.symbolic_s : stats.numeric_s) += seconds;
  }
}

// Runs `step` (EPSSetUp or EPSSolve) as stage `name`, with PETSc's factorisations inside it.
template <class Step>
double timed_step(const char* name, SolveStats& stats, Step&& step) {
  Stage stage(name);
  const EventTotal before[2] = {event_total("MatCholFctrSym"), event_total("MatCholFctrNum")};
  step();
  record_factorisations(before, stats);
  return stage.elapsed_s();
}

EpsPtr make_solver(const Matrix& K, const Matrix& M, const std::string& prefix) {
  EPS raw = nullptr;
  check(EPSCreate(K.layout().comm(), &raw), "EPSCreate");
  EpsPtr eps(raw);
  // Slicing's internal EPS takes this prefix too, and its ST, KSP, PC and MUMPS factor add "st_".
  check(EPSSetOptionsPrefix(raw, prefix.c_str()), "EPSSetOptionsPrefix");
  check(EPSSetOperators(raw, K.get(), M.get()), "EPSSetOperators");
  check(EPSSetFromOptions(raw), "EPSSetFromOptions");
  return eps;
}

// One prefix per solve in this process, so no solve reads another's options.
std::string next_prefix() {
  static long long solves = 0;
  return "clatter" + std::to_string(++solves) + "_";
}

// The options must have reached MUMPS: without ICNTL(13)=1 its parallel inertia is wrong.
void require_mumps_inertia(EPS eps) {
  KSP ksp = nullptr;
  PC pc = nullptr;
  Mat factor = nullptr;
  // Slicing solves in an internal EPS (one per partition); its solver holds the factor.
  check(EPSKrylovSchurGetKSP(eps, &ksp), "EPSKrylovSchurGetKSP");
  check(KSPGetPC(ksp, &pc), "KSPGetPC");
  check(PCFactorGetMatrix(pc, &factor), "PCFactorGetMatrix");
  PetscInt icntl13 = 0;
  check(MatMumpsGetIcntl(factor, 13, &icntl13), "MatMumpsGetIcntl(13)");
  if (icntl13 != 1)
    throw std::logic_error("solve_interval: MUMPS runs with ICNTL(13) = " + std::to_string(icntl13) +
                           ", not 1: the options database did not reach the factor");
}

// A fixed generic vector (a function of the global index only): the sign of an eigenvector's
// projection on it is the same on any number of ranks, unlike the sign of a largest entry that
// ties with another up to rounding.
Vector sign_reference(const Layout& layout) {
  std::vector<double> w(static_cast<std::size_t>(layout.local_size()));
  for (std::size_t i = 0; i < w.size(); ++i) {
    const double index = static_cast<double>(layout.begin()) + static_cast<double>(i);
    w[i] = 0.5 + (index * 0.6180339887498949 - std::floor(index * 0.6180339887498949));
  }
  return Vector(layout, w);
}

// M-normalises x, fixes its sign, and returns ||K x - lambda M x|| / ||K x||.
double finish_pair(const Matrix& K, const Matrix& M, double lambda, const Vector& reference, Vector& x) {
  Vector kx(K.layout()), mx(K.layout());
  check(MatMult(M.get(), x.get(), mx.get()), "MatMult");
  PetscScalar x_m_x = 0, along = 0;
  check(VecDot(x.get(), mx.get(), &x_m_x), "VecDot");
  check(VecDot(x.get(), reference.get(), &along), "VecDot");
  if (!(x_m_x > 0)) throw std::runtime_error("solve_interval: an eigenvector has x^T M x <= 0 (M not positive definite?)");
  const double scale = (along < 0 ? -1.0 : 1.0) / std::sqrt(x_m_x);
  check(VecScale(x.get(), scale), "VecScale");
  check(VecScale(mx.get(), scale), "VecScale");
  check(MatMult(K.get(), x.get(), kx.get()), "MatMult");
  PetscReal kx_norm = 0, r_norm = 0;
  check(VecNorm(kx.get(), NORM_2, &kx_norm), "VecNorm");
  check(VecAXPY(kx.get(), -lambda, mx.get()), "VecAXPY");  // kx <- K x - lambda M x
  check(VecNorm(kx.get(), NORM_2, &r_norm), "VecNorm");
  return kx_norm > 0 ? r_norm / kx_norm : r_norm;
}

// The converged pairs, ascending.
void collect(EPS eps, const Matrix& K, EigenSolution& out) {
  PetscInt n = 0;
  check(EPSGetConverged(eps, &n), "EPSGetConverged");
  std::vector<double> lambdas(static_cast<std::size_t>(n));
  std::vector<Vector> vectors;
  for (PetscInt i = 0; i < n; ++i) {
    vectors.emplace_back(K.layout());
    PetscScalar lambda = 0;
    check(EPSGetEigenpair(eps, i, &lambda, nullptr, vectors.back().get(), nullptr), "EPSGetEigenpair");
    lambdas[static_cast<std::size_t>(i)] = lambda;
  }
  std::vector<std::size_t> order(lambdas.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return lambdas[a] < lambdas[b]; });
  for (std::size_t i : order) {
    out.lambdas.push_back(lambdas[i]);
    out.vectors.push_back(std::move(vectors[i]));
  }
}

// x <- x - sum_j (z_j^T M x) z_j for M-orthonormal z; returns the fraction of x's squared M-norm
// that was in span(z).
double m_project_out(const Matrix& M, const std::vector<Vector>& z, Vector& x) {
  Vector mx(M.layout());
  check(MatMult(M.get(), x.get(), mx.get()), "MatMult");
  PetscScalar x_m_x = 0;
  check(VecDot(x.get(), mx.get(), &x_m_x), "VecDot");
  double weight = 0;
  for (const Vector& zj : z) {
    PetscScalar c = 0;
    check(VecDot(zj.get(), mx.get(), &c), "VecDot");
    weight += c * c;
    check(VecAXPY(x.get(), -c, zj.get()), "VecAXPY");
  }
  return x_m_x > 0 ? weight / x_m_x : 0.0;
}

std::vector<Vector> m_orthonormal_basis(const Matrix& M, std::span<const Vector> vectors) {
  std::vector<Vector> basis;
  for (const Vector& v : vectors) {
    Vector x(v.layout());
    check(VecCopy(v.get(), x.get()), "VecCopy");
    for (int pass = 0; pass < 2; ++pass) m_project_out(M, basis, x);  // twice is enough (Kahan)
    Vector mx(M.layout());
    check(MatMult(M.get(), x.get(), mx.get()), "MatMult");
    PetscScalar x_m_x = 0;
    check(VecDot(x.get(), mx.get(), &x_m_x), "VecDot");
    if (!(x_m_x > 0)) throw std::invalid_argument("solve_interval: the deflation vectors are linearly dependent");
    check(VecScale(x.get(), 1 / std::sqrt(x_m_x)), "VecScale");
    basis.push_back(std::move(x));
  }
  return basis;
}

// SLEPc 3.18 refuses a deflation space with spectrum slicing, so the interval is solved in full and
// the pairs lying in the deflation space (more than half their M-norm in it) are dropped after; the
// rest are made exactly M-orthogonal to it.
void remove_deflated(const Matrix& M, std::span<const Vector> deflation, EigenSolution& out) {
  if (deflation.empty()) return;
  const std::vector<Vector> z = m_orthonormal_basis(M, deflation);
  std::vector<double> lambdas;
  std::vector<Vector> vectors;
  for (std::size_t i = 0; i < out.lambdas.size(); ++i) {
    if (m_project_out(M, z, out.vectors[i]) >= 0.5) continue;
    lambdas.push_back(out.lambdas[i]);
    vectors.push_back(std::move(out.vectors[i]));
  }
  out.lambdas = std::move(lambdas);
  out.vectors = std::move(vectors);
}

void finish_pairs(const Matrix& K, const Matrix& M, EigenSolution& out) {
  const Vector reference = sign_reference(K.layout());
  for (std::size_t i = 0; i < out.lambdas.size(); ++i)
    out.relative_residuals.push_back(finish_pair(K, M, out.lambdas[i], reference, out.vectors[i]));
}

double rayleigh_quotient(const Matrix& K, const Matrix& M, const Vector& x) {
  Vector y(K.layout());
  PetscScalar x_k_x = 0, x_m_x = 0;
  check(MatMult(K.get(), x.get(), y.get()), "MatMult");
  check(VecDot(x.get(), y.get(), &x_k_x), "VecDot");
  check(MatMult(M.get(), x.get(), y.get()), "MatMult");
  check(VecDot(x.get(), y.get(), &x_m_x), "VecDot");
  return x_k_x / x_m_x;
}

// Sylvester at both ends, independent of SLEPc's own bookkeeping; throws CountMismatch.
void count_check(const Matrix& K, const Matrix& M, const SliceSettings& s, std::span<const Vector> deflation,
                 EigenSolution& out) {
  Stage stage("count check");
  out.below_lo = eigenvalues_below(K, M, s.lambda_lo);
  out.below_hi = eigenvalues_below(K, M, s.lambda_hi, &out.stats.check_factor);
  for (const Vector& v : deflation) {
    const double lambda = rayleigh_quotient(K, M, v);
    if (lambda >= s.lambda_lo && lambda <= s.lambda_hi) ++out.deflated_in_interval;
  }
  for (double lambda : out.lambdas)
    if (lambda < s.lambda_lo || lambda > s.lambda_hi)
      throw std::runtime_error("solve_interval: SLEPc returned lambda = " + std::to_string(lambda) + " outside the interval");
  check_count(static_cast<PetscInt>(out.lambdas.size()), out.below_hi - out.below_lo - out.deflated_in_interval,
              s.lambda_lo, s.lambda_hi);
}

double resident_memory_max_mb(MPI_Comm comm) {
  PetscLogDouble bytes = 0;
  check(PetscMemoryGetCurrentUsage(&bytes), "PetscMemoryGetCurrentUsage");
  return mpi::all_reduce_max(comm, bytes / 1e6);
}

}  // namespace

Options slice_options(const SliceSettings& s, bool same_pattern) {
  char interval[64];
  std::snprintf(interval, sizeof interval, "%.17g,%.17g", s.lambda_lo, s.lambda_hi);
  Options o;
  o.set("-eps_type", "krylovschur").set("-eps_gen_hermitian").set("-eps_all").set("-eps_interval", interval);
  o.set("-eps_tol", s.tolerance);
  if (s.max_iterations > 0) o.set("-eps_max_it", static_cast<long long>(s.max_iterations));
  if (s.nev_per_shift > 0) o.set("-eps_krylovschur_nev", static_cast<long long>(s.nev_per_shift));
  o.set("-st_type", "sinvert").set("-st_ksp_type", "preonly").set("-st_pc_type", "cholesky");
  o.set("-st_pc_factor_mat_solver_type", "mumps").set("-st_mat_mumps_icntl_13", 1LL);
  o.set("-st_matstructure", same_pattern ? "same" : "different");
  return o;
}

EigenSolution solve_interval(const Matrix& K, const Matrix& M, const SliceSettings& settings,
                             std::span<const Vector> deflation) {
  validate(K, M, settings, deflation);
  Stage stage("eigensolve");
  EigenSolution out;
  const Options options = slice_options(settings, K.pattern_fingerprint() == M.pattern_fingerprint());
  out.options = options.text();
  const ScopedOptions scoped(options, next_prefix());
  EpsPtr eps = make_solver(K, M, scoped.prefix());
  out.stats.setup_s = timed_step("setup", out.stats, [&] { check(EPSSetUp(eps.get()), "EPSSetUp"); });
  out.stats.solve_s = timed_step("solve", out.stats, [&] { check(EPSSolve(eps.get()), "EPSSolve"); });
  require_mumps_inertia(eps.get());
  PetscReal* shifts = nullptr;
  PetscInt* inertias = nullptr;
  check(EPSKrylovSchurGetInertias(eps.get(), &out.stats.shifts, &shifts, &inertias), "EPSKrylovSchurGetInertias");
  PetscFree(shifts);
  PetscFree(inertias);
  if (auto unused = scoped.unused(); !unused.empty())
    throw std::logic_error("solve_interval: PETSc never read option " + unused.front());
  collect(eps.get(), K, out);
  remove_deflated(M, deflation, out);
  finish_pairs(K, M, out);
  out.stats.memory_max_mb = resident_memory_max_mb(K.layout().comm());
  eps.reset();
  count_check(K, M, settings, deflation, out);
  return out;
}

EigenSolution lowest_eigenpairs(const Matrix& K, const Matrix& M, const LowestSettings& settings,
                                std::span<const Vector> deflation) {
  if (!(K.layout() == M.layout())) throw std::invalid_argument("lowest_eigenpairs: K and M have different row layouts");
  if (!(std::isfinite(settings.shift) && settings.count >= 1 && settings.tolerance > 0 && settings.tolerance < 1 &&
        settings.max_iterations >= 0))
    throw std::invalid_argument("lowest_eigenpairs: need a finite shift, count >= 1, tolerance in (0, 1), max_iterations >= 0");
  Stage stage("eigensolve");
  Options o;
  o.set("-eps_type", "krylovschur").set("-eps_gen_hermitian").set("-eps_nev", static_cast<long long>(settings.count));
  o.set("-eps_target", settings.shift).set("-eps_target_magnitude").set("-eps_tol", settings.tolerance);
  if (settings.max_iterations > 0) o.set("-eps_max_it", static_cast<long long>(settings.max_iterations));
  o.set("-st_type", "sinvert").set("-st_ksp_type", "preonly").set("-st_pc_type", "cholesky");
  o.set("-st_pc_factor_mat_solver_type", "mumps");
  o.set("-st_matstructure", K.pattern_fingerprint() == M.pattern_fingerprint() ? "same" : "different");
  EigenSolution out;
  out.options = o.text();
  const ScopedOptions scoped(o, next_prefix());
  EpsPtr eps = make_solver(K, M, scoped.prefix());
  std::vector<Vec> space;
  for (const Vector& v : deflation) space.push_back(v.get());
  if (!space.empty())
    check(EPSSetDeflationSpace(eps.get(), static_cast<PetscInt>(space.size()), space.data()), "EPSSetDeflationSpace");
  out.stats.setup_s = timed_step("setup", out.stats, [&] { check(EPSSetUp(eps.get()), "EPSSetUp"); });
  out.stats.solve_s = timed_step("solve", out.stats, [&] { check(EPSSolve(eps.get()), "EPSSolve"); });
  out.stats.shifts = 1;
  if (auto unused = scoped.unused(); !unused.empty())
    throw std::logic_error("lowest_eigenpairs: PETSc never read option " + unused.front());
  collect(eps.get(), K, out);
  if (static_cast<PetscInt>(out.lambdas.size()) < settings.count)
    throw std::runtime_error("lowest_eigenpairs: " + std::to_string(out.lambdas.size()) + " of " +
                             std::to_string(settings.count) + " eigenpairs converged");
  out.lambdas.resize(static_cast<std::size_t>(settings.count));
  out.vectors.erase(out.vectors.begin() + settings.count, out.vectors.end());
  finish_pairs(K, M, out);
  return out;
}

}  // namespace clatter::petsc
