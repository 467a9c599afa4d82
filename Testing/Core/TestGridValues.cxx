// SPDX-License-Identifier: BSD-3-Clause
// amrsp::GridValues: owned or borrowed values, shared by copies, copied only on write.
#include "amrsp/Hierarchy.h"

#include <gtest/gtest.h>

#include <memory>
#include <vector>

using amrsp::GridValues;

TEST(GridValues, BorrowedValuesAreReadInPlaceAndKeepTheirOwnerAlive)
{
  auto storage = std::make_shared<std::vector<float>>(std::vector<float>{ 1, 2, 3 });
  std::weak_ptr<std::vector<float>> watch = storage;
  GridValues v = GridValues::Borrow(storage->data(), storage->size(), storage);
  const float* where = storage->data();
  storage.reset();
  ASSERT_FALSE(watch.expired()); // the values hold their owner
  const GridValues& read = v;
  EXPECT_TRUE(v.IsBorrowed());
  EXPECT_EQ(read.data(), where); // reading does not copy
  EXPECT_EQ(read[2], 3.0f);
  v = GridValues();
  EXPECT_TRUE(watch.expired()); // and release it with the last copy
}

TEST(GridValues, WritingBorrowedValuesCopiesThemFirst)
{
  std::vector<float> storage{ 1, 2, 3 };
  GridValues v = GridValues::Borrow(storage.data(), storage.size(), nullptr);
  v[1] = 20.0f;
  EXPECT_EQ(storage[1], 2.0f); // the lender's memory is never written
  EXPECT_FALSE(v.IsBorrowed());
  EXPECT_EQ(static_cast<const GridValues&>(v)[1], 20.0f);
  EXPECT_EQ(v, GridValues({ 1, 20, 3 }));
}

TEST(GridValues, CopiesShareUntilOneIsWritten)
{
  GridValues a(std::vector<float>{ 1, 2, 3 });
  GridValues b = a;
  EXPECT_EQ(static_cast<const GridValues&>(a).data(), static_cast<const GridValues&>(b).data());
  b[0] = 10.0f;
  EXPECT_NE(static_cast<const GridValues&>(a).data(), static_cast<const GridValues&>(b).data());
  EXPECT_EQ(a[0], 1.0f);
  EXPECT_EQ(b[0], 10.0f);
  // an unshared owner is written in place
  const float* before = static_cast<const GridValues&>(a).data();
  a[2] = 30.0f;
  EXPECT_EQ(static_cast<const GridValues&>(a).data(), before);
}

TEST(GridValues, ConstructorsAndEquality)
{
  EXPECT_TRUE(GridValues().empty());
  EXPECT_EQ(GridValues(4, 2.5f).size(), 4u);
  EXPECT_EQ(GridValues(4, 2.5f)[3], 2.5f);
  EXPECT_EQ(GridValues({ 1, 2 }), GridValues(std::vector<float>{ 1, 2 }));
  EXPECT_NE(GridValues({ 1, 2 }), GridValues({ 1, 3 }));
  EXPECT_NE(GridValues({ 1, 2 }), GridValues({ 1, 2, 3 }));
}
