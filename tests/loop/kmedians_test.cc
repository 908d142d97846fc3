// Binary k-medians, the clustering step of vocabulary training.
#include <gtest/gtest.h>

#include <cstring>
#include <map>
#include <random>
#include <set>
#include <vector>

#include "drvslam/core/error.h"
#include "drvslam/feature/descriptor_distance.h"
#include "drvslam/tools/vocab/vocabulary_trainer.h"
#include "vocabulary_test_util.h"

namespace drvslam {
namespace {

struct HandMadeClusters {
  std::vector<PackedDescriptor> prototypes;
  std::vector<PackedDescriptor> data;
  std::vector<int> truth;  // prototype of each data entry
};

// Four random prototypes (about 128 bits apart) with 60 members each, every member differing
// from its prototype in up to 12 bits.
HandMadeClusters MakeClusters(uint64_t seed) {
  std::mt19937_64 rng(seed);
  const cv::Mat prototypes = test::RandomDescriptors(4, seed);
  HandMadeClusters clusters;
  for (int p = 0; p < 4; ++p) {
    clusters.prototypes.push_back(PackDescriptor(prototypes.ptr<uint8_t>(p)));
  }
  for (int i = 0; i < 240; ++i) {
    const int p = i % 4;
    const cv::Mat member = test::FlipBits(prototypes.row(p), static_cast<int>(rng() % 13), &rng);
    clusters.data.push_back(PackDescriptor(member.ptr<uint8_t>(0)));
    clusters.truth.push_back(p);
  }
  return clusters;
}

std::vector<uint32_t> AllMembers(std::size_t n) {
  std::vector<uint32_t> members(n);
  for (std::size_t i = 0; i < n; ++i) members[i] = static_cast<uint32_t>(i);
  return members;
}

// The portable bit count behind training (and behind Transform where popcnt is missing) agrees
// with the feature module's distance, and packing round-trips.
TEST(PackedDescriptorTest, HammingDistanceMatchesDescriptorDistance) {
  const cv::Mat a = test::RandomDescriptors(200, 1);
  const cv::Mat b = test::RandomDescriptors(200, 2);
  for (int r = 0; r < a.rows; ++r) {
    const PackedDescriptor pa = PackDescriptor(a.ptr<uint8_t>(r));
    const PackedDescriptor pb = PackDescriptor(b.ptr<uint8_t>(r));
    EXPECT_EQ(HammingDistance(pa, pb), DescriptorDistance(a.row(r), b.row(r)));
    EXPECT_EQ(HammingDistance(pa, pa), 0);
    uint8_t bytes[32];
    UnpackDescriptor(pa, bytes);
    EXPECT_EQ(std::memcmp(bytes, a.ptr<uint8_t>(r), 32), 0);
  }
  EXPECT_EQ(PopCount64(~uint64_t{0}), 64);
  EXPECT_EQ(PopCount64(0), 0);
  EXPECT_EQ(PopCount64(0x8000000000000001ULL), 2);
}

TEST(KMediansTest, RecoversHandMadeClustersAndTheirPrototypes) {
  const HandMadeClusters clusters = MakeClusters(7);
  std::mt19937_64 rng(1);
  const KMediansResult result =
      KMediansCluster(clusters.data, AllMembers(clusters.data.size()), 4, 20, &rng);
  ASSERT_EQ(result.centres.size(), 4u);
  ASSERT_EQ(result.labels.size(), clusters.data.size());
  // The labels are a relabelling of the truth: one centre per prototype and vice versa.
  std::map<int, int> centre_of_prototype;
  for (std::size_t i = 0; i < clusters.data.size(); ++i) {
    const auto [it, inserted] = centre_of_prototype.emplace(clusters.truth[i], result.labels[i]);
    EXPECT_EQ(it->second, result.labels[i]) << "member " << i << " split from its cluster";
  }
  std::set<int> centres_used;
  for (const auto& entry : centre_of_prototype) centres_used.insert(entry.second);
  EXPECT_EQ(centres_used.size(), 4u);
  // 60 members with sparse independent flips: the per-bit majority is the prototype itself.
  for (const auto& [prototype, centre] : centre_of_prototype) {
    EXPECT_EQ(HammingDistance(result.centres[centre], clusters.prototypes[prototype]), 0)
        << "prototype " << prototype;
  }
  EXPECT_GE(result.iterations, 1);
  EXPECT_LE(result.iterations, 20);
}

TEST(KMediansTest, EveryLabelNamesTheNearestCentre) {
  const HandMadeClusters clusters = MakeClusters(11);
  std::mt19937_64 rng(3);
  // k = 7 > 4 true clusters: the extra centres split clusters, still nearest-centre labels.
  const KMediansResult result =
      KMediansCluster(clusters.data, AllMembers(clusters.data.size()), 7, 2, &rng);
  for (std::size_t i = 0; i < clusters.data.size(); ++i) {
    const int own = HammingDistance(clusters.data[i], result.centres[result.labels[i]]);
    for (std::size_t c = 0; c < result.centres.size(); ++c) {
      const int other = HammingDistance(clusters.data[i], result.centres[c]);
      EXPECT_TRUE(own < other || (own == other && result.labels[i] <= static_cast<int>(c)))
          << "member " << i << " centre " << c;
    }
  }
}

TEST(KMediansTest, FewerDistinctDescriptorsThanKGiveOneCentreEach) {
  std::vector<PackedDescriptor> data;
  const cv::Mat distinct = test::RandomDescriptors(3, 5);
  for (int copy = 0; copy < 4; ++copy) {
    for (int d = 0; d < 3; ++d) data.push_back(PackDescriptor(distinct.ptr<uint8_t>(d)));
  }
  std::mt19937_64 rng(9);
  const KMediansResult result = KMediansCluster(data, AllMembers(data.size()), 10, 10, &rng);
  ASSERT_EQ(result.centres.size(), 3u);
  for (std::size_t i = 0; i < data.size(); ++i) {
    EXPECT_EQ(HammingDistance(data[i], result.centres[result.labels[i]]), 0);
  }
}

TEST(KMediansTest, ClustersOnlyTheGivenMembers) {
  const HandMadeClusters clusters = MakeClusters(13);
  std::vector<uint32_t> members;
  for (uint32_t i = 0; i < clusters.data.size(); ++i) {
    if (clusters.truth[i] == 2) members.push_back(i);
  }
  std::mt19937_64 rng(1);
  const KMediansResult result = KMediansCluster(clusters.data, members, 1, 10, &rng);
  ASSERT_EQ(result.centres.size(), 1u);
  EXPECT_EQ(result.labels.size(), members.size());
  EXPECT_EQ(HammingDistance(result.centres[0], clusters.prototypes[2]), 0);
}

TEST(KMediansTest, SameSeedSameResult) {
  const HandMadeClusters clusters = MakeClusters(17);
  std::mt19937_64 rng_a(42);
  std::mt19937_64 rng_b(42);
  const auto members = AllMembers(clusters.data.size());
  const KMediansResult a = KMediansCluster(clusters.data, members, 6, 10, &rng_a);
  const KMediansResult b = KMediansCluster(clusters.data, members, 6, 10, &rng_b);
  EXPECT_EQ(a.centres, b.centres);
  EXPECT_EQ(a.labels, b.labels);
}

TEST(KMediansTest, RejectsBadArguments) {
  const HandMadeClusters clusters = MakeClusters(19);
  std::mt19937_64 rng(1);
  EXPECT_THROW(KMediansCluster(clusters.data, {0, 1}, 0, 10, &rng), Error);
  EXPECT_THROW(KMediansCluster(clusters.data, {}, 2, 10, &rng), Error);
  EXPECT_THROW(KMediansCluster(clusters.data, {0, 100000}, 2, 10, &rng), Error);
  EXPECT_THROW(KMediansCluster(clusters.data, {0, 1}, 2, 10, nullptr), Error);
}

}  // namespace
}  // namespace drvslam
