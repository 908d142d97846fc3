// Line-oriented reading shared by the TUM list and trajectory readers: comments ('#') and blank
// lines are skipped, fields split on spaces, tabs and commas.
#pragma once

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

namespace drvslam {

// Calls `visit(line_number, line, fields)` for every line, comments and blank lines included
// (1-based numbers), until it returns false. Throws Error when the file cannot be opened.
void ForEachLine(
    const std::string& path,
    const std::function<bool(int, const std::string&, const std::vector<std::string>&)>& visit);

// Calls `visit(line_number, fields)` for each data line (1-based numbers). Throws Error when the
// file cannot be opened.
void ForEachDataLine(const std::string& path,
                     const std::function<void(int, const std::vector<std::string>&)>& visit);

// ForEachDataLine for files whose data lines hold exactly `count` fields: calls
// `visit(line_number, where, fields)` with where = "<path>:<line_number>". A line with another
// count throws Error("<where>: expected <shape>, found <n>"), where `shape` says what the fields
// are, e.g. "2 fields (timestamp image_path)".
void ForEachRecord(
    const std::string& path, std::size_t count, const std::string& shape,
    const std::function<void(int, const std::string&, const std::vector<std::string>&)>& visit);

// The fields of one line, split on spaces, tabs, commas and carriage returns (as
// ForEachDataLine splits them; comments are not removed).
std::vector<std::string> SplitFields(const std::string& line);

// Parses a whole field as a double (accepting "nan"/"inf" so the caller can name them); throws
// Error "<where>: '<field>' is not a number" otherwise.
double ParseNumber(const std::string& field, const std::string& where);

// ParseNumber on the first `count` fields into `values`, then an Error
// "<where>: value '<field>' is not finite" for the first that is nan or inf.
void ParseFiniteNumbers(const std::vector<std::string>& fields, std::size_t count,
                        const std::string& where, double* values);

}  // namespace drvslam
