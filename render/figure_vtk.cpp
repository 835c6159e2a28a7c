// The one VTK back end: draws a Figure off-screen and writes a PNG.
// Everything is unlit, flat-coloured and not anti-aliased (the palette
// colours must reach the image unchanged). Layer 0 holds each panel's 3D
// content; layer 1 the lines drawn over it (trajectories) and one
// full-window renderer for the 2D parts: title, legend, captions, scale
// bars, colour bar and labels.
#include <vtkActor.h>
#include <vtkActor2D.h>
#include <vtkCamera.h>
#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkIdTypeArray.h>
#include <vtkNew.h>
#include <vtkPNGWriter.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkPolyDataMapper2D.h>
#include <vtkProperty.h>
#include <vtkProperty2D.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkSmartPointer.h>
#include <vtkTextActor.h>
#include <vtkTextProperty.h>
#include <vtkUnsignedCharArray.h>
#include <vtkWindowToImageFilter.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <map>

#include "common/atomic_file.h"
#include "common/error.h"
#include "render/figure.h"
#include "render/palette.h"

namespace storey::render {
namespace {

using Eigen::Vector3d;

// ---- orthographic camera of a panel -------------------------------------

struct PanelCamera {
  Vector3d forward, up, right, focal;
  double parallel_scale = 1.0;  ///< half the panel height [m]
  double depth_half = 1.0;
  double pixels_per_metre = 1.0;
  PixelRect rect;

  /// Image pixel (x right, y down) of a world point.
  Eigen::Vector2d toPixel(const Vector3d& p) const {
    const Vector3d d = p - focal;
    return {0.5 * (rect.x0 + rect.x1) + d.dot(right) * pixels_per_metre,
            0.5 * (rect.y0 + rect.y1) - d.dot(up) * pixels_per_metre};
  }
};

template <typename F>
void forEachContentPoint(const Panel& panel, F f) {
  if (panel.fit) {
    const Eigen::AlignedBox3d& box = *panel.fit;
    for (int i = 0; i < 8; ++i) f(box.corner(static_cast<Eigen::AlignedBox3d::CornerType>(i)));
    return;
  }
  for (const PointLayer& layer : panel.points) {
    const std::size_t step = std::max<std::size_t>(1, layer.positions.size() / 200000);
    for (std::size_t i = 0; i < layer.positions.size(); i += step)
      f(layer.positions[i].cast<double>());
  }
  for (const PatchLayer& layer : panel.patches)
    for (const auto& patch : layer.patches)
      for (const Vector3d& v : patch.vertices) f(v);
  for (const LineLayer& layer : panel.lines)
    for (const auto& line : layer.polylines)
      for (const Vector3d& v : line) f(v);
}

PanelCamera fitCamera(const Panel& panel, const PixelRect& rect) {
  PanelCamera c;
  c.rect = rect;
  c.forward = panel.view_direction.normalized();
  c.up = (panel.view_up - panel.view_up.dot(c.forward) * c.forward).normalized();
  c.right = c.forward.cross(c.up).normalized();
  double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
  bool any = false;
  forEachContentPoint(panel, [&](const Vector3d& p) {
    if (!p.allFinite()) return;
    const double q[3] = {p.dot(c.right), p.dot(c.up), p.dot(c.forward)};
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::min(lo[k], q[k]);
      hi[k] = std::max(hi[k], q[k]);
    }
    any = true;
  });
  if (!any) {
    for (int k = 0; k < 3; ++k) lo[k] = -1.0, hi[k] = 1.0;
  }
  const double aspect = static_cast<double>(std::max(rect.width(), 1)) / std::max(rect.height(), 1);
  const double half_w = std::max(0.5 * (hi[0] - lo[0]), 0.5);
  const double half_h = std::max(0.5 * (hi[1] - lo[1]), 0.5);
  // Room for the caption (top) and the scale bar (bottom).
  c.parallel_scale = std::max(half_h * 1.22, half_w / aspect * 1.06);
  c.depth_half = std::max(0.5 * (hi[2] - lo[2]), 1.0) + 1.0;
  c.focal = 0.5 * (lo[0] + hi[0]) * c.right + 0.5 * (lo[1] + hi[1]) * c.up +
            0.5 * (lo[2] + hi[2]) * c.forward;
  c.pixels_per_metre = rect.height() / (2.0 * c.parallel_scale);
  return c;
}

// ---- VTK helpers ----------------------------------------------------------

vtkSmartPointer<vtkUnsignedCharArray> colourArray(std::size_t n) {
  auto colours = vtkSmartPointer<vtkUnsignedCharArray>::New();
  colours->SetName("colours");
  colours->SetNumberOfComponents(3);
  colours->SetNumberOfTuples(static_cast<vtkIdType>(n));
  return colours;
}

void setColour(vtkUnsignedCharArray* a, vtkIdType i, const Rgb& c) {
  a->SetTypedComponent(i, 0, c.r);
  a->SetTypedComponent(i, 1, c.g);
  a->SetTypedComponent(i, 2, c.b);
}

/// Unlit, flat, direct colours.
vtkSmartPointer<vtkActor> flatActor(vtkPolyData* data, bool cell_colours) {
  auto mapper = vtkSmartPointer<vtkPolyDataMapper>::New();
  mapper->SetInputData(data);
  mapper->SetColorModeToDirectScalars();
  mapper->ScalarVisibilityOn();
  if (cell_colours)
    mapper->SetScalarModeToUseCellData();
  else
    mapper->SetScalarModeToUsePointData();
  mapper->SetResolveCoincidentTopologyToPolygonOffset();
  auto actor = vtkSmartPointer<vtkActor>::New();
  actor->SetMapper(mapper);
  vtkProperty* p = actor->GetProperty();
  p->LightingOff();
  p->SetAmbient(1.0);
  p->SetDiffuse(0.0);
  p->SetSpecular(0.0);
  p->SetInterpolationToFlat();
  return actor;
}

vtkSmartPointer<vtkActor> pointActor(const PointLayer& layer) {
  const auto n = static_cast<vtkIdType>(layer.positions.size());
  vtkNew<vtkPoints> points;
  points->SetDataTypeToFloat();
  points->SetNumberOfPoints(n);
  auto colours = colourArray(layer.positions.size());
  for (vtkIdType i = 0; i < n; ++i) {
    const Eigen::Vector3f& p = layer.positions[static_cast<std::size_t>(i)];
    points->SetPoint(i, p.x(), p.y(), p.z());
    setColour(colours, i,
              i < static_cast<vtkIdType>(layer.colours.size())
                  ? layer.colours[static_cast<std::size_t>(i)]
                  : Rgb{128, 128, 128});
  }
  vtkNew<vtkIdTypeArray> offsets, connectivity;
  offsets->SetNumberOfValues(n + 1);
  connectivity->SetNumberOfValues(n);
  for (vtkIdType i = 0; i <= n; ++i) offsets->SetValue(i, i);
  for (vtkIdType i = 0; i < n; ++i) connectivity->SetValue(i, i);
  vtkNew<vtkCellArray> verts;
  verts->SetData(offsets, connectivity);
  auto data = vtkSmartPointer<vtkPolyData>::New();
  data->SetPoints(points);
  data->SetVerts(verts);
  data->GetPointData()->SetScalars(colours);
  auto actor = flatActor(data, false);
  actor->GetProperty()->SetPointSize(layer.size_px);
  actor->GetProperty()->SetRenderPointsAsSpheres(false);
  return actor;
}

std::vector<std::vector<Vector3d>> dashes(const std::vector<std::vector<Vector3d>>& lines,
                                          double dash) {
  std::vector<std::vector<Vector3d>> out;
  for (const auto& line : lines) {
    for (std::size_t i = 1; i < line.size(); ++i) {
      const Vector3d a = line[i - 1], b = line[i];
      const double length = (b - a).norm();
      const int n = std::max(1, static_cast<int>(length / dash));
      for (int k = 0; k < n; k += 2) {
        const double t0 = static_cast<double>(k) / n;
        const double t1 = std::min(1.0, static_cast<double>(k + 1) / n);
        out.push_back({a + t0 * (b - a), a + t1 * (b - a)});
      }
    }
  }
  return out;
}

vtkSmartPointer<vtkActor> lineActor(const std::vector<std::vector<Vector3d>>& polylines,
                                    const Rgb& colour, float width) {
  vtkNew<vtkPoints> points;
  vtkNew<vtkCellArray> cells;
  for (const auto& line : polylines) {
    if (line.size() < 2) continue;
    cells->InsertNextCell(static_cast<vtkIdType>(line.size()));
    for (const Vector3d& v : line) cells->InsertCellPoint(points->InsertNextPoint(v.data()));
  }
  auto colours = colourArray(static_cast<std::size_t>(cells->GetNumberOfCells()));
  for (vtkIdType i = 0; i < cells->GetNumberOfCells(); ++i) setColour(colours, i, colour);
  auto data = vtkSmartPointer<vtkPolyData>::New();
  data->SetPoints(points);
  data->SetLines(cells);
  data->GetCellData()->SetScalars(colours);
  auto actor = flatActor(data, true);
  actor->GetProperty()->SetLineWidth(width);
  return actor;
}

void addPatches(vtkRenderer* renderer, const PatchLayer& layer) {
  vtkNew<vtkPoints> fill_points, line_points;
  vtkNew<vtkCellArray> polys, lines;
  std::vector<Rgb> fill_colours, line_colours;
  for (const auto& patch : layer.patches) {
    if (patch.vertices.size() < 3) continue;
    if (patch.filled) {
      polys->InsertNextCell(static_cast<vtkIdType>(patch.vertices.size()));
      for (const Vector3d& v : patch.vertices)
        polys->InsertCellPoint(fill_points->InsertNextPoint(v.data()));
      fill_colours.push_back(patch.colour);
    } else {
      lines->InsertNextCell(static_cast<vtkIdType>(patch.vertices.size() + 1));
      vtkIdType first = -1;
      for (const Vector3d& v : patch.vertices) {
        const vtkIdType id = line_points->InsertNextPoint(v.data());
        if (first < 0) first = id;
        lines->InsertCellPoint(id);
      }
      lines->InsertCellPoint(first);
      line_colours.push_back(patch.colour);
    }
  }
  auto make = [&](vtkPoints* points, vtkCellArray* cells, const std::vector<Rgb>& colours,
                  bool as_lines) {
    if (colours.empty()) return;
    auto array = colourArray(colours.size());
    for (std::size_t i = 0; i < colours.size(); ++i)
      setColour(array, static_cast<vtkIdType>(i), colours[i]);
    auto data = vtkSmartPointer<vtkPolyData>::New();
    data->SetPoints(points);
    if (as_lines)
      data->SetLines(cells);
    else
      data->SetPolys(cells);
    data->GetCellData()->SetScalars(array);
    auto actor = flatActor(data, true);
    if (as_lines) actor->GetProperty()->SetLineWidth(layer.outline_px);
    renderer->AddActor(actor);
  };
  make(fill_points, polys, fill_colours, false);
  make(line_points, lines, line_colours, true);
}

// ---- 2D overlay (image pixel coordinates, y down) --------------------------

class Overlay {
 public:
  Overlay(vtkRenderer* renderer, int image_height) : renderer_(renderer), h_(image_height) {}

  void text(const std::string& s, double x, double y, int font_px, const Rgb& colour,
            bool bold = false, int justify = 0 /* -1 left, 0 centre, 1 right */,
            int vertical = 0 /* -1 top, 0 centre, 1 bottom */, bool backdrop = false) {
    if (s.empty()) return;
    auto actor = vtkSmartPointer<vtkTextActor>::New();
    actor->SetInput(s.c_str());
    vtkTextProperty* p = actor->GetTextProperty();
    p->SetFontFamilyToArial();
    p->SetFontSize(std::max(font_px, 6));
    p->SetColor(colour.r / 255.0, colour.g / 255.0, colour.b / 255.0);
    p->SetBold(bold);
    if (backdrop) {  // labels over the map stay readable
      p->SetBackgroundColor(1.0, 1.0, 1.0);
      p->SetBackgroundOpacity(0.85);
    }
    if (justify < 0)
      p->SetJustificationToLeft();
    else if (justify > 0)
      p->SetJustificationToRight();
    else
      p->SetJustificationToCentered();
    if (vertical < 0)
      p->SetVerticalJustificationToTop();
    else if (vertical > 0)
      p->SetVerticalJustificationToBottom();
    else
      p->SetVerticalJustificationToCentered();
    actor->SetDisplayPosition(static_cast<int>(std::lround(x)),
                              static_cast<int>(std::lround(h_ - y)));
    texts_.push_back(actor);  // added after the shapes, so text is drawn over them
  }
  void rect(double x0, double y0, double x1, double y1, const Rgb& colour) {
    quads_.push_back({x0, y0, x1, y1});
    quad_colours_.push_back(colour);
  }
  void line(double x0, double y0, double x1, double y1, const Rgb& colour, float width) {
    lines_[width].push_back({x0, y0, x1, y1, colour});
  }
  void frame(const PixelRect& r, const Rgb& colour) {
    line(r.x0 + 0.5, r.y0 + 0.5, r.x1 - 0.5, r.y0 + 0.5, colour, 1.0f);
    line(r.x1 - 0.5, r.y0 + 0.5, r.x1 - 0.5, r.y1 - 0.5, colour, 1.0f);
    line(r.x1 - 0.5, r.y1 - 0.5, r.x0 + 0.5, r.y1 - 0.5, colour, 1.0f);
    line(r.x0 + 0.5, r.y1 - 0.5, r.x0 + 0.5, r.y0 + 0.5, colour, 1.0f);
  }
  /// Adds the accumulated shapes (call once, after every shape).
  void flush() {
    if (!quads_.empty()) {
      vtkNew<vtkPoints> points;
      vtkNew<vtkCellArray> cells;
      auto colours = colourArray(quads_.size());
      for (std::size_t i = 0; i < quads_.size(); ++i) {
        const auto& q = quads_[i];
        const vtkIdType a = points->InsertNextPoint(q[0], h_ - q[1], 0.0);
        const vtkIdType b = points->InsertNextPoint(q[2], h_ - q[1], 0.0);
        const vtkIdType c = points->InsertNextPoint(q[2], h_ - q[3], 0.0);
        const vtkIdType d = points->InsertNextPoint(q[0], h_ - q[3], 0.0);
        const vtkIdType ids[4] = {a, b, c, d};
        cells->InsertNextCell(4, ids);
        setColour(colours, static_cast<vtkIdType>(i), quad_colours_[i]);
      }
      add2D(points, cells, colours, false, 1.0f);
    }
    for (const auto& [width, segments] : lines_) {
      vtkNew<vtkPoints> points;
      vtkNew<vtkCellArray> cells;
      auto colours = colourArray(segments.size());
      for (std::size_t i = 0; i < segments.size(); ++i) {
        const Segment& s = segments[i];
        const vtkIdType ids[2] = {points->InsertNextPoint(s.x0, h_ - s.y0, 0.0),
                                  points->InsertNextPoint(s.x1, h_ - s.y1, 0.0)};
        cells->InsertNextCell(2, ids);
        setColour(colours, static_cast<vtkIdType>(i), s.colour);
      }
      add2D(points, cells, colours, true, width);
    }
    for (const auto& t : texts_) renderer_->AddActor2D(t);
  }

 private:
  struct Segment {
    double x0, y0, x1, y1;
    Rgb colour;
  };
  void add2D(vtkPoints* points, vtkCellArray* cells, vtkUnsignedCharArray* colours, bool as_lines,
             float width) {
    vtkNew<vtkPolyData> data;
    data->SetPoints(points);
    if (as_lines)
      data->SetLines(cells);
    else
      data->SetPolys(cells);
    data->GetCellData()->SetScalars(colours);
    vtkNew<vtkPolyDataMapper2D> mapper;
    mapper->SetInputData(data);
    mapper->SetColorModeToDirectScalars();
    mapper->SetScalarModeToUseCellData();
    mapper->ScalarVisibilityOn();
    vtkNew<vtkActor2D> actor;
    actor->SetMapper(mapper);
    actor->GetProperty()->SetLineWidth(width);
    renderer_->AddActor2D(actor);
  }
  vtkRenderer* renderer_;
  int h_;
  std::vector<std::array<double, 4>> quads_;
  std::vector<Rgb> quad_colours_;
  std::map<float, std::vector<Segment>> lines_;
  std::vector<vtkSmartPointer<vtkTextActor>> texts_;
};

std::string formatMetres(double v) {
  char buf[32];
  if (v >= 1.0)
    std::snprintf(buf, sizeof(buf), "%g m", v);
  else
    std::snprintf(buf, sizeof(buf), "%g cm", v * 100.0);
  return buf;
}

void drawScaleBar(Overlay& overlay, const PanelCamera& camera, int font_px) {
  const PixelRect& r = camera.rect;
  const double target = 0.22 * r.width() / camera.pixels_per_metre;
  if (!(target > 0.0) || !std::isfinite(target)) return;
  const double base = std::pow(10.0, std::floor(std::log10(target)));
  double length = base;
  for (double m : {2.0, 5.0, 10.0})
    if (base * m <= target) length = base * m;
  const double px = length * camera.pixels_per_metre;
  const double x0 = r.x0 + font_px, y = r.y1 - font_px;
  const Rgb black{0, 0, 0};
  const Rgb white{255, 255, 255};
  overlay.rect(x0 - 3, y - font_px * 1.6, x0 + px + 3, y + 5, white);
  overlay.line(x0, y, x0 + px, y, black, 3.0f);
  overlay.line(x0, y - 6, x0, y + 3, black, 2.0f);
  overlay.line(x0 + px, y - 6, x0 + px, y + 3, black, 2.0f);
  overlay.line(x0 + px / 2, y - 4, x0 + px / 2, y, black, 1.0f);
  overlay.text(formatMetres(length), x0 + px / 2, y - 6, font_px, colours::kText, false, 0, 1);
}

// ---- legend -------------------------------------------------------------

void drawLegend(Overlay& overlay, const Figure& figure, const FigureLayout& layout, int base_font) {
  const PixelRect& r = layout.legend;
  const int margin = std::max(6, base_font / 2 + 4);
  int bar_space = 0;
  if (figure.colour_bar && figure.colour_bar->colours.size() >= 2) {
    // Horizontal colour bar at the bottom of the column.
    const ColourBar& bar = *figure.colour_bar;
    const double x0 = r.x0 + margin * 2, x1 = r.x1 - margin * 2;
    const double bar_h = base_font * 1.3;
    const double y1 = r.y1 - margin - base_font * 1.4;
    const double y0 = y1 - bar_h;
    const std::size_t n = bar.colours.size();
    for (std::size_t i = 0; i < n; ++i) {
      const double a = x0 + (x1 - x0) * static_cast<double>(i) / n;
      const double b = x0 + (x1 - x0) * static_cast<double>(i + 1) / n;
      overlay.rect(a, y0, b + 0.5, y1, bar.colours[i]);
    }
    const Rgb black{0, 0, 0};
    for (int k = 0; k <= 4; ++k) {
      const double x = x0 + (x1 - x0) * k / 4.0;
      overlay.line(x, y1, x, y1 + 5, black, 1.0f);
      char buf[32];
      std::snprintf(buf, sizeof(buf), "%.1f", bar.min + (bar.max - bar.min) * k / 4.0);
      overlay.text(buf, x, y1 + 6, base_font * 9 / 10, colours::kText, false, 0, -1);
    }
    overlay.text(bar.title, r.x0 + margin, y0 - 4, base_font, colours::kText, true, -1, 1);
    bar_space = static_cast<int>(r.y1 - (y0 - 4 - base_font * 1.3));
  }
  const int available = r.height() - 2 * margin - bar_space;
  if (figure.legend.empty()) return;
  // Rows: long texts wrap onto continuation rows. Font and columns are
  // chosen so that every row fits (down to 11 px and 3 columns).
  struct Row {
    const LegendItem* item;
    std::string text;
    bool first;
  };
  auto layoutRows = [&](int font, int columns) {
    const double col_w = static_cast<double>(r.width() - 2 * margin) / columns;
    const auto max_chars =
        static_cast<std::size_t>(std::max(6.0, (col_w - font * 2.0) / (0.5 * font)));
    std::vector<Row> rows;
    for (const LegendItem& item : figure.legend) {
      std::string rest = item.text;
      bool first = true;
      while (true) {
        if (rest.size() <= max_chars) {
          rows.push_back({&item, rest, first});
          break;
        }
        std::size_t cut = rest.rfind(' ', max_chars);
        if (cut == std::string::npos || cut < max_chars / 3) cut = max_chars;
        rows.push_back({&item, rest.substr(0, cut), first});
        rest = "  " + rest.substr(rest[cut] == ' ' ? cut + 1 : cut);
        first = false;
      }
    }
    return rows;
  };
  int font = base_font, columns = 1;
  auto rowsFit = [&](int f) { return std::max(1, available / (f + f / 2 + 2)); };
  std::vector<Row> rows = layoutRows(font, columns);
  while (static_cast<int>(rows.size()) > columns * rowsFit(font)) {
    if (font > 11)
      --font;
    else if (columns < 3)
      ++columns, font = std::max(11, base_font * 3 / (2 + columns));
    else
      break;
    rows = layoutRows(font, columns);
  }
  const int row_h = font + font / 2 + 2;
  const int per_column = rowsFit(font);
  const int n = static_cast<int>(rows.size());
  const int shown = std::min(n, per_column * columns);
  const double col_w = static_cast<double>(r.width() - 2 * margin) / columns;
  for (int i = 0; i < shown; ++i) {
    const Row& row = rows[static_cast<std::size_t>(i)];
    const LegendItem& item = *row.item;
    const int col = i / per_column, line = i % per_column;
    const double x = r.x0 + margin + col * col_w;
    const double y = r.y0 + margin + line * row_h + row_h / 2.0;
    const double text_x = x + font * 1.7;
    if (i == shown - 1 && shown < n) {
      overlay.text("... " + std::to_string(n - shown + 1) + " more rows", x, y, font,
                   colours::kText, false, -1, 0);
      continue;
    }
    switch (item.kind) {
      case LegendItem::Kind::kHeading:
        overlay.text(row.text, x, y, font, colours::kText, true, -1, 0);
        break;
      case LegendItem::Kind::kSwatch:
        if (row.first) overlay.rect(x, y - font * 0.5, x + font * 1.2, y + font * 0.5, item.colour);
        overlay.text(row.text, text_x, y, font, colours::kText, false, -1, 0);
        break;
      case LegendItem::Kind::kLine:
        if (row.first) overlay.line(x, y, x + font * 1.4, y, item.colour, 3.0f);
        overlay.text(row.text, text_x, y, font, colours::kText, false, -1, 0);
        break;
      case LegendItem::Kind::kText:
        overlay.text(row.text, x, y, font * 9 / 10, colours::kText, false, -1, 0);
        break;
    }
  }
}

}  // namespace

void renderFigure(const Figure& figure, const std::string& png_path) {
  const int w = figure.width, h = figure.height;
  if (w < 16 || h < 16)
    throw Error(png_path + ": image size " + std::to_string(w) + "x" + std::to_string(h) +
                " too small");
  const FigureLayout layout = figureLayout(w, h);
  const int base_font = std::clamp(h / 48, 10, 30);

  vtkNew<vtkRenderWindow> window;
  window->SetOffScreenRendering(1);
  window->SetMultiSamples(0);
  window->SetPointSmoothing(0);
  window->SetLineSmoothing(0);
  window->SetPolygonSmoothing(0);
  window->SetNumberOfLayers(2);
  window->SetSize(w, h);
  window->SetWindowName("storey render");

  const Rgb& bg = figure.background;
  vtkNew<vtkRenderer> background;
  background->SetLayer(0);
  background->SetBackground(bg.r / 255.0, bg.g / 255.0, bg.b / 255.0);
  background->SetViewport(0, 0, 1, 1);
  background->InteractiveOff();
  window->AddRenderer(background);

  vtkNew<vtkRenderer> overlay_renderer;
  overlay_renderer->SetLayer(1);
  overlay_renderer->SetViewport(0, 0, 1, 1);
  overlay_renderer->InteractiveOff();
  Overlay overlay(overlay_renderer, h);

  std::vector<vtkSmartPointer<vtkRenderer>> keep;
  for (const Panel& panel : figure.panels) {
    const PixelRect rect = panelRect(layout, panel);
    if (rect.width() < 4 || rect.height() < 4) continue;
    const PanelCamera pc = fitCamera(panel, rect);
    const double vx0 = static_cast<double>(rect.x0) / w, vx1 = static_cast<double>(rect.x1) / w;
    const double vy0 = 1.0 - static_cast<double>(rect.y1) / h,
                 vy1 = 1.0 - static_cast<double>(rect.y0) / h;

    vtkNew<vtkCamera> camera;
    camera->ParallelProjectionOn();
    camera->SetFocalPoint(pc.focal.data());
    const Vector3d position = pc.focal - pc.forward * (pc.depth_half + 10.0);
    camera->SetPosition(position.data());
    camera->SetViewUp(pc.up.data());
    camera->SetParallelScale(pc.parallel_scale);
    camera->SetClippingRange(std::max(0.01, 10.0 - 1.0), 10.0 + 2.0 * pc.depth_half + 1.0);

    auto scene = vtkSmartPointer<vtkRenderer>::New();
    scene->SetLayer(0);
    scene->SetViewport(vx0, vy0, vx1, vy1);
    scene->SetBackground(bg.r / 255.0, bg.g / 255.0, bg.b / 255.0);
    scene->SetActiveCamera(camera);
    scene->AutomaticLightCreationOff();
    scene->InteractiveOff();
    auto top = vtkSmartPointer<vtkRenderer>::New();
    top->SetLayer(1);
    top->SetViewport(vx0, vy0, vx1, vy1);
    top->SetActiveCamera(camera);
    top->AutomaticLightCreationOff();
    top->InteractiveOff();

    for (const PatchLayer& layer : panel.patches) addPatches(scene, layer);
    for (const PointLayer& layer : panel.points)
      if (!layer.positions.empty()) scene->AddActor(pointActor(layer));
    const double dash = 0.012 * 2.0 * pc.parallel_scale;
    for (const LineLayer& layer : panel.lines) {
      const auto lines = layer.dashed ? dashes(layer.polylines, dash) : layer.polylines;
      (layer.on_top ? top : scene)->AddActor(lineActor(lines, layer.colour, layer.width_px));
    }
    window->AddRenderer(scene);
    window->AddRenderer(top);
    keep.push_back(scene);
    keep.push_back(top);

    for (const WorldLabel& label : panel.labels) {
      const Eigen::Vector2d px = pc.toPixel(label.position);
      if (px.x() < rect.x0 || px.x() > rect.x1 || px.y() < rect.y0 || px.y() > rect.y1) continue;
      overlay.text(label.text, px.x(), px.y(), label.font_px, label.colour, false, -1, 0, true);
    }
    overlay.frame(rect, {210, 210, 210});
    if (!panel.caption.empty()) {
      overlay.text(panel.caption, rect.x0 + base_font * 0.6, rect.y0 + base_font * 0.5, base_font,
                   colours::kText, true, -1, -1);
    }
    if (panel.scale_bar) drawScaleBar(overlay, pc, base_font);
  }

  // Title band and legend column.
  const int title_font = std::clamp(layout.title.height() * 2 / 5, 12, 48);
  overlay.text(figure.title, base_font, layout.title.y0 + layout.title.height() * 0.36, title_font,
               colours::kText, true, -1, 0);
  overlay.text(figure.subtitle, base_font, layout.title.y0 + layout.title.height() * 0.78,
               std::max(9, title_font * 11 / 20), {70, 70, 70}, false, -1, 0);
  overlay.line(0, layout.title.y1 - 0.5, w, layout.title.y1 - 0.5, {180, 180, 180}, 1.0f);
  drawLegend(overlay, figure, layout, base_font);
  overlay.flush();
  window->AddRenderer(overlay_renderer);

  window->Render();
  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(window);
  grab->SetInputBufferTypeToRGB();
  grab->ReadFrontBufferOff();
  grab->ShouldRerenderOff();
  grab->Update();
  int dims[3] = {0, 0, 0};
  grab->GetOutput()->GetDimensions(dims);
  if (dims[0] != w || dims[1] != h) {
    throw Error(png_path + ": the off-screen window is " + std::to_string(dims[0]) + "x" +
                std::to_string(dims[1]) + " px, not the requested " + std::to_string(w) + "x" +
                std::to_string(h));
  }
  const std::string temporary = temporaryPathFor(png_path);
  vtkNew<vtkPNGWriter> writer;
  writer->SetFileName(temporary.c_str());
  writer->SetInputConnection(grab->GetOutputPort());
  writer->Write();
  if (writer->GetErrorCode() != 0) {
    std::remove(temporary.c_str());
    throw Error(png_path + ": cannot write the PNG (VTK error code " +
                std::to_string(writer->GetErrorCode()) + ")");
  }
  commitTemporary(temporary, png_path);
}

}  // namespace storey::render
