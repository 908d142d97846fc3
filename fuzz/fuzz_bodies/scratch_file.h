// Files for the readers that take a path: the fuzz bytes written to a file in one temporary
// folder per process, reused by every run and removed when the process ends normally.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

namespace drvslam::fuzz {

// The process's scratch folder (created on first use).
std::string ScratchFolder();

// Writes `bytes` to ScratchFolder()/name (replacing it) and returns the path.
std::string WriteScratchFile(const std::string& name, const std::string& bytes);
std::string WriteScratchFile(const std::string& name, const std::uint8_t* data, std::size_t size);

// Removes ScratchFolder()/name if it exists (a reader that looks for optional files beside the
// main one must not see a previous run's).
void RemoveScratchFile(const std::string& name);

}  // namespace drvslam::fuzz
