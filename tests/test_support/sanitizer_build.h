// Whether this build is instrumented by AddressSanitizer or ThreadSanitizer
// (scripts/sanitizers.sh), for tests whose bounds on speed cannot hold when every stage runs
// several times slower. GCC defines __SANITIZE_ADDRESS__ / __SANITIZE_THREAD__; clang 16 answers
// __has_feature instead.
#pragma once

namespace drvslam::test {

#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
constexpr bool kSanitizedBuild = true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(thread_sanitizer)
constexpr bool kSanitizedBuild = true;
#else
constexpr bool kSanitizedBuild = false;
#endif
#else
constexpr bool kSanitizedBuild = false;
#endif

}  // namespace drvslam::test
