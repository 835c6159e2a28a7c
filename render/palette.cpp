#include "render/palette.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace storey::render {
namespace {

// Hand-picked, well separated colours first (Tableau 10, then Kelly's
// colours without white, black and greys), then generated ones.
constexpr std::array<Rgb, 28> kBase{{
    {31, 119, 180},  {255, 127, 14}, {44, 160, 44},  {214, 39, 40}, {148, 103, 189}, {140, 86, 75},
    {227, 119, 194}, {188, 189, 34}, {23, 190, 207}, {255, 179, 0}, {128, 62, 117},  {255, 104, 0},
    {166, 189, 215}, {193, 0, 32},   {206, 162, 98}, {0, 125, 52},  {246, 118, 142}, {0, 83, 138},
    {255, 122, 92},  {83, 55, 122},  {255, 142, 0},  {179, 40, 81}, {244, 200, 0},   {127, 24, 13},
    {147, 170, 0},   {89, 51, 21},   {241, 58, 19},  {35, 44, 22},
}};

Rgb fromHsv(double h, double s, double v) {
  const double c = v * s;
  const double hp = std::fmod(h, 1.0) * 6.0;
  const double x = c * (1.0 - std::abs(std::fmod(hp, 2.0) - 1.0));
  double r = 0, g = 0, b = 0;
  if (hp < 1) {
    r = c;
    g = x;
  } else if (hp < 2) {
    r = x;
    g = c;
  } else if (hp < 3) {
    g = c;
    b = x;
  } else if (hp < 4) {
    g = x;
    b = c;
  } else if (hp < 5) {
    r = x;
    b = c;
  } else {
    r = c;
    b = x;
  }
  const double m = v - c;
  auto byte = [&](double u) { return static_cast<std::uint8_t>(std::lround(255.0 * (u + m))); };
  return {byte(r), byte(g), byte(b)};
}

std::array<Rgb, kSrpPaletteSize> buildSrpPalette() {
  std::array<Rgb, kSrpPaletteSize> palette{};
  int n = 0;
  auto taken = [&](const Rgb& c) {
    if (c.r == c.g && c.g == c.b) return true;  // no greys
    return std::find(palette.begin(), palette.begin() + n, c) != palette.begin() + n;
  };
  for (const Rgb& c : kBase) palette[static_cast<std::size_t>(n++)] = c;
  // Golden-ratio hues over a few saturation/value tiers.
  constexpr double kGolden = 0.61803398874989485;
  double h = 0.1;
  int step = 0;
  while (n < kSrpPaletteSize) {
    const double s = (step % 3 == 0) ? 0.85 : (step % 3 == 1 ? 0.6 : 1.0);
    const double v = (step % 2 == 0) ? 0.85 : 0.6;
    const Rgb c = fromHsv(h, s, v);
    if (!taken(c)) palette[static_cast<std::size_t>(n++)] = c;
    h = std::fmod(h + kGolden, 1.0);
    ++step;
  }
  return palette;
}

constexpr std::array<Rgb, 10> kStoreys{{
    {31, 119, 180},
    {255, 127, 14},
    {44, 160, 44},
    {214, 39, 40},
    {148, 103, 189},
    {140, 86, 75},
    {227, 119, 194},
    {188, 189, 34},
    {23, 190, 207},
    {255, 179, 0},
}};

// viridis at 0, 1/8, ..., 1
constexpr std::array<Rgb, 9> kViridis{{
    {68, 1, 84},
    {71, 44, 122},
    {59, 81, 139},
    {44, 113, 142},
    {33, 144, 141},
    {39, 173, 129},
    {92, 200, 99},
    {170, 220, 50},
    {253, 231, 37},
}};

}  // namespace

Rgb srpColour(int id) {
  static const std::array<Rgb, kSrpPaletteSize> palette = buildSrpPalette();
  const int i = id < 0 ? 0 : id % kSrpPaletteSize;
  return palette[static_cast<std::size_t>(i)];
}

Rgb storeyColour(int index) {
  if (index < 0) return {160, 160, 160};
  return kStoreys[static_cast<std::size_t>(index) % kStoreys.size()];
}

Rgb mapGrey(double t) {
  t = std::clamp(t, 0.0, 1.0);
  const auto v = static_cast<std::uint8_t>(std::lround(110.0 + 110.0 * t));
  return {v, v, v};
}

Rgb heightColour(double t) {
  if (!std::isfinite(t)) t = 0.0;
  t = std::clamp(t, 0.0, 1.0) * static_cast<double>(kViridis.size() - 1);
  const auto i = std::min<std::size_t>(static_cast<std::size_t>(t), kViridis.size() - 2);
  const double f = t - static_cast<double>(i);
  auto mix = [&](std::uint8_t a, std::uint8_t b) {
    return static_cast<std::uint8_t>(std::lround(a + f * (static_cast<double>(b) - a)));
  };
  const Rgb& a = kViridis[i];
  const Rgb& b = kViridis[i + 1];
  return {mix(a.r, b.r), mix(a.g, b.g), mix(a.b, b.b)};
}

std::vector<Rgb> heightScale(int n) {
  std::vector<Rgb> out;
  for (int i = 0; i < n; ++i) out.push_back(heightColour(static_cast<double>(i) / (n - 1)));
  return out;
}

}  // namespace storey::render
