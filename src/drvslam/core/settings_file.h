// SettingsFile: typed read access to one ORB-SLAM2-style YAML settings file (cv::FileStorage,
// flat dotted keys such as "Camera.fx"). It remembers which keys were read, so that after every
// module has taken its options, the keys nobody asked for can be logged as ignored.
// Not thread-safe: settings are loaded once, before threads start.
#pragma once

#include <opencv2/core/persistence.hpp>
#include <set>
#include <string>
#include <vector>

namespace drvslam {

class SettingsFile {
 public:
  // Throws drvslam::Error naming the path when it is missing or not a readable YAML/XML file.
  explicit SettingsFile(const std::string& path);

  const std::string& Path() const { return path_; }
  bool Has(const std::string& key) const;

  // Each getter returns `fallback` when the key is absent and throws drvslam::Error naming the
  // file and key when it is present with the wrong type.
  double GetDouble(const std::string& key, double fallback) const;
  int GetInt(const std::string& key, int fallback) const;
  // Accepts 0/1 numbers and true/false strings, as ORB-SLAM2 files use both.
  bool GetBool(const std::string& key, bool fallback) const;
  std::string GetString(const std::string& key, const std::string& fallback) const;
  // A sequence of strings ([a, b]) or one comma-separated string.
  std::vector<std::string> GetStringList(const std::string& key,
                                         const std::vector<std::string>& fallback) const;

  // Every top-level key of the file, in file order.
  std::vector<std::string> Keys() const;
  // Top-level keys present in the file but never read through a getter.
  std::vector<std::string> UnreadKeys() const;
  // Logs each unread key at debug level ("ignored").
  void LogUnreadKeys() const;

 private:
  cv::FileNode Node(const std::string& key) const;
  std::string WrongType(const std::string& key, const char* expected) const;

  std::string path_;
  cv::FileStorage storage_;
  mutable std::set<std::string> read_keys_;
};

}  // namespace drvslam
