// The PAN bank reader (io::read_pan_bank), structure-aware (tests/fuzz/h5_mutator.hpp): a valid
// bank mutated item by item, rebuilt as a well-formed HDF5 file. It must end in InputError (bad
// content) or std::runtime_error (HDF5 could not read what it holds), and a bank it returns must be
// one the evaluator can index without checks (kernels/pan/field.hpp).
#include "core/errors.hpp"
#include "io/pan_bank.hpp"
#include "tests/fuzz/bank_template.hpp"
#include "tests/fuzz/fuzz_input.hpp"
#include "tests/fuzz/h5_mutator.hpp"

namespace {

using namespace clatter;

const std::vector<fuzz::H5Item>& template_items() {
  static const std::vector<fuzz::H5Item> items = [] {
    const std::string path = fuzz::scratch_path("template-bank.h5");
    io::write_pan_bank(path, fuzz::template_bank(), "fuzz", "", 1);
    return fuzz::take_apart(path);
  }();
  return items;
}

void check(const model::PanBank& bank) {
  const auto& h = bank.header;
  for (std::size_t i = 0; i < h.radii_m.size(); ++i)  // the radial model's nodes (kernels/pan/radial.hpp)
    if (!(h.radii_m[i] > 0) || (i > 0 && !(h.radii_m[i] > h.radii_m[i - 1]))) fuzz::broken("radii not positive ascending");
  if (h.divisions < 2 || h.divisions % 2 != 0 || h.max_levels < 0 || h.max_levels > 16 || h.divisions > (1 << 20) >> h.max_levels)
    fuzz::broken("layout or lattice out of range");
  for (const auto& p : bank.proxies) {
    for (const auto& field : p.fields) fuzz::check_field(field, h.divisions, h.lattice(), h.values(), h.length);
    if (p.is_mesh() && (p.mesh.support_points_m.empty() || !(p.mesh.scale > 0)))  // the support distance needs a point
      fuzz::broken("a mesh entry without support points or scale");
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  FuzzedDataProvider input(data, size);
  std::vector<fuzz::H5Item> items = template_items();
  fuzz::mutate(items, input);
  const std::string path = fuzz::scratch_path("bank.h5");
  fuzz::build(items, path);
  try {
    check(io::read_pan_bank(path));
  } catch (const std::runtime_error&) {  // InputError, or an HDF5 read failure
  }
  return 0;
}
