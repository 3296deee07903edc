#pragma once
// FNV-1a, 64 bits, of a string's bytes, and its 16-digit hex form: the hashes that name a config
// (a sweep's id) and a mesh's content. Standard library only, so HDF5-free code (the input
// contracts, io/mesh.cpp) can use them; io/content_hash.hpp hashes whole HDF5 files the same way.
#include <cstdint>
#include <string>

namespace clatter::io {

std::uint64_t text_hash(const std::string& text);  // FNV-1a 64 of the bytes
std::string hash_hex(std::uint64_t hash);          // 16 lowercase hex digits

}  // namespace clatter::io
