#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "core/errors.hpp"
#include "io/h5.hpp"
#include "io/provenance.hpp"

namespace fs = std::filesystem;
using namespace clatter::io;
using clatter::InputError;

namespace {

// A fresh, empty folder per test.
fs::path scratch(const std::string& name) {
  fs::path p = fs::current_path() / "h5_scratch" / name;
  fs::remove_all(p);
  fs::create_directories(p);
  return p;
}

std::size_t entries_in(const fs::path& dir) {
  return static_cast<std::size_t>(std::distance(fs::directory_iterator(dir), fs::directory_iterator{}));
}

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no InputError";
  return {};
}

void write_sample(const std::string& path) {
  auto f = File::create(path);
  write_header(f, "clatter-test", 3);
  std::vector<float> p = {1, 2, 3, 4, 5, 6};
  write_dataset<float>(f, "/a/b/p", p, {2, 3}, "Pa");
  std::vector<std::int64_t> n = {7, -8};
  write_dataset<std::int64_t>(f, "/n", n, {2}, "1");
  write_attribute<double>(f, "/a/b/p", "t_s", 1.5e-3);
  write_attribute(f, "/", "note", std::string_view("h\u00e9llo"));
  f.commit();
}

}  // namespace

TEST(H5, RoundTripWithShapeTypeAndUnits) {
  auto dir = scratch("roundtrip");
  const std::string path = (dir / "s.h5").string();
  write_sample(path);
  auto f = File::open(path);
  check_header(f, "clatter-test", 3);
  Dims found;
  auto p = read_dataset<float>(f, "/a/b/p", {2, -1}, "Pa", &found);
  EXPECT_EQ(p, (std::vector<float>{1, 2, 3, 4, 5, 6}));
  EXPECT_EQ(found, (Dims{2, 3}));
  EXPECT_EQ(read_dataset<std::int64_t>(f, "/n", {2}, "1"), (std::vector<std::int64_t>{7, -8}));
  EXPECT_EQ(read_attribute<double>(f, "/a/b/p", "t_s"), 1.5e-3);
  EXPECT_EQ(read_string_attribute(f, "/", "note"), "h\u00e9llo");
  EXPECT_TRUE(exists(f, "/a/b/p"));
  EXPECT_FALSE(exists(f, "/a/c/p"));
}

TEST(H5, CheckedReadsNameFileDatasetExpectedAndFound) {
  auto dir = scratch("checked");
  const std::string path = (dir / "s.h5").string();
  write_sample(path);
  auto f = File::open(path);
  auto m = error_of([&] { read_dataset<float>(f, "/a/b/p", {3, 2}, "Pa"); });
  EXPECT_NE(m.find(path), std::string::npos) << m;
  EXPECT_NE(m.find("'/a/b/p'"), std::string::npos) << m;
  EXPECT_NE(m.find("expected float32 [3, 2] in 'Pa', found float32 [2, 3] in 'Pa'"), std::string::npos) << m;
  m = error_of([&] { read_dataset<double>(f, "/a/b/p", {2, 3}, "Pa"); });
  EXPECT_NE(m.find("expected float64 [2, 3] in 'Pa', found float32 [2, 3]"), std::string::npos) << m;
  m = error_of([&] { read_dataset<float>(f, "/a/b/p", {2, 3}, "m"); });
  EXPECT_NE(m.find("in 'm', found float32 [2, 3] in 'Pa'"), std::string::npos) << m;
  m = error_of([&] { read_dataset<float>(f, "/a/b/q", {2, 3}, "Pa"); });
  EXPECT_NE(m.find("dataset '/a/b/q' not found"), std::string::npos) << m;
  m = error_of([&] { read_attribute<std::int32_t>(f, "/a/b/p", "t_s"); });
  EXPECT_NE(m.find("expected a scalar int32, found float64"), std::string::npos) << m;
  m = error_of([&] { check_header(f, "clatter-test", 4); });
  EXPECT_NE(m.find("version 3, this build reads version 4"), std::string::npos) << m;
  m = error_of([&] { check_header(f, "clatter-pan", 3); });
  EXPECT_NE(m.find("format 'clatter-test', expected 'clatter-pan'"), std::string::npos) << m;
}

TEST(H5, OutputAppearsOnlyOnCommit) {
  auto dir = scratch("atomic");
  const std::string path = (dir / "sub" / "out.h5").string();
  {
    auto f = File::create(path);
    std::vector<double> x(1000, 1.0);
    write_dataset<double>(f, "/x", x, {1000}, "m");
    EXPECT_FALSE(fs::exists(path));  // still under its temporary name
    EXPECT_EQ(entries_in(dir / "sub"), 1u);
  }  // dropped without commit, as when an exception unwinds
  EXPECT_FALSE(fs::exists(path));
  EXPECT_EQ(entries_in(dir / "sub"), 0u) << "temporary left behind";

  auto f = File::create(path);
  std::vector<double> x(10, 2.0);
  write_dataset<double>(f, "/x", x, {10}, "m");
  f.commit();
  EXPECT_TRUE(fs::exists(path));
  EXPECT_EQ(entries_in(dir / "sub"), 1u);
}

TEST(H5, ReplacingAnExistingOutputIsAtomicToo) {
  auto dir = scratch("replace");
  const std::string path = (dir / "out.h5").string();
  write_sample(path);
  {
    auto f = File::create(path);
    write_header(f, "clatter-test", 99);
  }  // abandoned: the old file must be untouched
  check_header(File::open(path), "clatter-test", 3);
}

TEST(H5, NotHdf5OrTruncatedIsAnInputError) {
  auto dir = scratch("bad");
  const std::string text = (dir / "text.h5").string();
  std::ofstream(text) << "not hdf5";
  EXPECT_NE(error_of([&] { File::open(text); }).find("not a readable HDF5 file"), std::string::npos);
  EXPECT_NE(error_of([&] { File::open((dir / "missing.h5").string()); }).find("no such file"), std::string::npos);

  const std::string good = (dir / "good.h5").string(), cut = (dir / "cut.h5").string();
  write_sample(good);
  fs::copy_file(good, cut);
  fs::resize_file(cut, fs::file_size(good) / 2);
  EXPECT_ANY_THROW({
    auto f = File::open(cut);
    read_dataset<float>(f, "/a/b/p", {2, 3}, "Pa");
  });
}
