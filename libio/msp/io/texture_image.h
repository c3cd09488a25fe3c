#pragma once
// Small RGBA images for textures (the atlas checkerboard) and a PNG encoder for them, so a
// texture can travel inside a .glb or sit next to an .obj.
#include <array>
#include <cstdint>
#include <vector>

namespace msp {

using Rgba = std::array<std::uint8_t, 4>;

/// Row-major, top row first, 4 bytes per pixel.
struct RgbaImage {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> pixels;  ///< width * height * 4 bytes.

  RgbaImage() = default;
  RgbaImage(int w, int h, Rgba fill);
  [[nodiscard]] Rgba at(int x, int y) const;
  void set(int x, int y, Rgba colour);
};

/// Encodes `image` as an 8-bit RGBA PNG (zlib deflate, no filtering; checkerboards compress to
/// a few kilobytes).
/// \throw ricci::InvalidInputError if the image is empty or its pixel buffer has the wrong size.
[[nodiscard]] std::vector<std::uint8_t> encode_png(const RgbaImage& image);

struct CheckerboardOptions {
  int size = 1024;   ///< Width and height in pixels (a power of two keeps mipmaps exact).
  int squares = 32;  ///< Squares along each side; size must be a multiple of it.
  Rgba dark = {40, 40, 48, 255};
  Rgba light = {236, 236, 228, 255};
  /// Every `major` squares a thin coloured line helps follow rows across the surface (0: none).
  int major = 0;
  Rgba major_colour = {200, 60, 40, 255};
};

/// A checkerboard: square (i, j) is dark when i + j is even, the square at the origin (top-left)
/// dark. \throw ricci::InvalidInputError for a size that is not a positive multiple of squares.
[[nodiscard]] RgbaImage checkerboard(const CheckerboardOptions& options = {});

}  // namespace msp
