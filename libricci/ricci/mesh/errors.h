#pragma once
// Typed exceptions of libricci and libspline. A violated precondition throws one of these with a
// message that names the condition and where (file line, face or vertex index).
#include <stdexcept>
#include <string>

namespace ricci {

/// Base of every error the libraries throw on purpose.
class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// A file cannot be opened, read or written, or its contents are malformed.
class IOError : public Error {
 public:
  using Error::Error;
};

/// The input violates a precondition (NaN coordinates, degenerate faces, bad options, ...).
class InvalidInputError : public Error {
 public:
  using Error::Error;
};

/// The input's topology is unsuitable (non-manifold, non-orientable, several components, ...).
class TopologyError : public InvalidInputError {
 public:
  using InvalidInputError::InvalidInputError;
};

/// A target that no metric can reach (it violates Gauss-Bonnet, or a cone is impossible).
class InfeasibleTargetError : public InvalidInputError {
 public:
  using InvalidInputError::InvalidInputError;
};

/// A numerical solve failed (factorisation failed, NaN appeared, no progress).
class SolverError : public Error {
 public:
  using Error::Error;
};

/// A long computation stopped early because its caller asked it to (the cancellation flag it
/// was given: ricci/util/cancel.h). Nothing it was computing is delivered.
class Cancelled : public Error {
 public:
  using Error::Error;
};

}  // namespace ricci
