#include "png_check.h"

#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPNGReader.h>

namespace storey::test {

Image readPng(const std::string& path) {
  Image image;
  vtkNew<vtkPNGReader> reader;
  if (!reader->CanReadFile(path.c_str())) return image;
  reader->SetFileName(path.c_str());
  reader->Update();
  vtkImageData* data = reader->GetOutput();
  int dims[3];
  data->GetDimensions(dims);
  const int components = data->GetNumberOfScalarComponents();
  if (components < 3 || data->GetScalarType() != VTK_UNSIGNED_CHAR) return image;
  image.width = dims[0];
  image.height = dims[1];
  image.pixels.resize(static_cast<std::size_t>(dims[0]) * dims[1]);
  for (int y = 0; y < dims[1]; ++y) {
    for (int x = 0; x < dims[0]; ++x) {
      // VTK images start at the bottom row.
      const auto* p =
          static_cast<const unsigned char*>(data->GetScalarPointer(x, dims[1] - 1 - y, 0));
      image.pixels[static_cast<std::size_t>(y) * dims[0] + x] = {p[0], p[1], p[2]};
    }
  }
  return image;
}

std::set<std::uint32_t> coloursIn(const Image& image, const render::PixelRect& rect) {
  std::set<std::uint32_t> out;
  for (int y = std::max(0, rect.y0); y < std::min(image.height, rect.y1); ++y)
    for (int x = std::max(0, rect.x0); x < std::min(image.width, rect.x1); ++x)
      out.insert(key(image.at(x, y)));
  return out;
}

}  // namespace storey::test
