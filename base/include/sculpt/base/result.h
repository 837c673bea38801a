#pragma once
// Error values for bad input from outside (files, devices, command line).
//
// Internal invariants are asserts; anything a user can get wrong returns an
// Error whose message names the input and what is wrong with it, in one line,
// e.g. "part.nrrd: sizes: expected 3 numbers, got 2".

#include <cassert>
#include <string>
#include <utility>
#include <variant>

namespace sculpt {

/// One line that names the input and what is wrong with it.
class Error {
 public:
  explicit Error(std::string message) : message_(std::move(message)) {}
  const std::string& message() const { return message_; }

  /// Prefixes the message with the name of the input ("file.nrrd: ...").
  Error in(const std::string& input) const { return Error(input + ": " + message_); }

 private:
  std::string message_;
};

/// Either a value or an Error. Check `ok()` (or convert to bool) before `value()`.
template <class T>
class [[nodiscard]] Result {
 public:
  Result(T value) : state_(std::move(value)) {}      // NOLINT: implicit on purpose
  Result(Error error) : state_(std::move(error)) {}  // NOLINT

  bool ok() const { return std::holds_alternative<T>(state_); }
  explicit operator bool() const { return ok(); }

  T& value() & {
    assert(ok());
    return std::get<T>(state_);
  }
  const T& value() const& {
    assert(ok());
    return std::get<T>(state_);
  }
  T&& value() && {
    assert(ok());
    return std::get<T>(std::move(state_));
  }
  T* operator->() { return &value(); }
  const T* operator->() const { return &value(); }
  T& operator*() & { return value(); }
  const T& operator*() const& { return value(); }

  const Error& error() const {
    assert(!ok());
    return std::get<Error>(state_);
  }

 private:
  std::variant<T, Error> state_;
};

/// Success or an Error, for operations without a value.
class [[nodiscard]] Status {
 public:
  Status() = default;
  Status(Error error) : error_(std::move(error)), ok_(false) {}  // NOLINT: implicit on purpose

  bool ok() const { return ok_; }
  explicit operator bool() const { return ok_; }
  const Error& error() const {
    assert(!ok_);
    return error_;
  }

 private:
  Error error_{""};
  bool ok_ = true;
};

}  // namespace sculpt
