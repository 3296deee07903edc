// The sweep task-file reader: io::inspect_task, then io::read_pan_task for a task it finds done
// (what merge_pan_results does), structure-aware like fuzz_pan_bank. The first input byte says
// whether the content hash is recomputed after mutating: without that, almost every mutation
// would stop at the hash check and the payload reader would never see it.
#include "core/errors.hpp"
#include "io/content_hash.hpp"
#include "io/pan_bank.hpp"
#include "io/sweep_files.hpp"
#include "tests/fuzz/bank_template.hpp"
#include "tests/fuzz/fuzz_input.hpp"
#include "tests/fuzz/h5_mutator.hpp"

namespace {

using namespace clatter;

constexpr const char* kSweepId = "0123456789abcdef";
constexpr const char* kTask = "p001-f3";

const std::vector<fuzz::H5Item>& template_items() {
  static const std::vector<fuzz::H5Item> items = [] {
    const std::string path = fuzz::scratch_path("template-task.h5");
    const io::TaskPayloadWriter payload = [](io::File& file, const std::string& group) {
      io::write_pan_task(file, group, fuzz::template_task(), fuzz::template_bank().header.lattice(), fuzz::kTemplateValues);
    };
    io::write_task_file(path, kSweepId, kTask, "done", "", &payload);
    return fuzz::take_apart(path);
  }();
  return items;
}

// Stores the hash of the mutated content, as a writer would have.
void rehash(std::vector<fuzz::H5Item>& items, const std::string& path) {
  std::string hash;
  try {
    hash = io::hash_hex(io::content_hash(io::File::open(path), {{}, {"content_hash"}}));
  } catch (const std::runtime_error&) {
    return;
  }
  for (auto& item : items)
    if (item.object == "/" && item.attribute == "content_hash") item.texts = {hash}, item.kind = fuzz::Kind::str_var, item.dims = {};
  fuzz::build(items, path);
}

void check(const model::PanTaskResult& t) {
  const auto& h = fuzz::template_bank().header;
  if (!t.fit.solved()) fuzz::broken("a task without directions");
  fuzz::check_field(t.fit, h.divisions, h.lattice(), h.values(), h.length);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  FuzzedDataProvider input(data, size);
  const bool recompute_hash = input.ConsumeBool();
  std::vector<fuzz::H5Item> items = template_items();
  fuzz::mutate(items, input);
  const std::string path = fuzz::scratch_path("task.h5");
  fuzz::build(items, path);
  if (recompute_hash) rehash(items, path);
  const io::TaskRecord record = io::inspect_task(path, kTask, kSweepId);  // never throws
  if (record.state != io::TaskState::done) return 0;
  try {
    const io::File file = io::File::open(path);
    check(io::read_pan_task(file, "/result", fuzz::template_bank().header));
  } catch (const std::runtime_error&) {
  }
  return 0;
}
