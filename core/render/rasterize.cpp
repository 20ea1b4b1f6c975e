#include "core/render/rasterize.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace meshmark {

namespace {

const Rgb kBackground{255, 255, 255};

// Screen coordinates: x to the right, y down, depth along the view (smaller is nearer).
struct Camera {
  Eigen::Vector3d right, up, forward;
  Eigen::Vector2d lo;  // the framed extent's lower corner, in (right, up) units
  double pixels_per_unit = 1;
  int size = 0;
  Eigen::Vector3d to_screen(const Eigen::Vector3d& p) const {
    const double x = (p.dot(right) - lo.x()) * pixels_per_unit;
    const double y = size - (p.dot(up) - lo.y()) * pixels_per_unit;
    return {x, y, p.dot(forward)};
  }
};

Camera frame(const Vertices& V, const View& view, int size) {
  Camera c;
  c.forward = view.forward.normalized();
  c.up = (view.up - view.up.dot(c.forward) * c.forward).normalized();
  c.right = c.forward.cross(c.up);
  c.size = size;
  Eigen::Vector2d lo = Eigen::Vector2d::Constant(std::numeric_limits<double>::max()), hi = -lo;
  for (Eigen::Index i = 0; i < V.rows(); ++i) {
    const Eigen::Vector3d p = V.row(i).transpose();
    const Eigen::Vector2d q(p.dot(c.right), p.dot(c.up));
    lo = lo.cwiseMin(q);
    hi = hi.cwiseMax(q);
  }
  const double extent = std::max((hi - lo).maxCoeff(), 1e-300) * 1.1;  // a 5 % margin each side
  c.lo = (lo + hi) / 2 - Eigen::Vector2d::Constant(extent / 2);
  c.pixels_per_unit = size / extent;
  return c;
}

Rgb shaded(const Rgb& colour, double cosine) {
  const double light = 0.3 + 0.7 * std::abs(cosine);  // two-sided: a copy wound inward still shows
  auto channel = [light](std::uint8_t v) { return static_cast<std::uint8_t>(std::lround(v * light)); };
  return {channel(colour.r), channel(colour.g), channel(colour.b)};
}

// Edge function: twice the signed area of (a, b, p).
double edge(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double px, double py) {
  return (b.x() - a.x()) * (py - a.y()) - (b.y() - a.y()) * (px - a.x());
}

void draw_triangle(const Eigen::Vector3d (&s)[3], Rgb colour, Image& image, std::vector<double>& depth) {
  const double area = edge(s[0], s[1], s[2].x(), s[2].y());
  if (std::abs(area) < 1e-12) return;
  const int x0 = std::max(0, static_cast<int>(std::floor(std::min({s[0].x(), s[1].x(), s[2].x()}))));
  const int x1 = std::min(image.width - 1, static_cast<int>(std::ceil(std::max({s[0].x(), s[1].x(), s[2].x()}))));
  const int y0 = std::max(0, static_cast<int>(std::floor(std::min({s[0].y(), s[1].y(), s[2].y()}))));
  const int y1 = std::min(image.height - 1, static_cast<int>(std::ceil(std::max({s[0].y(), s[1].y(), s[2].y()}))));
  for (int y = y0; y <= y1; ++y)
    for (int x = x0; x <= x1; ++x) {
      const double px = x + 0.5, py = y + 0.5;
      const double w0 = edge(s[1], s[2], px, py) / area, w1 = edge(s[2], s[0], px, py) / area;
      const double w2 = 1 - w0 - w1;
      if (w0 < 0 || w1 < 0 || w2 < 0) continue;
      const double z = w0 * s[0].z() + w1 * s[1].z() + w2 * s[2].z();
      double& nearest = depth[static_cast<std::size_t>(y) * image.width + x];
      if (z >= nearest) continue;
      nearest = z;
      image.at(x, y) = colour;
    }
}

void draw_mesh(const Layer& layer, const Camera& camera, Image& image, std::vector<double>& depth) {
  const Mesh& mesh = *layer.mesh;
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
    Eigen::Vector3d corner[3], screen[3];
    for (int k = 0; k < 3; ++k) {
      const int v = mesh.F(f, k);
      if (v < 0 || v >= mesh.V.rows()) throw std::invalid_argument("render: a face names a vertex the mesh lacks");
      corner[k] = mesh.V.row(v).transpose();
      screen[k] = camera.to_screen(corner[k]);
    }
    const Eigen::Vector3d normal = (corner[1] - corner[0]).cross(corner[2] - corner[0]);
    const double length = normal.norm();
    if (length == 0) continue;
    draw_triangle(screen, shaded(layer.colour, normal.dot(camera.forward) / length), image, depth);
  }
}

}  // namespace

std::vector<View> front_and_side_views() {
  return {View{-Eigen::Vector3d::UnitZ(), Eigen::Vector3d::UnitY()},
          View{-Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY()}};
}

Image render_layers(const std::vector<Layer>& layers, const View& view, int size, const Vertices* framed) {
  if (size <= 0 || size > 4096) throw std::invalid_argument("render: a picture of 1 to 4096 pixels a side");
  Image image(size, size, kBackground);
  if (!framed && !layers.empty()) framed = &layers.front().mesh->V;
  if (!framed || framed->rows() == 0) return image;
  const Camera camera = frame(*framed, view, size);
  std::vector<double> depth(static_cast<std::size_t>(size) * size, std::numeric_limits<double>::infinity());
  for (const Layer& layer : layers) draw_mesh(layer, camera, image, depth);
  return image;
}

}  // namespace meshmark
