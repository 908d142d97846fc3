// Line-oriented reading shared by the TUM list and trajectory readers: comments ('#') and blank
// lines are skipped, fields split on spaces, tabs and commas.
#pragma once

#include <functional>
#include <string>
#include <vector>

namespace drvslam {

// Calls `visit(line_number, fields)` for each data line (1-based numbers). Throws Error when the
// file cannot be opened.
void ForEachDataLine(const std::string& path,
                     const std::function<void(int, const std::vector<std::string>&)>& visit);

// The fields of one line, split on spaces, tabs, commas and carriage returns (as
// ForEachDataLine splits them; comments are not removed).
std::vector<std::string> SplitFields(const std::string& line);

// Parses a whole field as a double (accepting "nan"/"inf" so the caller can name them); throws
// Error "<where>: '<field>' is not a number" otherwise.
double ParseNumber(const std::string& field, const std::string& where);

}  // namespace drvslam
