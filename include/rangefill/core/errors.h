// Exceptions thrown by the library. Every message is one line that names the file, hole or stage
// and what is wrong; the command-line tools map the classes to exit codes.
#pragma once

#include <stdexcept>
#include <string>

namespace rangefill {

/// Base of every exception the library throws on purpose.
class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// The input (a file, a mesh or an argument) is malformed or violates a documented precondition.
class InvalidInput : public Error {
 public:
  using Error::Error;
};

/// A file could not be opened, read, written or renamed.
class IoError : public Error {
 public:
  using Error::Error;
};

/// A well-formed input could not be processed (a solver diverged, a hole could not be filled).
class ProcessingError : public Error {
 public:
  using Error::Error;
};

}  // namespace rangefill
