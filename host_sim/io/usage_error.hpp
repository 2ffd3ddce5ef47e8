#pragma once
/// The error every host tool raises for bad input or an unusable output.

#include <stdexcept>

namespace mrd::io {

/// Bad input or an unusable output: the CLI prints the message on one line
/// and exits with status 2.
class UsageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace mrd::io
