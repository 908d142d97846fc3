#include "drvslam/io/text_lines.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "drvslam/core/error.h"

namespace drvslam {

void ForEachLine(
    const std::string& path,
    const std::function<bool(int, const std::string&, const std::vector<std::string>&)>& visit) {
  if (!std::filesystem::exists(path)) throw Error(path + ": file does not exist");
  if (std::filesystem::is_directory(path)) throw Error(path + ": is a folder, not a file");
  std::ifstream in(path);
  if (!in) throw Error(path + ": cannot open for reading");
  std::string line;
  int line_number = 0;
  while (std::getline(in, line)) {
    ++line_number;
    if (!visit(line_number, line, SplitFields(line))) return;
  }
  if (in.bad()) throw Error(path + ": read error");
}

void ForEachDataLine(const std::string& path,
                     const std::function<void(int, const std::vector<std::string>&)>& visit) {
  ForEachLine(path,
              [&](int line_number, const std::string&, const std::vector<std::string>& fields) {
                if (!fields.empty() && fields.front().front() != '#') visit(line_number, fields);
                return true;
              });
}

void ForEachRecord(
    const std::string& path, std::size_t count, const std::string& shape,
    const std::function<void(int, const std::string&, const std::vector<std::string>&)>& visit) {
  ForEachDataLine(path, [&](int line_number, const std::vector<std::string>& fields) {
    const std::string where = path + ":" + std::to_string(line_number);
    if (fields.size() != count) {
      throw Error(where + ": expected " + shape + ", found " + std::to_string(fields.size()));
    }
    visit(line_number, where, fields);
  });
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

void ParseFiniteNumbers(const std::vector<std::string>& fields, std::size_t count,
                        const std::string& where, double* values) {
  for (std::size_t k = 0; k < count; ++k) values[k] = ParseNumber(fields[k], where);
  for (std::size_t k = 0; k < count; ++k) {
    if (!std::isfinite(values[k])) {
      throw Error(where + ": value '" + fields[k] + "' is not finite");
    }
  }
}

}  // namespace drvslam
