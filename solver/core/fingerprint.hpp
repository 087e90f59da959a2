#pragma once
// A 64-bit FNV-1a fingerprint of bytes, as 16 hex digits: enough to tell that two case
// files or two meshes differ (not a cryptographic hash).

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <string>

namespace hfdda {

class Fingerprint {
 public:
  void add(const void* data, std::size_t bytes) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < bytes; ++i) hash_ = (hash_ ^ p[i]) * 1099511628211ULL;
  }
  void add(double value) { add(&value, sizeof value); }
  void add(const std::string& text) { add(text.data(), text.size()); }
  std::string hex() const {
    char text[17];
    std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(hash_));
    return text;
  }

 private:
  std::uint64_t hash_ = 1469598103934665603ULL;
};

}  // namespace hfdda
