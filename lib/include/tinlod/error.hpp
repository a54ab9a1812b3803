// The one exception type for bad files and bad user input: it names the file (or option) and the
// problem. Apps catch it, print what() on one line and exit non-zero.
#pragma once

#include <stdexcept>
#include <string>

namespace tinlod {

class Error : public std::runtime_error {
  public:
    // `subject` is the path or option at fault (may be empty); `reason` says what is wrong.
    Error(const std::string &subject, const std::string &reason)
        : std::runtime_error(subject.empty() ? reason : subject + ": " + reason), subject_(subject),
          reason_(reason) {}
    const std::string &subject() const { return subject_; }
    const std::string &reason() const { return reason_; }

  private:
    std::string subject_;
    std::string reason_;
};

} // namespace tinlod
