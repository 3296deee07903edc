// Attributes, groups and checked reads of io/h5.hpp.
#include "io/h5.hpp"

#include <stdexcept>

#include "core/errors.hpp"
#include "io/h5_detail.hpp"

namespace clatter::io {

using namespace detail;

namespace {

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
  Handle space(H5Aget_space(attr.get()), H5Sclose);
  // An array of strings would be read whole into room for one.
  if (H5Tget_class(type.get()) != H5T_STRING || H5Sget_simple_extent_npoints(space.get()) != 1)
    throw InputError(file.path() + ": attribute '" + name + "' of '" + object + "': expected a string, found " +
                     type_name(type.get()) + " x " + std::to_string(H5Sget_simple_extent_npoints(space.get())));
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

bool has_attribute(const File& file, const std::string& object, const std::string& name) {
  return H5Aexists(open_object(file, object).get(), name.c_str()) > 0;
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

std::vector<std::string> group_members(const File& file, const std::string& group) {
  if (!exists(file, group)) throw InputError(file.path() + ": group '" + group + "' not found");
  Handle g(H5Gopen2(file.id(), group.c_str(), H5P_DEFAULT), H5Gclose);
  if (g.get() < 0) {
    H5Eclear2(H5E_DEFAULT);
    throw InputError(file.path() + ": '" + group + "' is not a group");
  }
  std::vector<std::string> names;
  auto add = [](hid_t, const char* name, const H5L_info_t*, void* out) -> herr_t {
    static_cast<std::vector<std::string>*>(out)->emplace_back(name);
    return 0;
  };
  if (H5Literate(g.get(), H5_INDEX_NAME, H5_ITER_INC, nullptr, add, &names) < 0)
    fail(file.path(), "cannot list group '" + group + "'");
  return names;
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
  template void write_attribute<T>(File&, const std::string&, const std::string&, T);                            \
  template std::vector<T> read_dataset<T>(const File&, const std::string&, const std::vector<long long>&,        \
                                          std::string_view, Dims*);                                              \
  template T read_attribute<T>(const File&, const std::string&, const std::string&);
CLATTER_H5_ELEMENT_TYPES(CLATTER_H5_INSTANTIATE)
#undef CLATTER_H5_INSTANTIATE

}  // namespace clatter::io
