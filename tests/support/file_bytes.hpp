// A file's bytes, read and written whole: for tests that damage checkpoints.
#pragma once

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

namespace plab::testing_support {

inline std::string slurp(const std::filesystem::path& p) {
    std::ifstream f(p, std::ios::binary);
    return {std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>()};
}

inline void spit(const std::filesystem::path& p, const std::string& bytes) {
    std::ofstream f(p, std::ios::binary);
    f << bytes;
}

} // namespace plab::testing_support
