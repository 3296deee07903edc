#include <gtest/gtest.h>

#include "mpi/cart.hpp"

using clatter::mpi::block_of;

TEST(BlockOf, TilesTheAxisWithBalancedBlocks) {
  for (int n : {1, 2, 7, 64, 65, 1000})
    for (int parts = 1; parts <= std::min(n, 13); ++parts) {
      int next = 0, smallest = n, largest = 0;
      for (int i = 0; i < parts; ++i) {
        auto b = block_of(n, parts, i);
        EXPECT_EQ(b.start, next) << n << " cells, " << parts << " parts, block " << i;
        next = b.start + b.count;
        smallest = std::min(smallest, b.count);
        largest = std::max(largest, b.count);
      }
      EXPECT_EQ(next, n);
      EXPECT_LE(largest - smallest, 1);
      EXPECT_GE(smallest, 1);
    }
}
