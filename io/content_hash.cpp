#include "io/content_hash.hpp"

#include <algorithm>
#include <cstdio>

#include "core/errors.hpp"

namespace clatter::io {
namespace {

class Fnv1a {
 public:
  void bytes(const void* data, std::size_t n) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < n; ++i) h_ = (h_ ^ p[i]) * 0x100000001b3ULL;
  }
  void text(const std::string& s) {
    const std::uint64_t n = s.size();
    bytes(&n, sizeof n);  // length first: "ab" + "c" differs from "a" + "bc"
    bytes(s.data(), s.size());
  }
  void number(std::uint64_t v) { bytes(&v, sizeof v); }
  std::uint64_t value() const { return h_; }

 private:
  std::uint64_t h_ = 0xcbf29ce484222325ULL;
};

void fail(const File& file, const std::string& what) { throw InputError(file.path() + ": cannot hash " + what); }

// The type's class and size, and the values read in the matching native type.
void hash_values(Fnv1a& h, const File& file, const std::string& what, hid_t type, hid_t space,
                 herr_t (*read)(hid_t, hid_t, void*), hid_t object) {
  const H5T_class_t cls = H5Tget_class(type);
  h.number(static_cast<std::uint64_t>(cls));
  const int rank = H5Sget_simple_extent_ndims(space);
  std::vector<hsize_t> dims(static_cast<std::size_t>(std::max(rank, 0)));
  if (rank > 0) H5Sget_simple_extent_dims(space, dims.data(), nullptr);
  h.number(static_cast<std::uint64_t>(rank));
  for (hsize_t d : dims) h.number(d);
  const auto n = static_cast<std::size_t>(H5Sget_simple_extent_npoints(space));
  if (cls == H5T_STRING) {
    Handle mem(H5Tcopy(H5T_C_S1), H5Tclose);
    H5Tset_cset(mem.get(), H5Tget_cset(type));
    if (H5Tis_variable_str(type) > 0) {
      H5Tset_size(mem.get(), H5T_VARIABLE);
      std::vector<char*> text(n, nullptr);
      if (read(object, mem.get(), text.data()) < 0) fail(file, what);
      for (char* t : text) h.text(t ? t : "");
      Handle s(H5Scopy(space), H5Sclose);
      H5Dvlen_reclaim(mem.get(), s.get(), H5P_DEFAULT, text.data());
    } else {
      const std::size_t size = H5Tget_size(type);
      H5Tset_size(mem.get(), size);
      std::string text(n * size, '\0');
      if (read(object, mem.get(), text.data()) < 0) fail(file, what);
      h.text(text);
    }
    return;
  }
  Handle native(H5Tget_native_type(type, H5T_DIR_ASCEND), H5Tclose);
  const std::size_t size = H5Tget_size(native.get());
  h.number(size);
  std::vector<unsigned char> data(n * size);
  if (n > 0 && read(object, native.get(), data.data()) < 0) fail(file, what);
  h.bytes(data.data(), data.size());
}

herr_t read_attribute_values(hid_t attr, hid_t type, void* buf) { return H5Aread(attr, type, buf); }
herr_t read_dataset_values(hid_t dset, hid_t type, void* buf) {
  return H5Dread(dset, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, buf);
}

void hash_attributes(Fnv1a& h, const File& file, hid_t object, const std::string& path,
                     const std::vector<std::string>& skip) {
  std::vector<std::string> names;
  H5Aiterate2(
      object, H5_INDEX_NAME, H5_ITER_INC, nullptr,
      [](hid_t, const char* name, const H5A_info_t*, void* out) -> herr_t {
        static_cast<std::vector<std::string>*>(out)->push_back(name);
        return 0;
      },
      &names);
  for (const auto& name : names) {
    if (std::find(skip.begin(), skip.end(), name) != skip.end()) continue;
    Handle attr(H5Aopen(object, name.c_str(), H5P_DEFAULT), H5Aclose);
    if (attr.get() < 0) fail(file, path + " attribute " + name);
    Handle type(H5Aget_type(attr.get()), H5Tclose), space(H5Aget_space(attr.get()), H5Sclose);
    h.text("@" + name);
    hash_values(h, file, path + " attribute " + name, type.get(), space.get(), read_attribute_values, attr.get());
  }
}

}  // namespace

std::uint64_t content_hash(const File& file, const HashExclusions& exclude) {
  std::vector<std::string> paths;
  H5Lvisit(
      file.id(), H5_INDEX_NAME, H5_ITER_INC,
      [](hid_t, const char* name, const H5L_info_t*, void* out) -> herr_t {
        static_cast<std::vector<std::string>*>(out)->push_back(std::string("/") + name);
        return 0;
      },
      &paths);
  Fnv1a h;
  hash_attributes(h, file, file.id(), "/", exclude.root_attributes);
  for (const auto& path : paths) {
    bool skipped = false;
    for (const auto& g : exclude.groups)
      skipped = skipped || path == g || path.rfind(g + "/", 0) == 0;
    if (skipped) continue;
    Handle object(H5Oopen(file.id(), path.c_str(), H5P_DEFAULT), H5Oclose);
    if (object.get() < 0) fail(file, path);
    h.text(path);
    hash_attributes(h, file, object.get(), path, {});
    if (H5Iget_type(object.get()) == H5I_DATASET) {
      Handle type(H5Dget_type(object.get()), H5Tclose), space(H5Dget_space(object.get()), H5Sclose);
      hash_values(h, file, path, type.get(), space.get(), read_dataset_values, object.get());
    }
  }
  return h.value();
}

}  // namespace clatter::io
