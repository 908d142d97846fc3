#include "drvslam/io/text_lines.h"

#include <cerrno>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "drvslam/core/error.h"

namespace drvslam {

void ForEachDataLine(const std::string& path,
                     const std::function<void(int, const std::vector<std::string>&)>& visit) {
  if (!std::filesystem::exists(path)) throw Error(path + ": file does not exist");
  if (std::filesystem::is_directory(path)) throw Error(path + ": is a folder, not a file");
  std::ifstream in(path);
  if (!in) throw Error(path + ": cannot open for reading");
  std::string line;
  int line_number = 0;
  while (std::getline(in, line)) {
    ++line_number;
    const std::vector<std::string> fields = SplitFields(line);
    if (fields.empty() || fields.front().front() == '#') continue;
    visit(line_number, fields);
  }
  if (in.bad()) throw Error(path + ": read error");
}

std::vector<std::string> SplitFields(const std::string& line) {
  std::vector<std::string> fields;
  std::string field;
  for (const char ch : line) {
    if (ch == ' ' || ch == '\t' || ch == ',' || ch == '\r') {
      if (!field.empty()) fields.push_back(std::move(field));
      field.clear();
    } else {
      field.push_back(ch);
    }
  }
  if (!field.empty()) fields.push_back(std::move(field));
  return fields;
}

double ParseNumber(const std::string& field, const std::string& where) {
  errno = 0;
  char* end = nullptr;
  const double value = std::strtod(field.c_str(), &end);
  if (end == field.c_str() || *end != '\0' || errno == ERANGE) {
    throw Error(where + ": '" + field + "' is not a number");
  }
  return value;
}

}  // namespace drvslam
