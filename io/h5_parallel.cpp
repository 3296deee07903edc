#include "io/h5_parallel.hpp"

#include <optional>
#include <string>

#include "io/h5_detail.hpp"
#include "io/linked_libraries.hpp"

namespace clatter::io {
namespace {

class MpiCollective final : public Collective {
 public:
  explicit MpiCollective(MPI_Comm comm) : comm_(comm) {}
  int rank() const override {
    int r = 0;
    MPI_Comm_rank(comm_, &r);
    return r;
  }
  void broadcast(void* data, std::size_t bytes) const override {
    MPI_Bcast(data, static_cast<int>(bytes), MPI_BYTE, 0, comm_);
  }
  bool set_file_access(hid_t fapl) const override { return H5Pset_fapl_mpio(fapl, comm_, MPI_INFO_NULL) >= 0; }
  bool set_transfer(hid_t dxpl) const override { return H5Pset_dxpl_mpio(dxpl, H5FD_MPIO_COLLECTIVE) >= 0; }

 private:
  MPI_Comm comm_;
};

}  // namespace

File create_parallel(const std::string& path, MPI_Comm comm) {
  return File::create(path, std::make_unique<const MpiCollective>(comm));
}

template <Element T>
void write_dataset_block(File& file, const std::string& name, const Dims& global_dims, const Dims& offset,
                         const Dims& count, std::span<const T> data, std::string_view units, bool compress) {
  detail::write_block<T>(file, name, global_dims, offset, count, data, units, compress);
}

#define CLATTER_H5_INSTANTIATE(T)                                                                         \
  template void write_dataset_block<T>(File&, const std::string&, const Dims&, const Dims&, const Dims&, \
                                       std::span<const T>, std::string_view, bool);
CLATTER_H5_ELEMENT_TYPES(CLATTER_H5_INSTANTIATE)
#undef CLATTER_H5_INSTANTIATE

// Callable before MPI_Init (MPI 3.0), so --version needs no MPI start-up.
std::optional<std::string> mpi_library() {
  char text[MPI_MAX_LIBRARY_VERSION_STRING];
  int length = 0;  // Open MPI counts the terminating null in it
  if (MPI_Get_library_version(text, &length) != MPI_SUCCESS) return "unknown MPI library";
  const std::string s(text);  // null-terminated (MPI 3.0, 7.1.1)
  return s.substr(0, s.find_first_of("\n\r"));
}

}  // namespace clatter::io
