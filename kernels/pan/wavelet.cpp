#include "kernels/pan/wavelet.hpp"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_wavelet.h>

#include <map>
#include <stdexcept>
#include <string>

namespace clatter::kernels::pan {

struct Wavelet::Impl {
  gsl_wavelet* w = nullptr;
  gsl_wavelet_workspace* work = nullptr;
  ~Impl() {
    if (work) gsl_wavelet_workspace_free(work);
    if (w) gsl_wavelet_free(w);
  }
};

std::size_t next_power_of_two(std::size_t n) {
  std::size_t p = 2;
  while (p < n) p *= 2;
  return p;
}

Wavelet::Wavelet(std::size_t length) : impl_(std::make_unique<Impl>()), n_(length) {
  if (length < 2 || (length & (length - 1)) != 0)
    throw std::invalid_argument("wavelet length " + std::to_string(length) + " is not a power of two");
  gsl_set_error_handler_off();  // errors come back as return codes, turned into exceptions here
  impl_->w = gsl_wavelet_alloc(gsl_wavelet_daubechies, 10);
  impl_->work = gsl_wavelet_workspace_alloc(length);
  if (!impl_->w || !impl_->work) throw std::runtime_error("cannot allocate the GSL wavelet");
}

Wavelet::~Wavelet() = default;

const Wavelet& cached_wavelet(std::size_t length) {
  thread_local std::map<std::size_t, std::unique_ptr<Wavelet>> cache;
  auto& slot = cache[length];
  if (!slot) slot = std::make_unique<Wavelet>(length);
  return *slot;
}

double Wavelet::scaling_delay_samples() const {
  double moment = 0, sum = 0;
  for (std::size_t i = 0; i < impl_->w->nc; ++i) {
    moment += static_cast<double>(i) * impl_->w->h1[i];
    sum += impl_->w->h1[i];
  }
  return moment / sum;
}

void Wavelet::forward(std::vector<double>& data) const {
  if (data.size() != n_) throw std::invalid_argument("wavelet forward: wrong length");
  if (gsl_wavelet_transform_forward(impl_->w, data.data(), 1, n_, impl_->work) != GSL_SUCCESS)
    throw std::runtime_error("GSL wavelet forward transform failed");
}

void Wavelet::inverse(std::vector<double>& data) const {
  const std::size_t n = data.size();
  if (n < 2 || n > n_ || (n & (n - 1)) != 0) throw std::invalid_argument("wavelet inverse: bad length");
  if (gsl_wavelet_transform_inverse(impl_->w, data.data(), 1, n, impl_->work) != GSL_SUCCESS)
    throw std::runtime_error("GSL wavelet inverse transform failed");
}

}  // namespace clatter::kernels::pan
