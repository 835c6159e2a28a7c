// Where the parts of a figure go (shared by the VTK back end and the tests).
#include <algorithm>
#include <cmath>

#include "render/figure.h"

namespace storey::render {

FigureLayout figureLayout(int width, int height) {
  const int title_h = std::clamp(static_cast<int>(std::lround(height * 0.085)), 36, 130);
  const int legend_w = std::clamp(static_cast<int>(std::lround(width * 0.26)), 160, 560);
  FigureLayout layout;
  layout.title = {0, 0, width, title_h};
  layout.scene = {0, title_h, width - legend_w, height};
  layout.legend = {width - legend_w, title_h, width, height};
  return layout;
}

PixelRect panelRect(const FigureLayout& layout, const Panel& panel) {
  const PixelRect& s = layout.scene;
  auto at = [](int a, int b, double f) { return a + static_cast<int>(std::lround((b - a) * f)); };
  return {at(s.x0, s.x1, panel.x0), at(s.y0, s.y1, panel.y0), at(s.x0, s.x1, panel.x1),
          at(s.y0, s.y1, panel.y1)};
}

}  // namespace storey::render
