// JSON documents written atomically (json_io.hpp).
#include "tinlod/json_io.hpp"
#include "tinlod/error.hpp"
#include "tinlod/util.hpp"

#include <cerrno>
#include <cstring>
#include <fstream>

namespace tinlod {

void write_json(const std::string &path, const nlohmann::json &doc) {
    write_atomically(path, [&](const std::string &tmp) {
        std::ofstream out(tmp);
        out << doc.dump(2) << '\n';
        if (!out.flush())
            throw Error(path, "cannot write: " + std::string(std::strerror(errno)));
    });
}

} // namespace tinlod
