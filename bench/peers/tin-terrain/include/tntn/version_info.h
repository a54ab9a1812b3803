#pragma once

#include <string>

namespace tntn {

std::string get_git_description();

std::string get_git_hash();

std::string get_timestamp();

} // namespace tntn
