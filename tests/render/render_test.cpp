#include <gtest/gtest.h>
#include <zlib.h>

#include <cstring>
#include <set>

#include "core/mesh/example_shapes.hpp"
#include "core/render/alignment_pictures.hpp"
#include "core/render/image.hpp"
#include "core/render/preview_mesh.hpp"
#include "core/render/rasterize.hpp"

namespace meshmark {
namespace {

std::uint32_t big_endian_u32(const std::string& s, std::size_t at) {
  std::uint32_t v = 0;
  for (int k = 0; k < 4; ++k) v = (v << 8) | static_cast<unsigned char>(s[at + k]);
  return v;
}

TEST(EncodePng, ChunksCarryTheSizeAndThePixelsInflateBack) {
  Image image(3, 2, Rgb{10, 20, 30});
  image.at(2, 1) = Rgb{200, 100, 50};
  const std::string png = encode_png(image);
  ASSERT_EQ(png.substr(0, 8), std::string("\x89PNG\r\n\x1a\n"));
  EXPECT_EQ(png.substr(12, 4), "IHDR");
  EXPECT_EQ(big_endian_u32(png, 16), 3u);
  EXPECT_EQ(big_endian_u32(png, 20), 2u);
  // Every chunk's CRC covers its type and data.
  std::size_t at = 8;
  std::string idat;
  while (at < png.size()) {
    const std::uint32_t length = big_endian_u32(png, at);
    const std::string typed = png.substr(at + 4, 4 + length);
    EXPECT_EQ(big_endian_u32(png, at + 8 + length),
              crc32(0L, reinterpret_cast<const Bytef*>(typed.data()), static_cast<uInt>(typed.size())));
    if (typed.substr(0, 4) == "IDAT") idat += typed.substr(4);
    at += 12 + length;
  }
  EXPECT_EQ(at, png.size());
  std::string raw(2 * (1 + 9), '\0');
  uLongf size = static_cast<uLongf>(raw.size());
  ASSERT_EQ(uncompress(reinterpret_cast<Bytef*>(raw.data()), &size, reinterpret_cast<const Bytef*>(idat.data()),
                       static_cast<uLong>(idat.size())),
            Z_OK);
  EXPECT_EQ(static_cast<unsigned char>(raw[10 + 1 + 6]), 200);  // row 1, filter byte, pixel 2's red
  EXPECT_EQ(static_cast<unsigned char>(raw[1]), 10);
}

TEST(RenderLayers, NearerSurfaceHidesFartherAndTheShapeFillsTheFrame) {
  Mesh near, far;
  near.V.resize(3, 3);
  near.V << -1, -1, 1, 1, -1, 1, 0, 1, 1;  // z = 1: nearer to a camera looking along -z
  near.F.resize(1, 3);
  near.F << 0, 1, 2;
  far = near;
  far.V.col(2).setConstant(-1);
  const View view{-Eigen::Vector3d::UnitZ(), Eigen::Vector3d::UnitY()};
  for (const bool near_first : {true, false}) {
    std::vector<Layer> layers = {{&near, Rgb{255, 0, 0}}, {&far, Rgb{0, 0, 255}}};
    if (!near_first) std::swap(layers[0], layers[1]);
    const Image image = render_layers(layers, view, 64);
    const Rgb centre = image.at(32, 36);
    EXPECT_GT(centre.r, 0) << "the nearer red triangle must be seen, drawn first or not";
    EXPECT_EQ(centre.b, 0);
    EXPECT_EQ(image.at(0, 0), (Rgb{255, 255, 255}));  // the margin stays background
  }
}

TEST(RenderLayers, FrontAndSideViewsOfASphereShowADisc) {
  const Mesh sphere = icosphere(3);
  for (const View& view : front_and_side_views()) {
    const Image image = render_layers({{&sphere, Rgb{180, 180, 180}}}, view, 96);
    std::set<int> shades;
    int covered = 0;
    for (const Rgb& p : image.pixels) {
      if (p != Rgb{255, 255, 255}) ++covered;
      shades.insert(p.r);
    }
    // A disc of diameter 1/1.1 of the frame: pi/4/1.21 of it, about 65 %.
    EXPECT_NEAR(covered / double(image.pixels.size()), 0.649, 0.03);
    EXPECT_GT(shades.size(), 10u) << "shading varies across the sphere";
  }
}

TEST(PreviewPly, HeaderCountsAndBinaryBodyMatchTheMesh) {
  const Mesh sphere = icosphere(1);
  const std::vector<float> values(static_cast<std::size_t>(sphere.V.rows()), 0.25f);
  const std::string ply = write_preview_ply(sphere, values);
  const std::size_t body = ply.find("end_header\n") + 11;
  EXPECT_NE(ply.find("element vertex " + std::to_string(sphere.V.rows())), std::string::npos);
  EXPECT_NE(ply.find("property float displacement"), std::string::npos);
  EXPECT_EQ(ply.size() - body, static_cast<std::size_t>(sphere.V.rows()) * 16 + sphere.F.rows() * 13);
  float y = 0;
  std::memcpy(&y, ply.data() + body + 16 + 4, 4);  // vertex 1's y
  EXPECT_FLOAT_EQ(y, static_cast<float>(sphere.V(1, 1)));
  EXPECT_THROW(write_preview_ply(sphere, std::vector<float>(3)), std::invalid_argument);
}

TEST(NormalDisplacement, ReadsAnOutwardMoveAsPositivePercentAndIgnoresTangentialOnes) {
  const Mesh sphere = icosphere(2);  // unit sphere: diagonal 2*sqrt(3) of its box
  Vertices marked = sphere.V * 1.01;
  const std::vector<float> d = normal_displacement_percent(sphere, marked);
  const double diagonal = (sphere.V.colwise().maxCoeff() - sphere.V.colwise().minCoeff()).norm();
  for (const float v : d) EXPECT_NEAR(v, 100 * 0.01 / diagonal, 1e-3);
  EXPECT_THROW(normal_displacement_percent(sphere, marked.topRows(3)), std::invalid_argument);
}

TEST(AlignmentPictures, ASuspectOnTheOriginalCoversItsPlaceAndAMovedOneDoesNot) {
  const Mesh original = icosphere(2);
  Mesh moved = original;
  moved.V.col(0).array() += 5.0;  // far to the side: off the original's frame
  const auto on = alignment_pictures(original, original, 64), off = alignment_pictures(original, moved, 64);
  ASSERT_EQ(on.size(), 4u);
  EXPECT_NE(on[1].png, off[1].png);
  EXPECT_EQ(on[0].png, off[0].png);  // the original's picture does not depend on the suspect
  const Image blank(64, 64, Rgb{255, 255, 255});
  EXPECT_EQ(off[1].png, encode_png(blank)) << "a suspect off the frame leaves it empty";
}

}  // namespace
}  // namespace meshmark
