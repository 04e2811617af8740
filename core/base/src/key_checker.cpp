#include "rover/base/key_checker.hpp"

#include <cmath>

#include "rover/base/format.hpp"

namespace rover {

bool KeyChecker::Fail(const std::string& key, const std::string& message) {
  if (status_.ok()) {
    status_ = InvalidArgument(key + ": " + message);
    key_ = key;
  }
  return false;
}

bool KeyChecker::Finite(const std::string& key, double v) {
  return std::isfinite(v) || Fail(key, FormatNumber(v) + " is not a finite number");
}

bool KeyChecker::Positive(const std::string& key, double v) {
  return Finite(key, v) && (v > 0.0 || Fail(key, FormatNumber(v) + " must be > 0"));
}

bool KeyChecker::AtLeast(const std::string& key, double v, double lo) {
  return Finite(key, v) &&
         (v >= lo || Fail(key, FormatNumber(v) + " must be >= " + FormatNumber(lo)));
}

bool KeyChecker::InRange(const std::string& key, double v, double lo, double hi) {
  return Finite(key, v) &&
         ((v >= lo && v <= hi) || Fail(key, FormatNumber(v) + " is out of range [" +
                                                FormatNumber(lo) + ", " + FormatNumber(hi) + "]"));
}

}  // namespace rover
