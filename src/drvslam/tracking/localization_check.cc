#include "drvslam/tracking/localization_check.h"

#include "drvslam/core/enum_names.h"

namespace drvslam {

const char* LocalizationRejectionName(LocalizationRejection rejection) {
  static constexpr EnumName<LocalizationRejection> kNames[] = {
      {LocalizationRejection::kNone, "none"},
      {LocalizationRejection::kDepthDisagrees, "depth disagrees"},
      {LocalizationRejection::kNotConfirmed, "not confirmed"}};
  return NameOf(rejection, kNames, "unknown");
}

const char* LocalizationQualityName(LocalizationQuality quality) {
  static constexpr EnumName<LocalizationQuality> kNames[] = {
      {LocalizationQuality::kLost, "lost"},
      {LocalizationQuality::kTentative, "tentative"},
      {LocalizationQuality::kVerified, "verified"}};
  return NameOf(quality, kNames, "unknown");
}

bool LocalizationCheck::Confirm(const DepthAgreement& agreement,
                                const DepthAgreementOptions& options) {
  last_rejection_ = LocalizationRejection::kNone;
  if (!DepthAgrees(agreement, options)) {
    last_rejection_ = LocalizationRejection::kDepthDisagrees;
    ++depth_rejections_;
    // Closed: the next pose found starts a new window.
    confirmed_ = kConfirmFrames;
    return false;
  }
  ++confirmed_;
  if (confirmed_ == kConfirmFrames) ++verified_;
  return true;
}

void LocalizationCheck::Fail() {
  last_rejection_ = LocalizationRejection::kNotConfirmed;
  ++unconfirmed_rejections_;
  confirmed_ = kConfirmFrames;
}

LocalizationQuality LocalizationCheck::Quality(bool tracked) const {
  if (!tracked) return LocalizationQuality::kLost;
  return Pending() ? LocalizationQuality::kTentative : LocalizationQuality::kVerified;
}

}  // namespace drvslam
