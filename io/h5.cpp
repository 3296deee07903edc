#include "io/h5.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <fmt/format.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <stdexcept>

#include "core/cleanup.hpp"
#include "core/errors.hpp"
#include "io/h5_detail.hpp"

namespace clatter::io {

namespace detail {

void silence_hdf5() { H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr); }

std::string hdf5_error_text() {
  std::string text;
  H5Ewalk2(
      H5E_DEFAULT, H5E_WALK_UPWARD,
      [](unsigned n, const H5E_error2_t* e, void* out) -> herr_t {
        if (n == 0 && e->desc) *static_cast<std::string*>(out) = e->desc;
        return 0;
      },
      &text);
  H5Eclear2(H5E_DEFAULT);
  return text.empty() ? "unknown HDF5 error" : text;
}

void fail(const std::string& path, const std::string& what) {
  throw std::runtime_error(path + ": " + what + " (HDF5: " + hdf5_error_text() + ")");
}

Handle link_create_plist() {
  Handle lcpl(H5Pcreate(H5P_LINK_CREATE), H5Pclose);
  H5Pset_create_intermediate_group(lcpl.get(), 1);
  return lcpl;
}

}  // namespace detail

using namespace detail;

namespace {

// fsync a path opened read-only; directories too, so a rename survives a crash.
bool fsync_path(const std::string& path) {
  int fd = ::open(path.c_str(), O_RDONLY);
  if (fd < 0) return false;
  bool ok = ::fsync(fd) == 0;
  ::close(fd);
  return ok;
}

}  // namespace

Handle& Handle::operator=(Handle&& o) noexcept {
  if (this != &o) {
    reset();
    id_ = std::exchange(o.id_, H5I_INVALID_HID);
    close_ = o.close_;
  }
  return *this;
}

void Handle::reset() {
  if (id_ >= 0 && close_) close_(id_);
  id_ = H5I_INVALID_HID;
}

File File::create(const std::string& path) { return create(path, nullptr); }

File File::create(const std::string& path, std::unique_ptr<const Collective> collective) {
  silence_hdf5();
  namespace fs = std::filesystem;
  File f;
  f.path_ = path;
  f.collective_ = std::move(collective);
  const fs::path final_path(path);
  if (final_path.has_parent_path()) fs::create_directories(final_path.parent_path());
  // One temporary name for all ranks: rank 0's pid and clock, so two runs never collide.
  long long token[2] = {static_cast<long long>(::getpid()),
                        static_cast<long long>(std::chrono::steady_clock::now().time_since_epoch().count())};
  f.broadcast(token, sizeof token);
  // Hidden, in the same folder (so the final rename is atomic), e.g. ".field.h5.tmp-4242-917".
  std::string temp_name = fmt::format(".{}.tmp-{}-{}", final_path.filename().string(), token[0], token[1] % 1000000);
  f.temp_path_ = (final_path.parent_path() / temp_name).string();
  Handle fapl(H5Pcreate(H5P_FILE_ACCESS), H5Pclose);
  if (f.parallel() && !f.collective_->set_file_access(fapl.get())) fail(path, "cannot set up MPI-IO");
  register_temporary(f.temp_path_);
  hid_t id = H5Fcreate(f.temp_path_.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl.get());
  if (id < 0) {
    unregister_temporary(f.temp_path_);
    fail(path, "cannot create");
  }
  f.file_ = Handle(id, H5Fclose);
  return f;
}

File File::open(const std::string& path) {
  silence_hdf5();
  if (!std::filesystem::exists(path)) throw InputError(path + ": no such file");
  File f;
  f.path_ = path;
  hid_t id = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  if (id < 0) {
    H5Eclear2(H5E_DEFAULT);
    throw InputError(path + ": not a readable HDF5 file");
  }
  f.file_ = Handle(id, H5Fclose);
  return f;
}

File::File(File&& o) noexcept
    : path_(std::move(o.path_)),
      temp_path_(std::move(o.temp_path_)),
      collective_(std::move(o.collective_)),
      file_(std::move(o.file_)) {
  o.temp_path_.clear();
}


File::~File() { discard(); }

void File::discard() noexcept {
  if (temp_path_.empty()) return;
  // A parallel close is collective; an abandoned output may be abandoned by one rank alone (it is
  // unwinding towards MPI_Abort), so only a serial file is closed here. The temporary goes either way.
  if (parallel())
    file_.release();  // HDF5 closes it at MPI_Finalize, or MPI_Abort ends the process first
  else
    file_.reset();
  std::remove(temp_path_.c_str());
  unregister_temporary(temp_path_);
  temp_path_.clear();
}

void File::commit() {
  if (temp_path_.empty()) throw std::logic_error(path_ + ": commit() on a file not open for writing");
  if (H5Fclose(file_.release()) < 0) fail(path_, "cannot close");
  int error = 0;
  if (rank() == 0) {
    if (!fsync_path(temp_path_))
      error = errno ? errno : EIO;
    else if (std::rename(temp_path_.c_str(), path_.c_str()) != 0)
      error = errno;
    else {
      auto dir = std::filesystem::path(path_).parent_path();
      fsync_path(dir.empty() ? "." : dir.string());
    }
  }
  broadcast(&error, sizeof error);
  unregister_temporary(temp_path_);
  if (error != 0) {
    if (rank() == 0) std::remove(temp_path_.c_str());
    temp_path_.clear();
    throw std::runtime_error(path_ + ": cannot move into place: " + std::strerror(error));
  }
  temp_path_.clear();
}

namespace detail {
template <Element T>
void write_block(File& file, const std::string& name, const Dims& global_dims, const Dims& offset,
                 const Dims& count, std::span<const T> data, std::string_view units, bool compress) {
  if (offset.size() != global_dims.size() || count.size() != global_dims.size() || data.size() != element_count(count))
    throw std::invalid_argument(file.path() + ": dataset '" + name + "': block does not match its data");
  Handle file_space(H5Screate_simple(static_cast<int>(global_dims.size()), global_dims.data(), nullptr), H5Sclose);
  auto lcpl = link_create_plist();
  Handle dcpl(H5Pcreate(H5P_DATASET_CREATE), H5Pclose);
  if (compress && element_count(global_dims) > 0) {
    if (file.parallel()) throw std::logic_error(file.path() + ": compressed datasets are written serially");
    // Chunks of at most 2^18 elements along the first axis: small enough to cache, big enough to compress.
    Dims chunk = global_dims;
    const hsize_t rest = element_count(global_dims) / global_dims[0];
    chunk[0] = std::max<hsize_t>(1, std::min<hsize_t>(global_dims[0], (hsize_t{1} << 18) / std::max<hsize_t>(rest, 1)));
    H5Pset_chunk(dcpl.get(), static_cast<int>(chunk.size()), chunk.data());
    H5Pset_fletcher32(dcpl.get());
    H5Pset_shuffle(dcpl.get());
    H5Pset_deflate(dcpl.get(), 6);
  }
  Handle dset(H5Dcreate2(file.id(), name.c_str(), native_type<T>(), file_space.get(), lcpl.get(), dcpl.get(),
                         H5P_DEFAULT),
              H5Dclose);
  if (dset.get() < 0) fail(file.path(), "cannot create dataset '" + name + "'");
  const bool empty = element_count(count) == 0;
  Handle mem_space(H5Screate_simple(static_cast<int>(count.size()), count.data(), nullptr), H5Sclose);
  if (empty) {
    H5Sselect_none(file_space.get());
    H5Sselect_none(mem_space.get());
  } else if (H5Sselect_hyperslab(file_space.get(), H5S_SELECT_SET, offset.data(), nullptr, count.data(), nullptr) < 0) {
    fail(file.path(), "dataset '" + name + "': block outside the dataset");
  }
  Handle dxpl(H5Pcreate(H5P_DATASET_XFER), H5Pclose);
  if (file.parallel() && !file.collective()->set_transfer(dxpl.get()))
    fail(file.path(), "dataset '" + name + "': cannot set up a collective write");
  if (H5Dwrite(dset.get(), native_type<T>(), mem_space.get(), file_space.get(), dxpl.get(), data.data()) < 0)
    fail(file.path(), "cannot write dataset '" + name + "'");
  dset.reset();
  write_attribute(file, name, "units", units);
}
}  // namespace detail

template <Element T>
void write_dataset(File& file, const std::string& name, std::span<const T> data, const Dims& dims,
                   std::string_view units, bool compress) {
  // On a parallel file rank 0's copy is the one written; the call stays collective.
  const bool writer = file.rank() == 0;
  Dims count = writer ? dims : Dims(dims.size(), 0);
  write_block<T>(file, name, dims, Dims(dims.size(), 0), count,
                 writer ? data : std::span<const T>(), units, compress);
}

#define CLATTER_H5_INSTANTIATE(T)                                                                                 \
  template void write_dataset<T>(File&, const std::string&, std::span<const T>, const Dims&, std::string_view,  \
                                  bool);                                                                         \
  template void detail::write_block<T>(File&, const std::string&, const Dims&, const Dims&, const Dims&,         \
                                       std::span<const T>, std::string_view, bool);
CLATTER_H5_ELEMENT_TYPES(CLATTER_H5_INSTANTIATE)
#undef CLATTER_H5_INSTANTIATE

}  // namespace clatter::io
