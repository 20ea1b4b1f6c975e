#pragma once
// An RGB picture in memory, and its PNG encoding: what the evidence report shows of a mesh.

#include <cstdint>
#include <string>
#include <vector>

namespace meshmark {

struct Rgb {
  std::uint8_t r = 0, g = 0, b = 0;
  bool operator==(const Rgb&) const = default;
};

struct Image {
  Image(int width, int height, Rgb background) : width(width), height(height), pixels(width * height, background) {}
  int width = 0;
  int height = 0;
  std::vector<Rgb> pixels;  ///< row by row, top first
  Rgb& at(int x, int y) { return pixels[static_cast<std::size_t>(y) * width + x]; }
  const Rgb& at(int x, int y) const { return pixels[static_cast<std::size_t>(y) * width + x]; }
};

/// The image as a PNG file (8-bit RGB, no interlace), compressed with zlib.
std::string encode_png(const Image& image);

}  // namespace meshmark
