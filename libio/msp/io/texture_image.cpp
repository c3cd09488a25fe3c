// PNG encoding follows the PNG specification (signature, IHDR, IDAT, IEND chunks with CRC-32);
// zlib supplies deflate and the CRC.
#include "msp/io/texture_image.h"

#include <string>

#include <ricci/mesh/errors.h>
#include <zlib.h>

namespace msp {
namespace {

void put_u32(std::vector<std::uint8_t>& out, std::uint32_t v) {
  out.push_back(static_cast<std::uint8_t>(v >> 24));
  out.push_back(static_cast<std::uint8_t>(v >> 16));
  out.push_back(static_cast<std::uint8_t>(v >> 8));
  out.push_back(static_cast<std::uint8_t>(v));
}

void put_chunk(std::vector<std::uint8_t>& out, const char* type,
               const std::vector<std::uint8_t>& data) {
  put_u32(out, static_cast<std::uint32_t>(data.size()));
  const size_t start = out.size();
  out.insert(out.end(), type, type + 4);
  out.insert(out.end(), data.begin(), data.end());
  // The CRC covers the chunk type and data, not the length.
  uLong crc = crc32(0L, Z_NULL, 0);
  crc = crc32(crc, out.data() + start, static_cast<uInt>(out.size() - start));
  put_u32(out, static_cast<std::uint32_t>(crc));
}

}  // namespace

RgbaImage::RgbaImage(int w, int h, Rgba fill) : width(w), height(h) {
  if (w <= 0 || h <= 0) {
    throw ricci::InvalidInputError("image size " + std::to_string(w) + "x" + std::to_string(h) +
                                   " is not positive");
  }
  pixels.resize(static_cast<size_t>(w) * static_cast<size_t>(h) * 4);
  for (size_t i = 0; i < pixels.size(); i += 4) {
    for (int c = 0; c < 4; ++c) pixels[i + static_cast<size_t>(c)] = fill[static_cast<size_t>(c)];
  }
}

Rgba RgbaImage::at(int x, int y) const {
  const size_t i =
      (static_cast<size_t>(y) * static_cast<size_t>(width) + static_cast<size_t>(x)) * 4;
  return {pixels[i], pixels[i + 1], pixels[i + 2], pixels[i + 3]};
}

void RgbaImage::set(int x, int y, Rgba colour) {
  const size_t i =
      (static_cast<size_t>(y) * static_cast<size_t>(width) + static_cast<size_t>(x)) * 4;
  for (size_t c = 0; c < 4; ++c) pixels[i + c] = colour[c];
}

std::vector<std::uint8_t> encode_png(const RgbaImage& image) {
  const size_t row_bytes = static_cast<size_t>(image.width) * 4;
  if (image.width <= 0 || image.height <= 0 ||
      image.pixels.size() != row_bytes * static_cast<size_t>(image.height)) {
    throw ricci::InvalidInputError("encode_png: image " + std::to_string(image.width) + "x" +
                                   std::to_string(image.height) + " with " +
                                   std::to_string(image.pixels.size()) + " bytes of pixels");
  }
  // Each scanline starts with its filter type (0: none).
  std::vector<std::uint8_t> raw;
  raw.reserve((row_bytes + 1) * static_cast<size_t>(image.height));
  for (int y = 0; y < image.height; ++y) {
    raw.push_back(0);
    const auto* row = image.pixels.data() + row_bytes * static_cast<size_t>(y);
    raw.insert(raw.end(), row, row + row_bytes);
  }
  uLongf packed_size = compressBound(static_cast<uLong>(raw.size()));
  std::vector<std::uint8_t> packed(packed_size);
  if (compress2(packed.data(), &packed_size, raw.data(), static_cast<uLong>(raw.size()),
                Z_BEST_COMPRESSION) != Z_OK) {
    throw ricci::IOError("encode_png: zlib could not compress the image");
  }
  packed.resize(packed_size);

  std::vector<std::uint8_t> out = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  std::vector<std::uint8_t> header;
  put_u32(header, static_cast<std::uint32_t>(image.width));
  put_u32(header, static_cast<std::uint32_t>(image.height));
  header.insert(header.end(),
                {8, 6, 0, 0, 0});  // 8 bits, RGBA, deflate, adaptive filters, no interlace
  put_chunk(out, "IHDR", header);
  put_chunk(out, "IDAT", packed);
  put_chunk(out, "IEND", {});
  return out;
}

RgbaImage checkerboard(const CheckerboardOptions& o) {
  if (o.size <= 0 || o.squares <= 0 || o.size % o.squares != 0) {
    throw ricci::InvalidInputError("checkerboard: size " + std::to_string(o.size) +
                                   " is not a positive multiple of squares " +
                                   std::to_string(o.squares));
  }
  const int step = o.size / o.squares;
  RgbaImage image(o.size, o.size, o.light);
  // A major line is two pixels wide on each side of every `major`-th grid line (wrapping, so the
  // texture tiles).
  auto on_major = [&](int p) {
    if (o.major <= 0) return false;
    const int period = step * o.major;
    const int r = p % period;
    return r < 2 || r >= period - 2;
  };
  for (int y = 0; y < o.size; ++y) {
    for (int x = 0; x < o.size; ++x) {
      if (on_major(x) || on_major(y)) {
        image.set(x, y, o.major_colour);
      } else if ((x / step + y / step) % 2 == 0) {
        image.set(x, y, o.dark);
      }
    }
  }
  return image;
}

}  // namespace msp
