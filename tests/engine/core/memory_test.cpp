// Memory accounting: container bytes are capacity × element size; the peak RSS sees pages used.
#include "engine/core/memory.h"

#include <cstdint>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "engine/core/aligned.h"

namespace ptlab {
namespace {

TEST(Memory, VectorBytesIsCapacityTimesElementSize) {
  std::vector<double> d;
  EXPECT_EQ(VectorBytes(d), 0u);
  d.reserve(10);
  d.push_back(1.0);  // bytes count what is allocated, not what is used
  EXPECT_EQ(VectorBytes(d), d.capacity() * sizeof(double));
  EXPECT_GE(VectorBytes(d), 10 * sizeof(double));
  AlignedVector<uint16_t> a(7);
  EXPECT_EQ(VectorsBytes(d, a), d.capacity() * 8 + a.capacity() * 2);
  EXPECT_EQ(VectorsBytes(), 0u);
}

// Columns are cache-line aligned; from kHugePageBytes on they start on a 2 MiB boundary, which
// transparent huge pages need. Both keep their values through growth (the allocator frees with
// the alignment it allocated with: a mismatch is undefined behaviour, which ASan reports).
TEST(Memory, ColumnsAreAlignedAndLargeOnesToHugePages) {
  for (const size_t n : {size_t{1}, size_t{15}, size_t{1000}, kHugePageBytes / 4 - 1,
                         kHugePageBytes / 4, 3 * kHugePageBytes / 4 + 5}) {
    AlignedVector<float> v(n, 1.5f);
    const auto address = reinterpret_cast<uintptr_t>(v.data());
    EXPECT_EQ(address % kColumnAlignment, 0u) << n;
    if (n * sizeof(float) >= kHugePageBytes) {
      EXPECT_EQ(address % kHugePageBytes, 0u) << n;
    }
    v.push_back(2.5f);  // grows past capacity: a new column, the old one freed
    EXPECT_EQ(reinterpret_cast<uintptr_t>(v.data()) % kColumnAlignment, 0u) << n;
    EXPECT_EQ(v[n - 1], 1.5f) << n;
    EXPECT_EQ(v[n], 2.5f) << n;
  }
}

TEST(Memory, StringsBytesCountsHeapBuffersOfLongStrings) {
  const std::vector<std::string> short_names = {"a", "bc"};  // in the string objects
  EXPECT_EQ(StringsBytes(short_names), VectorBytes(short_names));
  const std::string long_name(100, 'x');
  const std::vector<std::string> names = {"a", long_name};
  EXPECT_EQ(StringsBytes(names), VectorBytes(names) + names[1].capacity() + 1);
}

TEST(Memory, PeakResidentBytesSeesTouchedPages) {
  const uint64_t before = PeakResidentBytes();
  EXPECT_GT(before, 0u);
  constexpr size_t kBytes = size_t{96} << 20;
  std::vector<char> block(kBytes, 1);  // written, so resident
  const uint64_t after = PeakResidentBytes();
  EXPECT_GE(after, before);
  EXPECT_GE(after, kBytes);
  EXPECT_EQ(block[kBytes - 1], 1);
}

}  // namespace
}  // namespace ptlab
