#pragma once
// RAII HDF5 files, datasets and attributes with checked reads. Every file Clatter creates is
// written under a temporary name and appears under its final name only on commit(); a run that
// fails before then leaves no output file at all.
// Serial API: this header and io/h5.cpp compile against a serial or a parallel HDF5 alike and know
// nothing of MPI. Files shared by MPI ranks are created by io/h5_parallel.hpp (parallel build only).
#include <hdf5.h>

#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace clatter::io {

// Owns one HDF5 identifier and closes it with the matching H5?close.
class Handle {
 public:
  using Closer = herr_t (*)(hid_t);
  Handle() = default;
  Handle(hid_t id, Closer close) : id_(id), close_(close) {}
  ~Handle() { reset(); }
  Handle(Handle&& o) noexcept : id_(std::exchange(o.id_, H5I_INVALID_HID)), close_(o.close_) {}
  Handle& operator=(Handle&& o) noexcept;
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  hid_t get() const { return id_; }
  // Gives up ownership without closing, for a close whose result must be checked.
  hid_t release() { return std::exchange(id_, H5I_INVALID_HID); }
  void reset();

 private:
  hid_t id_ = H5I_INVALID_HID;
  Closer close_ = nullptr;
};

// How the ranks sharing one file agree. io/h5_parallel.cpp implements it over an MPI communicator;
// a serial file has none.
class Collective {
 public:
  virtual ~Collective() = default;
  virtual int rank() const = 0;
  // Every rank's `bytes` bytes at `data` become rank 0's.
  virtual void broadcast(void* data, std::size_t bytes) const = 0;
  // MPI-IO on a file access property list; collective transfers on a dataset transfer one.
  virtual bool set_file_access(hid_t fapl) const = 0;
  virtual bool set_transfer(hid_t dxpl) const = 0;
};

class File {
 public:
  // Creates `path` (and its parent folders) for writing, under a temporary name in the same folder.
  static File create(const std::string& path);
  // The same, shared by the ranks of `collective` (io::create_parallel makes one over MPI-IO): this
  // call, every write of a dataset or attribute, commit() and destruction are collective.
  static File create(const std::string& path, std::unique_ptr<const Collective> collective);
  // Opens an existing file read-only (serial). Errors name the file.
  static File open(const std::string& path);

  File(File&&) noexcept;
  File& operator=(File&&) = delete;
  File(const File&) = delete;
  File& operator=(const File&) = delete;
  // An uncommitted output is closed and its temporary removed.
  ~File();

  // Closes the file, flushes it to stable storage (fsync) and renames it to its final path.
  void commit();

  const std::string& path() const { return path_; }
  hid_t id() const { return file_.get(); }
  bool parallel() const { return collective_ != nullptr; }
  const Collective* collective() const { return collective_.get(); }
  // This process's rank among the file's (0 for a serial file).
  int rank() const { return collective_ ? collective_->rank() : 0; }
  // Rank 0's bytes to every rank of a parallel file; nothing to do for a serial one.
  void broadcast(void* data, std::size_t bytes) const {
    if (collective_) collective_->broadcast(data, bytes);
  }

 private:
  File() = default;
  void discard() noexcept;
  std::string path_;       // the final name, used in every message
  std::string temp_path_;  // empty for files opened for reading
  std::unique_ptr<const Collective> collective_;  // null for a serial file
  Handle file_;
};

// Element types Clatter stores.
template <class T>
concept Element = std::is_same_v<T, float> || std::is_same_v<T, double> || std::is_same_v<T, std::int32_t> ||
                  std::is_same_v<T, std::int64_t> || std::is_same_v<T, std::uint8_t> ||
                  std::is_same_v<T, std::uint32_t> || std::is_same_v<T, std::uint64_t> ||
                  std::is_same_v<T, std::int16_t> || std::is_same_v<T, std::uint16_t>;

using Dims = std::vector<hsize_t>;

// Writes a whole dataset from this process (serial files) with a "units" attribute ("1" for
// dimensionless). Parent groups are created as needed. `compress`: chunked, byte-shuffled,
// deflated and Fletcher-32 checksummed, so corruption is detected on read (serial files only).
template <Element T>
void write_dataset(File& file, const std::string& name, std::span<const T> data, const Dims& dims,
                   std::string_view units, bool compress = false);

// Scalar attributes on `object` ("/" for the file). On a parallel file every rank must pass the same value.
template <Element T>
void write_attribute(File& file, const std::string& object, const std::string& name, T value);
void write_attribute(File& file, const std::string& object, const std::string& name, std::string_view value);

// Reads a dataset after checking that its element type is T, its shape matches `expected_dims`
// (-1 matches any extent) and its "units" attribute equals `expected_units`. A mismatch throws
// InputError naming the file, dataset, expected and found. `found_dims` receives the shape.
template <Element T>
std::vector<T> read_dataset(const File& file, const std::string& name, const std::vector<long long>& expected_dims,
                            std::string_view expected_units, Dims* found_dims = nullptr);

template <Element T>
T read_attribute(const File& file, const std::string& object, const std::string& name);
std::string read_string_attribute(const File& file, const std::string& object, const std::string& name);

bool has_attribute(const File& file, const std::string& object, const std::string& name);
bool exists(const File& file, const std::string& name);
// Creates a group (and its parents). Collective on a parallel file.
void create_group(File& file, const std::string& name);
// The names of a group's members (groups and datasets), in name order; InputError naming the file
// when `group` is not a group.
std::vector<std::string> group_members(const File& file, const std::string& group);

}  // namespace clatter::io
