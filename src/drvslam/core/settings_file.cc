#include "drvslam/core/settings_file.h"

#include <spdlog/spdlog.h>

#include <cmath>
#include <filesystem>
#include <opencv2/core.hpp>
#include <sstream>

#include "drvslam/core/error.h"

namespace drvslam {

SettingsFile::SettingsFile(const std::string& path) : path_(path) {
  if (!std::filesystem::exists(path)) throw Error(path + ": settings file does not exist");
  if (std::filesystem::is_directory(path)) throw Error(path + ": settings path is a folder");
  try {
    storage_.open(path, cv::FileStorage::READ);
  } catch (const cv::Exception& e) {
    throw Error(path + ": not a readable settings file (" + e.msg + ")");
  }
  if (!storage_.isOpened()) throw Error(path + ": not a readable settings file");
}

cv::FileNode SettingsFile::Node(const std::string& key) const {
  read_keys_.insert(key);
  return storage_[key];
}

bool SettingsFile::Has(const std::string& key) const {
  const cv::FileNode node = storage_[key];
  return !node.empty() && !node.isNone();
}

std::string SettingsFile::WrongType(const std::string& key, const char* expected) const {
  return path_ + ": " + key + " must be " + expected;
}

double SettingsFile::GetDouble(const std::string& key, double fallback) const {
  const cv::FileNode node = Node(key);
  if (node.empty() || node.isNone()) return fallback;
  if (!node.isReal() && !node.isInt()) throw Error(WrongType(key, "a number"));
  return node.real();
}

int SettingsFile::GetInt(const std::string& key, int fallback) const {
  const cv::FileNode node = Node(key);
  if (node.empty() || node.isNone()) return fallback;
  if (node.isInt()) return static_cast<int>(node);
  if (node.isReal()) {
    const double value = node.real();
    if (std::floor(value) == value) return static_cast<int>(value);
  }
  std::ostringstream what;
  what << "an integer";
  throw Error(WrongType(key, what.str().c_str()));
}

bool SettingsFile::GetBool(const std::string& key, bool fallback) const {
  const cv::FileNode node = Node(key);
  if (node.empty() || node.isNone()) return fallback;
  if (node.isInt()) {
    const int value = static_cast<int>(node);
    if (value == 0 || value == 1) return value == 1;
  } else if (node.isString()) {
    const std::string value = node.string();
    if (value == "true" || value == "on" || value == "1") return true;
    if (value == "false" || value == "off" || value == "0") return false;
  }
  throw Error(WrongType(key, "a boolean (0, 1, true or false)"));
}

std::string SettingsFile::GetString(const std::string& key, const std::string& fallback) const {
  const cv::FileNode node = Node(key);
  if (node.empty() || node.isNone()) return fallback;
  if (!node.isString()) throw Error(WrongType(key, "a string"));
  return node.string();
}

std::vector<std::string> SettingsFile::GetStringList(
    const std::string& key, const std::vector<std::string>& fallback) const {
  const cv::FileNode node = Node(key);
  if (node.empty() || node.isNone()) return fallback;
  std::vector<std::string> values;
  if (node.isSeq()) {
    for (const cv::FileNode& item : node) {
      if (!item.isString()) throw Error(WrongType(key, "a list of strings"));
      values.push_back(item.string());
    }
    return values;
  }
  if (!node.isString()) throw Error(WrongType(key, "a list of strings"));
  std::stringstream stream(node.string());
  std::string item;
  while (std::getline(stream, item, ',')) {
    const auto first = item.find_first_not_of(" \t");
    const auto last = item.find_last_not_of(" \t");
    if (first != std::string::npos) values.push_back(item.substr(first, last - first + 1));
  }
  return values;
}

std::vector<std::string> SettingsFile::Keys() const {
  std::vector<std::string> keys;
  for (const cv::FileNode& node : storage_.root()) keys.push_back(node.name());
  return keys;
}

std::vector<std::string> SettingsFile::UnreadKeys() const {
  std::vector<std::string> unread;
  const cv::FileNode root = storage_.root();
  for (const cv::FileNode& node : root) {
    if (read_keys_.count(node.name()) == 0) unread.push_back(node.name());
  }
  return unread;
}

void SettingsFile::LogUnreadKeys() const {
  for (const std::string& key : UnreadKeys()) {
    spdlog::debug("{}: ignoring unknown setting {}", path_, key);
  }
}

}  // namespace drvslam
