#pragma once
/// A picture described in plain C++ (no VTK): panels of 3D content seen
/// through orthographic cameras, a title, a legend and an optional colour
/// bar. The views (views_*.cpp) build Figures from a run's files; one VTK
/// back end (figure_vtk.cpp) draws them to PNG. Everything is drawn unlit in
/// flat colours without anti-aliasing, so the exact palette colours appear in
/// the image (the tests count them).
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace storey::render {

struct Rgb {
  std::uint8_t r = 0, g = 0, b = 0;
  friend bool operator==(const Rgb& a, const Rgb& b) {
    return a.r == b.r && a.g == b.g && a.b == b.b;
  }
  friend bool operator!=(const Rgb& a, const Rgb& b) { return !(a == b); }
};

/// Points (world frame) with one colour each.
struct PointLayer {
  std::vector<Eigen::Vector3f> positions;
  std::vector<Rgb> colours;  ///< same size as positions
  float size_px = 2.0f;
};

/// Polylines of one colour (trajectories, floor lines, outlines).
struct LineLayer {
  std::vector<std::vector<Eigen::Vector3d>> polylines;
  Rgb colour;
  float width_px = 2.0f;
  bool on_top = true;   ///< drawn over the points (no depth test against them)
  bool dashed = false;  ///< drawn as dashes (split into segments)
};

/// Planar polygons (SRP patches), each filled or outlined in its colour.
struct PatchLayer {
  struct Patch {
    std::vector<Eigen::Vector3d> vertices;  ///< convex, in order
    Rgb colour;
    bool filled = true;  ///< false: outline only
  };
  std::vector<Patch> patches;
  float outline_px = 2.0f;
};

/// Text anchored at a world point (drawn over everything in the panel).
struct WorldLabel {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  std::string text;
  Rgb colour;
  int font_px = 14;
};

/// One orthographic view. The camera looks along `view_direction` with
/// `view_up` up; the content (or `fit`, when given) fills the panel.
struct Panel {
  double x0 = 0.0, y0 = 0.0, x1 = 1.0, y1 = 1.0;  ///< fraction of the scene area, y down
  std::string caption;                            ///< drawn at the panel's top left
  Eigen::Vector3d view_direction{0.0, 1.0, 0.0};
  Eigen::Vector3d view_up{0.0, 0.0, 1.0};
  std::optional<Eigen::AlignedBox3d> fit;  ///< region that must be visible; default: all content
  std::vector<PointLayer> points;
  std::vector<PatchLayer> patches;
  std::vector<LineLayer> lines;
  std::vector<WorldLabel> labels;
  bool scale_bar = true;  ///< a bar of a round number of metres, bottom left
};

struct LegendItem {
  enum class Kind { kHeading, kSwatch, kLine, kText };
  Kind kind = Kind::kText;
  Rgb colour;
  std::string text;
};

/// A continuous colour scale (e.g. height), drawn in the legend column.
struct ColourBar {
  std::string title;
  double min = 0.0, max = 1.0;
  std::vector<Rgb> colours;  ///< samples from min to max (at least 2)
};

struct Figure {
  int width = 1600, height = 1000;  ///< [px]
  std::string title;
  std::string subtitle;
  Rgb background{255, 255, 255};
  std::vector<Panel> panels;
  std::vector<LegendItem> legend;
  std::optional<ColourBar> colour_bar;
};

/// Pixel rectangle in image coordinates: origin top left, y down, [x0, x1) x [y0, y1).
struct PixelRect {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  int width() const { return x1 - x0; }
  int height() const { return y1 - y0; }
};

/// Where the title band, the panels' area and the legend column go.
struct FigureLayout {
  PixelRect title;
  PixelRect scene;
  PixelRect legend;
};
FigureLayout figureLayout(int width, int height);
/// The pixel rectangle of a panel inside the scene area.
PixelRect panelRect(const FigureLayout& layout, const Panel& panel);

/// Draws the figure off-screen with VTK and writes it as PNG (atomically).
/// Needs a usable X display (see x_display.h). Throws storey::Error.
void renderFigure(const Figure& figure, const std::string& png_path);

}  // namespace storey::render
