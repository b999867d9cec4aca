// Errors as values. Every fallible library function returns Result<T>: either the value or an
// Error whose message names the file (or argument) and what is wrong with it, in one line. The
// library never prints and never exits; only the command line turns an Error into a message and
// an exit status (ErrorCode::Usage -> 2, everything else -> 1).
#pragma once

#include <string>
#include <utility>
#include <variant>

namespace lfcam {

enum class ErrorCode {
  Usage,        // the caller asked for something impossible (bad argument, missing metadata)
  Io,           // the file system refused: missing file, no permission, full disk
  Format,       // the file exists but its content is not what it should be
  Unsupported,  // a valid file of a kind or variant lfcam does not handle
  Resource,     // the input would need more memory than allowed
};

struct Error {
  ErrorCode code = ErrorCode::Format;
  std::string message;
};

inline Error makeError(ErrorCode code, std::string message) { return Error{code, std::move(message)}; }

template <class T>
class [[nodiscard]] Result {
 public:
  Result(T value) : state_(std::move(value)) {}
  Result(Error error) : state_(std::move(error)) {}

  bool ok() const { return state_.index() == 0; }
  explicit operator bool() const { return ok(); }

  T& value() & { return std::get<0>(state_); }
  const T& value() const& { return std::get<0>(state_); }
  T&& value() && { return std::get<0>(std::move(state_)); }
  T& operator*() & { return value(); }
  T&& operator*() && { return std::move(*this).value(); }
  T* operator->() { return &value(); }
  const T* operator->() const { return &value(); }

  const Error& error() const { return std::get<1>(state_); }

 private:
  std::variant<T, Error> state_;
};

template <>
class [[nodiscard]] Result<void> {
 public:
  Result() = default;
  Result(Error error) : error_(std::move(error)), ok_(false) {}
  bool ok() const { return ok_; }
  explicit operator bool() const { return ok_; }
  const Error& error() const { return error_; }

 private:
  Error error_;
  bool ok_ = true;
};

using Status = Result<void>;

}  // namespace lfcam

// Declares `declaration` (e.g. `auto image`) from the value of `expr`, a Result<T>, or returns its
// error from the enclosing function: LFCAM_ASSIGN_OR_RETURN(auto image, readImage(path));
#define LFCAM_ASSIGN_OR_RETURN(declaration, ...) \
  LFCAM_ASSIGN_OR_RETURN_NAMED(declaration, LFCAM_CONCAT(lfcam_assign_result_, __COUNTER__), __VA_ARGS__)
#define LFCAM_ASSIGN_OR_RETURN_NAMED(declaration, name, ...) \
  auto name = (__VA_ARGS__);                                 \
  if (!name) return name.error();                            \
  declaration = std::move(name).value()

// Propagates an error from an expression returning Result<...> / Status. Each use gets its own
// variable name, so uses nested in lambdas inside another use do not shadow it.
#define LFCAM_TRY(expr) LFCAM_TRY_NAMED(expr, LFCAM_CONCAT(lfcam_try_result_, __COUNTER__))
#define LFCAM_CONCAT(a, b) LFCAM_CONCAT_INNER(a, b)
#define LFCAM_CONCAT_INNER(a, b) a##b
#define LFCAM_TRY_NAMED(expr, name) \
  do {                              \
    auto&& name = (expr);           \
    if (!name) return name.error(); \
  } while (0)
