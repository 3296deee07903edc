#include <gtest/gtest.h>

#include <filesystem>

#include "io/h5_parallel.hpp"
#include "io/provenance.hpp"
#include "mpi/cart.hpp"

namespace fs = std::filesystem;
using namespace clatter;

namespace {
// A value that encodes the global index, so a block written to the wrong place is caught.
float pattern(int i, int j, int k) { return static_cast<float>(10000 * i + 100 * j + k); }

fs::path scratch(const std::string& name) {
  fs::path p = fs::current_path() / "h5_parallel_scratch" / name;
  if (mpi::rank(MPI_COMM_WORLD) == 0) {
    fs::remove_all(p);
    fs::create_directories(p);
  }
  MPI_Barrier(MPI_COMM_WORLD);
  return p;
}
}  // namespace

TEST(H5Parallel, CollectiveBlockWriteLandsEveryCellInPlace) {
  const auto dir = scratch("blocks");
  const std::string path = (dir / "grid.h5").string();
  const std::array<int, 3> n{13, 7, 5};
  mpi::CartTopology topo(MPI_COMM_WORLD, n);
  const auto s = topo.local_start(), c = topo.local_count();
  std::vector<float> block;
  for (int i = s[0]; i < s[0] + c[0]; ++i)
    for (int j = s[1]; j < s[1] + c[1]; ++j)
      for (int k = s[2]; k < s[2] + c[2]; ++k) block.push_back(pattern(i, j, k));
  {
    auto f = io::create_parallel(path, MPI_COMM_WORLD);
    io::write_header(f, "clatter-test", 1);
    io::write_dataset_block<float>(f, "/g/p", {13, 7, 5}, {hsize_t(s[0]), hsize_t(s[1]), hsize_t(s[2])},
                                   {hsize_t(c[0]), hsize_t(c[1]), hsize_t(c[2])}, block, "Pa");
    std::vector<double> meta = {1.0, 2.0, 3.0};  // rank 0's copy is written
    io::write_dataset<double>(f, "/g/meta", meta, {3}, "m");
    io::write_provenance(f, "test", "[a]\nb = 1\n", mpi::size(MPI_COMM_WORLD));
    f.commit();
  }
  if (mpi::rank(MPI_COMM_WORLD) == 0) {
    auto f = io::File::open(path);
    io::check_header(f, "clatter-test", 1);
    auto p = io::read_dataset<float>(f, "/g/p", {13, 7, 5}, "Pa");
    std::size_t idx = 0, wrong = 0;
    for (int i = 0; i < 13; ++i)
      for (int j = 0; j < 7; ++j)
        for (int k = 0; k < 5; ++k) wrong += p[idx++] != pattern(i, j, k);
    EXPECT_EQ(wrong, 0u);
    EXPECT_EQ(io::read_dataset<double>(f, "/g/meta", {3}, "m"), (std::vector<double>{1.0, 2.0, 3.0}));
    EXPECT_EQ(io::read_attribute<std::int32_t>(f, "/provenance/run", "n_ranks"), mpi::size(MPI_COMM_WORLD));
    EXPECT_EQ(io::read_string_attribute(f, "/provenance", "config_toml"), "[a]\nb = 1\n");
  }
}

TEST(H5Parallel, AbandonedParallelOutputLeavesNothing) {
  const auto dir = scratch("abandoned");
  {
    auto f = io::create_parallel((dir / "never.h5").string(), MPI_COMM_WORLD);
    std::vector<double> x = {1.0};
    io::write_dataset<double>(f, "/x", x, {1}, "m");
  }
  MPI_Barrier(MPI_COMM_WORLD);
  EXPECT_TRUE(fs::is_empty(dir));
}
