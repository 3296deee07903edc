// The TOML config reader with the PAN bank's schema (io::Config::merge_toml, jobs::pan_schema)
// and the PAN spec's checks (jobs::make_pan_spec). Only InputError may come out. A config that
// reads prints as TOML that reads back to the same config (io/config.hpp promises it: a bank's
// provenance is re-run from that text).
#include <string_view>

#include "core/errors.hpp"
#include "io/config.hpp"
#include "banks/pan/pan_spec.hpp"
#include "tests/fuzz/fuzz_input.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace clatter;
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  io::Config config(jobs::pan_schema());
  try {
    config.merge_toml(text, "fuzz.toml");
  } catch (const InputError&) {
    return 0;
  }
  const std::string printed = config.to_toml();
  io::Config again(jobs::pan_schema());
  again.merge_toml(printed, "printed.toml");
  if (again.to_toml() != printed) fuzz::broken("to_toml does not read back to the same config");
  try {
    const jobs::PanSpec spec = jobs::make_pan_spec(config);
    if (spec.length < 2 || (spec.length & (spec.length - 1)) != 0) fuzz::broken("wavelet length not a power of two");
  } catch (const InputError&) {
  }
  return 0;
}
