// The one refusal of the recording layer: a recording that cannot be read as it is, with the file
// (and line, column or JSON path) in the message.
#pragma once

#include <stdexcept>

namespace adahrs::hil {

class RecordingError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace adahrs::hil
