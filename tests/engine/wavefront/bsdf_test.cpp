// PartitionByMaterial against a plain stable counting sort: odd and even sizes, one tag for
// every row, invalid refs, runs of one tag.
#include "engine/wavefront/bsdf.h"

#include <gtest/gtest.h>

#include <vector>

#include "engine/core/rng.h"

namespace ptlab {
namespace {

// The reference: for each tag in order, the rows with that tag in input order.
void ExpectPartition(const std::vector<MaterialRef>& refs) {
  MaterialPartition part;
  PartitionByMaterial(refs.data(), refs.size(), &part);
  std::vector<uint32_t> slot, index;
  uint32_t begin = 0;
  for (int t = 0; t < kMaterialTagCount; ++t) {
    ASSERT_EQ(part.begin[t], begin) << "tag " << t;
    for (size_t i = 0; i < refs.size(); ++i)
      if (refs[i].valid() && int(refs[i].tag()) == t)
        slot.push_back(uint32_t(i)), index.push_back(refs[i].index());
    begin = uint32_t(slot.size());
  }
  ASSERT_EQ(part.begin[kMaterialTagCount], begin);
  ASSERT_EQ(std::vector<uint32_t>(part.slot.begin(), part.slot.end()), slot);
  ASSERT_EQ(std::vector<uint32_t>(part.index.begin(), part.index.end()), index);
}

TEST(PartitionByMaterial, MatchesAStableCountingSort) {
  Pcg32 rng(8, 1);
  for (const size_t n : {0, 1, 2, 3, 7, 64, 1001}) {
    SCOPED_TRACE(n);
    std::vector<MaterialRef> random, one_tag, runs;
    for (size_t i = 0; i < n; ++i) {
      const uint32_t t = rng.NextUint() % 6;  // 5: an invalid ref
      random.push_back(t == 5 ? MaterialRef::None()
                              : MaterialRef::Make(MaterialTag(t), rng.NextUint() >> 4));
      one_tag.push_back(MaterialRef::Make(MaterialTag::kDiffuse, uint32_t(i * 7)));
      runs.push_back(MaterialRef::Make(MaterialTag((i / 5) % 5), uint32_t(i)));
    }
    ExpectPartition(random);
    ExpectPartition(one_tag);
    ExpectPartition(runs);
    if (n > 0) {
      one_tag.back() = MaterialRef::None();  // one tag but not every row
      ExpectPartition(one_tag);
    }
  }
}

}  // namespace
}  // namespace ptlab
