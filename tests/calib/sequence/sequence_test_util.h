// Helpers shared by the sequence tests: a temporary file holding a JSON text, and the problems
// of a sequence flattened to one string for HasSubstr matchers.
#pragma once

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <unistd.h>

#include "calib/sequence/validation.h"

namespace adahrs::calib::testing {

/// Writes `text` to a file in the temporary directory (named with the process id, since ctest runs
/// tests in parallel) and removes it at scope end.
class TempFile {
 public:
  TempFile(const std::string& name, const std::string& text)
      : path_((std::filesystem::temp_directory_path() /
               ("adahrs_seq_" + std::to_string(::getpid()) + "_" + name))
                  .string()) {
    std::ofstream(path_) << text;
  }
  ~TempFile() { std::filesystem::remove(path_); }
  TempFile(const TempFile&) = delete;
  TempFile& operator=(const TempFile&) = delete;
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

inline std::string Joined(const std::vector<SequenceProblem>& problems, const std::string& source) {
  std::string text;
  for (const SequenceProblem& p : problems) text += p.Format(source) + "\n";
  return text;
}

}  // namespace adahrs::calib::testing
