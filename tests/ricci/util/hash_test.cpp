#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <cstring>
#include <string>

#include "ricci/util/hash.h"

// The published FNV-1a 64-bit test vectors (Fowler, Noll, Vo): "" is the offset basis.
TEST(Fnv1a, ReproducesThePublishedVectors) {
  const auto of = [](const std::string& s) {
    return ricci::Fnv1a().add_bytes(s.data(), s.size()).value();
  };
  EXPECT_EQ(of(""), 0xcbf29ce484222325ull);
  EXPECT_EQ(of("a"), 0xaf63dc4c8601ec8cull);
  EXPECT_EQ(of("foobar"), 0x85944171f73967e8ull);
}

// By words: each 8-byte word is one step, the tail goes byte by byte; the same words fed one by
// one give the same hash, and one flipped bit anywhere changes it.
TEST(Fnv1a, WordsAreOneStepEachAndTheTailGoesByBytes) {
  const std::array<std::uint64_t, 2> words{0x0123456789abcdefull, 0xfedcba9876543210ull};
  const unsigned char tail[3] = {1, 2, 3};
  unsigned char buffer[19];
  std::memcpy(buffer, words.data(), 16);
  std::memcpy(buffer + 16, tail, 3);
  const std::uint64_t stepped =
      ricci::Fnv1a().add(words[0]).add(words[1]).add(1).add(2).add(3).value();
  EXPECT_EQ(ricci::Fnv1a().add_words(buffer, sizeof buffer).value(), stepped);
  buffer[9] ^= 0x10;
  EXPECT_NE(ricci::Fnv1a().add_words(buffer, sizeof buffer).value(), stepped);
  EXPECT_NE(ricci::WordsHash()(words), ricci::WordsHash()(std::array<std::uint64_t, 2>{
                                                                words[1], words[0]}));
}
