// KeyFrameDatabase: a changed view of a place must rank that place's keyframe first; erased,
// culled and cleared keyframes must not come back; covisible keyframes form one group; loop
// candidates leave out the keyframe's neighbours.
#include "drvslam/loop/keyframe_database.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <string>
#include <vector>

#include "drvslam/loop/bow_vocabulary.h"
#include "plane_views.h"
#include "test_support/missing_data.h"

namespace drvslam {
namespace {

const std::vector<std::string> kPlaces = {"baboon.jpg",       "fruits.jpg", "building.jpg",
                                          "graf1.png",        "home.jpg",   "messi5.jpg",
                                          "starry_night.jpg", "board.jpg"};

class KeyFrameDatabaseTest : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!scene_.LoadVocabulary()) DRVSLAM_MISSING_TEST_DATA() << "no default vocabulary was built";
    for (const std::string& name : kPlaces) {
      const cv::Mat photo = test::LoadPhoto(name);
      if (photo.empty())
        DRVSLAM_MISSING_TEST_DATA() << name << " missing in " << DRVSLAM_OPENCV_DATA_DIR;
      photos_.push_back(photo);
      keyframes_.push_back(scene_.MakeKeyFrame(photo, SE3::Identity()));
      ASSERT_TRUE(keyframes_.back());
      ASSERT_TRUE(keyframes_.back()->HasBow());
      database_.Add(keyframes_.back());
    }
  }

  // A revisit of place `index`: rotated, shifted and closer.
  Frame Revisit(std::size_t index) {
    Frame frame =
        scene_.MakeFrame(photos_[index], test::ViewPose(0.06, -0.08, 0.1, 0.12, -0.06, 0.25));
    scene_.ComputeBow(frame);
    return frame;
  }

  test::PlaneScene scene_;
  std::vector<cv::Mat> photos_;
  std::vector<std::shared_ptr<KeyFrame>> keyframes_;
  KeyFrameDatabase database_;
};

TEST_F(KeyFrameDatabaseTest, RevisitedViewRanksFirst) {
  EXPECT_EQ(database_.Size(), kPlaces.size());
  for (std::size_t place = 0; place < kPlaces.size(); ++place) {
    const Frame query = Revisit(place);
    // The raw scores already rank it first ...
    const double own = BowVocabulary::Score(query.bow, keyframes_[place]->Bow());
    for (std::size_t other = 0; other < kPlaces.size(); ++other) {
      if (other == place) continue;
      EXPECT_GT(own, BowVocabulary::Score(query.bow, keyframes_[other]->Bow()))
          << kPlaces[place] << " vs " << kPlaces[other];
    }
    // ... and so does the database.
    const auto candidates = database_.RelocalizationCandidates(query.bow);
    ASSERT_FALSE(candidates.empty()) << kPlaces[place];
    EXPECT_EQ(candidates.front(), keyframes_[place]) << kPlaces[place];
  }
}

TEST_F(KeyFrameDatabaseTest, AddIsIdempotentAndKeyFramesWithoutBowAreIgnored) {
  database_.Add(keyframes_[2]);
  EXPECT_EQ(database_.Size(), kPlaces.size());
  const cv::Mat photo = photos_[0];
  Frame frame = scene_.MakeFrame(photo, SE3::Identity());
  auto no_bow = CreateInitialKeyFrame(frame, scene_.map, 50);
  ASSERT_TRUE(no_bow);
  database_.Add(no_bow);
  database_.Add(nullptr);
  EXPECT_EQ(database_.Size(), kPlaces.size());
}

TEST_F(KeyFrameDatabaseTest, ErasedBadAndClearedKeyFramesAreNotReturned) {
  const Frame query = Revisit(3);
  database_.Erase(*keyframes_[3]);
  EXPECT_EQ(database_.Size(), kPlaces.size() - 1);
  for (const auto& candidate : database_.RelocalizationCandidates(query.bow)) {
    EXPECT_NE(candidate, keyframes_[3]);
  }
  // Erasing twice is harmless.
  database_.Erase(*keyframes_[3]);
  EXPECT_EQ(database_.Size(), kPlaces.size() - 1);

  // A culled keyframe (set bad) is skipped; keyframe 0 cannot be set bad, so use another.
  const Frame query5 = Revisit(5);
  keyframes_[5]->SetBad();
  ASSERT_TRUE(keyframes_[5]->IsBad());
  for (const auto& candidate : database_.RelocalizationCandidates(query5.bow)) {
    EXPECT_NE(candidate, keyframes_[5]);
  }
  // Later additions sweep it out of the index.
  const std::size_t before = database_.Size();
  for (int i = 0; i < KeyFrameDatabase::kSweepInterval; ++i) {
    database_.Add(scene_.MakeKeyFrame(photos_[i % 2], SE3::Identity()));
  }
  EXPECT_EQ(database_.Size(), before + KeyFrameDatabase::kSweepInterval - 1);

  database_.Clear();
  EXPECT_EQ(database_.Size(), 0u);
  EXPECT_TRUE(database_.RelocalizationCandidates(query.bow).empty());
  EXPECT_TRUE(database_.RelocalizationCandidates(BowVector()).empty());
}

TEST_F(KeyFrameDatabaseTest, CovisibleKeyFramesFormOneGroup) {
  // A second keyframe of place 1, covisible with the first: one group, returned once, through
  // its better-scoring member.
  const auto second =
      scene_.MakeKeyFrame(photos_[1], test::ViewPose(0.05, -0.07, 0.09, 0.1, -0.05, 0.2));
  ASSERT_TRUE(second);
  database_.Add(second);
  keyframes_[1]->AddConnection(second, 200);
  second->AddConnection(keyframes_[1], 200);
  const Frame query = Revisit(1);
  const auto candidates = database_.RelocalizationCandidates(query.bow);
  ASSERT_FALSE(candidates.empty());
  const double score_first = BowVocabulary::Score(query.bow, keyframes_[1]->Bow());
  const double score_second = BowVocabulary::Score(query.bow, second->Bow());
  EXPECT_EQ(candidates.front(), score_second > score_first ? second : keyframes_[1]);
  EXPECT_EQ(std::count_if(candidates.begin(), candidates.end(),
                          [&](const auto& kf) { return kf == second || kf == keyframes_[1]; }),
            1);
}

TEST_F(KeyFrameDatabaseTest, LoopCandidatesLeaveOutCovisibleKeyFrames) {
  // Place 2 revisited by a keyframe covisible with a third view and not with the original.
  const auto revisit =
      scene_.MakeKeyFrame(photos_[2], test::ViewPose(0.06, -0.08, 0.1, 0.12, -0.06, 0.25));
  const auto neighbour =
      scene_.MakeKeyFrame(photos_[2], test::ViewPose(0.04, -0.05, 0.07, 0.08, -0.04, 0.15));
  ASSERT_TRUE(revisit && neighbour);
  database_.Add(revisit);
  database_.Add(neighbour);
  revisit->AddConnection(neighbour, 300);
  neighbour->AddConnection(revisit, 300);

  const auto candidates = database_.LoopCandidates(revisit, 0.0);
  ASSERT_FALSE(candidates.empty());
  EXPECT_EQ(candidates.front(), keyframes_[2]);
  for (const auto& candidate : candidates) {
    EXPECT_NE(candidate, revisit);
    EXPECT_NE(candidate, neighbour);
  }
  // A score no keyframe reaches leaves nothing.
  EXPECT_TRUE(database_.LoopCandidates(revisit, 1.01).empty());
  EXPECT_TRUE(database_.LoopCandidates(nullptr, 0.0).empty());
}

}  // namespace
}  // namespace drvslam
