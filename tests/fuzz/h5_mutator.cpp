#include "tests/fuzz/h5_mutator.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>

namespace clatter::fuzz {
namespace {

struct Id {  // closes an HDF5 id on scope exit
  hid_t id;
  herr_t (*close)(hid_t);
  ~Id() {
    if (id >= 0 && close) close(id);
  }
};

hid_t file_type(Kind k, std::size_t fixed_size) {
  switch (k) {
    case Kind::u8: return H5T_STD_U8LE;
    case Kind::i16: return H5T_STD_I16LE;
    case Kind::u16: return H5T_STD_U16LE;
    case Kind::i32: return H5T_STD_I32LE;
    case Kind::u32: return H5T_STD_U32LE;
    case Kind::i64: return H5T_STD_I64LE;
    case Kind::u64: return H5T_STD_U64LE;
    case Kind::f32: return H5T_IEEE_F32LE;
    case Kind::f64: return H5T_IEEE_F64LE;
    default: {
      hid_t t = H5Tcopy(H5T_C_S1);
      H5Tset_size(t, k == Kind::str_var ? H5T_VARIABLE : std::max<std::size_t>(fixed_size, 1));
      return t;
    }
  }
}

bool is_string(Kind k) { return k == Kind::str_var || k == Kind::str_fixed; }

Kind kind_of(hid_t type) {
  const H5T_class_t c = H5Tget_class(type);
  const std::size_t size = H5Tget_size(type);
  if (c == H5T_STRING) return H5Tis_variable_str(type) > 0 ? Kind::str_var : Kind::str_fixed;
  if (c == H5T_FLOAT) return size == 4 ? Kind::f32 : Kind::f64;
  const bool is_signed = H5Tget_sign(type) == H5T_SGN_2;
  if (size == 1) return Kind::u8;
  if (size == 2) return is_signed ? Kind::i16 : Kind::u16;
  if (size == 4) return is_signed ? Kind::i32 : Kind::u32;
  return is_signed ? Kind::i64 : Kind::u64;
}

std::size_t count(const std::vector<hsize_t>& dims) {
  std::size_t n = 1;
  for (hsize_t d : dims) n *= d;
  return n;
}

// Reads the values (or strings) of a dataset or attribute whose type and space are given.
void read_payload(H5Item& item, hid_t obj, hid_t type, hid_t space, bool attribute) {
  const int rank = H5Sget_simple_extent_ndims(space);
  item.dims.resize(static_cast<std::size_t>(std::max(rank, 0)));
  H5Sget_simple_extent_dims(space, item.dims.data(), nullptr);
  const std::size_t n = count(item.dims);
  item.kind = kind_of(type);
  if (is_string(item.kind)) {
    Id mem{H5Tcopy(H5T_C_S1), H5Tclose};
    H5Tset_size(mem.id, H5T_VARIABLE);
    std::vector<char*> ptrs(n, nullptr);
    const herr_t read = attribute ? H5Aread(obj, mem.id, ptrs.data()) : H5Dread(obj, mem.id, H5S_ALL, H5S_ALL, H5P_DEFAULT, ptrs.data());
    if (read >= 0)
      for (char* p : ptrs) item.texts.push_back(p ? p : "");
    for (char* p : ptrs) H5free_memory(p);
    return;
  }
  item.values.assign(n, 0.0);
  if (attribute) H5Aread(obj, H5T_NATIVE_DOUBLE, item.values.data());
  else H5Dread(obj, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, item.values.data());
}

herr_t add_attribute(hid_t obj, const char* name, const H5A_info_t*, void* out) {
  auto& items = *static_cast<std::vector<H5Item>*>(out);
  H5Item item;
  item.object = items.back().object;
  item.attribute = name;
  Id attr{H5Aopen(obj, name, H5P_DEFAULT), H5Aclose};
  Id type{H5Aget_type(attr.id), H5Tclose};
  Id space{H5Aget_space(attr.id), H5Sclose};
  read_payload(item, attr.id, type.id, space.id, true);
  items.push_back(std::move(item));
  return 0;
}

herr_t add_object(hid_t root, const char* name, const H5O_info_t* info, void* out) {
  auto& items = *static_cast<std::vector<H5Item>*>(out);
  H5Item item;
  item.object = std::string(name) == "." ? "/" : "/" + std::string(name);
  Id obj{H5Oopen(root, name, H5P_DEFAULT), H5Oclose};
  if (info->type == H5O_TYPE_DATASET) {
    Id type{H5Dget_type(obj.id), H5Tclose};
    Id space{H5Dget_space(obj.id), H5Sclose};
    Id dcpl{H5Dget_create_plist(obj.id), H5Pclose};
    item.compressed = H5Pget_layout(dcpl.id) == H5D_CHUNKED;
    read_payload(item, obj.id, type.id, space.id, false);
  }
  items.push_back(item);
  hsize_t at = 0;
  H5Aiterate2(obj.id, H5_INDEX_NAME, H5_ITER_INC, &at, add_attribute, out);
  return 0;
}

// A value a reader may trip over: extremes, specials, small integers, or anything.
double tricky_value(FuzzedDataProvider& in) {
  switch (in.ConsumeIntegralInRange(0, 5)) {
    case 0: return in.ConsumeIntegralInRange<int>(-3, 70);
    case 1: return std::numeric_limits<double>::quiet_NaN();
    case 2: return in.ConsumeBool() ? INFINITY : -INFINITY;
    case 3: return static_cast<double>(in.ConsumeIntegral<std::uint32_t>());
    case 4: return std::ldexp(in.ConsumeBool() ? 1.0 : -1.0, in.ConsumeIntegralInRange(-1100, 1100));
    default: return in.ConsumeFloatingPoint<double>();
  }
}

void reshape(H5Item& item, FuzzedDataProvider& in) {
  const int rank = in.ConsumeIntegralInRange(0, item.attribute.empty() ? 4 : 1);
  item.dims.clear();
  // At most 4096 elements, so that each build stays fast.
  for (hsize_t r = 0, n = 1; r < static_cast<hsize_t>(rank); ++r) {
    const hsize_t d = std::min(in.ConsumeIntegralInRange<hsize_t>(0, 300), n > 0 ? 4096 / n : 300);
    item.dims.push_back(d);
    n *= d;
  }
  const std::size_t n = count(item.dims);
  auto cycle = [n](auto& v, auto fill) {
    const std::size_t old = v.size();
    v.resize(n, fill);
    for (std::size_t i = old; old > 0 && i < n; ++i) v[i] = v[i % old];
  };
  cycle(item.values, 0.0);
  cycle(item.texts, std::string());
}

void retype(H5Item& item, FuzzedDataProvider& in) {
  const Kind to = static_cast<Kind>(in.ConsumeIntegralInRange(1, static_cast<int>(Kind::str_fixed)));
  const std::size_t n = count(item.dims);
  if (is_string(to) && !is_string(item.kind)) {
    item.texts.clear();
    for (double v : item.values) item.texts.push_back(std::to_string(v));
  } else if (!is_string(to) && is_string(item.kind)) {
    item.values.clear();
    for (const auto& t : item.texts) item.values.push_back(std::strtod(t.c_str(), nullptr));
  }
  item.values.resize(is_string(to) ? 0 : n, 0.0);
  item.texts.resize(is_string(to) ? n : 0);
  item.kind = to;
}

void change_one(H5Item& item, FuzzedDataProvider& in) {
  if (is_string(item.kind) && !item.texts.empty()) {
    item.texts[in.ConsumeIntegralInRange<std::size_t>(0, item.texts.size() - 1)] = in.ConsumeRandomLengthString(80);
  } else if (!item.values.empty()) {
    double& v = item.values[in.ConsumeIntegralInRange<std::size_t>(0, item.values.size() - 1)];
    v = in.ConsumeBool() ? tricky_value(in) : v + in.ConsumeIntegralInRange(-2, 2);
  }
}

}  // namespace

std::vector<H5Item> take_apart(const std::string& path) {
  std::vector<H5Item> items;
  Id file{H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose};
  if (file.id < 0) std::abort();
  H5Ovisit(file.id, H5_INDEX_NAME, H5_ITER_INC, add_object, &items);
  return items;
}

void mutate(std::vector<H5Item>& items, FuzzedDataProvider& in) {
  for (int op = in.ConsumeIntegralInRange(0, 8); op > 0 && !items.empty() && in.remaining_bytes() > 0; --op) {
    const std::size_t i = in.ConsumeIntegralInRange<std::size_t>(0, items.size() - 1);
    H5Item& item = items[i];
    switch (in.ConsumeIntegralInRange(0, 5)) {
      case 0: items.erase(items.begin() + static_cast<std::ptrdiff_t>(i)); break;
      case 1:
        if (item.kind != Kind::group) retype(item, in);
        break;
      case 2:
        if (item.kind != Kind::group) reshape(item, in);
        break;
      case 3:
        if (item.kind != Kind::group) change_one(item, in);
        break;
      case 4: {  // a copy under another name: an extra object, or one replacing another
        H5Item copy = item;
        const H5Item& other = items[in.ConsumeIntegralInRange<std::size_t>(0, items.size() - 1)];
        copy.object = other.object;
        copy.attribute = item.attribute.empty() ? "" : in.ConsumeBool() ? other.attribute : in.ConsumeRandomLengthString(12);
        if (item.attribute.empty()) copy.object += "/" + in.ConsumeRandomLengthString(12);
        items.push_back(std::move(copy));
        break;
      }
      default:
        for (auto& v : item.values) v = tricky_value(in);
    }
  }
}

void build(const std::vector<H5Item>& items, const std::string& path) {
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  // Built in memory and written out once on close: several times faster than many small writes.
  Id fapl{H5Pcreate(H5P_FILE_ACCESS), H5Pclose};
  H5Pset_fapl_core(fapl.id, 1 << 16, 1);
  Id file{H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl.id), H5Fclose};
  if (file.id < 0) std::abort();
  Id lcpl{H5Pcreate(H5P_LINK_CREATE), H5Pclose};
  H5Pset_create_intermediate_group(lcpl.id, 1);
  for (const H5Item& item : items) {
    if (item.kind == Kind::group) {
      if (item.object != "/") H5Gclose(H5Gcreate2(file.id, item.object.c_str(), lcpl.id, H5P_DEFAULT, H5P_DEFAULT));
      continue;
    }
    std::size_t longest = 1;
    std::vector<const char*> ptrs;
    for (const auto& t : item.texts) longest = std::max(longest, t.size() + 1), ptrs.push_back(t.c_str());
    std::vector<char> fixed(longest * item.texts.size(), '\0');
    for (std::size_t k = 0; k < item.texts.size(); ++k) std::copy(item.texts[k].begin(), item.texts[k].end(), &fixed[k * longest]);
    Id type{file_type(item.kind, longest), is_string(item.kind) ? H5Tclose : nullptr};
    Id space{item.dims.empty() ? H5Screate(H5S_SCALAR) : H5Screate_simple(static_cast<int>(item.dims.size()), item.dims.data(), nullptr),
             H5Sclose};
    const hid_t mem = is_string(item.kind) ? type.id : H5T_NATIVE_DOUBLE;
    const void* buf = item.kind == Kind::str_var ? static_cast<const void*>(ptrs.data())
                      : is_string(item.kind)     ? static_cast<const void*>(fixed.data())
                                                 : static_cast<const void*>(item.values.data());
    if (!is_string(item.kind) && item.values.size() < count(item.dims)) continue;
    if (is_string(item.kind) && item.texts.size() < count(item.dims)) continue;
    if (!item.attribute.empty()) {
      Id obj{H5Oopen(file.id, item.object.c_str(), H5P_DEFAULT), H5Oclose};
      if (obj.id < 0) continue;
      Id attr{H5Acreate2(obj.id, item.attribute.c_str(), type.id, space.id, H5P_DEFAULT, H5P_DEFAULT), H5Aclose};
      if (attr.id >= 0) H5Awrite(attr.id, mem, buf);
      continue;
    }
    Id dcpl{H5Pcreate(H5P_DATASET_CREATE), H5Pclose};
    if (item.compressed && !item.dims.empty() && count(item.dims) > 0) {
      std::vector<hsize_t> chunk(item.dims);
      H5Pset_chunk(dcpl.id, static_cast<int>(chunk.size()), chunk.data());
      H5Pset_shuffle(dcpl.id);
      H5Pset_deflate(dcpl.id, 1);
      H5Pset_fletcher32(dcpl.id);
    }
    Id dset{H5Dcreate2(file.id, item.object.c_str(), type.id, space.id, lcpl.id, dcpl.id, H5P_DEFAULT), H5Dclose};
    if (dset.id >= 0) H5Dwrite(dset.id, mem, H5S_ALL, H5S_ALL, H5P_DEFAULT, buf);
  }
}

}  // namespace clatter::fuzz
