#pragma once
// FNV-1a, the one 64-bit hash of the libraries' keys and fingerprints (tables keyed by the bits
// of points, duplicate faces, a tessellation's fingerprint, the bench's mesh hashes).
#include <array>
#include <cstddef>
#include <cstdint>
#include <cstring>

namespace ricci {

/// 64-bit FNV-1a (Fowler, Noll, Vo), fed by words or by bytes; value() is the hash so far.
/// The same data fed by words and by bytes hashes differently: keep one way per use.
class Fnv1a {
 public:
  /// Mixes one 64-bit word in one FNV-1a step.
  constexpr Fnv1a& add(std::uint64_t word) {
    hash_ = (hash_ ^ word) * kPrime;
    return *this;
  }
  /// Mixes `bytes` bytes at `data` by 8-byte words (native byte order), the tail byte by byte.
  Fnv1a& add_words(const void* data, std::size_t bytes) {
    const auto* p = static_cast<const unsigned char*>(data);
    std::size_t i = 0;
    for (; i + 8 <= bytes; i += 8) {
      std::uint64_t word;
      std::memcpy(&word, p + i, 8);
      add(word);
    }
    return add_bytes(p + i, bytes - i);
  }
  /// Mixes `bytes` bytes at `data` byte by byte (the textbook FNV-1a).
  Fnv1a& add_bytes(const void* data, std::size_t bytes) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < bytes; ++i) add(p[i]);
    return *this;
  }
  [[nodiscard]] constexpr std::uint64_t value() const { return hash_; }

 private:
  static constexpr std::uint64_t kOffsetBasis = 14695981039346656037ull;
  static constexpr std::uint64_t kPrime = 1099511628211ull;
  std::uint64_t hash_ = kOffsetBasis;
};

/// A hasher for std::unordered_map keys of N 64-bit words (for example a point's coordinate
/// bits): FNV-1a of the words with its high half folded onto the low one, which picks buckets.
struct WordsHash {
  template <std::size_t N>
  std::size_t operator()(const std::array<std::uint64_t, N>& key) const {
    Fnv1a h;
    for (std::uint64_t word : key) h.add(word);
    return static_cast<std::size_t>(h.value() ^ (h.value() >> 32));
  }
};

}  // namespace ricci
