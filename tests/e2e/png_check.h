#pragma once
/// Reads a PNG (VTK's reader) for the render tests: size, pixels, colour counts.
#include <cstdint>
#include <set>
#include <string>
#include <vector>

#include "render/figure.h"

namespace storey::test {

struct Image {
  int width = 0, height = 0;
  std::vector<render::Rgb> pixels;  ///< row-major, top row first
  const render::Rgb& at(int x, int y) const {
    return pixels[static_cast<std::size_t>(y) * width + x];
  }
};

/// Empty image (width 0) when the file is not a readable PNG.
Image readPng(const std::string& path);
/// Distinct colours inside [x0, x1) x [y0, y1).
std::set<std::uint32_t> coloursIn(const Image& image, const render::PixelRect& rect);
inline std::uint32_t key(const render::Rgb& c) {
  return (c.r << 16) | (c.g << 8) | c.b;
}

}  // namespace storey::test
