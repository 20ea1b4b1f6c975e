#include "core/attacks/bend_twist.hpp"

#include <Eigen/Geometry>
#include <cmath>
#include <stdexcept>

#include "core/mesh/surface_moments.hpp"

namespace meshmark {

namespace {

// The surface's frame: centroid and principal axes, and its extent along the first.
struct AxisFrame {
  Eigen::Vector3d centroid;
  Eigen::Matrix3d axes;  // columns: longest, second, third (right-handed)
  double low = 0, high = 0;
};

AxisFrame axis_frame(const Mesh& mesh) {
  const SurfaceMoments moments = surface_moments(mesh);
  AxisFrame frame{moments.centroid, moments.axes};
  frame.axes.col(2) = frame.axes.col(0).cross(frame.axes.col(1));
  const Eigen::VectorXd along = (mesh.V.rowwise() - frame.centroid.transpose()) * frame.axes.col(0);
  frame.low = along.minCoeff();
  frame.high = along.maxCoeff();
  return frame;
}

void check_angle(double degrees, double limit, const char* what) {
  if (!std::isfinite(degrees) || std::abs(degrees) > limit)
    throw std::invalid_argument(std::string("the ") + what + " angle must be within ±" +
                                std::to_string(static_cast<int>(limit)) + " degrees");
}

}  // namespace

Mesh twist(const Mesh& mesh, double degrees) {
  check_angle(degrees, 360, "twist");
  if (mesh.V.rows() == 0) return mesh;
  const AxisFrame frame = axis_frame(mesh);
  const double length = std::max(frame.high - frame.low, 1e-300), mid = 0.5 * (frame.low + frame.high);
  Mesh out = mesh;
  for (Eigen::Index v = 0; v < mesh.V.rows(); ++v) {
    const Eigen::Vector3d local = frame.axes.transpose() * (mesh.V.row(v).transpose() - frame.centroid);
    const double angle = degrees * M_PI / 180 * (local.x() - mid) / length;
    const Eigen::Vector3d turned = Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitX()) * local;
    out.V.row(v) = (frame.centroid + frame.axes * turned).transpose();
  }
  return out;
}

Mesh bend(const Mesh& mesh, double degrees) {
  check_angle(degrees, 180, "bend");
  if (mesh.V.rows() == 0 || degrees == 0) return mesh;
  const AxisFrame frame = axis_frame(mesh);
  const double length = std::max(frame.high - frame.low, 1e-300), mid = 0.5 * (frame.low + frame.high);
  const double radius = length / (degrees * M_PI / 180);  // the arc through the centre keeps its length
  Mesh out = mesh;
  for (Eigen::Index v = 0; v < mesh.V.rows(); ++v) {
    const Eigen::Vector3d local = frame.axes.transpose() * (mesh.V.row(v).transpose() - frame.centroid);
    const double phi = (local.x() - mid) / radius, r = radius - local.y();
    const Eigen::Vector3d bent(mid + r * std::sin(phi), radius - r * std::cos(phi), local.z());
    out.V.row(v) = (frame.centroid + frame.axes * bent).transpose();
  }
  return out;
}

}  // namespace meshmark
