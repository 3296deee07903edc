#include "io/h5.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <fmt/format.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <numeric>
#include <stdexcept>

#include "core/cleanup.hpp"
#include "core/errors.hpp"

namespace clatter::io {
namespace {

// HDF5 prints its error stack to stderr by default; Clatter reports errors itself, in one line.
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

[[noreturn]] void fail(const std::string& path, const std::string& what) {
  throw std::runtime_error(path + ": " + what + " (HDF5: " + hdf5_error_text() + ")");
}

template <class T>
hid_t native_type() {
  if constexpr (std::is_same_v<T, float>) return H5T_NATIVE_FLOAT;
  if constexpr (std::is_same_v<T, double>) return H5T_NATIVE_DOUBLE;
  if constexpr (std::is_same_v<T, std::int32_t>) return H5T_NATIVE_INT32;
  if constexpr (std::is_same_v<T, std::int64_t>) return H5T_NATIVE_INT64;
  if constexpr (std::is_same_v<T, std::uint8_t>) return H5T_NATIVE_UINT8;
  if constexpr (std::is_same_v<T, std::uint32_t>) return H5T_NATIVE_UINT32;
  if constexpr (std::is_same_v<T, std::uint64_t>) return H5T_NATIVE_UINT64;
  if constexpr (std::is_same_v<T, std::int16_t>) return H5T_NATIVE_INT16;
  if constexpr (std::is_same_v<T, std::uint16_t>) return H5T_NATIVE_UINT16;
}

template <class T>
std::string type_name() {
  if constexpr (std::is_floating_point_v<T>) return "float" + std::to_string(8 * sizeof(T));
  if constexpr (std::is_signed_v<T>) return "int" + std::to_string(8 * sizeof(T));
  return "uint" + std::to_string(8 * sizeof(T));
}

std::string type_name(hid_t type) {
  const std::size_t bits = 8 * H5Tget_size(type);
  switch (H5Tget_class(type)) {
    case H5T_FLOAT: return "float" + std::to_string(bits);
    case H5T_INTEGER: return (H5Tget_sign(type) == H5T_SGN_NONE ? "uint" : "int") + std::to_string(bits);
    case H5T_STRING: return "string";
    case H5T_COMPOUND: return "compound";
    default: return "type class " + std::to_string(static_cast<int>(H5Tget_class(type)));
  }
}

template <class T>
bool type_matches(hid_t type) {
  const H5T_class_t want = std::is_floating_point_v<T> ? H5T_FLOAT : H5T_INTEGER;
  if (H5Tget_class(type) != want || H5Tget_size(type) != sizeof(T)) return false;
  if constexpr (std::is_integral_v<T>) return (H5Tget_sign(type) != H5T_SGN_NONE) == std::is_signed_v<T>;
  return true;
}

std::string shape_text(const std::vector<long long>& dims) {
  std::string s = "[";
  for (std::size_t i = 0; i < dims.size(); ++i)
    s += (i ? ", " : "") + (dims[i] < 0 ? std::string("*") : std::to_string(dims[i]));
  return s + "]";
}

std::string shape_text(const Dims& dims) { return shape_text(std::vector<long long>(dims.begin(), dims.end())); }

hsize_t element_count(const Dims& dims) {
  return std::accumulate(dims.begin(), dims.end(), hsize_t{1}, std::multiplies<>());
}

Handle link_create_plist() {
  Handle lcpl(H5Pcreate(H5P_LINK_CREATE), H5Pclose);
  H5Pset_create_intermediate_group(lcpl.get(), 1);
  return lcpl;
}

int comm_rank(MPI_Comm comm) {
  int r = 0;
  if (comm != MPI_COMM_NULL) MPI_Comm_rank(comm, &r);
  return r;
}

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

File File::create(const std::string& path, MPI_Comm comm) {
  silence_hdf5();
  namespace fs = std::filesystem;
  File f;
  f.path_ = path;
  f.comm_ = comm;
  const fs::path final_path(path);
  if (final_path.has_parent_path()) fs::create_directories(final_path.parent_path());
  // One temporary name for all ranks: rank 0's pid and clock, so two runs never collide.
  long long token[2] = {static_cast<long long>(::getpid()),
                        static_cast<long long>(std::chrono::steady_clock::now().time_since_epoch().count())};
  if (comm != MPI_COMM_NULL) MPI_Bcast(token, 2, MPI_LONG_LONG, 0, comm);
  // Hidden, in the same folder (so the final rename is atomic), e.g. ".field.h5.tmp-4242-917".
  std::string temp_name = fmt::format(".{}.tmp-{}-{}", final_path.filename().string(), token[0], token[1] % 1000000);
  f.temp_path_ = (final_path.parent_path() / temp_name).string();
  Handle fapl(H5Pcreate(H5P_FILE_ACCESS), H5Pclose);
  if (comm != MPI_COMM_NULL && H5Pset_fapl_mpio(fapl.get(), comm, MPI_INFO_NULL) < 0)
    fail(path, "cannot set up MPI-IO");
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
    : path_(std::move(o.path_)), temp_path_(std::move(o.temp_path_)), comm_(o.comm_), file_(std::move(o.file_)) {
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
  if (comm_rank(comm_) == 0) {
    if (!fsync_path(temp_path_))
      error = errno ? errno : EIO;
    else if (std::rename(temp_path_.c_str(), path_.c_str()) != 0)
      error = errno;
    else {
      auto dir = std::filesystem::path(path_).parent_path();
      fsync_path(dir.empty() ? "." : dir.string());
    }
  }
  if (parallel()) MPI_Bcast(&error, 1, MPI_INT, 0, comm_);
  unregister_temporary(temp_path_);
  if (error != 0) {
    if (comm_rank(comm_) == 0) std::remove(temp_path_.c_str());
    temp_path_.clear();
    throw std::runtime_error(path_ + ": cannot move into place: " + std::strerror(error));
  }
  temp_path_.clear();
}

template <Element T>
void write_dataset_block(File& file, const std::string& name, const Dims& global_dims, const Dims& offset,
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
  if (file.parallel()) H5Pset_dxpl_mpio(dxpl.get(), H5FD_MPIO_COLLECTIVE);
  if (H5Dwrite(dset.get(), native_type<T>(), mem_space.get(), file_space.get(), dxpl.get(), data.data()) < 0)
    fail(file.path(), "cannot write dataset '" + name + "'");
  dset.reset();
  write_attribute(file, name, "units", units);
}

template <Element T>
void write_dataset(File& file, const std::string& name, std::span<const T> data, const Dims& dims,
                   std::string_view units, bool compress) {
  // On a parallel file rank 0's copy is the one written; the call stays collective.
  const bool writer = comm_rank(file.comm()) == 0;
  Dims count = writer ? dims : Dims(dims.size(), 0);
  write_dataset_block<T>(file, name, dims, Dims(dims.size(), 0), count,
                         writer ? data : std::span<const T>(), units, compress);
}

namespace {
Handle open_object(const File& file, const std::string& object) {
  Handle obj(H5Oopen(file.id(), object.c_str(), H5P_DEFAULT), H5Oclose);
  if (obj.get() < 0) {
    H5Eclear2(H5E_DEFAULT);
    throw InputError(file.path() + ": object '" + object + "' not found");
  }
  return obj;
}

Handle create_attribute(File& file, const std::string& object, const std::string& name, hid_t type) {
  auto obj = open_object(file, object);
  if (H5Aexists(obj.get(), name.c_str()) > 0) H5Adelete(obj.get(), name.c_str());
  Handle space(H5Screate(H5S_SCALAR), H5Sclose);
  Handle attr(H5Acreate2(obj.get(), name.c_str(), type, space.get(), H5P_DEFAULT, H5P_DEFAULT), H5Aclose);
  if (attr.get() < 0) fail(file.path(), "cannot create attribute '" + name + "' on '" + object + "'");
  return attr;
}

Handle open_attribute(const File& file, const std::string& object, const std::string& name) {
  auto obj = open_object(file, object);
  if (H5Aexists(obj.get(), name.c_str()) <= 0)
    throw InputError(file.path() + ": '" + object + "' has no attribute '" + name + "'");
  return Handle(H5Aopen(obj.get(), name.c_str(), H5P_DEFAULT), H5Aclose);
}
}  // namespace

template <Element T>
void write_attribute(File& file, const std::string& object, const std::string& name, T value) {
  auto attr = create_attribute(file, object, name, native_type<T>());
  if (H5Awrite(attr.get(), native_type<T>(), &value) < 0) fail(file.path(), "cannot write attribute '" + name + "'");
}

void write_attribute(File& file, const std::string& object, const std::string& name, std::string_view value) {
  // Variable-length UTF-8: h5py reads it as a Python str.
  Handle type(H5Tcopy(H5T_C_S1), H5Tclose);
  H5Tset_size(type.get(), H5T_VARIABLE);
  H5Tset_cset(type.get(), H5T_CSET_UTF8);
  auto attr = create_attribute(file, object, name, type.get());
  std::string text(value);
  const char* ptr = text.c_str();
  if (H5Awrite(attr.get(), type.get(), &ptr) < 0) fail(file.path(), "cannot write attribute '" + name + "'");
}

std::string read_string_attribute(const File& file, const std::string& object, const std::string& name) {
  auto attr = open_attribute(file, object, name);
  Handle type(H5Aget_type(attr.get()), H5Tclose);
  if (H5Tget_class(type.get()) != H5T_STRING)
    throw InputError(file.path() + ": attribute '" + name + "' of '" + object + "': expected a string, found " +
                     type_name(type.get()));
  if (H5Tis_variable_str(type.get()) > 0) {
    Handle mem(H5Tcopy(H5T_C_S1), H5Tclose);
    H5Tset_size(mem.get(), H5T_VARIABLE);
    H5Tset_cset(mem.get(), H5Tget_cset(type.get()));
    char* ptr = nullptr;
    if (H5Aread(attr.get(), mem.get(), &ptr) < 0) fail(file.path(), "cannot read attribute '" + name + "'");
    std::string s = ptr ? ptr : "";
    H5free_memory(ptr);
    return s;
  }
  std::string s(H5Tget_size(type.get()), '\0');
  if (H5Aread(attr.get(), type.get(), s.data()) < 0) fail(file.path(), "cannot read attribute '" + name + "'");
  return s.substr(0, s.find('\0'));
}

template <Element T>
T read_attribute(const File& file, const std::string& object, const std::string& name) {
  auto attr = open_attribute(file, object, name);
  Handle type(H5Aget_type(attr.get()), H5Tclose);
  Handle space(H5Aget_space(attr.get()), H5Sclose);
  if (!type_matches<T>(type.get()) || H5Sget_simple_extent_npoints(space.get()) != 1)
    throw InputError(file.path() + ": attribute '" + name + "' of '" + object + "': expected a scalar " +
                     type_name<T>() + ", found " + type_name(type.get()));
  T value{};
  if (H5Aread(attr.get(), native_type<T>(), &value) < 0) fail(file.path(), "cannot read attribute '" + name + "'");
  return value;
}

bool exists(const File& file, const std::string& name) {
  // H5Lexists needs every parent link to exist, so walk the path one component at a time.
  std::size_t pos = 0;
  while (pos != std::string::npos) {
    pos = name.find('/', pos + 1);
    std::string prefix = name.substr(0, pos);
    if (prefix.empty() || prefix == "/") continue;
    if (H5Lexists(file.id(), prefix.c_str(), H5P_DEFAULT) <= 0) {
      H5Eclear2(H5E_DEFAULT);
      return false;
    }
  }
  return true;
}

void create_group(File& file, const std::string& name) {
  auto lcpl = link_create_plist();
  Handle group(H5Gcreate2(file.id(), name.c_str(), lcpl.get(), H5P_DEFAULT, H5P_DEFAULT), H5Gclose);
  if (group.get() < 0) fail(file.path(), "cannot create group '" + name + "'");
}

template <Element T>
std::vector<T> read_dataset(const File& file, const std::string& name, const std::vector<long long>& expected_dims,
                            std::string_view expected_units, Dims* found_dims) {
  if (!exists(file, name)) throw InputError(file.path() + ": dataset '" + name + "' not found");
  Handle dset(H5Dopen2(file.id(), name.c_str(), H5P_DEFAULT), H5Dclose);
  if (dset.get() < 0) fail(file.path(), "cannot open dataset '" + name + "'");
  Handle type(H5Dget_type(dset.get()), H5Tclose);
  Handle space(H5Dget_space(dset.get()), H5Sclose);
  const int rank = H5Sget_simple_extent_ndims(space.get());
  Dims dims(static_cast<std::size_t>(std::max(rank, 0)));
  H5Sget_simple_extent_dims(space.get(), dims.data(), nullptr);
  std::string units = "(none)";
  if (H5Aexists(dset.get(), "units") > 0) units = read_string_attribute(file, name, "units");

  bool ok = type_matches<T>(type.get()) && dims.size() == expected_dims.size() && units == expected_units;
  for (std::size_t i = 0; ok && i < dims.size(); ++i)
    ok = expected_dims[i] < 0 || static_cast<hsize_t>(expected_dims[i]) == dims[i];
  if (!ok)
    throw InputError(file.path() + ": dataset '" + name + "': expected " + type_name<T>() + " " +
                     shape_text(expected_dims) + " in '" + std::string(expected_units) + "', found " +
                     type_name(type.get()) + " " + shape_text(dims) + " in '" + units + "'");
  std::vector<T> data(element_count(dims));
  if (H5Dread(dset.get(), native_type<T>(), H5S_ALL, H5S_ALL, H5P_DEFAULT, data.data()) < 0) {
    const std::string why = hdf5_error_text();
    throw InputError(file.path() + ": dataset '" + name + "' cannot be read: corrupt or truncated file (HDF5: " + why + ")");
  }
  if (found_dims) *found_dims = dims;
  return data;
}

#define CLATTER_H5_INSTANTIATE(T)                                                                                 \
  template void write_dataset<T>(File&, const std::string&, std::span<const T>, const Dims&, std::string_view,  \
                                  bool);                                                                         \
  template void write_dataset_block<T>(File&, const std::string&, const Dims&, const Dims&, const Dims&,         \
                                       std::span<const T>, std::string_view, bool);                              \
  template void write_attribute<T>(File&, const std::string&, const std::string&, T);                            \
  template std::vector<T> read_dataset<T>(const File&, const std::string&, const std::vector<long long>&,        \
                                          std::string_view, Dims*);                                              \
  template T read_attribute<T>(const File&, const std::string&, const std::string&);
CLATTER_H5_INSTANTIATE(float)
CLATTER_H5_INSTANTIATE(double)
CLATTER_H5_INSTANTIATE(std::int32_t)
CLATTER_H5_INSTANTIATE(std::int64_t)
CLATTER_H5_INSTANTIATE(std::uint8_t)
CLATTER_H5_INSTANTIATE(std::uint32_t)
CLATTER_H5_INSTANTIATE(std::uint64_t)
CLATTER_H5_INSTANTIATE(std::int16_t)
CLATTER_H5_INSTANTIATE(std::uint16_t)
#undef CLATTER_H5_INSTANTIATE

}  // namespace clatter::io
