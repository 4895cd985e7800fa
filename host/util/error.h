// error.h — the exceptions that cross the host boundary. main() turns them into a message and a
// non-zero exit; nothing is written after one is thrown during set-up.
#pragma once
#include <stdexcept>
#include <string>

namespace seasim {

// Bad input in a scene or job file: what() reads "FILE:LINE: key 'KEY': message".
class InputError : public std::runtime_error {
 public:
  InputError(std::string file, int line, std::string key, const std::string& message)
      : std::runtime_error(file + ":" + std::to_string(line) + ": " +
                           (key.empty() ? std::string() : "key '" + key + "': ") + message),
        file_(std::move(file)), line_(line), key_(std::move(key)) {}
  const std::string& file() const { return file_; }
  int line() const { return line_; }
  const std::string& key() const { return key_; }

 private:
  std::string file_;
  int line_;
  std::string key_;
};

// A device, driver or kernel-build failure: the message names the OpenCL call or kernel file.
class DeviceError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Any other user-facing failure (I/O, missing data).
class RuntimeError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace seasim
