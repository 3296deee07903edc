#pragma once
// The Daubechies wavelet with 5 vanishing moments (GSL member 10), periodic, on power-of-two
// lengths. Coefficient order (GSL's packed form, as the paper's section 4.2 assumes): [0] the
// smoothing coefficient, [2^l, 2^(l+1)) the details of level l; so the first T/2 coefficients
// divided by sqrt(2) describe the same signal at half the sample rate (Algorithm 1).
#include <cstddef>
#include <memory>
#include <vector>

namespace clatter::kernels::pan {

class Wavelet {
 public:
  explicit Wavelet(std::size_t length);  // a power of two >= 2
  ~Wavelet();
  Wavelet(const Wavelet&) = delete;
  Wavelet& operator=(const Wavelet&) = delete;
  std::size_t length() const { return n_; }
  void forward(std::vector<double>& data) const;  // in place, data.size() == length()
  void inverse(std::vector<double>& data) const;  // any power-of-two size <= length()
  // DC group delay of the scaling filter, sum n h_n / sum h_n, in samples (1.19 for this member):
  // a reconstruction from the first T / 2^L coefficients lags by (2^L - 1) times this, in samples
  // of the full rate (measured 1.2, 3.7 for L = 1, 2; docs/pan.md).
  double scaling_delay_samples() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  std::size_t n_;
};

std::size_t next_power_of_two(std::size_t n);

// A transform of this length, built once per thread (GSL allocates filters and a workspace; the
// synthesizer evaluates a field per impact).
const Wavelet& cached_wavelet(std::size_t length);

}  // namespace clatter::kernels::pan
