// Stats files: JSON documents written atomically (tinlod::io; core's interface holds no JSON).
#pragma once

#include <nlohmann/json.hpp>

#include <string>

namespace tinlod {

// Writes a JSON document atomically (pretty-printed).
void write_json(const std::string &path, const nlohmann::json &doc);

} // namespace tinlod
